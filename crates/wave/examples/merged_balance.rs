//! How far a merged run's fields drift from the wall's impulse (momentum)
//! and above the impact's energy, checked after every leap and every
//! thousandth step (every step with `every`): a diagnostic for leaps and
//! lattice deposits on slow rods.
//!
//! cargo run --release -p impact-wave --example merged_balance -- SCENE.json P [noleap|every]
//!
//! `P` is the lattice spacing in transits; the spacing in the longest
//! transit is `P / 50`, as the ladder pairs them.
use impact_model::Scene;
use impact_wave::{Resolution, StepKind, WaveConfig, WaveEngine};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (Some(path), Some(p)) = (args.get(1), args.get(2)) else {
        return Err("usage: merged_balance SCENE.json P [noleap|every]".into());
    };
    let scene: Scene = serde_json::from_str(&std::fs::read_to_string(path)?)?;
    let rod = scene.validate()?;
    let p: f64 = p.parse()?;
    let option = args.get(3).map(String::as_str);
    let config = WaveConfig {
        resolution: Resolution::Merged {
            per_transit: p,
            per_longest: p / 50.0,
        },
        leap_quiet_layers: option != Some("noleap"),
        max_events: u64::MAX / 4,
        ..WaveConfig::default()
    };
    let mut engine = WaveEngine::new(&rod, config)?;
    let e0 = rod.initial_energy();
    let p0 = rod.mass() * rod.impact_speed();
    let (mut worst_momentum, mut worst_gain) = (0f64, 0f64);
    let mut steps = 0u64;
    loop {
        let step = engine.step()?;
        if let StepKind::Stopped(_) = step.kind {
            break;
        }
        steps += 1;
        let leap = matches!(step.kind, StepKind::Leap { .. });
        if leap || option == Some("every") || steps.is_multiple_of(1000) {
            let f = engine.field_totals();
            let drift = (f.momentum - p0 * engine.restitution()).abs() / p0;
            if drift > 1e-9 && worst_momentum <= 1e-9 {
                println!(
                    "first drift over 1e-9: step {steps}, t = {}, {drift:.2e} ({:?})",
                    engine.time(),
                    step.kind
                );
            }
            worst_momentum = worst_momentum.max(drift);
            worst_gain = worst_gain.max((f.energy - e0) / e0);
        }
    }
    println!(
        "e {}: momentum drift up to {worst_momentum:.2e} of M v_b, energy gain up to {worst_gain:.2e}; {:?}",
        engine.restitution(),
        engine.truncation()
    );
    Ok(())
}

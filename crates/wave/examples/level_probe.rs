//! One merged run per lattice spacing on a scene file, timed: what each
//! level of the merged ladder costs (work, boundary events, leapt events,
//! seconds) and the `e` it gives, for tuning leaps and budgets.
//!
//! cargo run --release -p impact-wave --example level_probe -- SCENE.json P [P...]
//!
//! `P` is the lattice spacing in transits (at most 0.5); the spacing in the
//! longest transit is `P / 50`, as the ladder pairs them, unless given as
//! `P:L` (to vary the two apart).
use impact_model::Scene;
use impact_wave::{Resolution, WaveConfig, WaveEngine};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let Some(path) = args.get(1) else {
        return Err("usage: level_probe SCENE.json P [P...]".into());
    };
    let scene: Scene = serde_json::from_str(&std::fs::read_to_string(path)?)?;
    let rod = scene.validate()?;
    for p in &args[2..] {
        let (p, l): (f64, f64) = match p.split_once(':') {
            Some((p, l)) => (p.parse()?, l.parse()?),
            None => (p.parse()?, p.parse::<f64>()? / 50.0),
        };
        let config = WaveConfig {
            resolution: Resolution::Merged {
                per_transit: p,
                per_longest: l,
            },
            max_events: u64::MAX / 4,
            // NO_LEAPS=1: every boundary event through the loop
            leap_quiet_layers: std::env::var_os("NO_LEAPS").is_none(),
            ..WaveConfig::default()
        };
        let start = std::time::Instant::now();
        let mut engine = WaveEngine::new(&rod, config)?;
        let finished = engine.run().map_or("stopped", |_| "finished");
        println!(
            "p {p:.3e} l {l:.3e}: {finished}, e {:.10}, work {}, events {} ({} leapt), {:.2} s",
            engine.restitution(),
            engine.steps(),
            engine.events(),
            engine.leaped_events(),
            start.elapsed().as_secs_f64()
        );
    }
    Ok(())
}

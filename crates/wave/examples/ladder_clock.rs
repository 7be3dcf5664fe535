//! When a solve's phases end: the exact try, each merged level, the
//! twins, the end, in seconds from the start (what a slow rod's wall
//! time is made of).
//!
//! cargo run --release -p impact-wave --example ladder_clock -- SCENE.json
use impact_model::Scene;
use impact_wave::{LadderProgress, WaveConfig, solve_observed};
use std::time::Instant;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let Some(path) = args.get(1) else {
        return Err("usage: ladder_clock SCENE.json".into());
    };
    let scene: Scene = serde_json::from_str(&std::fs::read_to_string(path)?)?;
    let rod = scene.validate()?;
    let start = Instant::now();
    let clock = || start.elapsed().as_secs_f64();
    let show = |p: LadderProgress| match p {
        LadderProgress::LadderStarted { exact_events } => {
            println!("{:7.3} s  exact run past {exact_events} events", clock())
        }
        LadderProgress::LevelDone {
            level,
            per_transit,
            restitution,
            bound,
            work,
        } => println!(
            "{:7.3} s  level {level} ({per_transit:.3e}): e {restitution:.10}, bound {bound:.1e}, work {work}",
            clock()
        ),
        LadderProgress::ExactAgain { events } => {
            println!("{:7.3} s  exact run again, up to {events} events", clock())
        }
        LadderProgress::FurtherTwins {
            level,
            first_difference,
        } => println!(
            "{:7.3} s  level {level}: further twins ({first_difference:.1e})",
            clock()
        ),
    };
    // a block's trace on each layer's own lattice with `NOONE=1`
    let config = WaveConfig {
        one_lattice_blocks: std::env::var_os("NOONE").is_none(),
        ..WaveConfig::default()
    };
    let solution = solve_observed(&rod, &config, &show)?;
    println!(
        "{:7.3} s  done: e {:.10} ± {:.1e}",
        clock(),
        solution.outcome.restitution,
        solution.outcome.error_bound.unwrap_or(f64::NAN)
    );
    Ok(())
}

//! Runs the event loop at the paper's hard corner (x = 0.995, alpha =
//! 0.005) many times, for profilers: `valgrind --tool=callgrind` counts
//! instructions per event without the noise of a shared machine. One exact
//! run of the tracer each time (not the point's error estimate).
//!
//! cargo run --release -p impact-wave --example corner_profile -- [REPEATS]
use impact_model::Bilayer;
use impact_wave::{WaveConfig, WaveEngine};

fn main() {
    let repeats: u32 = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(100);
    let rod = Bilayer::new(0.995, 0.005)
        .and_then(|b| b.scene().validate())
        .expect("the corner is a valid bilayer");
    let config = WaveConfig::default();
    let (mut events, mut steps) = (0, 0);
    let start = std::time::Instant::now();
    for _ in 0..repeats {
        let mut engine = WaveEngine::new(&rod, config.clone()).expect("a valid rod");
        engine.run().expect("the corner finishes");
        events += engine.events();
        steps += engine.steps();
    }
    let ns = start.elapsed().as_secs_f64() * 1e9;
    println!(
        "{} events, {} loop steps per point; {:.1} ns per event, {:.1} ns per step",
        events / u64::from(repeats),
        steps / u64::from(repeats),
        ns / events as f64,
        ns / steps as f64
    );
}

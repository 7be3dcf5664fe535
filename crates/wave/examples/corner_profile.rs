//! Runs the event loop at the paper's hard corner (x = 0.995, alpha =
//! 0.005), or at another bilayer, many times, for profilers: `valgrind
//! --tool=callgrind` counts instructions per event without the noise of a
//! shared machine. One exact run of the tracer each time, or with `point`
//! a whole point as `impact run` computes it (its error estimate included).
//!
//! cargo run --release -p impact-wave --example corner_profile -- [REPEATS [X ALPHA [point]]]
use impact_model::Bilayer;
use impact_wave::{WaveConfig, WaveEngine, simulate};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let number = |k: usize, default: f64| {
        args.get(k)
            .and_then(|s| s.parse::<f64>().ok())
            .unwrap_or(default)
    };
    let repeats = number(1, 100.0) as u32;
    let (x, alpha) = (number(2, 0.995), number(3, 0.005));
    let whole_point = args.get(4).is_some_and(|s| s == "point");
    let rod = Bilayer::new(x, alpha)
        .and_then(|b| b.scene().validate())
        .expect("a valid bilayer");
    let config = WaveConfig::default();
    let (mut events, mut steps) = (0, 0);
    let mut fastest = f64::INFINITY;
    let start = std::time::Instant::now();
    for _ in 0..repeats {
        let one = std::time::Instant::now();
        if whole_point {
            let outcome = simulate(&rod, &config).expect("the point finishes");
            events += outcome.events.unwrap_or(0);
        } else {
            let mut engine = WaveEngine::new(&rod, config.clone()).expect("a valid rod");
            engine.run().expect("the rod finishes");
            events += engine.events();
            steps += engine.steps();
        }
        fastest = fastest.min(one.elapsed().as_secs_f64());
    }
    let ns = start.elapsed().as_secs_f64() * 1e9;
    println!(
        "x {x} alpha {alpha}: {} events, {} loop steps per run; {:.1} ns per event, {:.1} ns per step; fastest run {:.1} us, mean {:.1} us",
        events / u64::from(repeats),
        steps / u64::from(repeats),
        ns / events as f64,
        ns / steps as f64,
        fastest * 1e6,
        ns / 1e3 / f64::from(repeats)
    );
}

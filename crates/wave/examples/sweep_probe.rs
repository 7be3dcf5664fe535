//! The 20 hardest points of the paper's grid (`x = 0.9..0.995`, `alpha =
//! 0.005`, those of `scripts/bench-tracker.sh`) as a one-thread sweep
//! computes them, pass after pass in one process: the first pass is what a
//! fresh `impact sweep` pays (its memory faulted in, its caches cold), the
//! later ones the warm figure a criterion bench reports.
//!
//! cargo run --release -p impact-wave --example sweep_probe -- [PASSES [print]]
use impact_model::Bilayer;
use impact_wave::{WaveConfig, simulate};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let passes: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(3);
    let print = args.get(2).is_some_and(|s| s == "print");
    let config = WaveConfig::default();
    let rods: Vec<_> = (0..20)
        .map(|k| {
            let x = 0.9 + 0.005 * f64::from(k);
            let rod = Bilayer::new(x, 0.005)
                .and_then(|b| b.scene().validate())
                .expect("a valid bilayer");
            (x, rod)
        })
        .collect();
    for pass in 0..passes {
        let start = std::time::Instant::now();
        for (x, rod) in &rods {
            let outcome = simulate(rod, &config).expect("the point finishes");
            if print && pass == 0 {
                println!(
                    "x {x:.3}: e {:.15}, {} bounces, {} events",
                    outcome.restitution,
                    outcome.bounces,
                    outcome.events.unwrap_or(0)
                );
            }
            std::hint::black_box(outcome);
        }
        if pass < 3 || pass + 1 == passes {
            println!("pass {pass}: {:.2} ms", start.elapsed().as_secs_f64() * 1e3);
        }
    }
}

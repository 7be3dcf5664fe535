//! How far `e` moves when the bottom's modulus is nudged by `k 1e-12`, on
//! one merged lattice (a diagnostic for the chaos of chattering rods):
//! `nudge_spread SCENE.json PER_TRANSIT PER_LONGEST K`, runs `k = -K..=K`.
use impact_model::Scene;
use impact_wave::{Resolution, WaveConfig, WaveEngine};
use rayon::prelude::*;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if args.len() != 5 {
        eprintln!("usage: nudge_spread SCENE.json PER_TRANSIT PER_LONGEST K (K >= 1)");
        std::process::exit(2);
    }
    let text = std::fs::read_to_string(&args[1]).expect("a scene file");
    let scene: Scene = serde_json::from_str(&text).expect("a scene");
    let p: f64 = args[2].parse().expect("PER_TRANSIT");
    let l: f64 = args[3].parse().expect("PER_LONGEST");
    let k: i32 = args[4].parse().expect("K");
    assert!(k >= 1, "K >= 1: a spread needs two runs");
    let config = WaveConfig {
        resolution: Resolution::Merged {
            per_transit: p,
            per_longest: l,
        },
        ..WaveConfig::default()
    };
    let es: Vec<(i32, f64, u64)> = (-k..=k)
        .into_par_iter()
        .map(|j| {
            let mut nudged = scene.clone();
            nudged.layers[0].modulus *= 1.0 + f64::from(j) * 1e-12;
            let rod = nudged.validate().expect("a valid scene");
            let mut engine = WaveEngine::new(&rod, config.clone()).expect("a valid rod");
            while engine.stopped().is_none() {
                engine.step().expect("a step");
            }
            (j, engine.restitution(), engine.steps())
        })
        .collect();
    for (j, e, steps) in &es {
        println!("{j} {e:.12} {steps}");
    }
    let mean = es.iter().map(|x| x.1).sum::<f64>() / es.len() as f64;
    let sd = (es.iter().map(|x| (x.1 - mean).powi(2)).sum::<f64>() / (es.len() - 1) as f64).sqrt();
    let lo = es.iter().map(|x| x.1).fold(f64::INFINITY, f64::min);
    let hi = es.iter().map(|x| x.1).fold(f64::NEG_INFINITY, f64::max);
    println!("mean {mean:.9} sd {sd:.2e} range {:.2e}", hi - lo);
}

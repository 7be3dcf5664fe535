//! A rod's answered blocks and their traced responses, as JSON: what a
//! port sums over, for studying how a response rings (whether its tail is
//! a few decaying modes: `scripts/block-tail.py` reads this).
//!
//! cargo run --release -p impact-wave --example block_taps -- SCENE.json P LENGTH > taps.json
//!
//! `P` is the lattice spacing in transits (`P / 50` of the longest), as
//! the ladder's levels pair them; `LENGTH` how long after an input to
//! trace, in the scene's time units.
use impact_model::Scene;
use impact_wave::{Resolution, WaveConfig, WaveEngine};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().collect();
    let (Some(path), Some(p), Some(length)) = (args.get(1), args.get(2), args.get(3)) else {
        return Err("usage: block_taps SCENE.json P LENGTH".into());
    };
    let (p, length): (f64, f64) = (p.parse()?, length.parse()?);
    let scene: Scene = serde_json::from_str(&std::fs::read_to_string(path)?)?;
    let rod = scene.validate()?;
    let config = WaveConfig {
        resolution: Resolution::Merged {
            per_transit: p,
            per_longest: p / 50.0,
        },
        ..WaveConfig::default()
    };
    let mut engine = WaveEngine::new(&rod, config)?;
    let blocks = engine.answered_blocks();
    let responses = engine.block_responses(length);
    let out: Vec<serde_json::Value> = blocks
        .iter()
        .zip(responses)
        .map(|(&(lower, upper), inputs)| {
            serde_json::json!({
                "lower": lower,
                "upper": upper,
                "inputs": inputs.iter().map(|ports| ports.iter().map(|r| {
                    serde_json::json!({ "spacing": r.spacing, "taps": r.taps, "exact": r.exact })
                }).collect::<Vec<_>>()).collect::<Vec<_>>(),
            })
        })
        .collect();
    println!("{}", serde_json::to_string(&out)?);
    Ok(())
}

//! A rod with and without blocks of fast layers answered by their response:
//! `block_probe SCENE.json [on|off|both]`.
use impact_model::Scene;
use impact_wave::{WaveConfig, simulate};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let text = std::fs::read_to_string(&args[1]).expect("a scene file");
    let scene: Scene = serde_json::from_str(&text).expect("a scene");
    let rod = scene.validate().expect("a valid scene");
    let which = args.get(2).map_or("both", String::as_str);
    for blocks in [true, false] {
        if (which == "on" && !blocks) || (which == "off" && blocks) {
            continue;
        }
        let config = WaveConfig {
            fast_blocks: blocks,
            ..WaveConfig::default()
        };
        let start = std::time::Instant::now();
        let o = simulate(&rod, &config).expect("an outcome");
        println!(
            "blocks {blocks}: e {:.10} ± {:.1e}, {:.2} s, {} events{}",
            o.restitution,
            o.error_bound.unwrap_or(f64::NAN),
            start.elapsed().as_secs_f64(),
            o.events.unwrap_or(0),
            o.error_estimate
                .as_ref()
                .map_or(String::new(), |e| format!(", {}", e.method)),
        );
    }
}

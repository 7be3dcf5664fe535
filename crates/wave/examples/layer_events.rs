//! Which boundaries a merged run's events fall on (a diagnostic for slow
//! rods, or exact ones): `layer_events SCENE.json [PER_TRANSIT [PER_LONGEST [noleap]]]`.
use impact_model::Scene;
use impact_wave::{Resolution, StepKind, WaveConfig, WaveEngine};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let text = std::fs::read_to_string(&args[1]).expect("a scene file");
    let scene: Scene = serde_json::from_str(&text).expect("a scene");
    let rod = scene.validate().expect("a valid scene");
    let p = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(0.2);
    let l = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(4e-3);
    // `PER_TRANSIT` 0: the exact resolution
    let config = WaveConfig {
        resolution: if p > 0.0 {
            Resolution::Merged {
                per_transit: p,
                per_longest: l,
            }
        } else {
            Resolution::Exact
        },
        leap_quiet_layers: args.get(4).is_none_or(|s| s != "noleap"),
        // blocks of fast layers answered by their response only with
        // `BLOCKS=1` (on by default in runs): the loop's own events here
        fast_blocks: std::env::var_os("BLOCKS").is_some(),
        // a block's fastest layer nested in its trace unless `NONEST=1`
        nest_blocks: std::env::var_os("NONEST").is_none(),
        // a block's trace on one lattice unless `NOONE=1`
        one_lattice_blocks: std::env::var_os("NOONE").is_none(),
        // small large fronts of a block's response on its ports' lattices
        // unless `NOFOLD=1`
        fold_small_exact: std::env::var_os("NOFOLD").is_none(),
        // the bottom group stepped only with `GROUP=1`
        step_bottom_group: std::env::var_os("GROUP").is_some(),
        // a finer lattice than the ladder's takes more events than the
        // default limit: `MAX_EVENTS=N`
        max_events: std::env::var("MAX_EVENTS")
            .ok()
            .and_then(|s| s.parse::<f64>().ok())
            .map_or(WaveConfig::default().max_events, |n| n as u64),
        ..WaveConfig::default()
    };
    let mut engine = WaveEngine::new(&rod, config).expect("a valid rod");
    let n = rod.layers().len();
    let (mut at, mut leaps, mut leapt) = (vec![0u64; n + 2], vec![0u64; n], vec![0u64; n]);
    let mut stepped = 0u64;
    let start = std::time::Instant::now();
    loop {
        let step = engine.step().expect("a step");
        match step.kind {
            StepKind::Interface(b) => at[b] += 1,
            StepKind::Top => at[n] += 1,
            StepKind::Wall { .. } | StepKind::Reconnected => at[0] += 1,
            StepKind::Leap { layer, events } => {
                leaps[layer] += 1;
                leapt[layer] += events;
            }
            StepKind::Stepped { fronts } => stepped += fronts,
            StepKind::Stopped(_) => break,
        }
    }
    println!(
        "{:.2} s, {} steps, e {}",
        start.elapsed().as_secs_f64(),
        engine.steps(),
        engine.restitution()
    );
    let o = engine.outcome();
    println!(
        "contacts {:?}, end {:.4}, stop {:?}",
        o.contacts, o.end_time, o.stop_reason
    );
    println!("boundary events (0 wall, {n} top): {at:?}");
    println!("fronts stepped in the bottom group: {stepped}");
    println!("leaps per layer: {leaps:?}\nevents leapt per layer: {leapt:?}");
}

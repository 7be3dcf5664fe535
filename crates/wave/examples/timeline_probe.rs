//! The shape of a bilayer's run, step by step: runs of wall (`w`),
//! interface (`i`) and top (`t`) events between separations, landings and
//! leaps (a leap of layer `L` standing for `E` events: `LEAP L:E`). At the
//! hard corner it shows the chatter the event loop spends its time on: 48
//! one-round-trip contacts, each decided front by front over the base's
//! fifty-odd fronts.
//!
//! cargo run --release -p impact-wave --example timeline_probe -- [X ALPHA]
use impact_model::Bilayer;
use impact_wave::{StepKind, WaveConfig, WaveEngine};

fn main() {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|s| s.parse().ok())
        .collect();
    let (x, alpha) = (
        args.first().copied().unwrap_or(0.995),
        args.get(1).copied().unwrap_or(0.005),
    );
    let rod = Bilayer::new(x, alpha)
        .and_then(|b| b.scene().validate())
        .expect("a valid bilayer");
    let mut engine = WaveEngine::new(&rod, WaveConfig::default()).expect("a valid rod");
    let mut line: Vec<String> = Vec::new();
    let mut counts = [0u32; 3];
    let flush = |counts: &mut [u32; 3], line: &mut Vec<String>| {
        if counts.iter().any(|&c| c > 0) {
            line.push(format!("[w{} i{} t{}]", counts[0], counts[1], counts[2]));
        }
        *counts = [0; 3];
    };
    loop {
        let step = engine.step().expect("a step");
        let mark = match step.kind {
            StepKind::Wall { separated: false } => {
                counts[0] += 1;
                continue;
            }
            StepKind::Interface(_) => {
                counts[1] += 1;
                continue;
            }
            StepKind::Top => {
                counts[2] += 1;
                continue;
            }
            StepKind::Wall { separated: true } => format!("SEP@{:.4}", step.time),
            StepKind::Reconnected => format!("LAND@{:.4}", step.time),
            StepKind::Leap { layer, events } => format!("LEAP{layer}:{events}@{:.4}", step.time),
            StepKind::Stepped { fronts } => format!("STEP:{fronts}@{:.4}", step.time),
            StepKind::Stopped(reason) => format!("STOP({reason:?})@{:.4}", step.time),
        };
        flush(&mut counts, &mut line);
        line.push(mark);
        if matches!(step.kind, StepKind::Stopped(_)) {
            break;
        }
    }
    println!("{}", line.join(" "));
    println!(
        "{} loop steps, {} events, {} fronts alive at the end",
        engine.steps(),
        engine.events(),
        engine.live_fronts()
    );
}

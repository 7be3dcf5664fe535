//! Leaps against the loop. A layer whose neighbours stay quiet is advanced
//! in closed form (`leap.rs`); an exact run does so by default. The loop,
//! event by event, is the reference: both must give the same contacts and
//! the same `e` within their rounding bounds, and the fields the fronts
//! carry must keep the rod's energy after every step.

mod common;
use common::{XorShift, exact_run, random_scene};
use impact_model::{Bilayer, Outcome, Rod};
use impact_wave::{Resolution, StepKind, WaveConfig, WaveEngine, WaveError};

/// The loop's events an exact reference may take (a few tenths of a second).
const EXACT_EVENTS: u64 = 3_000_000;

/// An exact double-precision run, leaping or event by event: its outcome
/// (with the bound the engine states) and how many events leaps took;
/// `None` past [`EXACT_EVENTS`] loop steps.
fn exact(rod: &Rod, leap: bool) -> Option<(Outcome, u64)> {
    let outcome = exact_run(rod, EXACT_EVENTS, leap)?;
    let config = WaveConfig {
        resolution: Resolution::Exact,
        leap_quiet_layers: leap,
        ..WaveConfig::default()
    };
    let mut engine = WaveEngine::new(rod, config).expect("a valid rod");
    engine.run().expect("it finished once");
    Some((outcome, engine.leaped_events()))
}

fn random_rod(rng: &mut XorShift) -> Rod {
    random_scene(rng, 6, 100.0)
        .validate()
        .expect("a valid random rod")
}

/// The paper's stiff-bottom corner, its fast tops, and random rods of two to
/// six layers with unequal densities: leaping changes rounding, nothing
/// else.
#[test]
fn exact_leaps_agree_with_the_event_loop_to_rounding() {
    let mut rods: Vec<(String, Rod)> = Vec::new();
    for x in [0.5, 0.8, 0.9, 0.95, 0.99, 0.995] {
        for alpha in [0.005, 0.01, 0.05, 0.2] {
            let rod = Bilayer::new(x, alpha).unwrap().scene().validate().unwrap();
            rods.push((format!("bilayer ({x}, {alpha})"), rod));
        }
    }
    for x in [0.005, 0.02, 0.05] {
        for alpha in [0.3, 0.5, 0.9] {
            let rod = Bilayer::new(x, alpha).unwrap().scene().validate().unwrap();
            rods.push((format!("fast top ({x}, {alpha})"), rod));
        }
    }
    let mut rng = XorShift(0x5eed_1ea9_0000_0001);
    while rods.len() < 90 {
        let rod = random_rod(&mut rng);
        rods.push((format!("random rod {}", rods.len()), rod));
    }
    let (mut leapt, mut compared) = (0, 0);
    let mut worst: f64 = 0.0;
    for (label, rod) in &rods {
        let Some((loop_run, _)) = exact(rod, false) else {
            eprintln!("{label}: the loop needs over {EXACT_EVENTS} events");
            continue;
        };
        let (leaping, leaped) = exact(rod, true).expect("a leaping run takes fewer steps");
        compared += 1;
        leapt += usize::from(leaped > 0);
        let d = (leaping.restitution - loop_run.restitution).abs();
        let bound = leaping.error_bound.unwrap() + loop_run.error_bound.unwrap();
        worst = worst.max(d / bound);
        eprintln!(
            "{label}: {leaped} events leapt, |de| = {d:.1e}, {:.3} of the bounds",
            d / bound
        );
        assert!(
            d <= bound,
            "{label}: e {} vs {} (bounds {bound:.1e})",
            leaping.restitution,
            loop_run.restitution
        );
        assert_eq!(leaping.separations, loop_run.separations, "{label}");
        assert_eq!(leaping.bounces, loop_run.bounces, "{label}");
        let (a, b) = (leaping.contact_time, loop_run.contact_time);
        assert!((a - b).abs() <= 1e-9 * b, "{label}: t_c {a} vs {b}");
    }
    eprintln!("{compared} rods compared, {leapt} leapt, worst |de| {worst:.3} of the bounds");
    assert!(
        leapt >= 30,
        "only {leapt} rods leapt: the comparison proves little"
    );
}

/// After every step, leaps included, the fronts' fields hold the rod's
/// energy (elastic: all of it). A leap that ran past an arrival from
/// outside its layer (a neighbour's front reflected at its far end, as on
/// the three-layer rod of `tests/conservation.rs`) breaks this at once.
#[test]
fn every_leap_keeps_the_energy_in_the_fields() {
    let mut rods = vec![
        Bilayer::new(0.995, 0.005)
            .unwrap()
            .scene()
            .validate()
            .unwrap(),
    ];
    let mut rng = XorShift(0x0dd_ba11_0000_0003);
    while rods.len() < 40 {
        rods.push(random_rod(&mut rng));
    }
    let mut leaps = 0;
    for (k, rod) in rods.iter().enumerate() {
        // the first steps of each (the fields cost a pass over the fronts)
        let config = WaveConfig {
            resolution: Resolution::Exact,
            max_events: 5_000,
            ..WaveConfig::default()
        };
        let mut engine = WaveEngine::new(rod, config).unwrap();
        let e0 = rod.initial_energy();
        while engine.stopped().is_none() {
            match engine.step() {
                Ok(step) => leaps += u64::from(matches!(step.kind, StepKind::Leap { .. })),
                Err(WaveError::EventLimit { .. }) => break,
                Err(e) => panic!("rod {k}: {e}"),
            }
            let energy = engine.field_totals().energy;
            assert!(
                (energy - e0).abs() <= 1e-11 * e0,
                "rod {k} at t = {}: energy {energy} of {e0}",
                engine.time()
            );
        }
    }
    eprintln!("{} rods, {leaps} leaps", rods.len());
    assert!(leaps >= 15, "only {leaps} leaps: the test proves little");
}

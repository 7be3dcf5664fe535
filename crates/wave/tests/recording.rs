//! Records exist only when asked, and agree with the engine's own state.

mod common;
use common::*;
use impact_wave::{ContactState, Record, WaveConfig, WaveEngine};

#[test]
fn a_plain_run_records_nothing() {
    let eng = engine(&rod(0.4, 0.05), WaveConfig::default());
    assert!(eng.recording().wall.is_empty());
    assert!(eng.recording().fronts.is_empty());
}

#[test]
fn recorded_fronts_have_ancestry_back_to_the_impact_or_a_landing() {
    let config = WaveConfig {
        record: Record {
            wall: true,
            fronts: true,
        },
        ..WaveConfig::default()
    };
    let eng = engine(&rod(0.4, 0.05), config);
    let rec = eng.recording();
    let o = eng.outcome();
    assert!(!rec.fronts.is_empty());
    let landings: Vec<f64> = o.contacts.iter().skip(1).map(|c| c[0]).collect();
    for f in &rec.fronts {
        assert_eq!(
            f.id as usize,
            rec.fronts.iter().position(|g| g.id == f.id).unwrap()
        );
        if f.parents.is_empty() {
            // the impact front, or a front launched by a landing
            assert!(
                f.born == 0.0 || landings.iter().any(|&t| (t - f.born).abs() < 1e-12),
                "{f:?}"
            );
        }
        for &p in &f.parents {
            let parent = &rec.fronts[p as usize];
            assert!(
                (parent.arrives - f.born).abs() < 1e-9,
                "parent arrives when child is born"
            );
        }
    }
    // the wall history starts with the impact strain and ends free
    assert!((rec.wall[0].strain + 1.0 / 0.95f64.sqrt()).abs() < 1e-15);
    assert_eq!(rec.wall.last().unwrap().strain, 0.0);
}

#[test]
fn the_field_at_the_wall_is_the_wall_strain_at_every_event() {
    for &(x, alpha) in &[(0.4, 0.05), (0.6, 0.8), (0.3, 0.3)] {
        let rod = rod(x, alpha);
        let mut eng = WaveEngine::new(&rod, WaveConfig::default()).unwrap();
        while eng.stopped().is_none() {
            eng.step().unwrap();
            let at_wall = eng.field_at(0.0);
            match eng.contact_state() {
                ContactState::InContact { strain } => {
                    assert!(
                        (at_wall.strain - strain).abs() < 1e-12,
                        "t = {}",
                        eng.time()
                    );
                    assert!(at_wall.velocity.abs() < 1e-12, "bottom at rest in contact");
                }
                ContactState::Free { velocity, .. } => {
                    assert!(
                        at_wall.strain.abs() < 1e-12,
                        "free bottom is unstrained: {x} {alpha} t = {} {at_wall:?} {:?}",
                        eng.time(),
                        eng.contact_state()
                    );
                    assert!((at_wall.velocity - velocity).abs() < 1e-12);
                }
            }
        }
    }
}

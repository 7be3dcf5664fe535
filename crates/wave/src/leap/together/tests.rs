//! Trains deposited together against one by one (`emit`).

use super::*;
use crate::config::{Resolution, WaveConfig};
use crate::engine::WaveEngine;
use crate::lane::Lane;
use crate::leap::crossing::count_before;
use impact_model::{Layer, Scene};
use std::collections::BTreeMap;

/// A merged engine for its lanes and ledgers: a soft layer on a stiff
/// one, lattices of a tenth of a transit.
fn engine() -> WaveEngine {
    let scene = Scene {
        impact_speed: 1.0,
        layers: vec![Layer::elastic(1.0, 1.0, 1.0), Layer::elastic(0.5, 1e4, 2.0)],
        wall_contact: None,
    };
    let config = WaveConfig {
        resolution: Resolution::Merged {
            per_transit: 0.1,
            per_longest: 0.1,
        },
        ..WaveConfig::default()
    };
    WaveEngine::new(&scene.validate().unwrap(), config).unwrap()
}

/// The deposits gathered, summed at each lattice point.
fn at_points(e: &WaveEngine) -> BTreeMap<u64, f64> {
    let mut points = BTreeMap::new();
    for &(_, at, d) in &e.deposits {
        *points.entry(at.to_bits()).or_insert(0.0) += d;
    }
    points
}

/// Deposits `trains` into `lane` of `base` one by one (`emit`) and
/// together (`emit_ringing`): the same on every lattice point, the same
/// base (to rounding, and the base's own ulps) and merge count; whether
/// together made fewer deposits. `split`: trains with large fronts.
fn same_deposits(
    base: &WaveEngine,
    lane: usize,
    trains: &[Train<f64>],
    q: f64,
    split: u64,
) -> bool {
    let mut one = base.clone();
    for &t in trains {
        one.emit(lane, t).unwrap();
    }
    let mut together = base.clone();
    together
        .emit_ringing(lane, trains, &mut Work::default())
        .unwrap();
    // (where the trains die under the drop threshold within the
    // window they all go one by one)
    assert!(together.deposits.len() <= one.deposits.len());
    let (a, b) = (at_points(&one), at_points(&together));
    let scale: f64 = trains.iter().map(|t| t.c.abs()).sum::<f64>() / (1.0 - q.abs());
    for (at, d) in &a {
        let e = b.get(at).copied().unwrap_or(0.0);
        assert!(
            (d - e).abs() <= 1e-12 * scale,
            "q {q}: at {}: {d:e} one by one, {e:e} together",
            f64::from_bits(*at)
        );
    }
    for at in b.keys() {
        assert!(
            a.contains_key(at),
            "q {q}: a deposit at {}",
            f64::from_bits(*at)
        );
    }
    let (x, y) = (one.down_base[0], together.down_base[0]);
    assert!(
        (x - y).abs() <= 1e-12 * scale + 4.0 * f64::EPSILON * x.abs(),
        "q {q}: base {x:e} {y:e}"
    );
    // (a train split at its large fronts counts its life under the drop
    // threshold from the rest: the last front may fall either side)
    let (x, y) = (
        one.drops.truncation.merged_fronts,
        together.drops.truncation.merged_fronts,
    );
    assert!(x.abs_diff(y) <= split, "q {q}: merged {x} {y}");
    together.deposits.len() < one.deposits.len()
}

/// Trains taken together deposit on every lattice point what they
/// deposit one by one (`emit`), to rounding, with the same base and
/// merge count: periods shorter and longer than a cell, ratios near 1,
/// negative and small, trains that start rounds later (a leap's
/// arrivals) and trains cut off by the horizon a period apart.
#[test]
fn together_deposits_what_one_by_one_does() {
    let lane = Lane::<f64>::index(0, Direction::Down);
    let base = engine();
    let MergeRule::Lattice { spacing: w, .. } = base.lanes[lane].rule else {
        panic!("a lattice lane")
    };
    let mut draw = crate::test_random::xorshift(0x1234_5678_9abc_def1u64);
    let mut uniform = || (draw() >> 11) as f64 / (1u64 << 53) as f64;
    let (mut cases, mut fewer) = (0, 0);
    for (q, period_in_cells) in [
        (0.999, 1.0 / 7.3),
        (0.97, 1.0 / 2.2),
        (-0.9, 1.0 / 5.1),
        (0.5, 1.0 / 3.3),
        (0.98, 2.7),
        (-0.995, 1.6),
    ] {
        let period = w * period_in_cells;
        let t0 = 3.0 + 10.0 * w * uniform();
        let horizon = t0 + 40.0 * w * (1.0 + uniform());
        let trains: Vec<Train<f64>> = (0..24)
            .map(|k| {
                // a third start rounds later
                let late = if k % 3 == 0 {
                    10.0 * period * uniform()
                } else {
                    0.0
                };
                let start = t0 + period * uniform() + late;
                Train {
                    start,
                    period,
                    c: (uniform() - 0.5) * 1e-4,
                    q,
                    count: count_before(start, period, horizon),
                }
            })
            .collect();
        fewer += usize::from(same_deposits(&base, lane, &trains, q, 0));
        cases += 1;
    }
    assert_eq!(cases, 6);
    assert!(fewer >= 4, "only {fewer} cases went together");
}

/// What a fast bottom's leap that takes arrivals sends its neighbour
/// (`leap/arrivals.rs`): trains that start hundreds of periods apart
/// (taken in groups), end where their phases die (any count), and
/// start with fronts large enough to be kept where they are born (sent
/// one by one, the rest taken together). One by one and together
/// deposit the same, and together deposits less.
#[test]
fn trains_apart_ending_anywhere_and_large_at_first_deposit_the_same() {
    let lane = Lane::<f64>::index(0, Direction::Down);
    let mut base = engine();
    let MergeRule::Lattice {
        spacing: w,
        keep_above,
        ..
    } = base.lanes[lane].rule
    else {
        panic!("a lattice lane")
    };
    // every large front kept where it is born: the lane keeps 32 at
    // most, and which ones then depends on the order trains come in
    base.lanes[lane].rule = MergeRule::Lattice {
        spacing: w,
        keep_above,
        keep_at_most: usize::MAX,
    };
    let mut draw = crate::test_random::xorshift(0x0dd_ba11_5eed_0042u64);
    let mut uniform = || (draw() >> 11) as f64 / (1u64 << 53) as f64;
    let mut fewer = 0;
    for (q, period_in_cells) in [(0.97, 0.9), (-0.99, 1.0 / 3.1), (0.8, 2.3)] {
        let period = w * period_in_cells;
        let t0 = 3.0 + 10.0 * w * uniform();
        let rounds = 600.0;
        let horizon = t0 + rounds * period;
        let trains: Vec<Train<f64>> = (0..60)
            .map(|k| {
                let start = t0 + rounds * period * uniform() * 0.9;
                let left = count_before(start, period, horizon);
                // a third end early, a fifth start above `keep_above`
                let count = if k % 3 == 0 {
                    1 + (left as f64 * uniform()) as u64
                } else {
                    left
                };
                let size = if k % 5 == 0 { 30.0 } else { 0.5 };
                Train {
                    start,
                    period,
                    c: (uniform() - 0.5) * size * keep_above,
                    q,
                    count,
                }
            })
            .collect();
        let split = trains.iter().filter(|t| t.c.abs() >= keep_above).count();
        fewer += usize::from(same_deposits(&base, lane, &trains, q, split as u64));
    }
    assert_eq!(fewer, 3, "only {fewer} of 3 cases went together");
}

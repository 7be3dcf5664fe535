//! What a leap's trains would do to an exact lane, foreseen without
//! spawning their fronts: which merge, which would be dropped, where the
//! last is born.
//!
//! Spawned one by one (`Lane::push_exact`), a front born within the
//! simultaneity window of the lane's newest is added into it. The trains
//! of a leap ring with one period, their starts within it, so round `k`'s
//! births are `s_j + k P`, and two neighbouring trains' births stay
//! `s_{j+1} - s_j` apart up to rounding (a few ulps of the birth), while
//! the window grows with the birth. Neighbours whose gap clears the widest
//! window by more than that rounding never merge; nor do fronts further
//! apart. Only runs of neighbours closer than that ("clusters": a tie of
//! the ringing layer split by rounding) are followed round by round, with
//! the very arithmetic of `Trains::give`. A train whose fronts would fall
//! under the drop threshold, or a first front merging into the lane's
//! newest, or the last train of a round close to the first of the next,
//! are not foreseen: the leap then spawns the fronts.

use super::Ring;
use crate::real::Real;
use crate::window::Window;
use std::cmp::Ordering;

/// What the trains of one leap give, as the lane would hold them.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Given<R> {
    /// Fronts given, and fronts the lane holds of them.
    pub given: u64,
    pub held: u64,
    pub last_born: R,
    /// The births of the given fronts that merge into the one before, in
    /// order.
    pub merging: Vec<R>,
    /// `(gap, birth)` of each of those merges whose births are apart (the
    /// lane's `push_exact` reports them, and the tracer counts those
    /// wider than rounding as uses of its tolerance).
    pub gaps: Vec<(R, R)>,
}

/// Foresees `rings` (sorted by start, one period, their starts within it;
/// `jump` their first jumps) spawned into an exact lane of simultaneity
/// `window` and drop threshold `thr` whose newest front was born at
/// `newest`. `None` when a front would be dropped or merge into the lane's
/// newest, or the rounds could run into each other.
pub(crate) fn foresee<R: Real>(
    rings: &[Ring<R>],
    window: Window<R>,
    thr: R,
    newest: Option<R>,
) -> Option<Given<R>> {
    let rings: Vec<&Ring<R>> = rings.iter().filter(|r| r.count > 0).collect();
    let (first, last) = (rings.first()?, rings.last()?);
    let period = first.period;
    let born = |r: &Ring<R>, k: u64| r.start + R::of(k as f64) * r.period;
    let eps = R::of(f64::EPSILON);
    for r in &rings {
        // the smallest jump is the first or the last (|q^k| is monotone);
        // a product a round drifts by an ulp a round from `q^k`
        let tail = if r.count == 1 {
            r.jump.abs()
        } else if r.q == R::zero() {
            return None;
        } else {
            r.jump.abs() * r.q.abs().powf(R::of((r.count - 1) as f64))
        };
        let margin = R::one() + R::of(16.0) * R::of(r.count as f64) * eps;
        if r.jump == R::zero() || r.jump.abs().min(tail) < thr * margin {
            return None;
        }
    }
    let rounds = rings.iter().map(|r| r.count).max()?;
    let last_born = rings
        .iter()
        .rev()
        .find(|r| r.count == rounds)
        .map(|r| born(r, rounds - 1))?;
    let first_born = born(first, 0);
    if newest.is_some_and(|n| first_born - n <= window.at(first_born)) {
        return None;
    }
    // how far rounding can move a gap between births, and the widest window
    let big = first_born.abs().max(last_born.abs());
    let slack = R::of(8.0) * eps * (big + period);
    let widest = window.at(big);
    let apart = |gap: R| gap - slack > widest;
    if !apart(first.start + period - last.start) {
        return None;
    }
    let mut given = Given {
        given: rings.iter().map(|r| r.count).sum(),
        held: 0,
        last_born,
        merging: Vec::new(),
        gaps: Vec::new(),
    };
    // the ring giving the last front
    let final_ring = rings.iter().rposition(|r| r.count == rounds)?;
    let mut j = 0;
    while j < rings.len() {
        // a cluster: rings j..end, each close to the one before
        let mut end = j + 1;
        while end < rings.len() && !apart(rings[end].start - rings[end - 1].start) {
            end += 1;
        }
        if end - j > 1 {
            let newest = follow(&rings[j..end], window, &mut given);
            if (j..end).contains(&final_ring) {
                // the last front may have merged into one before it
                given.last_born = newest?;
            }
        }
        j = end;
    }
    given
        .merging
        .sort_by(|a, b| a.partial_cmp(b).unwrap_or(Ordering::Equal));
    given.held = given.given - given.merging.len() as u64;
    Some(given)
}

/// A cluster of close trains round by round, as the lane takes them: a
/// front born within the window of the newest held one merges into it.
/// The birth of the newest held front after the cluster's last round.
fn follow<R: Real>(cluster: &[&Ring<R>], window: Window<R>, given: &mut Given<R>) -> Option<R> {
    let rounds = cluster.iter().map(|r| r.count).max().unwrap_or(0);
    let mut newest: Option<R> = None;
    for k in 0..rounds {
        let kk = R::of(k as f64);
        newest = None;
        for r in cluster.iter().filter(|r| k < r.count) {
            let born = r.start + kk * r.period;
            match newest {
                Some(n) if born - n <= window.at(born) => {
                    if born - n > R::zero() {
                        given.gaps.push((born - n, born));
                    }
                    given.merging.push(born);
                }
                _ => newest = Some(born),
            }
        }
    }
    newest
}

#[cfg(test)]
mod tests {
    use super::super::{Front, Lane, MergeRule, Pushed, Trains};
    use super::*;
    use crate::lane::Direction;
    use proptest::prelude::*;

    /// A lane holding one front born at `newest`.
    fn lane(newest: Option<f64>) -> Lane<f64> {
        let mut lane = Lane::new(
            1,
            Direction::Up,
            3.0,
            MergeRule::Simultaneous { window: window() },
        );
        if let Some(born) = newest {
            lane.push(born, 0.5, 99);
        }
        lane
    }

    /// The oracle: the trains spawned one by one into a lane whose newest
    /// front was born at `newest`, as the leap did before trains could
    /// wait (`leap::trains::rounds`, `Spawning::put`): the lane, whether a
    /// front was dropped or merged into the newest, the merges' gaps.
    fn spawned(rings: &[Ring<f64>], thr: f64, newest: Option<f64>) -> (Lane<f64>, bool, Vec<f64>) {
        let window = window();
        let mut lane = lane(newest);
        let mut dropped = false;
        let mut gaps = Vec::new();
        let mut id = 0;
        let rounds = rings.iter().map(|r| r.count).max().unwrap_or(0);
        let mut jumps: Vec<f64> = rings.iter().map(|r| r.jump).collect();
        for k in 0..rounds {
            for (r, jump) in rings.iter().zip(jumps.iter_mut()) {
                if k < r.count {
                    let born = r.start + k as f64 * r.period;
                    if jump.abs() < thr {
                        dropped = true;
                    } else if let Some((gap, _)) = lane.push_exact(born, *jump, id, window) {
                        dropped |= newest.is_some_and(|n| born - n <= window.at(born));
                        if gap > 0.0 {
                            gaps.push(gap);
                        }
                    } else {
                        id += 1;
                    }
                    *jump *= r.q;
                }
            }
        }
        (lane, dropped, gaps)
    }

    fn window() -> Window<f64> {
        Window {
            fixed: 0.0,
            ulps: 64.0 * f64::EPSILON,
            scale: 0.005,
        }
    }

    /// Rings within one period, some a rounding apart (split ties).
    fn rings() -> impl Strategy<Value = Vec<Ring<f64>>> {
        let ring = (0.0..1.0f64, 0..4u8, 1..60u64, -1.0..1.0f64, 0.8..0.999f64);
        (0.0..50.0f64, proptest::collection::vec(ring, 1..12)).prop_map(|(t0, parts)| {
            let period = 0.01;
            let mut rings: Vec<Ring<f64>> = Vec::new();
            for (at, tie, count, jump, q) in parts {
                // a tie: 0 to 3 ulps-to-window widths after the one before
                let start = match (tie, rings.last()) {
                    (1..=3, Some(r)) => r.start + f64::from(tie) * 1e-14 * (1.0 + t0),
                    _ => t0 + at * 0.9 * period,
                };
                rings.push(Ring {
                    start,
                    period,
                    q: if jump < 0.0 { -q } else { q },
                    count,
                    jump: jump + 2.0f64.copysign(jump),
                });
            }
            rings.sort_by(|a, b| a.start.total_cmp(&b.start));
            rings
        })
    }

    proptest! {
        #[test]
        fn foreseen_trains_are_the_spawned_fronts(
            rings in rings(),
            thr in prop_oneof![Just(1e-12), Just(1e-2)],
            before in prop_oneof![Just(None), Just(Some(0.0)), Just(Some(1e-15)), Just(Some(0.002))],
        ) {
            let newest = before.map(|gap| rings[0].start - gap);
            let (eager, refused, mut gaps) = spawned(&rings, thr, newest);
            match foresee(&rings, window(), thr, newest) {
                // (the starts lie within 0.9 of the period: only a drop,
                // or a merge into the lane's newest)
                None => prop_assert!(refused, "not foreseen, yet nothing dropped"),
                Some(given) => {
                    prop_assert!(!refused);
                    let mut foreseen: Vec<f64> = given.gaps.iter().map(|g| g.0).collect();
                    foreseen.sort_by(f64::total_cmp);
                    gaps.sort_by(f64::total_cmp);
                    prop_assert_eq!(foreseen, gaps);
                    let trains = Trains::new(rings.clone(), window(), given.clone(), 0);
                    let lazy: Vec<(f64, f64)> = trains.map(|f| (f.born, f.jump)).collect();
                    let eager: Vec<(f64, f64)> = eager.fronts().map(|f| (f.born, f.jump)).skip(usize::from(newest.is_some())).collect();
                    prop_assert_eq!(lazy.len() as u64, given.held);
                    prop_assert_eq!(lazy, eager.clone());
                    prop_assert_eq!(Some(given.last_born), eager.last().map(|f| f.0));
                    // the lane counts the fronts born by a time as the
                    // spawned lane does
                    let mut lazy = lane(newest);
                    lazy.add_trains(Trains::new(rings.clone(), window(), given, 0));
                    let held = u64::from(newest.is_some());
                    for &(at, _) in eager.iter().step_by(7) {
                        let by = |b: f64| b <= at;
                        prop_assert_eq!(lazy.count_born_by(by), held + eager.iter().take_while(|f| by(f.0)).count() as u64);
                    }
                    // and gives them, the front before them first
                    let all: Vec<(f64, f64)> = lazy.fronts().map(|f| (f.born, f.jump)).collect();
                    prop_assert_eq!(&all[usize::from(newest.is_some())..], &eager[..]);
                    prop_assert_eq!(lazy.len(), all.len());
                }
            }
        }
    }

    proptest! {
        /// A lane with waiting trains is the lane with their fronts
        /// spawned: heads, pops, and fronts pushed behind them (merged
        /// into their last when born with it).
        #[test]
        fn a_lane_with_waiting_trains_is_the_spawned_lane(
            rings in rings(),
            pops in 0usize..6,
            after in prop_oneof![Just(0.0), Just(1e-15), Just(0.004)],
        ) {
            let newest = Some(rings[0].start - 0.002);
            let Some(given) = foresee(&rings, window(), 1e-12, newest) else {
                return Ok(());
            };
            let (mut eager, _, _) = spawned(&rings, 1e-12, newest);
            let mut lazy = lane(newest);
            let (last, held) = (given.last_born, given.held);
            lazy.add_trains(Trains::new(rings.clone(), window(), given, 0));
            let front = |f: Option<Front<f64>>| f.map(|f| (f.born, f.jump));
            for _ in 0..pops {
                prop_assert_eq!(lazy.head_arrival(), eager.head_arrival());
                prop_assert_eq!(front(lazy.pop()), front(eager.pop()));
            }
            for (k, born) in [last + after, last + after + 0.5].into_iter().enumerate() {
                let a = lazy.push(born, 0.25, 0);
                let b = eager.push(born, 0.25, 0);
                // (merged into the trains' last unless it was taken)
                let waiting = (pops as u64) <= held;
                prop_assert_eq!(k == 0 && after < 1e-3 && waiting, matches!(a, Pushed::Merged { .. }));
                prop_assert_eq!(a, b);
            }
            prop_assert_eq!(lazy.len(), eager.len());
            while let Some(f) = eager.pop() {
                prop_assert_eq!(lazy.head_arrival(), Some(eager.arrival_of(f.born)));
                prop_assert_eq!(front(lazy.pop()), Some((f.born, f.jump)));
            }
            prop_assert!(lazy.is_empty() && lazy.head_arrival().is_none());
        }
    }
}

//! A merged leap's ringing trains into one lattice lane, deposited
//! together.
//!
//! Each train a leap sends into a neighbour fills every lattice cell it
//! crosses: `m` phases over `C` cells cost `m C`. On the layer survey's rod
//! 22 at a twentieth of a transit, a fast layer's sixty phases each filled
//! twenty cells of the layer below at every leap, and depositing them was
//! half the run (`emit`, and sorting what it gathered another eighth).
//!
//! The trains of one leap into one lane share the period `P` and the ratio
//! `q`. Write each start as `B + K_p P + r_p` (`B` the earliest start,
//! `0 <= r_p < P`) and its jumps as `c_p q^j = c~_p q^(K_p + j)` with
//! `c~_p = c_p q^-K_p`. A birth `B + r_p + i P` comes before the time
//! `x = B + K P + phi` exactly when `i < K + [r_p < phi]`. So the jump
//! born before `x`, summed over the trains that started, is
//! `G0(K + 1) S_< + G0(K) S_>= - sum c~_p G0(K_p)`, with
//! `G0(n) = sum_{i<n} q^i` (`geometric::sums`) and `S_<`, `S_>=` the sums
//! of `c~_p` over the trains with `r_p` below and above `phi`: prefix sums
//! over the trains sorted by `r_p` (a Fenwick tree, as trains start one
//! after another). The first moment is the same with `c~_p r_p` and
//! `G1(n) = sum i q^i`. Each lattice cell's jump and moment are
//! differences of these at its two ends: `C log m` for the lane instead of
//! `m C`, the same deposits to rounding (tested against `emit`, `tests`
//! below).
//!
//! Taken together: trains with the lane's `P` and `q`, no front large
//! enough to be kept where it was born, none under the drop threshold, and
//! `|q|^K_p >= 1e-3` (`c~_p` stays within three digits of `c_p`). The rest
//! go through `emit` one by one. The formula runs up to the last lattice
//! point before the earliest last birth; the births after it (a cell or
//! two a train) are deposited train by train as `emit` does, each counted
//! exactly once because the count the formula used is where they start.

use super::Train;
use super::scratch::{TogetherRoom, Work};
use crate::engine::Tracer;
use crate::error::WaveError;
use crate::geometric::sums;
use crate::lane::{Direction, MergeRule};
use crate::leap::crossing::{count_before_near, pow};
use crate::real::Real;

/// Fewer trains than this go one by one (sorting and the tree cost more).
const TOGETHER_FROM: usize = 4;

/// A train taken together.
#[derive(Debug, Clone, Copy)]
pub(super) struct Member<R> {
    start: R,
    c: R,
    count: u64,
    /// Whole periods from the earliest start, the rest of the way, and
    /// the jump referred to round 0 (`c q^-k0`).
    k0: u64,
    r: R,
    scaled: R,
}

/// `G0(n) = sum_{i<n} q^i` and `G1(n) = sum_{i<n} i q^i`, and `q^n`, kept
/// for an `n` that only grows.
#[derive(Debug, Clone, Copy)]
struct Geometric<R> {
    q: R,
    n: u64,
    g0: R,
    g1: R,
    qn: R,
}

impl<R: Real> Geometric<R> {
    fn new(q: R) -> Self {
        Self {
            q,
            n: 0,
            g0: R::zero(),
            g1: R::zero(),
            qn: R::one(),
        }
    }

    /// Moves to `n` (term by term for a few, else in closed form).
    fn at(&mut self, n: u64) -> Sums<R> {
        if n < self.n || n - self.n > 16 {
            let (g0, g1, _) = sums(self.q, n);
            *self = Self {
                q: self.q,
                n,
                g0,
                g1,
                qn: pow(self.q, n),
            };
        }
        while self.n < n {
            self.g0 += self.qn;
            self.g1 += R::of(self.n as f64) * self.qn;
            self.qn = self.qn * self.q;
            self.n += 1;
        }
        (self.g0, self.g1, self.qn)
    }
}

/// `(G0(n), G1(n), q^n)`.
type Sums<R> = (R, R, R);

/// [`Sums`] for the last two `n` asked (a train's full cells hold one of
/// two counts).
#[derive(Debug, Default)]
struct Remembered<R> {
    last: [Option<(u64, Sums<R>)>; 2],
}

impl<R: Real> Remembered<R> {
    fn get(&mut self, q: R, n: u64) -> Sums<R> {
        for (m, s) in self.last.iter().flatten() {
            if *m == n {
                return *s;
            }
        }
        let (g0, g1, _) = sums(q, n);
        let s = (g0, g1, pow(q, n));
        self.last = [Some((n, s)), self.last[0]];
        s
    }
}

/// Prefix sums of `(c~, c~ r)` over trains ranked by `r`, as they start
/// (in a vector kept from one leap to the next).
struct Fenwick<'a, R> {
    tree: &'a mut Vec<(R, R)>,
}

impl<'a, R: Real> Fenwick<'a, R> {
    fn new(m: usize, tree: &'a mut Vec<(R, R)>) -> Self {
        tree.clear();
        tree.resize(m + 1, (R::zero(), R::zero()));
        Self { tree }
    }

    fn add(&mut self, rank: usize, v: (R, R)) {
        let mut k = rank + 1;
        while k < self.tree.len() {
            self.tree[k].0 += v.0;
            self.tree[k].1 += v.1;
            k += k & k.wrapping_neg();
        }
    }

    /// The sums over ranks `< n`.
    fn below(&self, mut n: usize) -> (R, R) {
        let mut s = (R::zero(), R::zero());
        while n > 0 {
            s.0 += self.tree[n].0;
            s.1 += self.tree[n].1;
            n -= n & n.wrapping_neg();
        }
        s
    }
}

impl<R: Real> Tracer<R> {
    /// A ringing train into `lane`: held for depositing together if the
    /// lane is a lattice, else emitted now.
    #[inline(always)]
    pub(super) fn emit_or_hold(
        &mut self,
        lane: usize,
        train: Train<R>,
        held: &mut Vec<(usize, Train<R>)>,
    ) -> Result<(), WaveError> {
        if matches!(self.lanes[lane].rule, MergeRule::Lattice { .. }) {
            held.push((lane, train));
            Ok(())
        } else {
            self.emit(lane, train)
        }
    }

    /// The held trains, lane by lane (a leap feeds two lanes at most).
    /// Lanes in increasing order, each lane's trains in the order they
    /// were held (what a stable sort by lane gives, without the sort).
    pub(super) fn emit_held(&mut self, held: &mut Vec<(usize, Train<R>)>) -> Result<(), WaveError> {
        let mut room = std::mem::take(&mut self.together);
        room.lanes.clear();
        for &(lane, _) in held.iter() {
            if !room.lanes.contains(&lane) {
                room.lanes.push(lane);
            }
        }
        room.lanes.sort_unstable();
        let TogetherRoom { lanes, group, work } = &mut room;
        for &lane in lanes.iter() {
            group.clear();
            group.extend(held.iter().filter(|h| h.0 == lane).map(|h| h.1));
            self.emit_ringing(lane, group, work)?;
        }
        held.clear();
        self.together = room;
        Ok(())
    }

    /// Deposits a leap's ringing trains into lattice lane `lane`, those
    /// that can be together (module doc), the rest one by one (`emit`).
    pub(super) fn emit_ringing(
        &mut self,
        lane: usize,
        trains: &[Train<R>],
        work: &mut Work<R>,
    ) -> Result<(), WaveError> {
        let MergeRule::Lattice {
            spacing: w,
            keep_above,
            ..
        } = self.lanes[lane].rule
        else {
            unreachable!("only lattice lanes take trains together")
        };
        let Some(first) = trains.first() else {
            return Ok(());
        };
        let (q, period) = (first.q, first.period);
        let layer = self.lanes[lane].layer;
        let thr = self.layers[layer].drop_strain();
        let same =
            |t: &Train<R>| t.q == q && t.period == period && t.count >= 2 && t.c != R::zero();
        work.same.clear();
        if q != R::zero() {
            work.same.extend(trains.iter().copied().filter(same));
        }
        if work.same.len() < TOGETHER_FROM {
            for &t in trains {
                self.emit(lane, t)?;
            }
            return Ok(());
        }
        for &t in trains.iter().filter(|t| !same(t)) {
            self.emit(lane, t)?;
        }
        let Work { same, members, .. } = work;
        let trains = &same[..];
        let first = &trains[0];
        let b = trains
            .iter()
            .map(|t| t.start)
            .fold(first.start, |m, s| if s < m { s } else { m });
        let last = |t: &Train<R>| t.start + R::of((t.count - 1) as f64) * period;
        let latest = trains
            .iter()
            .map(last)
            .fold(last(first), |m, s| if s > m { s } else { m });
        members.clear();
        for &t in trains {
            let d = t.start - b;
            let k0 = (d / period).floor().to_f64().max(0.0) as u64;
            let qk = pow(q, k0);
            let together = t.c.abs() < keep_above
                && qk.abs() >= R::of(1e-3)
                && last(&t) + period >= latest
                && self.life_within(t.c, q, thr, 0, t.count) >= t.count;
            if !together {
                self.emit(lane, t)?;
                continue;
            }
            members.push(Member {
                start: t.start,
                c: t.c,
                count: t.count,
                k0,
                r: d - R::of(k0 as f64) * period,
                scaled: t.c / qk,
            });
        }
        self.deposit_together(lane, work, b, period, q, w)
    }

    /// The deposits of `work.members` (trains of period `period` and ratio
    /// `q` starting from `b`) on the lattice of spacing `w` of `lane`.
    fn deposit_together(
        &mut self,
        lane: usize,
        work: &mut Work<R>,
        b: R,
        period: R,
        q: R,
        w: R,
    ) -> Result<(), WaveError> {
        let Work {
            members,
            by_r,
            rank,
            sorted_r,
            tree,
            ..
        } = work;
        if members.is_empty() {
            return Ok(());
        }
        let m = members.len();
        members.sort_by(|x, y| {
            x.start
                .partial_cmp(&y.start)
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        // ranks by r
        by_r.clear();
        by_r.extend(members.iter().enumerate().map(|(k, p)| (p.r, k)));
        by_r.sort_by(|x, y| x.0.partial_cmp(&y.0).unwrap_or(std::cmp::Ordering::Equal));
        rank.clear();
        rank.resize(m, 0);
        for (at, &(_, k)) in by_r.iter().enumerate() {
            rank[k] = at;
        }
        sorted_r.clear();
        sorted_r.extend(by_r.iter().map(|x| x.0));
        // the formula's lattice points: after the earliest start, up to the
        // earliest last birth
        let earliest_last = members
            .iter()
            .map(|p| p.start + R::of((p.count - 1) as f64) * period)
            .fold(-R::neg_infinity(), |a, s| if s < a { s } else { a });
        let j_lo = (b / w).floor();
        let j_cut = (earliest_last / w).floor();
        let mut tree = Fenwick::new(m, tree);
        let mut g = Geometric::new(q);
        let (mut total_c, mut total_cr) = (R::zero(), R::zero());
        let (mut off_jump, mut off_moment) = (R::zero(), R::zero());
        let (mut jump_before, mut moment_before) = (R::zero(), R::zero());
        let mut started = 0;
        let mut deposits = std::mem::take(&mut self.deposits);
        let mut total = R::zero();
        let mut cells = 0u64;
        let mut j = j_lo + R::one();
        let mut split = (R::zero(), 0u64); // (phi, K) at the last point
        while j <= j_cut {
            let x = j * w;
            while started < m && members[started].start < x {
                let p = members[started];
                let (g0, g1, _) = sums(q, p.k0);
                tree.add(rank[started], (p.scaled, p.scaled * p.r));
                total_c += p.scaled;
                total_cr += p.scaled * p.r;
                off_jump += p.scaled * g0;
                off_moment += p.scaled * (p.r * g0 + period * g1);
                started += 1;
            }
            let d = x - b;
            let k = (d / period).floor().to_f64().max(0.0) as u64;
            let phi = d - R::of(k as f64) * period;
            let below = sorted_r.partition_point(|&r| r < phi);
            let (s_c, s_cr) = tree.below(below);
            let (g0, g1, qk) = g.at(k);
            let (h0, h1) = (g0 + qk, g1 + R::of(k as f64) * qk);
            let (a_c, a_cr) = (total_c - s_c, total_cr - s_cr);
            let jump = h0 * s_c + g0 * a_c - off_jump;
            let moment = h0 * s_cr + g0 * a_cr + period * (h1 * s_c + g1 * a_c) - off_moment;
            let (cell_jump, cell_moment) = (jump - jump_before, moment - moment_before);
            (jump_before, moment_before) = (jump, moment);
            // (the lattice points as `emit` computes them, `j w`: `x - w`
            // can be an ulp off, and a lane merges deposits born together
            // only)
            let lo = (j - R::one()) * w;
            let at_hi = (cell_moment - cell_jump * (lo - b)) / w;
            for (at, dj) in [(lo, cell_jump - at_hi), (x, at_hi)] {
                if dj != R::zero() {
                    deposits.push((lane, at, dj));
                }
            }
            total += cell_jump;
            cells += 1;
            split = (phi, k);
            j += R::one();
        }
        // the births after the last point, one by one, from the count the
        // formula took for each train
        let (phi, k) = split;
        let mut merged = 0u64;
        let mut tail_sums = Remembered::default();
        for (index, p) in members.iter().enumerate() {
            merged += p.count;
            let from = if index < started {
                let n = k + u64::from(p.r < phi);
                n.saturating_sub(p.k0).min(p.count)
            } else {
                0
            };
            // cell by cell in closed form, as `emit` does
            let mut i = from;
            let mut amp = p.c * pow(q, from);
            let mut n = 0;
            while i < p.count {
                let born = p.start + R::of(i as f64) * period;
                let cell = (born / w).floor();
                let (lo, hi) = (cell * w, (cell + R::one()) * w);
                n = count_before_near(born, period, hi, n).clamp(1, p.count - i);
                let (s0, s1, qn) = tail_sums.get(q, n);
                let jump = amp * s0;
                let at_hi = amp * ((born - lo) * s0 + period * s1) / w;
                for (at, dj) in [(lo, jump - at_hi), (hi, at_hi)] {
                    if dj != R::zero() {
                        deposits.push((lane, at, dj));
                    }
                }
                total += jump;
                cells += 1;
                amp = amp * qn;
                i += n;
            }
        }
        self.deposits = deposits;
        self.leap_work += cells + m as u64;
        self.drops.truncation.merged_fronts += merged;
        match self.lanes[lane].direction {
            Direction::Up => self.up_base[self.lanes[lane].layer] += total,
            Direction::Down => self.down_base[self.lanes[lane].layer] += total,
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
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
        let mut state = 0x1234_5678_9abc_def1u64;
        let mut uniform = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
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
            let mut one = base.clone();
            for &t in &trains {
                one.emit(lane, t).unwrap();
            }
            let mut together = base.clone();
            together
                .emit_ringing(lane, &trains, &mut Work::default())
                .unwrap();
            // (where the trains die under the drop threshold within the
            // window they all go one by one)
            assert!(together.deposits.len() <= one.deposits.len());
            fewer += usize::from(together.deposits.len() < one.deposits.len());
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
            assert!((x - y).abs() <= 1e-12 * scale, "q {q}: base {x:e} {y:e}");
            assert_eq!(
                one.drops.truncation.merged_fronts,
                together.drops.truncation.merged_fronts
            );
            cases += 1;
        }
        assert_eq!(cases, 6);
        assert!(fewer >= 4, "only {fewer} cases went together");
    }
}

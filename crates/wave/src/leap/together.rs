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
//! Taken together: trains with the lane's `P` and `q`, none under the drop
//! threshold, in groups whose starts lie within `K` periods of the group's
//! first, `|q|^K >= 0.1` ([`REFERRED_AT_LEAST`]: `c~_p` stays within ten
//! times `c_p`); a train's first fronts large enough to be kept where
//! they are born go through `emit` one by one, and so does any train
//! alone. A train that ends before the others goes on as a train of the
//! opposite jump from its first missing birth: the same `r_p`, `c~_p`
//! negated, so it leaves the prefix sums exactly where it ends. The
//! formula runs up to the last lattice point before the latest last
//! birth; the births after it (a cell or two a train) are deposited train
//! by train as `emit` does, each counted exactly once because the count
//! the formula used is where they start.
//!
//! The groups and the trains' ends are what a fast bottom's leap that
//! takes its neighbour's arrivals needs (`arrivals.rs`): a train starts at
//! each arrival, all through a window of a thousand periods, and each ends
//! where its phase falls under the drop threshold. Gone one by one, its
//! thousand trains of a thousand cells each made the leap as slow as the
//! loop (119 ms for a million events; 1.8 ms together).

use super::Train;
use super::scratch::{TogetherRoom, Work};
use crate::engine::Tracer;
use crate::error::WaveError;
use crate::geometric::{AscendingSums, sums};
use crate::lane::{Direction, MergeRule};
use crate::leap::crossing::{count_before_near, pow, pow_small};
use crate::real::Real;
use crate::runs::sort_by_few_keys;

/// Fewer trains than this go one by one (sorting and the tree cost more).
const TOGETHER_FROM: usize = 4;

/// The least `|q|^K_p` of a train taken together: its jumps referred to
/// round 0 are at most ten times its own. At a thousandth, trains
/// starting hundreds of periods apart (a fast bottom's leap taking
/// arrivals, a ratio of 0.97) deposited `6e-9` of a front off what they
/// deposit one by one: the first moments' sums cancel that many digits.
const REFERRED_AT_LEAST: f64 = 0.1;

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
        // a train's fronts large enough to be kept where they are born go
        // one by one, the rest of it may still be taken together (the
        // fronts a fast bottom sends a slow neighbour start large and ring
        // for hundreds of periods)
        for k in 0..work.same.len() {
            let t = work.same[k];
            if t.c.abs() < keep_above {
                continue;
            }
            // (the count `emit` keeps, `|c q^k| >= keep_above` as it
            // computes it: the logarithms may be a front off)
            let mut big = self.life_within(t.c, q, keep_above, 0, t.count);
            while big > 0 && (t.c * pow(q, big - 1)).abs() < keep_above {
                big -= 1;
            }
            while big < t.count && (t.c * pow(q, big)).abs() >= keep_above {
                big += 1;
            }
            if big < t.count {
                self.emit(lane, Train { count: big, ..t })?;
                work.same[k] = Train {
                    start: t.start + R::of(big as f64) * period,
                    c: t.c * pow(q, big),
                    count: t.count - big,
                    ..t
                };
            }
        }
        // in groups by start (module doc)
        work.same.sort_by(|x, y| {
            x.start
                .partial_cmp(&y.start)
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        let mut from = 0;
        while from < work.same.len() {
            let b = work.same[from].start;
            let mut to = from + 1;
            while to < work.same.len() {
                let k0 = ((work.same[to].start - b) / period).floor().to_f64() as u64;
                if pow_small(q, k0).abs() < R::of(REFERRED_AT_LEAST) {
                    break;
                }
                to += 1;
            }
            self.gather_members(lane, work, from..to, b, thr, keep_above)?;
            self.deposit_together(lane, work, b, period, q, w)?;
            from = to;
        }
        Ok(())
    }

    /// The trains `work.same[range]` (starting from `b`) that can be taken
    /// together into `work.members`; the rest emitted one by one.
    fn gather_members(
        &mut self,
        lane: usize,
        work: &mut Work<R>,
        range: std::ops::Range<usize>,
        b: R,
        thr: R,
        keep_above: R,
    ) -> Result<(), WaveError> {
        let Work { same, members, .. } = work;
        let trains = &same[range];
        let Some(first) = trains.first() else {
            return Ok(());
        };
        let (q, period) = (first.q, first.period);
        members.clear();
        for &t in trains {
            let d = t.start - b;
            let k0 = (d / period).floor().to_f64().max(0.0) as u64;
            let qk = pow_small(q, k0);
            let together = t.c.abs() < keep_above
                && qk.abs() >= R::of(REFERRED_AT_LEAST)
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
        Ok(())
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
            by_end,
            spare_ends,
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
        // where each train ends: it goes on as a train of the opposite
        // jump from its first missing birth, round `k0 + count` at the same
        // `r` (`c~` negated: no precision is lost however late it ends).
        // It leaves at the first point whose `(k, phi)` would count that
        // birth, as the formula counts births: comparing the birth's time
        // with the point's instead, a birth on a lattice point was counted
        // there and not taken back (a front's jump too many, found by the
        // momentum balance of `tests/leaps.rs`).
        // (taken in order of `r`, by the round alone is by both: the
        // rounds take one of a few values)
        by_end.clear();
        by_end.extend(by_r.iter().map(|&(r, k)| {
            let p = &members[k];
            (p.k0 + p.count, r, k)
        }));
        sort_by_few_keys(by_end, spare_ends, |e| e.0);
        // the formula's lattice points: after the earliest start, up to the
        // latest last birth
        let latest_last = members
            .iter()
            .map(|p| p.start + R::of((p.count - 1) as f64) * period)
            .fold(R::neg_infinity(), |a, s| if s > a { s } else { a });
        let j_lo = (b / w).floor();
        let j_cut = (latest_last / w).floor();
        let mut tree = Fenwick::new(m, tree);
        let mut g = Geometric::new(q);
        // (the trains start and end in order of their rounds)
        let (mut start_sums, mut end_sums) = (AscendingSums::new(q), AscendingSums::new(q));
        let (mut total_c, mut total_cr) = (R::zero(), R::zero());
        let (mut off_jump, mut off_moment) = (R::zero(), R::zero());
        let (mut jump_before, mut moment_before) = (R::zero(), R::zero());
        let (mut started, mut ended) = (0, 0);
        let mut deposits = std::mem::take(&mut self.deposits);
        let mut total = R::zero();
        let mut cells = 0u64;
        let mut j = j_lo + R::one();
        let mut split = (R::zero(), 0u64); // (phi, K) at the last point
        while j <= j_cut {
            let x = j * w;
            while started < m && members[started].start < x {
                let p = members[started];
                let (g0, g1, _) = start_sums.at(p.k0);
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
            while ended < m && {
                let (round, r, _) = by_end[ended];
                round < k || (round == k && r < phi)
            } {
                let p = members[by_end[ended].2];
                let (g0, g1, _) = end_sums.at(p.k0 + p.count);
                tree.add(rank[by_end[ended].2], (-p.scaled, -p.scaled * p.r));
                total_c -= p.scaled;
                total_cr -= p.scaled * p.r;
                off_jump -= p.scaled * g0;
                off_moment -= p.scaled * (p.r * g0 + period * g1);
                ended += 1;
            }
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
        // (the trains' first tail cells hold nearly the same count, from
        // nearly the same round: each train's is the guess and the power
        // for the next)
        let (mut first_count, mut first_power) = (0, None);
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
            let q_from = match first_power {
                Some((k, qk)) if k == from => qk,
                _ => pow(q, from),
            };
            first_power = Some((from, q_from));
            let mut amp = p.c * q_from;
            let mut n = first_count;
            let mut first_cell = true;
            while i < p.count {
                let born = p.start + R::of(i as f64) * period;
                let cell = (born / w).floor();
                let (lo, hi) = (cell * w, (cell + R::one()) * w);
                let counted = count_before_near(born, period, hi, n);
                if first_cell {
                    (first_count, first_cell) = (counted, false);
                }
                n = counted.clamp(1, p.count - i);
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
mod tests;

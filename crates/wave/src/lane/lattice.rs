//! Lattice lanes: a merged run's fronts deposited on a lattice of birth
//! times (`MergeRule::Lattice`), so that a lane holds a bounded number of
//! fronts however many are born. A deposit keeps its jump and first moment
//! (momentum exact, energy only falling); the few large fronts that decide
//! contacts are kept where they were born; a leap's trains are placed in
//! one pass, and its rebuilt fronts merged within their cells.

use super::{Front, Lane, Pushed};
use crate::real::Real;

/// The most lattice points a leap's deposits into a lane may spread over,
/// per deposit, to be summed point by point ([`sum_on_points`]).
const POINTS_PER_DEPOSIT: usize = 4;

/// A leap's deposits `(at, d)` into a lattice lane of spacing `w`, summed
/// point by point in the order they came and left in order of their
/// points: `batch` becomes one deposit a point, sorted (a point whose
/// deposits cancel exactly left out, as if none came). A leap's trains
/// deposit on the points of every cell they cross, one train after
/// another, so a point takes a deposit from each: sorting them all
/// (stably, to sum them in a fixed order) was half of placing them, and
/// placing them a seventh of a leaping rod's instructions (callgrind,
/// seed 3's rod 5 of the layer survey at 0.1 of a transit). Every deposit
/// is born on a point `k w` as `emit` computes it (`k` a whole number):
/// one that is not, or deposits spread over many more points than they
/// are, leave `batch` as it came (false), for [`Lane::place_all`] to sort.
pub(crate) fn sum_on_points<R: Real>(batch: &mut Vec<(R, R)>, w: R, sums: &mut Vec<R>) -> bool {
    if batch.len() < 2 {
        return true;
    }
    let per = 1.0 / w.to_f64();
    // (births are at or after the impact: truncation after a half is the
    // rounding, without the call into libm)
    let point = |at: R| (at.to_f64() * per + 0.5) as i64;
    let (mut first, mut last) = (i64::MAX, i64::MIN);
    for &(at, _) in batch.iter() {
        let k = point(at);
        if k < 0 || R::of(k as f64) * w != at {
            return false;
        }
        (first, last) = (first.min(k), last.max(k));
    }
    if (last - first) as usize >= POINTS_PER_DEPOSIT * batch.len() {
        return false;
    }
    sums.clear();
    sums.resize((last - first) as usize + 1, R::zero());
    for &(at, d) in batch.iter() {
        sums[(point(at) - first) as usize] += d;
    }
    batch.clear();
    for (j, &sum) in sums.iter().enumerate() {
        if sum != R::zero() {
            batch.push((R::of((first + j as i64) as f64) * w, sum));
        }
    }
    true
}

impl<R: Real> Lane<R> {
    /// Appends the fronts of one lattice cell, merged onto its first and
    /// last birth (see [`Lane::set_fronts`]).
    pub(super) fn flush_cell(&mut self, cell: &mut Vec<Front<R>>) {
        match cell.as_slice() {
            [] => {}
            [f] => self.fronts.push_back(*f),
            [first, .., last] => {
                let (a, b) = (first.born, last.born);
                let (mut at_a, mut at_b) = (R::zero(), R::zero());
                for f in cell.iter() {
                    let w = if b > a {
                        (f.born - a) / (b - a)
                    } else {
                        R::zero()
                    };
                    at_b += f.jump * w;
                    at_a += f.jump * (R::one() - w);
                }
                let id = first.id;
                // (fronts all born at one instant: one front at `a`)
                let ends = if b > a { 2 } else { 1 };
                for (born, jump) in [(a, at_a), (b, at_b)].into_iter().take(ends) {
                    if jump != R::zero() {
                        self.fronts.push_back(Front {
                            born,
                            jump,
                            id,
                            kept: false,
                        });
                    }
                }
            }
        }
        cell.clear();
    }

    /// [`Lane::push`] under [`MergeRule::Lattice`]: merged runs only, kept
    /// out of the exact event loop's inlined path.
    #[inline(never)]
    pub(super) fn push_on_lattice(
        &mut self,
        born: R,
        jump: R,
        id: u32,
        spacing: R,
        keep_above: R,
        keep_at_most: usize,
    ) -> Pushed<R> {
        let head_before = self.fronts.front().map(|f| f.born);
        let was_empty = self.fronts.is_empty();
        let inserted = if jump.abs() >= keep_above && self.kept < keep_at_most {
            self.kept += 1;
            self.add_at(born, jump, id, true)
        } else {
            self.deposit(born, jump, id, spacing)
        };
        self.refresh_head();
        match (was_empty, inserted) {
            (true, _) => Pushed::New { was_empty: true },
            (false, true) if self.fronts.front().map(|f| f.born) == head_before => {
                Pushed::New { was_empty: false }
            }
            _ => Pushed::Merged {
                id,
                moved_head: self.fronts.front().map(|f| f.born) != head_before,
                beyond_simultaneity: true,
                gap: R::zero(),
            },
        }
    }

    /// Deposits a jump on the lattice (see [`MergeRule::Lattice`]); true if
    /// a front was inserted.
    fn deposit(&mut self, born: R, jump: R, id: u32, spacing: R) -> bool {
        let k = (born / spacing).floor();
        let (lo, hi) = (k * spacing, (k + R::one()) * spacing);
        let f = (born - lo) / spacing;
        let (at_lo, at_hi) = (jump * (R::one() - f), jump * f);
        // The usual places, without a search: births only move forward, so
        // the newest front sits before `lo`, on it, or on `hi` (a deposit in
        // the cell of the one before). The same result as `add_at` twice.
        if at_lo == R::zero() || at_hi == R::zero() {
            return self.deposit_apart(lo, at_lo, hi, at_hi, id);
        }
        let new = |born, jump| Front {
            born,
            jump,
            id,
            kept: false,
        };
        let n = self.fronts.len();
        let shape = |i: usize| {
            let f: &Front<R> = &self.fronts[i];
            (f.born, f.kept)
        };
        let last = n.checked_sub(1).map(shape);
        let before = n.checked_sub(2).map(shape);
        match (before, last) {
            // empty, or ending before `lo`
            (_, None) => {}
            (_, Some((born, _))) if born < lo => {}
            (_, Some((born, false))) if born == lo => {
                self.fronts[n - 1].jump += at_lo;
                self.fronts.push_back(new(hi, at_hi));
                return true;
            }
            (Some((b, false)), Some((born, false))) if born == hi && b == lo => {
                self.fronts[n - 1].jump += at_hi;
                self.fronts[n - 2].jump += at_lo;
                return false;
            }
            (b, Some((born, false))) if born == hi && b.is_none_or(|(b, _)| b < lo) => {
                // `lo` goes between the two (or first)
                self.fronts[n - 1].jump += at_hi;
                let last = self.fronts.pop_back();
                self.fronts.push_back(new(lo, at_lo));
                self.fronts.extend(last);
                return true;
            }
            _ => return self.deposit_apart(lo, at_lo, hi, at_hi, id),
        }
        self.fronts.push_back(new(lo, at_lo));
        self.fronts.push_back(new(hi, at_hi));
        true
    }

    /// A deposit's two parts placed one by one, each where it belongs.
    fn deposit_apart(&mut self, lo: R, at_lo: R, hi: R, at_hi: R, id: u32) -> bool {
        let mut inserted = false;
        for (at, d) in [(lo, at_lo), (hi, at_hi)] {
            if d != R::zero() {
                inserted |= self.add_at(at, d, id, false);
            }
        }
        inserted
    }

    /// Adds lattice deposits `(at, d)` (sorted here) in one pass over the
    /// lane's newest fronts: the deposits of a leap's trains spread over
    /// many cells, and placing them one by one would walk the lane once
    /// each. They are births from now on, so they land behind nearly every
    /// front the lane holds: only the fronts born at or after the first
    /// deposit are taken out and merged with them (a lattice lane never
    /// holds two unkept fronts born together, so the older ones would come
    /// through a merge unchanged; asserted in debug builds). Rebuilding the
    /// whole lane each time cost a copy of a thousand fronts per leap.
    /// (A leap's deposits come summed point by point and in order where
    /// they can, [`sum_on_points`]: the sort then finds one run. A
    /// counting sort by point that kept every deposit, tried before, took
    /// 7 % more instructions on survey rod 22.)
    pub fn place_all(&mut self, deposits: &mut [(R, R)], spare: &mut Vec<Front<R>>) {
        if deposits.is_empty() {
            return;
        }
        deposits.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal));
        let first = deposits[0].0;
        let older = self.fronts.partition_point(|f| f.born < first);
        debug_assert!(
            self.fronts
                .range(..older)
                .zip(self.fronts.range(..older).skip(1))
                .all(|(a, b)| a.born != b.born || a.kept || b.kept),
            "a lattice lane holds two unkept fronts born together"
        );
        let newer = spare;
        newer.clear();
        newer.extend(self.fronts.drain(older..));
        let merged = &mut self.fronts;
        let mut news = deposits.iter().copied().peekable();
        let deposit = |merged: &mut super::Fifo<Front<R>>, at: R, d: R| match merged.back_mut() {
            Some(last) if last.born == at && !last.kept => last.jump += d,
            _ => merged.push_back(Front {
                born: at,
                jump: d,
                id: 0,
                kept: false,
            }),
        };
        for &f in newer.iter() {
            while let Some(&(at, d)) = news.peek() {
                if at > f.born {
                    break;
                }
                if at == f.born && !f.kept {
                    break;
                }
                deposit(merged, at, d);
                news.next();
            }
            match merged.back_mut() {
                Some(last) if last.born == f.born && !last.kept && !f.kept => last.jump += f.jump,
                _ => merged.push_back(f),
            }
        }
        for (at, d) in news {
            deposit(merged, at, d);
        }
        self.refresh_head();
    }

    /// Adds `d` to the lattice front born at `at`, or inserts a front there
    /// keeping birth order (a kept front is always inserted); true if one
    /// was inserted. The place is among the newest fronts: births only move
    /// forward, and lattice points by at most one spacing.
    fn add_at(&mut self, at: R, d: R, id: u32, kept: bool) -> bool {
        let front = Front {
            born: at,
            jump: d,
            id,
            kept,
        };
        // the usual places first: behind the newest front, or on it (a
        // deposit's upper point, and most lower ones)
        match self.fronts.back_mut() {
            None => {
                self.fronts.push_back(front);
                return true;
            }
            Some(last) if last.born < at => {
                self.fronts.push_back(front);
                return true;
            }
            Some(last) if last.born == at && !kept && !last.kept => {
                last.jump += d;
                return false;
            }
            Some(_) => {}
        }
        let i = self.fronts.len() - self.fronts.iter().rev().take_while(|f| f.born > at).count();
        if !kept && i > 0 && self.fronts[i - 1].born == at && !self.fronts[i - 1].kept {
            self.fronts[i - 1].jump += d;
            return false;
        }
        self.fronts.insert(i, front);
        true
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Direction, MergeRule};
    use super::*;

    /// A lattice of quarters keeping one front of a unit jump or more.
    fn quarter_lattice() -> MergeRule<f64> {
        MergeRule::Lattice {
            spacing: 0.25,
            keep_above: 1.0,
            keep_at_most: 1,
        }
    }

    #[test]
    fn lattice_deposits_keep_the_jump_and_its_moment() {
        let mut lane = Lane::new(1, Direction::Down, 2.0, quarter_lattice());
        lane.push(1.1, 0.5, 0);
        lane.push(1.2, -0.25, 1);
        // a large front is kept where it was born
        lane.push(1.3, 2.0, 2);
        // the next large one is deposited: one kept front at most
        lane.push(1.35, 2.0, 3);
        let births: Vec<f64> = lane.fronts.iter().map(|f| f.born).collect();
        assert_eq!(births, vec![1.0, 1.25, 1.3, 1.5]);
        let total: f64 = lane.fronts.iter().map(|f| f.jump).sum();
        let moment: f64 = lane.fronts.iter().map(|f| f.jump * f.born).sum();
        assert!((total - 4.25).abs() < 1e-15);
        assert!((moment - (0.5 * 1.1 - 0.25 * 1.2 + 2.0 * 1.3 + 2.0 * 1.35)).abs() < 1e-14);
        assert_eq!(lane.kept, 1);
        while lane.pop().is_some() {}
        assert_eq!(lane.kept, 0);
    }

    /// The lattice rule written out the plain way, as the oracle of the
    /// deposit's shortcuts: each part of a deposit goes to its lattice
    /// point, found by a search from the newest front, and merges with an
    /// unkept front there or is inserted after every front born no later.
    fn plain_lattice_push(lane: &mut Vec<Front<f64>>, kept: &mut usize, born: f64, jump: f64) {
        let place = |lane: &mut Vec<Front<f64>>, at: f64, d: f64, keep: bool| {
            let i = lane.iter().rposition(|f| f.born <= at).map_or(0, |i| i + 1);
            match lane.get_mut(i.wrapping_sub(1)) {
                Some(f) if !keep && f.born == at && !f.kept => f.jump += d,
                _ => lane.insert(
                    i,
                    Front {
                        born: at,
                        jump: d,
                        id: 0,
                        kept: keep,
                    },
                ),
            }
        };
        if jump.abs() >= 1.0 && *kept < 1 {
            *kept += 1;
            place(lane, born, jump, true);
            return;
        }
        let k = (born / 0.25).floor();
        let (lo, hi) = (k * 0.25, (k + 1.0) * 0.25);
        let f = (born - lo) / 0.25;
        for (at, d) in [(lo, jump * (1.0 - f)), (hi, jump * f)] {
            if d != 0.0 {
                place(lane, at, d, false);
            }
        }
    }

    proptest::proptest! {
        /// Deposits on a lattice lane, among them large fronts kept where
        /// they were born, births on lattice points and heads taken in
        /// between (a fast layer's lane holds two or three fronts), give
        /// the plain rule's fronts bit for bit.
        #[test]
        fn lattice_deposits_are_the_plain_rules(
            steps in proptest::collection::vec((0u8..7, -3.0f64..3.0), 1..80)
        ) {
            let mut lane = Lane::new(0, Direction::Up, 2.0, quarter_lattice());
            let (mut plain, mut kept) = (Vec::new(), 0);
            let mut born = 1.0;
            for (step, jump) in steps {
                // births move forward: by nothing, to the next lattice
                // point, or by parts of a cell; or the head arrives
                born = match step {
                    0 => born,
                    1 => ((born / 0.25).floor() + 1.0) * 0.25,
                    6 => {
                        let head = lane.pop().map(|f| (f.born, f.jump, f.kept));
                        let want = (!plain.is_empty()).then(|| plain.remove(0));
                        if want.is_some_and(|f: Front<f64>| f.kept) {
                            kept -= 1;
                        }
                        proptest::prop_assert_eq!(head, want.map(|f| (f.born, f.jump, f.kept)));
                        continue;
                    }
                    g => born + f64::from(g) * 0.07,
                };
                lane.push(born, jump, 0);
                plain_lattice_push(&mut plain, &mut kept, born, jump);
                let got: Vec<(f64, f64, bool)> =
                    lane.fronts.iter().map(|f| (f.born, f.jump, f.kept)).collect();
                let want: Vec<(f64, f64, bool)> =
                    plain.iter().map(|f| (f.born, f.jump, f.kept)).collect();
                proptest::prop_assert_eq!(got, want);
                proptest::prop_assert_eq!(
                    lane.head_arrival(),
                    plain.first().map(|f| f.born + 2.0)
                );
            }
        }
    }

    /// `sum (s_{k+1} - s_k) v_k^2` over the steps between a lane's fronts
    /// (the energy the lane holds between its first and last front, up to
    /// a constant), written out independently of the merge.
    fn energy_between(fronts: &[(f64, f64)]) -> f64 {
        let mut v = 0.0;
        let mut e = 0.0;
        for w in fronts.windows(2) {
            v += w[0].1;
            e += v * v * (w[1].0 - w[0].0);
        }
        e
    }

    #[test]
    fn a_leaps_fronts_merge_within_their_lattice_cells() {
        let mut lane = Lane::new(1, Direction::Up, 2.0, quarter_lattice());
        // two born at one instant (once lost by the merge), a cell of
        // three with mixed signs, a large one kept, a lone one
        let given = [
            (1.01, 0.3),
            (1.01, -0.1),
            (1.26, 0.2),
            (1.3, -0.4),
            (1.45, 0.25),
            (1.6, 2.0),
            (1.9, 0.05),
        ];
        let fronts: Vec<Front<f64>> = given
            .iter()
            .enumerate()
            .map(|(i, &(born, jump))| Front {
                born,
                jump,
                id: i as u32,
                kept: false,
            })
            .collect();
        lane.set_fronts(&fronts, &mut Vec::new());
        let got: Vec<(f64, f64)> = lane.fronts.iter().map(|f| (f.born, f.jump)).collect();
        let sum = |v: &[(f64, f64)]| v.iter().map(|f| f.1).sum::<f64>();
        let moment = |v: &[(f64, f64)]| v.iter().map(|f| f.0 * f.1).sum::<f64>();
        assert!((sum(&got) - sum(&given)).abs() < 1e-15, "{got:?}");
        assert!((moment(&got) - moment(&given)).abs() < 1e-14, "{got:?}");
        // cells [1, 1.25): one front at 1.01; [1.25, 1.5): onto 1.26 and
        // 1.45; the large front kept; the lone one as it was
        let births: Vec<f64> = got.iter().map(|f| f.0).collect();
        assert_eq!(births, vec![1.01, 1.26, 1.45, 1.6, 1.9]);
        assert!((got[0].1 - 0.2).abs() < 1e-15);
        assert_eq!(lane.kept, 1);
        assert!(lane.fronts[3].kept);
        assert!(energy_between(&got) <= energy_between(&given) + 1e-15);
        assert_eq!(lane.head_arrival(), Some(3.01));
    }

    /// [`sum_on_points`] against sums in a map, taken in the order the
    /// deposits came (the same bits): deposits on the points `k w` of an
    /// awkward spacing, far from zero, in random order, with repeats and
    /// with two that cancel; and the batches it leaves as they came, one
    /// deposit off the lattice (an ulp), or deposits spread too far.
    #[test]
    fn deposits_are_summed_on_their_points_in_the_order_they_came() {
        let w = 0.1 / 3.0;
        let mut next = crate::test_random::xorshift(0x853c_49e6_748f_ea9bu64);
        let mut sums = Vec::new();
        for case in 0..300 {
            let base = 1_000_000 * (case % 3) as i64;
            let n = 2 + next() % 40;
            let mut batch: Vec<(f64, f64)> = (0..n)
                .map(|_| {
                    let k = base + (next() % (2 * n)) as i64;
                    ((k as f64) * w, (next() % 1000) as f64 / 7.0 - 70.0)
                })
                .collect();
            if case % 5 == 0 {
                let (at, d) = batch[0];
                batch.push((at, -d));
                batch.push((at, d));
                batch.push((at, -d));
            }
            let mut want = std::collections::BTreeMap::<i64, f64>::new();
            for &(at, d) in &batch {
                *want.entry((at / w).round() as i64).or_insert(0.0) += d;
            }
            let want: Vec<(f64, f64)> = want
                .into_iter()
                .filter(|&(_, d)| d != 0.0)
                .map(|(k, d)| ((k as f64) * w, d))
                .collect();
            assert!(sum_on_points(&mut batch, w, &mut sums));
            assert_eq!(batch, want, "case {case}");
        }
        let mut off = vec![(3.0 * w, 1.0), ((5.0 * w).next_up(), 2.0), (3.0 * w, 1.0)];
        let came = off.clone();
        assert!(!sum_on_points(&mut off, w, &mut sums));
        assert_eq!(off, came);
        let mut spread = vec![(0.0, 1.0), (100.0 * w, 2.0), (50.0 * w, 1.0)];
        let came = spread.clone();
        assert!(!sum_on_points(&mut spread, w, &mut sums));
        assert_eq!(spread, came);
    }
}

//! A port's responses' large fronts that are small once scaled by their
//! arrival, put on the port's lattice at the arrival.
//!
//! A response's large fronts (`response.rs`) are kept apart so that they
//! reach the neighbour at their exact times, as a lattice lane keeps its
//! large fronts where they were born. But "large" is judged on a unit
//! arrival: scaled by an arrival's jump (most arrivals are lattice points,
//! small), nearly all of them fall under the neighbour lane's
//! `keep_above`, and the lane deposits them on its lattice anyway. On the
//! fast-bottom draw's rod 36 each arrival brought 16 of them, each sorted
//! into the port's queue of exact fronts (84 long) and spawned one by one:
//! 16 times the arrivals' own work. Such a front is put on the port's
//! lattice when its arrival comes instead, split between its two points
//! as the lane would split it (jump and first moment kept), and delivered
//! with the lattice sums: each point receives the same total, to rounding
//! (the split is taken at `t / h + delay / h`, the lane's at `(t + delay)
//! / h`), summed in another order. Fronts under the drop threshold, which
//! the lane would have dropped one by one (and counted as dropped in the
//! error estimate), are summed with the rest instead.
//!
//! Where the earlier of its two points is the one the port delivered
//! last, which is nearly always so when the neighbour's lattice is far
//! coarser than the response's delays, that point is already in the
//! lane: its share is summed `behind` and the caller deposits the sum
//! there at the arrival, one deposit for all the arrival's fronts.

use crate::lane::Fifo;
use crate::real::Real;

/// Jumps added on a port's lattice points from `from` on, to be delivered
/// with those points' sums, and what falls on the point delivered last.
#[derive(Debug, Clone, Default)]
pub(crate) struct Folded<R> {
    from: i64,
    jumps: Fifo<R>,
    /// The lower shares on the point before `next`, which the lane holds
    /// already: taken by [`Folded::take_behind`] and deposited there at
    /// once, one deposit for the arrival's fronts instead of one each.
    behind: R,
}

impl<R: Real> Folded<R> {
    pub(crate) fn is_empty(&self) -> bool {
        self.jumps.is_empty()
    }

    /// A jump born at `x` lattice spacings, split between its two points
    /// as a lattice lane deposits it (`lane/lattice.rs`), if its earlier
    /// point is `next - 1` or later (that point's share goes `behind`);
    /// false if it is earlier (the jump is then left to its caller).
    #[inline]
    pub(crate) fn deposit(&mut self, x: R, jump: R, next: i64) -> bool {
        let k = x.floor();
        let f = x - k;
        let k = k.to_f64() as i64;
        if k < next - 1 {
            return false;
        }
        let (lower, upper) = (jump * (R::one() - f), jump * f);
        if k < next {
            self.behind += lower;
        } else {
            self.add_on(k, lower);
        }
        self.add_on(k + 1, upper);
        true
    }

    /// Adds `jump` on point `k`, holding the points from `k` on. A point
    /// already held is found by one comparison (an arrival's fronts come
    /// in the order of their delays, so after the first few each lands on
    /// a point held: `add_on` was a tenth of the fast-bottom draw's rod
    /// 23's instructions when every call took the general path).
    #[inline(always)]
    fn add_on(&mut self, k: i64, jump: R) {
        if let Ok(i) = usize::try_from(k.wrapping_sub(self.from))
            && let Some(x) = self.jumps.get_mut(i)
        {
            *x += jump;
        } else {
            self.add_outside(k, jump);
        }
    }

    /// [`Folded::add_on`] on a point not held: the first, one before the
    /// earliest held, or one past the last.
    #[inline(never)]
    fn add_outside(&mut self, k: i64, jump: R) {
        if self.jumps.is_empty() {
            self.from = k;
        }
        // (before the earliest held: a shorter delay after a longer one;
        // the gap put in front at once)
        if k < self.from {
            let gap = usize::try_from(self.from - k).unwrap_or(0);
            let held: Vec<R> = self.jumps.iter().copied().collect();
            self.jumps.clear();
            self.jumps
                .extend(std::iter::repeat_n(R::zero(), gap).chain(held));
            self.from = k;
        }
        let i = usize::try_from(k - self.from).unwrap_or(0);
        while self.jumps.len() <= i {
            self.jumps.push_back(R::zero());
        }
        self.jumps[i] += jump;
    }

    /// What was put on the point before `next` since the last call, taken.
    pub(crate) fn take_behind(&mut self) -> R {
        std::mem::replace(&mut self.behind, R::zero())
    }

    /// What point `m` holds, taken; the points before it must have been
    /// taken already.
    pub(crate) fn take(&mut self, m: i64) -> R {
        if self.jumps.is_empty() || m < self.from {
            return R::zero();
        }
        debug_assert_eq!(m, self.from, "folded points taken in order");
        self.from += 1;
        self.jumps.pop_front().unwrap_or(R::zero())
    }

    /// `sum |jump|` over the points held.
    pub(crate) fn total_abs(&self) -> R {
        self.jumps.iter().fold(R::zero(), |s, &d| s + d.abs())
    }
}

#[cfg(test)]
mod tests {
    use super::Folded;

    /// A jump between two points keeps its jump and first moment about
    /// the lattice (`sum a_k k h = jump * born`), and points come out in
    /// order with what was added on each.
    #[test]
    fn a_deposit_keeps_the_jump_and_its_moment() {
        let h = 0.25;
        let mut folded = Folded::<f64>::default();
        assert!(folded.deposit(1.3 / h, 2.0, 5));
        assert!(folded.deposit(1.5 / h, -1.0, 5));
        assert_eq!(folded.take(4), 0.0);
        let taken: Vec<f64> = (5..9).map(|m| folded.take(m)).collect();
        assert!(folded.is_empty());
        let jump: f64 = taken.iter().sum();
        let moment: f64 = taken.iter().zip(5..).map(|(a, k)| a * k as f64 * h).sum();
        assert!((jump - 1.0).abs() < 1e-15, "{taken:?}");
        assert!((moment - (2.0 * 1.3 - 1.5)).abs() < 1e-14, "{taken:?}");
        // 1.5 sits on point 6: nothing on 7 from it
        assert!((taken[1] - (2.0 * 0.2 - 1.0)).abs() < 1e-15, "{taken:?}");
        assert_eq!(taken[2], 0.0, "{taken:?}");
    }

    /// A jump whose earlier point is the last delivered puts its share
    /// there `behind`, the rest on the next point; one from before that is
    /// refused and nothing is held; one born before the earliest held
    /// point goes before it.
    #[test]
    fn a_delivered_point_is_refused() {
        let mut folded = Folded::<f64>::default();
        assert!(!folded.deposit(0.8, 1.0, 2));
        assert!(folded.is_empty());
        assert_eq!(folded.take_behind(), 0.0);
        assert!(folded.deposit(1.75, 2.0, 2));
        assert_eq!(folded.take_behind(), 0.5);
        assert_eq!(folded.take_behind(), 0.0);
        assert_eq!(folded.take(2), 1.5);
        assert!(folded.is_empty());
        assert!(folded.deposit(4.0, 1.0, 2));
        assert!(folded.deposit(2.0, 1.0, 2));
        assert_eq!(folded.take(2), 1.0);
        assert_eq!(folded.take(3), 0.0);
        assert_eq!(folded.take(4), 1.0);
        assert_eq!(folded.take(5), 0.0);
        assert!(folded.is_empty());
        assert_eq!(folded.total_abs(), 0.0);
    }

    /// Many deposits onto points already held (the path an arrival's
    /// fronts nearly always take), some past the last held and some before
    /// the first, while points are taken: each point gives what the
    /// definition puts on it, `jump (1 - f)` on `floor(x)` and `jump f` on
    /// the next, summed in the order of the deposits (so to the bit).
    #[test]
    fn held_points_take_what_the_definition_puts_on_them() {
        use std::collections::BTreeMap;
        let mut folded = Folded::<f64>::default();
        let mut by_definition: BTreeMap<i64, f64> = BTreeMap::new();
        let mut taken: Vec<(i64, f64)> = Vec::new();
        let mut expected: Vec<(i64, f64)> = Vec::new();
        let (mut next, mut state) = (10_i64, 12345_u64);
        for n in 0..400 {
            // (a fixed sequence of positions a few points on from `next`,
            // an arrival's fronts in the order of their delays)
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let spread = (state >> 11) as f64 / (1u64 << 53) as f64;
            let x = next as f64 + 6.0 * spread;
            let jump = if n % 3 == 0 { -0.7 } else { 1.0 + spread };
            assert!(folded.deposit(x, jump, next));
            let (k, f) = (x.floor() as i64, x - x.floor());
            for (point, share) in [(k, jump * (1.0 - f)), (k + 1, jump * f)] {
                *by_definition.entry(point).or_insert(0.0) += share;
            }
            if n % 7 == 6 {
                // the point before `next` went `behind`: none here
                assert_eq!(folded.take_behind(), 0.0);
                taken.push((next, folded.take(next)));
                expected.push((next, by_definition.remove(&next).unwrap_or(0.0)));
                next += 1;
            }
        }
        while !folded.is_empty() {
            taken.push((next, folded.take(next)));
            expected.push((next, by_definition.remove(&next).unwrap_or(0.0)));
            next += 1;
        }
        assert!(
            by_definition.values().all(|&v| v == 0.0),
            "{by_definition:?}"
        );
        assert_eq!(taken, expected);
    }
}

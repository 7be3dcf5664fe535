//! A lane's births on its lattice points, one number a point: how a
//! block's trace (`block/response.rs`) and a stepped bottom group
//! (`group.rs`) hold their fronts, where a lane of the event loop holds
//! one front a point with its birth and id.

use super::Fifo;
use crate::real::Real;

/// One lane's births on each point of its lattice, point `base` first (a vector read from a moving head, as a lane's
/// fronts are: `VecDeque`'s growth by `resize` was a tenth of a trace).
#[derive(Debug, Clone, Default)]
pub(crate) struct LatticePoints<R> {
    pub(crate) base: i64,
    pub(crate) points: Fifo<R>,
}

impl<R: Real> LatticePoints<R> {
    /// Adds `d` at lattice point `k`. A point before the lane's first is
    /// one no front has reached yet (a front born within a step arrives
    /// after it, see `Trace::step`): the lanes are taken one after another
    /// within a step, so an emptied lane may first take a later birth.
    #[inline(always)]
    pub(crate) fn add(&mut self, k: i64, d: R) {
        // (a held point found by one comparison, not two: 3 % of the
        // instructions of seed 7's rod 20, whose trace is its time)
        match usize::try_from(k.wrapping_sub(self.base)) {
            Ok(i) => {
                if let Some(x) = self.points.get_mut(i) {
                    *x += d;
                } else if i == self.points.len() && i > 0 {
                    // the next point: the common case, a lane grows at its end
                    self.points.push_back(d);
                } else {
                    self.add_outside(k, d);
                }
            }
            _ => self.add_outside(k, d),
        }
    }

    /// Adds `lo * run[j]` at point `k + j` and `hi * run[j]` at point
    /// `k + j + 1`, for every `j`: a run of births that all fall the same
    /// share of a cell past a lattice point (`hi` of the birth on the upper
    /// point, as [`LatticePoints::add`] splits one), which is how a lane's
    /// run lands on a lattice of the same spacing (a block traced on one
    /// lattice, `block/response.rs`). Each point takes its two shares in one
    /// sum, in a loop the compiler can vectorise.
    pub(crate) fn add_shifted(&mut self, k: i64, run: &[R], lo: R, hi: R) {
        let Some(&last) = run.last() else {
            return;
        };
        self.cover(k, k + run.len() as i64);
        let start = (k - self.base) as usize;
        let points = &mut self.points.as_mut_slice()[start..=start + run.len()];
        let mut before = R::zero();
        for (x, &d) in points.iter_mut().zip(run) {
            *x += lo * d + hi * before;
            before = d;
        }
        points[run.len()] += hi * last;
    }

    /// [`LatticePoints::add_shifted`] with the run's points `stride` points
    /// apart: `lo * run[j]` at point `k + j stride` and `hi * run[j]` at the
    /// one after it (a run of a lane whose spacing is `stride` times this
    /// one's, `block/response/one_lattice.rs`).
    pub(crate) fn add_strided(&mut self, k: i64, stride: usize, run: &[R], lo: R, hi: R) {
        if stride <= 1 {
            return self.add_shifted(k, run, lo, hi);
        }
        if run.is_empty() {
            return;
        }
        self.cover(k, k + ((run.len() - 1) * stride) as i64 + 1);
        let start = (k - self.base) as usize;
        let points = &mut self.points.as_mut_slice()[start..];
        for (pair, &d) in points.chunks_mut(stride).zip(run) {
            pair[0] += lo * d;
            pair[1] += hi * d;
        }
    }

    /// A run of a lane `shares.len()` times finer than this one (a power
    /// of two), from point `k` on: its points in groups of that many, the
    /// `c`-th of group `q` split between points `k + q + off` and the one
    /// after as `shares[c] = (off, lo, hi)` says (the points of one class
    /// fall the same share of a cell past this lane's points,
    /// `block/response/one_lattice.rs`).
    pub(crate) fn add_classes(&mut self, k: i64, run: &[R], shares: &[(usize, R, R)]) {
        if run.is_empty() {
            return;
        }
        let groups = run.len().div_ceil(shares.len());
        self.cover(k, k + groups as i64 + 1);
        let start = (k - self.base) as usize;
        let points = &mut self.points.as_mut_slice()[start..=start + groups + 1];
        for (q, group) in run.chunks(shares.len()).enumerate() {
            for (&d, &(off, lo, hi)) in group.iter().zip(shares) {
                points[q + off] += lo * d;
                points[q + off + 1] += hi * d;
            }
        }
    }

    /// Makes the lane hold points `from` to `to` (zeros where it held
    /// none).
    pub(crate) fn cover(&mut self, from: i64, to: i64) {
        if self.points.is_empty() {
            self.base = from;
        }
        while from < self.base {
            self.points.insert(0, R::zero());
            self.base -= 1;
        }
        let end = usize::try_from(to - self.base + 1).unwrap_or(0);
        let more = end.saturating_sub(self.points.len());
        self.points.extend(std::iter::repeat_n(R::zero(), more));
    }

    /// What point `k` holds, if the lane holds it and it is not zero.
    pub(crate) fn get(&self, k: i64) -> Option<R> {
        usize::try_from(k.wrapping_sub(self.base))
            .ok()
            .and_then(|i| self.points.get(i).copied())
            .filter(|&d| d != R::zero())
    }

    /// [`LatticePoints::add`] on a point the lane does not hold yet, not next
    /// to its newest.
    #[inline(never)]
    fn add_outside(&mut self, k: i64, d: R) {
        if self.points.is_empty() {
            self.base = k;
            self.points.push_back(d);
            return;
        }
        while k < self.base {
            self.points.insert(0, R::zero());
            self.base -= 1;
        }
        let i = (k - self.base) as usize;
        for _ in self.points.len()..=i {
            self.points.push_back(R::zero());
        }
        self.points[i] += d;
    }
}

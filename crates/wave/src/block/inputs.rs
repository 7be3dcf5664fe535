//! What one input port put on an output port's lattice, point by point:
//! the sequence a port's deliveries convolve with the block's response.
//!
//! The first build kept each arrival's two shares as a list of `(point,
//! jump)` and summed, at every delivered point, over the list. On layer
//! survey rod 12 (seed 7) a response rang for 9,000 points and the list
//! held 18,000 shares, so each point cost 28,000 multiply-adds through a
//! deque, 70 % of the run. Kept dense (one number a point, the two shares
//! of neighbouring arrivals added on their common point), the sum is a
//! dot product of two contiguous slices, one read backwards, in four
//! independent running sums that the compiler keeps in vector registers.

use crate::lane::Fifo;
use crate::real::Real;

/// Jumps on consecutive lattice points from `first` on (the points between
/// arrivals hold zero), oldest first.
#[derive(Debug, Clone, Default)]
pub(crate) struct LatticeInputs<R> {
    first: i64,
    jumps: Fifo<R>,
}

impl<R: Real> LatticeInputs<R> {
    pub(crate) fn is_empty(&self) -> bool {
        self.jumps.is_empty()
    }

    /// The oldest point held.
    pub(crate) fn first(&self) -> Option<i64> {
        (!self.jumps.is_empty()).then_some(self.first)
    }

    /// Adds `jump` on point `k`.
    pub(crate) fn add(&mut self, k: i64, jump: R) {
        if self.jumps.is_empty() {
            self.first = k;
        }
        // older than the oldest held (after the old ones were let go): rare
        while k < self.first {
            self.jumps.insert(0, R::zero());
            self.first -= 1;
        }
        let i = usize::try_from(k - self.first).unwrap_or(0);
        while self.jumps.len() <= i {
            self.jumps.push_back(R::zero());
        }
        self.jumps[i] += jump;
    }

    /// Lets go of the points before `k`.
    pub(crate) fn let_go_before(&mut self, k: i64) {
        while self.first < k && self.jumps.pop_front().is_some() {
            self.first += 1;
        }
    }

    /// `sum x[k] taps[m - k]` over the points `k <= m` held within the
    /// taps' reach, and how many multiply-adds it took.
    pub(crate) fn response_at(&self, m: i64, taps: &[R]) -> (R, u64) {
        let (Some(last), Ok(reach)) = (
            self.first.checked_add(self.jumps.len() as i64 - 1),
            i64::try_from(taps.len()),
        ) else {
            return (R::zero(), 0);
        };
        let (lo, hi) = (self.first.max(m - reach + 1), m.min(last));
        if self.jumps.is_empty() || lo > hi {
            return (R::zero(), 0);
        }
        let at = |k: i64| usize::try_from(k).unwrap_or(0);
        let xs = &self.jumps.as_slice()[at(lo - self.first)..=at(hi - self.first)];
        let ts = &taps[at(m - hi)..=at(m - lo)];
        (dot_reversed(xs, ts), xs.len() as u64)
    }
}

/// `sum xs[i] ts[n - 1 - i]` for slices of one length `n`, in four running
/// sums (each a fixed share of the terms, so the result does not depend on
/// anything but the numbers).
#[inline]
fn dot_reversed<R: Real>(xs: &[R], ts: &[R]) -> R {
    debug_assert_eq!(xs.len(), ts.len());
    let mut acc = [R::zero(); 4];
    let (x4, t4) = (xs.chunks_exact(4), ts.rchunks_exact(4));
    let (x_rest, t_rest) = (x4.remainder(), t4.remainder());
    for (x, t) in x4.zip(t4) {
        acc[0] += x[0] * t[3];
        acc[1] += x[1] * t[2];
        acc[2] += x[2] * t[1];
        acc[3] += x[3] * t[0];
    }
    let mut sum = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    for (x, t) in x_rest.iter().zip(t_rest.iter().rev()) {
        sum += *x * *t;
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The plain double sum over every held point, the definition.
    fn by_definition(points: &[(i64, f64)], m: i64, taps: &[f64]) -> f64 {
        points
            .iter()
            .filter_map(|&(k, x)| {
                usize::try_from(m - k)
                    .ok()
                    .and_then(|i| taps.get(i))
                    .map(|t| x * t)
            })
            .sum()
    }

    /// Shares added out of order, on repeated points, after gaps and before
    /// the oldest, with old points let go: every response over a range of
    /// `m` (before, inside and after the held points) is the definition's
    /// to rounding, for taps of every length up to 11 (the four running
    /// sums' remainders).
    #[test]
    fn responses_are_the_convolution_by_definition() {
        let mut next = crate::test_random::xorshift(0x9e37_79b9_7f4a_7c15u64);
        for len in 0..12usize {
            let taps: Vec<f64> = (0..len).map(|i| 1.0 / (1.0 + i as f64) - 0.3).collect();
            let mut inputs = LatticeInputs::<f64>::default();
            let mut held: Vec<(i64, f64)> = Vec::new();
            for step in 0..200 {
                let k = 40 + (next() % 30) as i64 - 10 + step / 4;
                let x = (next() % 1000) as f64 / 500.0 - 1.0;
                inputs.add(k, x);
                held.push((k, x));
                if step % 50 == 49 {
                    let cut = held.iter().map(|p| p.0).min().unwrap_or(0) + 3;
                    inputs.let_go_before(cut);
                    held.retain(|p| p.0 >= cut);
                }
                for m in 20..120 {
                    let (got, adds) = inputs.response_at(m, &taps);
                    let want = by_definition(&held, m, &taps);
                    let scale: f64 = held.iter().map(|p| p.1.abs()).sum::<f64>() + 1.0;
                    assert!(
                        (got - want).abs() <= 1e-14 * scale,
                        "len {len} m {m}: {got} vs {want}"
                    );
                    assert!(adds as usize <= len);
                }
            }
        }
    }
}

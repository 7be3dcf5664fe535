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

//!
//! Past [`DIRECT`] taps a long response is summed by FFT in levels of
//! doubling blocks (`partitioned.rs`); shorter ones as before, to the bit.

use super::partitioned::{DIRECT, LEVELS, Level, Points, TOP, block_size, last_tap};
use crate::lane::Fifo;
use crate::real::Real;

/// Jumps on consecutive lattice points from `first` on (the points between
/// arrivals hold zero), oldest first.
#[derive(Debug, Clone, Default)]
pub(crate) struct LatticeInputs<R> {
    first: i64,
    jumps: Fifo<R>,
    /// The partitioned sums' levels, once a response reached them.
    levels: Vec<Level>,
}

impl<R: Real> LatticeInputs<R> {
    pub(crate) fn is_empty(&self) -> bool {
        self.jumps.is_empty()
    }

    /// `sum |jump|` over the points held.
    pub(crate) fn total_abs(&self) -> R {
        self.jumps.iter().fold(R::zero(), |s, &d| s + d.abs())
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
        // (an arrival on a point a level has read: rare, see `partitioned.rs`)
        for level in &mut self.levels {
            if k < level.read_before() {
                level.forget();
            }
        }
    }

    /// Lets go of the points before `k`. The levels are not told: a port
    /// lets go only the points whose later taps are past its response's
    /// final length (`Block::due`), so what a level read of them adds
    /// zeros (to rounding) to every later output.
    pub(crate) fn let_go_before(&mut self, k: i64) {
        while self.first < k && self.jumps.pop_front().is_some() {
            self.first += 1;
        }
    }

    /// How many of the partitioned sums' levels the sum at `m` takes, and
    /// the first tap past theirs (summed directly; none past the top's). A
    /// level is taken once some held arrival reaches its taps (from `2 n`
    /// on) while the response may still hold any there (`done`: the taps
    /// are the `len` final ones). Below the top it also waits for its
    /// taps to be final through `final_through`: the trace is not extended
    /// ahead for it, which doubled the time of a layer-survey rod whose
    /// trace was all its time (seed 3's rod 32); until then its taps are
    /// summed directly. The top reads a partition ahead of the span.
    fn levels_at(&self, m: i64, done: bool, len: usize, final_through: i64) -> (usize, i64) {
        let Some(oldest) = self.first().filter(|_| R::FFT_SUMS) else {
            return (0, i64::MAX);
        };
        let span = m - oldest;
        let len = i64::try_from(len).unwrap_or(i64::MAX);
        let taken = (0..LEVELS)
            .take_while(|&c| {
                let n = block_size(c);
                let reached = 2 * n <= span && (!done || 2 * n < len);
                reached && (n == TOP || done || final_through >= 4 * n - 1)
            })
            .count();
        let rest = if taken < LEVELS {
            2 * block_size(taken)
        } else {
            i64::MAX
        };
        (taken, rest)
    }

    /// The last tap the sum at `m` reads, which must be final before
    /// [`LatticeInputs::response_at`]: at least the span of the arrivals
    /// held, and the top level's last partition.
    pub(crate) fn last_tap(&self, m: i64, done: bool, len: usize, final_through: i64) -> i64 {
        let Some(oldest) = self.first() else {
            return m;
        };
        let span = m - oldest;
        match self.levels_at(m, done, len, final_through.max(span)) {
            (LEVELS, _) => span.max(last_tap(LEVELS - 1, m, oldest)),
            _ => span,
        }
    }

    /// `sum x[k] taps[m - k]` over the points `k <= m` held within the
    /// taps' reach, and how many multiply-adds it took (about, for the
    /// FFT's part). The taps through [`LatticeInputs::last_tap`] are final,
    /// and those through `final_through`.
    pub(crate) fn response_at(
        &mut self,
        m: i64,
        taps: &[R],
        done: bool,
        final_through: i64,
    ) -> (R, u64) {
        let (c, rest_from) = self.levels_at(m, done, taps.len(), final_through);
        if c == 0 {
            for level in &mut self.levels {
                level.forget();
            }
            return self.direct_at(m, taps, 0);
        }
        let (direct, mut adds) = self.direct_at(m, &taps[..taps.len().min(DIRECT as usize)], 0);
        while self.levels.len() < c {
            self.levels.push(Level::new(self.levels.len()));
        }
        let x = Points {
            first: self.first,
            jumps: self.jumps.as_slice(),
        };
        let mut fft = 0.0;
        for level in &mut self.levels[..c] {
            fft += level.at(m, &x, taps, &mut adds);
        }
        for level in &mut self.levels[c..] {
            level.forget();
        }
        let (rest, rest_adds) = self.direct_at(m, taps, rest_from);
        (direct + R::of(fft) + rest, adds + rest_adds)
    }

    /// `sum x[k] taps[m - k]` over the taps from `from` on, directly.
    fn direct_at(&self, m: i64, taps: &[R], from: i64) -> (R, u64) {
        let (Some(last), Ok(reach)) = (
            self.first.checked_add(self.jumps.len() as i64 - 1),
            i64::try_from(taps.len()),
        ) else {
            return (R::zero(), 0);
        };
        let (lo, hi) = (
            self.first.max(m - reach + 1),
            m.min(last).min(m.saturating_sub(from)),
        );
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
                    let (got, adds) = inputs.response_at(m, &taps, true, i64::MAX);
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

    /// Long responses, summed by the partitioned FFT's levels up to the
    /// top's many partitions (`partitioned.rs`), against the definition:
    /// arrivals land as a port's do (on the point being delivered or the
    /// one before), a few far behind (on points a level has read), the
    /// oldest are let go once the taps are final, and, while the response
    /// is not done, its taps are final only as far as `last_tap` asks or a
    /// random stretch further (later ones are garbage until then, so a
    /// level that read one too early would fail).
    #[test]
    fn long_responses_summed_by_fft_are_the_convolution_by_definition() {
        let mut next = crate::test_random::xorshift(0x2545_f491_4f6c_dd1du64);
        for (len, done, points) in [
            (300, true, 3_000),
            (5_000, false, 12_000),
            (40_000, true, 75_000),
            (45_000, false, 80_000),
        ] {
            let taps: Vec<f64> = (0..len)
                .map(|i| (0.37 * i as f64).sin() * (-(i as f64) / 9_000.0).exp())
                .collect();
            let mut inputs = LatticeInputs::<f64>::default();
            let mut held: Vec<(i64, f64)> = Vec::new();
            let mut seen = if done { taps.clone() } else { vec![1e6; len] };
            let (mut ready, mut worst, mut far) = (if done { i64::MAX } else { -1 }, 0.0f64, 0);
            for m in 0..points {
                if next().is_multiple_of(23) {
                    // a far late one, now and then
                    let back = if next().is_multiple_of(9) {
                        150 + (next() % 400) as i64
                    } else {
                        next() as i64 % 2
                    };
                    let k = (m - back).max(0);
                    let x = (next() % 1000) as f64 / 500.0 - 1.0;
                    far += usize::from(back > 1);
                    inputs.add(k, x);
                    held.push((k, x));
                }
                if done && m % 1_000 == 999 {
                    let cut = m - len as i64 + 1;
                    inputs.let_go_before(cut);
                    held.retain(|p| p.0 >= cut);
                }
                let last = inputs.last_tap(m, done, len, ready);
                if !done && last > ready {
                    // the trace goes as far as asked, now and then further
                    let further = if next().is_multiple_of(5) {
                        (next() % 3_000) as i64
                    } else {
                        0
                    };
                    let to = (last + further).min(len as i64 - 1);
                    for i in (ready + 1).max(0)..=to {
                        seen[i as usize] = taps[i as usize];
                    }
                    ready = last + further;
                }
                let (got, _) = inputs.response_at(m, &seen, done, ready);
                if m % 7 == 0 {
                    let want = by_definition(&held, m, &taps);
                    let scale: f64 = held.iter().map(|p| p.1.abs()).sum::<f64>() + 1.0;
                    worst = worst.max((got - want).abs() / scale);
                }
            }
            assert!(worst <= 1e-13, "len {len}: worst {worst:e}");
            assert!(far > 3, "len {len}: {far} far late arrivals");
            assert!(!inputs.levels.is_empty(), "len {len}: no level used");
        }
    }

    /// The price the choice of blocks charges (`adds_per_point`, in
    /// `partitioned.rs`) is what the sums count: an arrival on every point
    /// of a response that has not rung out, whose taps are final only as
    /// far as `last_tap` asks, costs what the price says at each point's
    /// reach, within a tenth over the finer levels, the coarser ones and
    /// the top's (it was 1.07, 1.03 and 1.04: the partitions' spectra,
    /// computed once, and a level's first blocks, read twice as it starts,
    /// are not priced); one that has rung out
    /// (`len` taps, the oldest arrivals let go as a port lets them go)
    /// costs no more.
    #[test]
    fn the_sums_cost_what_the_price_says() {
        use super::super::partitioned::adds_per_point;
        // ringing: the reach grows with the run, through every level
        let end = 300_000i64;
        let taps: Vec<f64> = (0..end + 4 * TOP).map(|i| 1.0 / (1.0 + i as f64)).collect();
        let mut inputs = LatticeInputs::<f64>::default();
        let ranges = [(200, 4_096), (4_096, 70_000), (70_000, end)];
        let mut sums = [(0u64, 0.0); 3];
        for m in 0..end {
            inputs.add(m, 1.0);
            let ready = inputs.last_tap(m, false, taps.len(), -1);
            let (_, adds) = inputs.response_at(m, &taps, false, ready);
            if let Some(r) = ranges.iter().position(|&(a, b)| (a..b).contains(&m)) {
                sums[r].0 += adds;
                sums[r].1 += adds_per_point(m as f64);
            }
        }
        for (&(a, b), &(counted, priced)) in ranges.iter().zip(&sums) {
            let ratio = counted as f64 / priced;
            assert!(
                (ratio - 1.0).abs() < 0.1,
                "ringing, points {a} to {b}: {ratio}"
            );
        }
        for len in [200usize, 1_000, 9_000, 40_000, 150_000] {
            let taps: Vec<f64> = (0..len).map(|i| 1.0 / (1.0 + i as f64)).collect();
            let window = 8 * TOP;
            // rung out
            let mut inputs = LatticeInputs::<f64>::default();
            let mut counted = 0u64;
            for m in 0..2 * len as i64 + window {
                inputs.add(m, 1.0);
                inputs.let_go_before(m - len as i64 + 1);
                let (_, adds) = inputs.response_at(m, &taps, true, i64::MAX);
                if m >= 2 * len as i64 {
                    counted += adds;
                }
            }
            let per_point = counted as f64 / window as f64;
            let priced = adds_per_point(len as f64 - 1.0);
            assert!(
                per_point < 1.05 * priced,
                "len {len}, rung out: {per_point} against {priced}"
            );
        }
    }
}

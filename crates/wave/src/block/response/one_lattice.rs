//! A block traced on one lattice: every lane of the block on the spacing
//! of its finest.
//!
//! On its layers' own lattices (a share of each layer's transit) a lane's
//! run of points lands on a neighbour's lattice at points that drift
//! against it, so each point is placed alone: its two shares computed, two
//! additions, about 35 ns a front on seed 7's rod 20, whose trace was 96 %
//! of its time. On one lattice a transit is the same whole number of cells
//! and share of a cell for every point of a lane, so a run lands shifted:
//! two multiply-adds a point in a loop the compiler vectorises. The slower
//! layers hold more points (each of the block's lanes as many a unit of
//! time as its fastest), but they are finer for it: the trace stays first
//! order in the lattice spacing, on a lattice that halves with the
//! ladder's, and the ladder measures it with the rest. The fastest layer
//! is not nested (`nested.rs`): its neighbours' lattices are its own.
//!
//! What a traced point costs in the work the budget counts stays what the
//! fronts it stands for on the layer's own lattice cost, so a ladder runs
//! the levels it ran before; and what the block still holds is summed no
//! more often than the trace takes eight times the points it holds.

use super::{Shape, Trace};
use crate::real::Real;

#[cfg(test)]
mod tests;

/// On one lattice, what the block holds is summed once the trace has taken
/// this many times the points it held at the last sum: the sums then cost
/// an eighth of a multiply-add a point taken (at one, they took a fifth of
/// the time), and the trace runs on at most that much past its end.
const HELD_EVERY: usize = 8;

/// The most points a block's lanes may hold on one lattice (a transit's
/// worth each, on the finest spacing): 2 MiB of them a trace. Seed 3's
/// rod 32, whose block holds two layers 77,000 times slower than its
/// fastest, would hold 7 M points a trace, and its run peaked at 521 MiB
/// against 34 on each layer's own lattice.
const MOST_POINTS: f64 = (1 << 18) as f64;

impl<R: Real> Shape<R> {
    /// Whether the block's lanes fit on one lattice: at most
    /// [`MOST_POINTS`] on its finest spacing.
    pub(crate) fn fits_one_lattice(&self) -> bool {
        let finest = self
            .spacing
            .iter()
            .map(|s| s.to_f64())
            .fold(f64::INFINITY, f64::min);
        let points: f64 = self
            .layers
            .iter()
            .map(|l| 2.0 * l.transit_time.to_f64() / finest)
            .sum();
        points <= MOST_POINTS
    }

    /// Puts every lane of the block on its finest lattice: the spacings,
    /// each layer's transit in cells, and what a point stands for.
    pub(crate) fn share_one_lattice(&mut self) {
        let finest = self
            .spacing
            .iter()
            .copied()
            .fold(-R::neg_infinity(), |a, b| a.min(b));
        self.work_share = self
            .spacing
            .iter()
            .map(|&s| (finest / s).to_f64())
            .collect();
        self.shift = Some(
            self.layers
                .iter()
                .map(|l| {
                    let cells = l.transit_time / finest;
                    let whole = cells.floor();
                    (whole.to_f64() as i64, cells - whole)
                })
                .collect(),
        );
        self.spacing.iter_mut().for_each(|s| *s = finest);
        self.per_spacing
            .iter_mut()
            .for_each(|s| *s = R::one() / finest);
        self.nest = None;
    }
}

impl<R: Real> Trace<R> {
    /// Lane `i`'s points arriving before `end`, taken out and added to
    /// their destinations shifted by the lane's transit (`cells` whole
    /// cells and `share` of one): [`Trace::take_lane`] on one lattice.
    pub(super) fn take_lane_shifted(
        &mut self,
        shape: &Shape<R>,
        i: usize,
        end: R,
        (cells, share): (i64, R),
    ) {
        let (m, up) = (i / 2, i.is_multiple_of(2));
        let (s, transit) = (shape.spacing[m], shape.layers[m].transit_time);
        let lane = &mut self.lanes[i];
        let first = lane.base;
        let arrives = |j: usize| R::of((first + j as i64) as f64) * s + transit;
        let len = lane.points.len();
        // the first point arriving at or after `end`, from its estimate
        let guess = ((end - transit) / s).ceil().to_f64() - first as f64;
        let mut n = guess.clamp(0.0, len as f64) as usize;
        while n > 0 && arrives(n - 1) >= end {
            n -= 1;
        }
        while n < len && arrives(n) < end {
            n += 1;
        }
        if n == 0 {
            return;
        }
        let run = self.take_run(i, n);
        self.shared_work += n as f64 * shape.work_share[m];
        self.taken_since += n;
        let from = (first, s, transit);
        let top = shape.layers.len() - 1;
        let to = first + cells;
        let shifted = |trace: &mut Self, (m, up): (usize, bool), coef: R| {
            trace.lanes[2 * m + usize::from(!up)].add_shifted(
                to,
                &run,
                coef * (R::one() - share),
                coef * share,
            );
        };
        match (up, m) {
            (true, m) if m < top => {
                let k = shape.inner[m];
                shifted(self, (m, false), k.up_reflected);
                shifted(self, (m + 1, true), k.up_transmitted);
            }
            (true, _) => match shape.upper {
                Some(k) => {
                    shifted(self, (m, false), k.up_reflected);
                    self.leave_shifted(shape, &run, from, 1, k.up_transmitted);
                }
                None => shifted(self, (m, false), -R::one()),
            },
            (false, 0) => {
                let k = shape.lower;
                shifted(self, (0, true), k.down_reflected);
                self.leave_shifted(shape, &run, from, 0, k.down_transmitted);
            }
            (false, m) => {
                let k = shape.inner[m - 1];
                shifted(self, (m, true), k.down_reflected);
                shifted(self, (m - 1, false), k.down_transmitted);
            }
        }
        self.run = run;
    }

    /// The fronts `coef * x` that a run's points cause leaving at port
    /// `o`, on its lattice: [`Trace::leave_run`] with the points' places
    /// on the port's lattice stepped by one product each (a division per
    /// point was a sixth of the trace's time).
    fn leave_shifted(
        &mut self,
        shape: &Shape<R>,
        run: &[R],
        (first, s, transit): (i64, R, R),
        o: usize,
        coef: R,
    ) {
        let per = R::one() / shape.port_spacing[o];
        let (start, step) = ((R::of(first as f64) * s + transit) * per, s * per);
        let last = start + R::of(run.len() as f64) * step;
        let taps = &mut self.taps[o];
        let need = last.floor().to_f64() as usize + 2;
        if taps.len() < need {
            taps.resize(need, R::zero());
        }
        // a port's cells are mostly many of the block's: each cell's
        // points are summed apart (their jumps, and their jumps by index,
        // from which the upper shares follow) and added once, not point
        // by point through memory (two thirds of the trace of seed 7's
        // rod 12)
        let place = |j: usize| start + R::of(j as f64) * step;
        let mut j = 0;
        while j < run.len() {
            // (places are not negative: truncation is the floor)
            let k = place(j).to_f64() as usize;
            let next = R::of((k + 1) as f64);
            let mut end =
                (((next - start) / step).ceil().to_f64().max(0.0) as usize).clamp(j + 1, run.len());
            while end > j + 1 && place(end - 1) >= next {
                end -= 1;
            }
            while end < run.len() && place(end) < next {
                end += 1;
            }
            let (jumps, by_index) = sums(&run[j..end]);
            let upper = (place(j) - R::of(k as f64)) * jumps + step * by_index;
            taps[k] += coef * (jumps - upper);
            taps[k + 1] += coef * upper;
            j = end;
        }
    }

    /// Whether what the block holds is due to be summed: every sixteenth
    /// step, and on one lattice only once the trace has taken
    /// [`HELD_EVERY`] times the points it held at the last sum (its slow
    /// layers hold many, each taken once a transit).
    pub(super) fn held_due(&mut self, shape: &Shape<R>) -> bool {
        if !self.steps.is_multiple_of(16) {
            return false;
        }
        if shape.shift.is_none() {
            return true;
        }
        if self.taken_since < HELD_EVERY * self.held_points {
            return false;
        }
        self.taken_since = 0;
        self.held_points = self.lanes.iter().map(|l| l.points.len()).sum();
        true
    }
}

/// `(sum x_i, sum i x_i)` over `xs`, in four independent sums each (a
/// single sum waits on its last addition).
fn sums<R: Real>(xs: &[R]) -> (R, R) {
    let (mut s, mut w) = ([R::zero(); 4], [R::zero(); 4]);
    let mut chunks = xs.chunks_exact(4);
    let mut i = R::zero();
    for c in &mut chunks {
        for l in 0..4 {
            s[l] += c[l];
            w[l] += (i + R::of(l as f64)) * c[l];
        }
        i += R::of(4.0);
    }
    for (l, &x) in chunks.remainder().iter().enumerate() {
        s[l] += x;
        w[l] += (i + R::of(l as f64)) * x;
    }
    ((s[0] + s[1]) + (s[2] + s[3]), (w[0] + w[1]) + (w[2] + w[3]))
}

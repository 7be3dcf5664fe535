//! A block traced on one lattice: every lane of the block on its finest
//! lane's spacing `h` times a power of two.
//!
//! On its layers' own lattices (a share of each layer's transit) a lane's
//! run of points lands on a neighbour's lattice at points that drift
//! against it, so each point is placed alone: its two shares computed, two
//! additions, about 35 ns a front on seed 7's rod 20, whose trace was 96 %
//! of its time. On lattices that nest (each layer's `h 2^a`, the largest
//! not coarser than its own) a transit is the same whole number of cells
//! and share of a cell for every point of a lane, so a run lands shifted:
//! two multiply-adds a point. Into a lane as fine, in a loop the compiler
//! vectorises; into a finer one, a point every `2^a` of its points; into
//! a coarser one, class by class of the run's points (those `2^a` apart
//! fall the same share of a cell past the destination's points), or,
//! where 16 or more share a cell ([`BY_CELL_FROM`]), summed cell by cell
//! as at a port. Each layer's lattice is its own or up to twice as fine: the
//! trace stays first order in a spacing that halves with the ladder's,
//! and the ladder measures it with the rest. (On the finest lattice in
//! every lane, as first built, a slow layer held as many points a unit of
//! time as the fastest: seed 7's rod 12 took 389 M points for its own
//! lattices' 99 M fronts, and seed 3's rod 32, two of whose layers are
//! 77,000 times slower than its fastest, would have held 7 M points a
//! trace.) The fastest layer is not nested (`nested.rs`): its neighbours'
//! lattices are its own.
//!
//! A block's fastest layer, where the next is at least 1.1 times slower,
//! is swept point by point within the others' step (`sweep.rs`), not
//! taken a few points a step.
//!
//! What a traced point costs in the work the budget counts stays what the
//! fronts it stands for on the layer's own lattice cost, so a ladder runs
//! the levels it ran before; and what the block still holds is summed no
//! more often than the trace takes eight times the points it holds.

use super::{Shape, Trace};
use crate::real::Real;

mod sweep;
#[cfg(test)]
mod tests;

/// On one lattice, what the block holds is summed once the trace has taken
/// this many times the points it held at the last sum: the sums then cost
/// an eighth of a multiply-add a point taken (at one, they took a fifth of
/// the time), and the trace runs on at most that much past its end.
const HELD_EVERY: usize = 8;

/// The most points a block's lanes may hold on one lattice (a transit's
/// worth each): 2 MiB of them a trace. A lane holds at most twice what it
/// holds on its layer's own lattice, so only a block whose own lattices
/// hold over half as many stays on them. (On the finest spacing in every
/// lane, seed 3's rod 32 held 7 M points a trace and peaked at 521 MiB,
/// against 34 on each layer's own lattice.)
const MOST_POINTS: f64 = (1 << 18) as f64;

/// A run into a lane `2^BY_CELL_FROM` times coarser or more is summed cell
/// by cell (a division and a search a cell); into one less coarse, class
/// by class of its points.
const BY_CELL_FROM: u32 = 4;

impl<R: Real> Shape<R> {
    /// The finest of the block's spacings, and each layer's power of two
    /// over it on one lattice: the largest that is not coarser than its
    /// own spacing.
    fn one_lattice_powers(&self) -> (R, Vec<u32>) {
        let finest = self
            .spacing
            .iter()
            .copied()
            .fold(-R::neg_infinity(), |a, b| a.min(b));
        let powers = self
            .spacing
            .iter()
            .map(|&s| (s / finest).to_f64().log2().floor().clamp(0.0, 60.0) as u32)
            .collect();
        (finest, powers)
    }

    /// Whether the block's lanes fit on one lattice: at most
    /// [`MOST_POINTS`] there.
    pub(crate) fn fits_one_lattice(&self) -> bool {
        let (finest, powers) = self.one_lattice_powers();
        let points: f64 = self
            .layers
            .iter()
            .zip(&powers)
            .map(|(l, &a)| 2.0 * l.transit_time.to_f64() / (finest.to_f64() * 2f64.powi(a as i32)))
            .sum();
        points <= MOST_POINTS
    }

    /// Puts every lane of the block on its finest lattice times a power
    /// of two: the spacings, and how many fronts of the layer's own
    /// lattice a point stands for.
    pub(crate) fn share_one_lattice(&mut self) {
        let (finest, powers) = self.one_lattice_powers();
        let shared: Vec<R> = powers
            .iter()
            .map(|&a| finest * R::of(2f64.powi(a as i32)))
            .collect();
        self.work_share = shared
            .iter()
            .zip(&self.spacing)
            .map(|(&n, &s)| (n / s).to_f64())
            .collect();
        self.per_spacing = shared.iter().map(|&s| R::one() / s).collect();
        self.spacing = shared;
        self.powers = Some(powers);
        self.nest = None;
    }
}

impl<R: Real> Trace<R> {
    /// Lane `i`'s points arriving before `end`, taken out and added to
    /// their destinations shifted by the lane's transit: [`Trace::take_lane`]
    /// on one lattice.
    pub(super) fn take_lane_shifted(&mut self, shape: &Shape<R>, i: usize, end: R, powers: &[u32]) {
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
        let shifted = |trace: &mut Self, to: (usize, bool), coef: R| {
            trace.land_shifted(shape, powers, (m, first), &run, to, coef);
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

    /// The fronts `coef * x` that the points `x` of a run of layer `m`'s
    /// lane (from its lattice point `first` on) cause in lane (`d`, up or
    /// down), landed shifted by the layer's transit.
    pub(super) fn land_shifted(
        &mut self,
        shape: &Shape<R>,
        powers: &[u32],
        (m, first): (usize, i64),
        run: &[R],
        (d, up): (usize, bool),
        coef: R,
    ) {
        let transit = shape.layers[m].transit_time;
        let lane = &mut self.lanes[2 * d + usize::from(!up)];
        // the run's arrivals in the destination's cells
        let cells = transit * shape.per_spacing[d];
        if powers[m] >= powers[d] {
            // every point the same share of a cell past one of its
            // points, `stride` of them apart
            let stride = 1usize << (powers[m] - powers[d]);
            let whole = cells.floor();
            let share = cells - whole;
            let to = first * stride as i64 + whole.to_f64() as i64;
            lane.add_strided(to, stride, run, coef * (R::one() - share), coef * share);
        } else if powers[d] - powers[m] < BY_CELL_FROM {
            // the points `every` apart fall the same share of a cell
            // past the destination's points: each class's share once
            let every = 1usize << (powers[d] - powers[m]);
            let per = R::one() / R::of(every as f64);
            let at = R::of(first as f64) * per + cells;
            let whole = at.floor();
            let mut shares = [(0, R::zero(), R::zero()); 1 << (BY_CELL_FROM - 1)];
            for (c, s) in shares[..every].iter_mut().enumerate() {
                let past = (at - whole) + R::of(c as f64) * per;
                let (off, share) = if past >= R::one() {
                    (1, past - R::one())
                } else {
                    (0, past)
                };
                *s = (off, coef * (R::one() - share), coef * share);
            }
            lane.add_classes(whole.to_f64() as i64, run, &shares[..every]);
        } else {
            // many points to a cell: summed apart, as at a port
            let per = R::one() / R::of(2f64.powi((powers[d] - powers[m]) as i32));
            let start = R::of(first as f64) * per + cells;
            by_cell(run, start, per, |k, lower, upper| {
                lane.add(k as i64, coef * lower);
                lane.add(k as i64 + 1, coef * upper);
            });
        }
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
        by_cell(run, start, step, |k, lower, upper| {
            taps[k] += coef * lower;
            taps[k + 1] += coef * upper;
        });
    }

    /// Whether what the block holds is due to be summed: every sixteenth
    /// step, and on one lattice only once the trace has taken
    /// [`HELD_EVERY`] times the points it held at the last sum (its slow
    /// layers hold many, each taken once a transit).
    pub(super) fn held_due(&mut self, shape: &Shape<R>) -> bool {
        if !self.steps.is_multiple_of(16) {
            return false;
        }
        if shape.powers.is_none() {
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

/// The points of a run placed at `start + j step` (in cells, not
/// negative) cell by cell: `put(k, lower, upper)` with what falls on cell
/// `k`'s lower and upper points, jump and first moment kept.
fn by_cell<R: Real>(run: &[R], start: R, step: R, mut put: impl FnMut(usize, R, R)) {
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
        put(k, jumps - upper, upper);
        j = end;
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

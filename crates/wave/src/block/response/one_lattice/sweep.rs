//! A block's fastest layer on one lattice, swept point by point.
//!
//! A trace's step is the shortest transit less a cell, so that no front
//! born within a step arrives within it. The block's fastest layer sets
//! the step, and every step takes each of its lanes a run of a few
//! points and pays a run's bookkeeping for them: far the most where that
//! layer is far faster than the rest: seed 3's rod 32 (a layer of
//! transit `1.1e-6` beside ones of `1.7e-5` and more) spent about 1,850
//! instructions a step, nearly all of its time, on runs of four points.
//! Within a step of the other layers that layer's two lanes feed only
//! each other, and a point's reflection lands at least a cell after it
//! (its transit is at least a cell). So where the next layer is at least
//! [`SWEEP_FROM`] times slower, the step is the other layers', and the
//! fastest layer's points are swept in time order, each taken
//! final, its two reflections added to the points ahead, and what it
//! sends out gathered into runs landed on its neighbours as any lane's.
//! The deposits are the same, summed in another order: the taps agree
//! to rounding (`one_lattice/tests.rs` sets them against the lattice
//! taken point by point).

use super::super::{Shape, Trace};
use crate::real::Real;

/// The fastest layer is swept where every other layer's transit less a
/// cell is at least this many times its own (where two are as fast,
/// nothing is gained). A step only a little longer pays already: at the
/// ladder's first level (callgrind of the `level_probe` example at 0.2
/// of a transit), sweeping from 1.5 instead of 4 took seed 29's rod 3
/// (a neighbour 2.3 times slower) 34 % fewer instructions, the
/// fast-bottom draw's rods 5, 13 and 20 31, 27 and 18 % fewer, and from
/// 1.1 its rod 31 18 % fewer again.
const SWEEP_FROM: f64 = 1.1;

impl<R: Real> Shape<R> {
    /// On one lattice: the layer whose lanes are swept point by point,
    /// and the step the others allow.
    pub(crate) fn swept_layer(&self) -> Option<(usize, R)> {
        self.powers.as_ref()?;
        let room = |m: usize| self.layers[m].transit_time - self.spacing[m];
        let f = (0..self.layers.len())
            .min_by(|&a, &b| room(a).to_f64().total_cmp(&room(b).to_f64()))?;
        let step = (0..self.layers.len())
            .filter(|&m| m != f)
            .map(room)
            .fold(-R::neg_infinity(), |a, b| a.min(b));
        let at_least_a_cell = self.layers[f].transit_time >= self.spacing[f];
        (at_least_a_cell && step.is_finite() && step >= R::of(SWEEP_FROM) * room(f))
            .then_some((f, step))
    }
}

impl<R: Real> Trace<R> {
    /// Layer `f`'s points arriving before `end`, swept in time order: each
    /// point's reflection added ahead in the other lane, and what leaves
    /// the layer landed on its neighbours (or ports) run by run.
    pub(in crate::block::response) fn sweep(
        &mut self,
        shape: &Shape<R>,
        f: usize,
        end: R,
        powers: &[u32],
    ) {
        let (h, transit) = (shape.spacing[f], shape.layers[f].transit_time);
        let (up, down) = (2 * f, 2 * f + 1);
        let Some(first) = [up, down]
            .iter()
            .filter(|&&i| !self.lanes[i].points.is_empty())
            .map(|&i| self.lanes[i].base)
            .min()
        else {
            return;
        };
        // the first point arriving at or after `end`
        let arrives = |k: i64| R::of(k as f64) * h + transit;
        let mut n = ((end - transit) / h).ceil().to_f64() as i64;
        while arrives(n - 1) >= end {
            n -= 1;
        }
        while arrives(n) < end {
            n += 1;
        }
        if n <= first {
            return;
        }
        let len = (n - first) as usize;
        let cells = transit * shape.per_spacing[f];
        let whole = cells.floor();
        let share = cells - whole;
        let w = whole.to_f64() as usize;
        let top = shape.layers.len() - 1;
        let at_top = match (f < top, shape.upper) {
            (true, _) => shape.inner[f].up_reflected,
            (false, Some(k)) => k.up_reflected,
            (false, None) => -R::one(),
        };
        let at_bottom = match f {
            0 => shape.lower.down_reflected,
            _ => shape.inner[f - 1].down_reflected,
        };
        for i in [up, down] {
            self.lanes[i].cover(first, n + w as i64);
        }
        let (below, above) = self.lanes.split_at_mut(down);
        let (u, d) = (
            below[up].points.as_mut_slice(),
            above[0].points.as_mut_slice(),
        );
        let (top_lo, top_hi) = (at_top * (R::one() - share), at_top * share);
        let (bottom_lo, bottom_hi) = (at_bottom * (R::one() - share), at_bottom * share);
        for i in 0..len {
            let (x, y) = (u[i], d[i]);
            d[i + w] += top_lo * x;
            d[i + w + 1] += top_hi * x;
            u[i + w] += bottom_lo * y;
            u[i + w + 1] += bottom_hi * y;
        }
        let up_run = self.take_run(up, len);
        let room = std::mem::take(&mut self.run_down);
        let down_run = self.take_run_into(down, len, room);
        self.shared_work += 2.0 * len as f64 * shape.work_share[f];
        self.taken_since += 2 * len;
        let from = (first, h, transit);
        match (f < top, shape.upper) {
            (true, _) => {
                let k = shape.inner[f].up_transmitted;
                self.land_shifted(shape, powers, (f, first), &up_run, (f + 1, true), k);
            }
            (false, Some(k)) => self.leave_shifted(shape, &up_run, from, 1, k.up_transmitted),
            (false, None) => {}
        }
        match f {
            0 => self.leave_shifted(shape, &down_run, from, 0, shape.lower.down_transmitted),
            _ => {
                let k = shape.inner[f - 1].down_transmitted;
                self.land_shifted(shape, powers, (f, first), &down_run, (f - 1, false), k);
            }
        }
        self.run = up_run;
        self.run_down = down_run;
    }
}

//! A block's response: what comes out of its ports, on the neighbours'
//! lattices, for one front going in.
//!
//! The block's layers are traced alone between neighbours that take every
//! front leaving it and send nothing back: what the neighbours send back
//! is a later input, answered by the same response (the block is linear
//! and does not change in time). The trace is the merged engine's own on
//! a small scale: the same scattering at every boundary, the same lattice
//! of births in each of the block's lanes, placed from the input's
//! instant. A front leaving the block is deposited on its port's lattice
//! as a lattice lane deposits it (split between the two nearest points so
//! that its jump and first moment are kept), with the input on the
//! lattice's point 0.
//!
//! The trace goes only as far as the run needs it: a port about to deliver
//! lattice point `m` asks for the response up to `m` cells after its
//! oldest input, so a block costs at most what its trace of the run's
//! length costs, however long it rings. It is done when what the block
//! still holds could carry less than a `1e-13` share of the input's
//! velocity; that rest is counted as dropped at every input.

use crate::engine::LayerConst;
use crate::lane::LatticePoints as TraceLane;
use crate::real::Real;
use impact_model::InterfaceCoefficients;
use nested::Inner;

mod nested;
mod one_lattice;
pub(crate) use nested::nested_layer;

/// What the block still holds, as a share of the input's velocity, when
/// its trace is done.
pub(crate) const REST: f64 = 1e-13;

/// Fronts carrying at least this share of the input's velocity are
/// followed at their exact times, as a lattice lane keeps its large fronts
/// where they were born (`KEEP_ABOVE` in the engine's setup): the first
/// fronts through a block decide contacts, and on the lattice their
/// timing was lost by up to the block's round trip whatever the spacing
/// (a four-layer rod's contact ended `2e-4` early, `e` off by `4e-4` under
/// a bound of `3e-13`: the levels agreed).
pub(crate) const KEEP_SHARE: f64 = 1e-2;

/// At most this many fronts of one trace followed exactly.
pub(crate) const KEEP_AT_MOST: usize = 32;

/// The block between its neighbours, as its trace needs it.
#[derive(Debug, Clone)]
pub(crate) struct Shape<R> {
    /// The block's layers, bottom first.
    pub layers: Vec<LayerConst<R>>,
    /// The block's own interfaces, bottom first (`layers.len() - 1`).
    pub inner: Vec<InterfaceCoefficients<R>>,
    /// The interface with the layer below.
    pub lower: InterfaceCoefficients<R>,
    /// The interface with the layer above, or `None` at the free top.
    pub upper: Option<InterfaceCoefficients<R>>,
    /// Lattice spacing of the block's lanes, per layer.
    pub spacing: Vec<R>,
    /// Their reciprocals (a division was most of a front's price).
    pub per_spacing: Vec<R>,
    /// Lattice spacing of the lane each port feeds (lower, then upper).
    pub port_spacing: Vec<R>,
    /// Wave speeds of the neighbours an input comes from (lower, upper).
    pub port_speed: Vec<R>,
    /// The layer answered by its own response inside the trace, if any
    /// (`response/nested.rs`).
    pub nest: Option<usize>,
    /// Whether the response's large fronts are followed at their exact
    /// times: not in a nested block's response for the lattice points
    /// arriving at it, where each arrival would queue them (on survey rod
    /// 20 the queues took half the time); they go on its ports' lattices
    /// with the rest, and the trace's own large fronts take a copy that
    /// keeps them (`response/nested.rs`).
    pub keep_exact: bool,
    /// Where the block's lanes all share one lattice (`one_lattice.rs`):
    /// per layer, its spacing is the finest's times two to this power.
    pub powers: Option<Vec<u32>>,
    /// Per layer: how many fronts on the layer's own lattice one traced
    /// point stands for, in the work counted (1 without a shared lattice).
    pub work_share: Vec<f64>,
}

/// The response to a unit jump arriving at one input port, traced as far
/// as asked.
#[derive(Debug, Clone)]
pub(crate) struct Trace<R> {
    lanes: Vec<TraceLane<R>>,
    /// Per output port: deposits on its lattice, point `k` at `[k]`.
    pub taps: Vec<Vec<R>>,
    /// Per output port: the fronts that leave it from exactly followed
    /// ones, `(delay, jump)` in the order they leave.
    pub exact: Vec<Vec<(R, R)>>,
    /// Fronts followed exactly: born, jump, lane.
    kept: Vec<(R, R, usize)>,
    /// The points of a lane being taken (room kept from step to step).
    run: Vec<R>,
    /// The swept layer's down lane's points being taken (room kept).
    run_down: Vec<R>,
    /// On one lattice: the layer swept point by point within each step
    /// (`one_lattice/sweep.rs`).
    swept: Option<usize>,
    /// A run's arrivals at the nested layer, `(time, jump)` (room kept).
    arrivals: Vec<(R, R)>,
    /// How many were ever kept.
    kept_ever: usize,
    /// A front is kept when its velocity jump is at least this.
    keep: R,
    /// Every front arriving before this has been followed.
    pub reached: R,
    /// The trace's step: no front born within it arrives within it (a
    /// front is born at most a spacing before its birth on the lattice,
    /// and travels a transit), but in the swept layer, whose points are
    /// taken in time order within it (`one_lattice/sweep.rs`).
    step: R,
    /// Nothing the block holds matters any more: the taps are final.
    pub done: bool,
    /// Velocity (`sum |d| c`) and force (`sum E |d|`) of what was dropped
    /// or left when done, per unit input.
    pub rest: (f64, f64),
    dropped: (R, R),
    stop: R,
    tiny: R,
    /// Fronts followed.
    followed: u64,
    /// On one lattice: the fronts the points taken stand for
    /// (`one_lattice.rs`).
    shared_work: f64,
    /// On one lattice: points taken since what the block holds was last
    /// summed, and how many it held then.
    taken_since: usize,
    held_points: usize,
    /// On one lattice: per lane, the time before which its arrivals were
    /// taken.
    taken_until: Vec<R>,
    steps: u64,
    /// The nested layer's block, if the shape nests one.
    inner: Option<Inner<R>>,
}

/// Splits a jump born at `t` between the lattice points around it: the
/// lower point's index and the two shares.
fn split<R: Real>(t: R, spacing: R) -> (R, R, R) {
    let k = (t / spacing).floor();
    let f = (t - k * spacing) / spacing;
    (k, R::one() - f, f)
}

/// Deposits `d` born at `t` on a port's lattice.
fn deposit<R: Real>(taps: &mut Vec<R>, t: R, d: R, spacing: R) {
    let (k, lo, hi) = split(t, spacing);
    let k = k.to_f64() as usize;
    if taps.len() < k + 2 {
        taps.resize(k + 2, R::zero());
    }
    taps[k] += d * lo;
    taps[k + 1] += d * hi;
}

impl<R: Real> Trace<R> {
    /// The trace of a unit jump arriving at port `input` at time 0, before
    /// any front is followed.
    pub(crate) fn start(shape: &Shape<R>, input: usize) -> Self {
        let nb = shape.layers.len();
        // fronts too small to follow, and when to stop, in velocity per
        // unit input (the input's velocity jump is `c_in`)
        let stop = R::of(REST) * shape.port_speed[input];
        let swept = shape.swept_layer();
        let step = match (shape.nest, swept) {
            (Some(f), _) => Self::nested_step(shape, f),
            (None, Some((_, step))) => step,
            (None, None) => shape
                .layers
                .iter()
                .zip(&shape.spacing)
                .map(|(l, &s)| l.transit_time - s)
                .fold(-R::neg_infinity(), |a, b| a.min(b)),
        };
        let mut trace = Self {
            lanes: (0..2 * nb).map(|_| TraceLane::default()).collect(),
            taps: vec![Vec::new(); shape.port_spacing.len()],
            exact: vec![Vec::new(); shape.port_spacing.len()],
            kept: Vec::new(),
            run: Vec::new(),
            run_down: Vec::new(),
            swept: swept.map(|(f, _)| f),
            arrivals: Vec::new(),
            kept_ever: 0,
            keep: if shape.keep_exact {
                R::of(KEEP_SHARE) * shape.port_speed[input]
            } else {
                -R::neg_infinity()
            },
            reached: R::zero(),
            step,
            steps: 0,
            done: false,
            rest: (0.0, 0.0),
            dropped: (R::zero(), R::zero()),
            stop,
            tiny: stop * R::of(1e-6),
            followed: 0,
            shared_work: 0.0,
            taken_since: 0,
            held_points: 0,
            taken_until: vec![R::zero(); 2 * nb],
            inner: shape.nest.map(|f| Inner::new(shape, f)),
        };
        match (input, shape.upper) {
            (0, _) => trace.enter(shape, 0, true, R::zero(), shape.lower.up_transmitted, true),
            (_, Some(upper)) => trace.enter(
                shape,
                nb - 1,
                false,
                R::zero(),
                upper.down_transmitted,
                true,
            ),
            (_, None) => trace.done = true,
        }
        // the exact fronts are few and leave within a few round trips:
        // all their outputs are known before the first arrival
        while !trace.kept.is_empty() && !trace.done {
            let next = trace.reached + trace.step;
            trace.extend_to(shape, next);
        }
        trace
    }

    /// A front born at `t` in lane (`m`, up or down): followed exactly if
    /// its parent was and it is large enough (and few were), else on the
    /// lane's lattice.
    #[inline]
    fn enter(&mut self, shape: &Shape<R>, m: usize, up: bool, t: R, d: R, exact: bool) {
        let lane = 2 * m + usize::from(!up);
        if exact
            && (d * shape.layers[m].wave_speed).abs() >= self.keep
            && self.kept_ever < KEEP_AT_MOST
        {
            self.kept_ever += 1;
            self.kept.push((t, d, lane));
        } else {
            self.push(shape, m, up, t, d);
        }
    }

    /// A front leaving the block at port `o` at `t`: exactly, or on the
    /// port's lattice.
    #[inline]
    fn leave(&mut self, shape: &Shape<R>, o: usize, t: R, d: R, exact: bool) {
        if exact {
            self.exact[o].push((t, d));
        } else {
            deposit(&mut self.taps[o], t, d, shape.port_spacing[o]);
        }
    }

    /// Whether port `out`'s tap `k` is final.
    #[inline]
    pub(crate) fn has(&self, shape: &Shape<R>, out: usize, k: i64) -> bool {
        self.done || R::of((k + 1) as f64) * shape.port_spacing[out] <= self.reached
    }

    /// The last of port `out`'s taps that is final (all of them once done).
    pub(crate) fn final_through(&self, shape: &Shape<R>, out: usize) -> i64 {
        if self.done {
            return i64::MAX;
        }
        let mut k = (self.reached / shape.port_spacing[out]).floor().to_f64() as i64 - 1;
        while k >= 0 && !self.has(shape, out, k) {
            k -= 1;
        }
        while self.has(shape, out, k + 1) {
            k += 1;
        }
        k
    }

    /// A front born at `t` in the block's lane (`m`, up or down), on the
    /// lane's lattice.
    fn push(&mut self, shape: &Shape<R>, m: usize, up: bool, t: R, d: R) {
        let l = &shape.layers[m];
        if (d * l.wave_speed).abs() < self.tiny {
            self.dropped.0 += (d * l.wave_speed).abs();
            self.dropped.1 += (d * l.modulus).abs();
            return;
        }
        let lane = &mut self.lanes[2 * m + usize::from(!up)];
        // (births are at or after the input, so truncation is the floor)
        let x = t * shape.per_spacing[m];
        let k = x.to_f64() as i64;
        let hi = x - R::of(k as f64);
        lane.add(k, d * (R::one() - hi));
        if hi != R::zero() {
            lane.add(k + 1, d * hi);
        }
    }

    /// Follows fronts until port `out`'s tap `k` is final (or the trace is
    /// done); the fronts followed. Step by step: every front arriving
    /// within a step was born before it, so the lanes are taken one after
    /// another (scattering is linear, and deposits add).
    pub(crate) fn extend(&mut self, shape: &Shape<R>, out: usize, k: i64) -> u64 {
        let before = self.work();
        let until = R::of((k + 1) as f64) * shape.port_spacing[out];
        self.extend_to(shape, until);
        self.work() - before
    }

    /// The fronts followed, and those the points taken on one lattice stand
    /// for.
    fn work(&self) -> u64 {
        self.followed + self.shared_work as u64
    }

    /// Follows every front arriving before `until` (or until done).
    fn extend_to(&mut self, shape: &Shape<R>, until: R) {
        while !self.done && self.reached < until {
            if self.kept.is_empty()
                && self.lanes.iter().all(|l| l.points.is_empty())
                && self.nested_pending() == R::zero()
            {
                self.finish(shape);
                break;
            }
            self.steps += 1;
            if self.held_due(shape) && self.held(shape) < self.stop {
                self.finish(shape);
                break;
            }
            let end = self.reached + self.step;
            let mut n = 0;
            while n < self.kept.len() {
                let (born, d, lane) = self.kept[n];
                let at = born + shape.layers[lane / 2].transit_time;
                if at < end {
                    self.kept.swap_remove(n);
                    self.followed += 1;
                    self.scatter(shape, lane / 2, lane % 2 == 0, at, d, true);
                } else {
                    n += 1;
                }
            }
            match &shape.powers {
                Some(powers) => {
                    for i in 0..self.lanes.len() {
                        if self.taken_until[i] < end && Some(i / 2) != self.swept {
                            // every point born before `reached` less a
                            // cell is final: a slow lane takes them all
                            let (s, t) = (shape.spacing[i / 2], shape.layers[i / 2].transit_time);
                            let until = self.reached - s + t;
                            self.take_lane_shifted(shape, i, until, powers);
                            self.taken_until[i] = until;
                        }
                    }
                    if let Some(f) = self.swept {
                        self.sweep(shape, f, end, powers);
                    }
                }
                None => {
                    for i in 0..self.lanes.len() {
                        self.take_lane(shape, i, end);
                    }
                }
            }
            if self.inner.is_some() {
                self.deliver_nested(shape, end);
            }
            self.reached = end;
        }
    }

    /// Lane `i`'s points arriving before `end`, taken out and scattered
    /// together. Each of the two fronts a point causes goes into one lane
    /// or port, at times in arithmetic progression, so the lane's run is
    /// one tight loop per destination instead of a call per front and
    /// destination (rod 20 of the layer survey spent 95 % of its time in
    /// the trace, at about 36 ns a front). A destination's points take
    /// this lane's fronts in birth order, as front by front: the same
    /// deposits, added in the same order.
    fn take_lane(&mut self, shape: &Shape<R>, i: usize, end: R) {
        let (m, up) = (i / 2, i.is_multiple_of(2));
        let (s, transit) = (shape.spacing[m], shape.layers[m].transit_time);
        let lane = &mut self.lanes[i];
        let first = lane.base;
        let arrives = |j: usize| R::of((first + j as i64) as f64) * s + transit;
        let n = (0..lane.points.len())
            .find(|&j| arrives(j) >= end)
            .unwrap_or(lane.points.len());
        if n == 0 {
            return;
        }
        let run = self.take_run(i, n);
        self.followed += run.iter().filter(|&&d| d != R::zero()).count() as u64;
        let from = (first, s, transit);
        let top = shape.layers.len() - 1;
        if let Some(input) = self.nested_input(m, up) {
            // into the nested layer: the reflection here, the rest its
            // block's arrival
            let k = Self::reflected_before_nested(shape, m, up);
            self.push_run(shape, &run, from, (m, !up), k);
            let mut arrivals = std::mem::take(&mut self.arrivals);
            arrivals.clear();
            for (j, &x) in run.iter().enumerate() {
                if x != R::zero() {
                    arrivals.push((R::of((first + j as i64) as f64) * s + transit, x));
                }
            }
            self.arrive_nested(shape, input, &arrivals);
            self.arrivals = arrivals;
            self.run = run;
            return;
        }
        match (up, m) {
            (true, m) if m < top => {
                let k = shape.inner[m];
                self.push_run(shape, &run, from, (m, false), k.up_reflected);
                self.push_run(shape, &run, from, (m + 1, true), k.up_transmitted);
            }
            (true, _) => match shape.upper {
                Some(k) => {
                    self.leave_run(shape, &run, from, 1, k.up_transmitted);
                    self.push_run(shape, &run, from, (m, false), k.up_reflected);
                }
                None => self.push_run(shape, &run, from, (m, false), -R::one()),
            },
            (false, 0) => {
                let k = shape.lower;
                self.leave_run(shape, &run, from, 0, k.down_transmitted);
                self.push_run(shape, &run, from, (0, true), k.down_reflected);
            }
            (false, m) => {
                let k = shape.inner[m - 1];
                self.push_run(shape, &run, from, (m, true), k.down_reflected);
                self.push_run(shape, &run, from, (m - 1, false), k.down_transmitted);
            }
        }
        self.run = run;
    }

    /// Lane `i`'s oldest `n` points, taken out into the trace's room for a
    /// run (to be put back in `self.run` once scattered).
    fn take_run(&mut self, i: usize, n: usize) -> Vec<R> {
        let room = std::mem::take(&mut self.run);
        self.take_run_into(i, n, room)
    }

    /// [`Trace::take_run`] into the room of `run`.
    fn take_run_into(&mut self, i: usize, n: usize, mut run: Vec<R>) -> Vec<R> {
        run.clear();
        let lane = &mut self.lanes[i];
        run.extend_from_slice(&lane.points.as_slice()[..n]);
        lane.points.skip(n);
        lane.base += n as i64;
        run
    }

    /// The fronts `coef * x` that the points `x` of a run (from lattice
    /// point `first` of a lane of spacing `s` and `transit`) cause in
    /// lane (`m`, up or down), on its lattice, as [`Trace::push`] puts one.
    #[inline(always)]
    fn push_run(
        &mut self,
        shape: &Shape<R>,
        run: &[R],
        (first, s, transit): (i64, R, R),
        (m, up): (usize, bool),
        coef: R,
    ) {
        let l = &shape.layers[m];
        let (c, modulus, per) = (l.wave_speed, l.modulus, shape.per_spacing[m]);
        let lane = &mut self.lanes[2 * m + usize::from(!up)];
        for (j, &x) in run.iter().enumerate() {
            if x == R::zero() {
                continue;
            }
            let d = coef * x;
            if (d * c).abs() < self.tiny {
                self.dropped.0 += (d * c).abs();
                self.dropped.1 += (d * modulus).abs();
                continue;
            }
            let at = R::of((first + j as i64) as f64) * s + transit;
            let x = at * per;
            let k = x.to_f64() as i64;
            let hi = x - R::of(k as f64);
            lane.add(k, d * (R::one() - hi));
            if hi != R::zero() {
                lane.add(k + 1, d * hi);
            }
        }
    }

    /// The fronts `coef * x` that a run's points cause leaving at port
    /// `o`, on its lattice.
    #[inline(always)]
    fn leave_run(
        &mut self,
        shape: &Shape<R>,
        run: &[R],
        (first, s, transit): (i64, R, R),
        o: usize,
        coef: R,
    ) {
        let spacing = shape.port_spacing[o];
        for (j, &x) in run.iter().enumerate() {
            if x != R::zero() {
                let at = R::of((first + j as i64) as f64) * s + transit;
                deposit(&mut self.taps[o], at, coef * x, spacing);
            }
        }
    }

    /// A front of lane (`m`, up or down) arriving at `at` with jump `d`,
    /// followed exactly or on the lattice.
    #[inline]
    fn scatter(&mut self, shape: &Shape<R>, m: usize, up: bool, at: R, d: R, exact: bool) {
        let top = shape.layers.len() - 1;
        if let Some(input) = self.nested_input(m, up) {
            let k = Self::reflected_before_nested(shape, m, up);
            self.enter(shape, m, !up, at, k * d, exact);
            if exact {
                self.arrive_nested_large(shape, input, at, d);
            } else {
                self.arrive_nested(shape, input, &[(at, d)]);
            }
            return;
        }
        match (up, m) {
            (true, m) if m < top => {
                let k = shape.inner[m];
                self.enter(shape, m, false, at, k.up_reflected * d, exact);
                self.enter(shape, m + 1, true, at, k.up_transmitted * d, exact);
            }
            (true, _) => match shape.upper {
                Some(k) => {
                    self.leave(shape, 1, at, k.up_transmitted * d, exact);
                    self.enter(shape, m, false, at, k.up_reflected * d, exact);
                }
                None => self.enter(shape, m, false, at, -d, exact),
            },
            (false, 0) => {
                let k = shape.lower;
                self.leave(shape, 0, at, k.down_transmitted * d, exact);
                self.enter(shape, 0, true, at, k.down_reflected * d, exact);
            }
            (false, m) => {
                let k = shape.inner[m - 1];
                self.enter(shape, m, true, at, k.down_reflected * d, exact);
                self.enter(shape, m - 1, false, at, k.down_transmitted * d, exact);
            }
        }
    }

    /// Done: what is left counts as dropped at every input.
    fn finish(&mut self, shape: &Shape<R>) {
        let (mut velocity, mut force) = self.dropped;
        for (i, lane) in self.lanes.iter_mut().enumerate() {
            let l = &shape.layers[i / 2];
            for &d in lane.points.iter() {
                velocity += (d * l.wave_speed).abs();
                force += (d * l.modulus).abs();
            }
            lane.points.clear();
        }
        for &(_, d, lane) in &self.kept {
            let l = &shape.layers[lane / 2];
            velocity += (d * l.wave_speed).abs();
            force += (d * l.modulus).abs();
        }
        self.kept.clear();
        if let Some(f) = self.inner.as_ref().map(|i| i.layer) {
            // what the nested block may still deliver, at the stiffer
            // neighbour's force for its velocity
            let pending = self.nested_pending();
            let z = shape.layers[f - 1]
                .impedance
                .max(shape.layers[f + 1].impedance);
            velocity += pending;
            force += pending * z;
        }
        self.rest = (velocity.to_f64(), force.to_f64());
        self.done = true;
    }

    /// The velocity the block's fronts could carry: `sum |d| c`.
    fn held(&self, shape: &Shape<R>) -> R {
        let kept = self
            .kept
            .iter()
            .fold(self.nested_pending(), |s, &(_, d, lane)| {
                s + (d * shape.layers[lane / 2].wave_speed).abs()
            });
        self.lanes.iter().enumerate().fold(kept, |s, (i, lane)| {
            let c = shape.layers[i / 2].wave_speed;
            lane.points.iter().fold(s, |s, &d| s + (d * c).abs())
        })
    }
}

#[cfg(test)]
mod tests;

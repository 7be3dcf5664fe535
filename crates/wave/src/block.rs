//! Blocks of fast layers, answered by their response (merged runs only).
//!
//! A few adjacent layers, each much faster than the slower layers around
//! them, ring for millions of round trips between those neighbours' events,
//! and none of them may leap (each one's neighbour is another fast layer,
//! whose round trip ends a leap). But the block is linear and does not
//! change in time: a front arriving at one of its ports causes, at each
//! port, the same fronts whenever it arrives, scaled by its jump. So the
//! block is traced once per run (`block/response.rs`), and each arrival
//! adds its response, on the neighbours' lattices, to what the ports will
//! deliver: `K` multiply-adds per arrival for a response of `K` lattice
//! points, where the loop spent a million events.
//!
//! The block's own boundary events disappear: its lanes stay empty and its
//! layers' queue keys schedule the ports' deliveries instead. An arrival is
//! put on the port's lattice as a deposit is (split between the two
//! nearest points, jump and first moment kept), so the response is first
//! order in the lattice spacing as the rest of a merged run is, and the
//! ladder measures it with the rest; the response's few large fronts are
//! delivered at their exact times (`response.rs`), as a lattice lane keeps
//! its large fronts where they were born. What the block holds is not in
//! the lanes: a run with blocks stops on the escape bound from the energy
//! balance alone, and its fields leave the block out.

use crate::engine::LayerConst;
use crate::lane::Direction;
use crate::real::Real;
use folded::Folded;
use impact_model::InterfaceCoefficients;
use inputs::LatticeInputs;
use std::collections::VecDeque;

mod choice;
mod flow;
mod folded;
mod inputs;
mod partitioned;
mod real_fft;
mod response;

pub(crate) use choice::{allowance, apart, candidates, priced_run};
pub(crate) use response::{Shape, Trace};

/// A traced front's price in a port's multiply-adds (the work counted, see
/// `flow.rs`): about sixty nanoseconds against one.
pub(crate) const FRONT_ADDS: u64 = 64;

/// The most lattice points of its finest port a block's responses are
/// traced over to see whether they ring out (`Block::rings_out_within`):
/// a few megabytes of taps for each port.
const PROBE_CELLS: i64 = 1 << 20;

/// What a block's trace may nest (`response/nested.rs`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Nesting {
    /// Its fastest layer, where that pays.
    Allowed,
    /// Nothing: it follows every front of its layers.
    Never,
    /// Nothing, and it is itself nested in a trace: its response's large
    /// fronts go on the lattice with the rest.
    Inside,
}

/// One port: where the block meets a slower neighbour, and the arrivals
/// whose responses it still delivers into the neighbour's lane.
#[derive(Debug, Clone)]
pub(crate) struct Port<R> {
    /// The boundary it sits at.
    pub boundary: usize,
    /// The neighbour's layer and the direction its outputs travel.
    pub out: (usize, Direction),
    /// Its lane's lattice spacing.
    pub spacing: R,
    /// Arrivals on this port's lattice, per input port.
    arrivals: Vec<LatticeInputs<R>>,
    /// The next lattice point to deliver.
    next: i64,
    /// Fronts to deliver at their exact times (the responses' large
    /// fronts, see `response.rs`): born, jump; in time order.
    exact: VecDeque<(R, R)>,
    /// Per input port, its response's large fronts here: delay, delay in
    /// this port's spacings, jump (the trace's `exact`, all known before
    /// the first arrival).
    exact_per_input: Vec<Vec<(R, R, R)>>,
    /// Large fronts under `keep_above` once scaled by their arrival, on
    /// the lattice (`folded.rs`).
    folded: Folded<R>,
    /// What the neighbour's lane keeps where it is born; zero (nothing
    /// folded) until [`Block::fold_below`] says.
    keep_above: R,
    /// The block layer whose queue key schedules the deliveries.
    pub key_layer: usize,
}

/// One input's response at one port, as [`Block::responses`] reports it:
/// the port's spacing, its taps, and its exact fronts `(delay, jump)`.
pub(crate) type PortResponse<R> = (R, Vec<R>, Vec<(R, R)>);

/// A block of fast layers `lower..=upper`.
#[derive(Debug, Clone)]
pub(crate) struct Block<R> {
    pub lower: usize,
    pub upper: usize,
    shape: Shape<R>,
    /// The response to each input port, traced as far as asked.
    traces: Vec<Trace<R>>,
    /// The lower port, and the upper one unless the block is the top.
    pub ports: Vec<Port<R>>,
    /// Per input port, until its trace is done: `sum |d|` and
    /// `sum |d| t` of its arrivals, whose rest is counted then.
    owed: Vec<(f64, f64)>,
    /// The folded jumps `due` found on the points it delivered (`(born,
    /// jump)`), to be deposited (never kept apart, as the fronts folded
    /// into them would not have been); the caller empties it.
    pub folded_due: Vec<(R, R)>,
}

impl<R: Real> Block<R> {
    /// The block `lower..=upper` of a rod's layers; `spacing` gives a
    /// lane's lattice spacing; `nesting`, what its trace may nest or
    /// whether it is nested itself (`response/nested.rs`).
    pub(crate) fn new(
        layers: &[LayerConst<R>],
        interfaces: &[InterfaceCoefficients<R>],
        (lower, upper): (usize, usize),
        spacing: &dyn Fn(usize, Direction) -> R,
        (nesting, one_lattice): (Nesting, bool),
    ) -> Self {
        let top = upper + 1 == layers.len();
        let mut outs = vec![(lower - 1, Direction::Down)];
        if !top {
            outs.push((upper + 1, Direction::Up));
        }
        let mut shape = Shape {
            layers: layers[lower..=upper].to_vec(),
            inner: interfaces[lower..upper].to_vec(),
            lower: interfaces[lower - 1],
            upper: (!top).then(|| interfaces[upper]),
            spacing: (lower..=upper).map(|m| spacing(m, Direction::Up)).collect(),
            per_spacing: (lower..=upper)
                .map(|m| R::one() / spacing(m, Direction::Up))
                .collect(),
            port_spacing: outs.iter().map(|&(j, d)| spacing(j, d)).collect(),
            port_speed: outs.iter().map(|&(j, _)| layers[j].wave_speed).collect(),
            nest: None,
            keep_exact: nesting != Nesting::Inside,
            powers: None,
            work_share: vec![1.0; upper + 1 - lower],
        };
        if nesting == Nesting::Allowed {
            shape.nest = response::nested_layer(&shape);
        }
        if one_lattice && shape.nest.is_none() && shape.fits_one_lattice() {
            shape.share_one_lattice();
        }
        let traces: Vec<Trace<R>> = (0..outs.len()).map(|j| Trace::start(&shape, j)).collect();
        let ports = outs
            .iter()
            .enumerate()
            .map(|(o, &out)| Port {
                boundary: if o == 0 { lower } else { upper + 1 },
                out,
                spacing: shape.port_spacing[o],
                arrivals: vec![LatticeInputs::default(); outs.len()],
                next: i64::MIN,
                exact: VecDeque::new(),
                exact_per_input: traces
                    .iter()
                    .map(|trace| {
                        let h = shape.port_spacing[o];
                        trace.exact[o]
                            .iter()
                            .map(|&(delay, jump)| (delay, delay / h, jump))
                            .collect()
                    })
                    .collect(),
                folded: Folded::default(),
                keep_above: R::zero(),
                key_layer: if o == 0 { lower } else { upper },
            })
            .collect();
        Self {
            lower,
            upper,
            shape,
            traces,
            ports,
            owed: vec![(0.0, 0.0); outs.len()],
            folded_due: Vec::new(),
        }
    }

    /// Whether every input's response is over within `length` of its
    /// arrival, traced that far at most (and never past [`PROBE_CELLS`]
    /// of its finest port's lattice, whose taps grow the most); the fronts
    /// followed.
    pub(crate) fn rings_out_within(&mut self, length: R) -> (bool, u64) {
        let ports = &self.shape.port_spacing;
        let finest = (0..ports.len())
            .min_by(|&a, &b| ports[a].to_f64().total_cmp(&ports[b].to_f64()))
            .unwrap_or(0);
        let h = ports[finest];
        let cells = (length / h).ceil().to_f64().min(PROBE_CELLS as f64) as i64;
        let mut followed = 0;
        for trace in &mut self.traces {
            followed += trace.extend(&self.shape, finest, cells);
        }
        (self.traces.iter().all(|t| t.done), followed)
    }

    /// Every input's response at every port, traced to `length` after its
    /// arrival (or until done): per input, per port, the port's lattice
    /// spacing, its taps, and the large fronts followed at their exact
    /// times (`(delay, jump)`). A diagnostic: the engine reads taps one by
    /// one, as a port needs them ([`Block::tap`]).
    pub(crate) fn responses(&mut self, length: R) -> Vec<Vec<PortResponse<R>>> {
        let shape = &self.shape;
        self.traces
            .iter_mut()
            .map(|trace| {
                (0..shape.port_spacing.len())
                    .map(|o| {
                        let h = shape.port_spacing[o];
                        trace.extend(shape, o, (length / h).ceil().to_f64() as i64);
                        (h, trace.taps[o].clone(), trace.exact[o].clone())
                    })
                    .collect()
            })
            .collect()
    }

    /// Response tap `i` of input `j` at port `o`, traced if need be; the
    /// fronts the trace followed for it are added to `work`.
    fn tap(&mut self, j: usize, o: usize, i: i64, work: &mut u64) -> R {
        let trace = &mut self.traces[j];
        if !trace.has(&self.shape, o, i) {
            *work += FRONT_ADDS * trace.extend(&self.shape, o, i);
        }
        usize::try_from(i)
            .ok()
            .and_then(|i| trace.taps[o].get(i).copied())
            .unwrap_or(R::zero())
    }

    /// Port by port, the least jump the neighbour's lane keeps where it
    /// is born (`MergeRule::Lattice`'s `keep_above`): a response's large
    /// front scaled under it by its arrival goes on the port's lattice
    /// (`folded.rs`). Until this is said, every large front is delivered
    /// at its time.
    pub(crate) fn fold_below(&mut self, keep_above: &dyn Fn(usize, Direction) -> R) {
        for port in &mut self.ports {
            port.keep_above = keep_above(port.out.0, port.out.1);
        }
    }

    /// A jump `d` arriving at input port `input` at `t`: put on each
    /// port's lattice. Its response on points a port has already delivered
    /// goes into `late` (`(port, born, jump)`), to be spawned now; so do
    /// the large fronts the lane would deposit whose earlier point it has
    /// (`late.deposited`). The work done (fronts traced, multiply-adds)
    /// and the large fronts put on a lattice (`folded.rs`: merged, as the
    /// lane would have merged them).
    pub(crate) fn arrive(&mut self, input: usize, t: R, d: R, late: &mut Late<R>) -> (u64, u64) {
        let (mut work, mut folded) = (0, 0);
        let owed = &mut self.owed[input];
        owed.0 += d.abs().to_f64();
        owed.1 += d.abs().to_f64() * t.to_f64();
        for o in 0..self.ports.len() {
            let h = self.ports[o].spacing;
            let k = (t / h).floor();
            let f = (t - k * h) / h;
            let k = k.to_f64() as i64;
            let port = &mut self.ports[o];
            if port.arrivals.iter().all(LatticeInputs::is_empty) && port.folded.is_empty() {
                port.next = port.next.max(k);
            }
            // the large fronts at their exact times, or on the lattice
            // where the lane would put them there (under its `keep_above`,
            // as the lane tests it)
            let x = t / h;
            debug_assert_eq!(
                port.exact_per_input[input].len(),
                self.traces[input].exact[o].len()
            );
            for &(delay, per_h, jump) in &port.exact_per_input[input] {
                let jump = d * jump;
                let at = t + delay;
                if jump.abs() < port.keep_above {
                    if port.folded.deposit(x + per_h, jump, port.next) {
                        folded += 1;
                    } else {
                        // its earlier point was delivered before the last:
                        // the lane takes it now on the same two points (it
                        // would not keep it, being small), not at an event
                        // of its own (the lane counts it merged)
                        late.deposited.push((o, at, jump));
                    }
                    continue;
                }
                let i = port.exact.partition_point(|e| e.0 <= at);
                port.exact.insert(i, (at, jump));
            }
            let behind = port.folded.take_behind();
            if behind != R::zero() {
                late.deposited
                    .push((o, R::of((port.next - 1) as f64) * h, behind));
            }
            for (k, a) in [(k, d * (R::one() - f)), (k + 1, d * f)] {
                if a == R::zero() {
                    continue;
                }
                for idx in k..self.ports[o].next {
                    let c = self.tap(input, o, idx - k, &mut work);
                    if c != R::zero() {
                        late.spawned.push((o, R::of(idx as f64) * h, a * c));
                    }
                }
                self.ports[o].arrivals[input].add(k, a);
            }
        }
        (work, folded)
    }

    /// Port `o`'s deliveries due by `now` into `due` (`(born, jump)`: the
    /// lattice points' sums, then the exact fronts) and the folded jumps
    /// on those points into [`Block::folded_due`]; when the next is due,
    /// the work done, and how many of `due` are lattice points.
    pub(crate) fn due(
        &mut self,
        o: usize,
        now: R,
        due: &mut Vec<(R, R)>,
    ) -> (Option<R>, u64, usize) {
        let mut work = 0;
        let h = self.ports[o].spacing;
        let waiting =
            |port: &Port<R>| !port.folded.is_empty() || port.arrivals.iter().any(|a| !a.is_empty());
        while waiting(&self.ports[o]) && R::of(self.ports[o].next as f64) * h <= now {
            let m = self.ports[o].next;
            let folded = self.ports[o].folded.take(m);
            if folded != R::zero() {
                self.folded_due.push((R::of(m as f64) * h, folded));
            }
            let mut sum = R::zero();
            for (j, trace) in self.traces.iter_mut().enumerate() {
                let arrivals = &mut self.ports[o].arrivals[j];
                // points whose response is over at `m` are let go
                if trace.done {
                    arrivals.let_go_before(m - trace.taps[o].len() as i64 + 1);
                }
                if arrivals.is_empty() {
                    continue;
                }
                let mut ready = trace.final_through(&self.shape, o);
                let last = arrivals.last_tap(m, trace.done, trace.taps[o].len(), ready);
                if !trace.has(&self.shape, o, last) {
                    work += FRONT_ADDS * trace.extend(&self.shape, o, last);
                    ready = trace.final_through(&self.shape, o);
                }
                let (response, adds) = arrivals.response_at(m, &trace.taps[o], trace.done, ready);
                sum += response;
                work += adds;
            }
            if sum != R::zero() {
                due.push((R::of(m as f64) * h, sum));
            }
            self.ports[o].next += 1;
        }
        let on_lattice = due.len();
        let port = &mut self.ports[o];
        while let Some(&(at, jump)) = port.exact.front() {
            if at > now {
                break;
            }
            due.push((at, jump));
            port.exact.pop_front();
        }
        let lattice = waiting(port).then(|| R::of(port.next as f64) * h);
        let next = match (lattice, port.exact.front()) {
            (Some(a), Some(&(b, _))) => Some(a.min(b)),
            (a, b) => a.or(b.map(|e| e.0)),
        };
        (next, work, on_lattice)
    }

    /// The most velocity (`sum |d| c`) the block may still deliver: each
    /// held arrival times everything its input's response delivers, and
    /// the large fronts waiting; infinite while a response with arrivals
    /// held is still traced.
    pub(crate) fn pending(&self) -> R {
        let mut pending = R::zero();
        for (j, trace) in self.traces.iter().enumerate() {
            // (each port holds the arrivals on its own lattice, and lets
            // them go when its own taps are past)
            let held = self
                .ports
                .iter()
                .fold(R::zero(), |h, port| h.max(port.arrivals[j].total_abs()));
            if held == R::zero() {
                continue;
            }
            if !trace.done {
                return -R::neg_infinity();
            }
            let gain = (0..self.ports.len()).fold(R::zero(), |g, o| {
                let taps = trace.taps[o].iter().fold(R::zero(), |s, &t| s + t.abs());
                let exact = trace.exact[o].iter().fold(R::zero(), |s, e| s + e.1.abs());
                g + (taps + exact) * self.shape.port_speed[o]
            });
            pending += held * gain;
        }
        for (o, port) in self.ports.iter().enumerate() {
            let exact = port.exact.iter().fold(R::zero(), |s, e| s + e.1.abs());
            pending += (exact + port.folded.total_abs()) * self.shape.port_speed[o];
        }
        pending
    }

    /// The layer (of the rod) its traces answer by that layer's own
    /// response, if any.
    pub(crate) fn nested(&self) -> Option<usize> {
        self.shape.nest.map(|f| self.lower + f)
    }

    /// Whether its traces run on one lattice (`response/one_lattice.rs`).
    pub(crate) fn on_one_lattice(&self) -> bool {
        self.shape.powers.is_some()
    }

    /// What the arrivals at inputs whose trace is done left in the block
    /// beyond its response, not yet counted: `(velocity, force, force
    /// times birth)` as for dropped fronts.
    pub(crate) fn take_rest(&mut self) -> Option<(f64, f64, f64)> {
        let mut rest = None;
        for (trace, owed) in self.traces.iter().zip(self.owed.iter_mut()) {
            if trace.done && owed.0 > 0.0 {
                let (v, f) = trace.rest;
                let r = rest.get_or_insert((0.0, 0.0, 0.0));
                r.0 += v * owed.0;
                r.1 += f * owed.0;
                r.2 += f * owed.1;
                *owed = (0.0, 0.0);
            }
        }
        rest
    }
}

/// What an arrival's response puts on points a port has already
/// delivered, to go into the neighbour's lane at once.
#[derive(Debug, Clone)]
pub(crate) struct Late<R> {
    /// Lattice points' sums (`(port, born, jump)`), spawned.
    pub spawned: Vec<(usize, R, R)>,
    /// Large fronts under the lane's `keep_above` whose earlier point the
    /// lane holds already (`(port, born, jump)`), deposited: the shares
    /// on the point delivered last, summed (`Folded::take_behind`), or
    /// now and then one front born at its exact time, which the lane
    /// splits as it would have at its birth. The later share is delivered
    /// with its point's sum (`folded.rs`). On the fast-bottom draw's rod
    /// 16, whose upper neighbour's lattice is four thousand of its
    /// response's delays wide, nearly every such front fell on a
    /// delivered point, and each was a loop event of its own: 22 M of the
    /// 35 M at 0.2 of a transit.
    pub deposited: Vec<(usize, R, R)>,
}

impl<R> Late<R> {
    /// Empties both lists, keeping their room for the next arrival.
    pub(crate) fn clear(&mut self) {
        self.spawned.clear();
        self.deposited.clear();
    }
}

impl<R> Default for Late<R> {
    fn default() -> Self {
        Self {
            spawned: Vec::new(),
            deposited: Vec::new(),
        }
    }
}

/// A run's blocks, with where their ports and keys are.
#[derive(Debug, Clone, Default)]
pub(crate) struct Blocks<R> {
    pub list: Vec<Block<R>>,
    /// Per boundary: the block and port there.
    pub port_at: Vec<Option<(usize, usize)>>,
    /// Per layer: the block and port whose deliveries its key schedules.
    pub key_of: Vec<Option<(usize, usize)>>,
    /// Deliveries to spawn, kept from one arrival to the next.
    pub spawns: Vec<(R, R)>,
    /// An arrival's late deliveries, kept so.
    pub late: Late<R>,
    /// How much earlier than its arrival's lattice point a delivery may be
    /// born: twice the widest port spacing (the arrival and the response
    /// are each split onto the lattice).
    pub margin: R,
}

impl<R: Real> Blocks<R> {
    /// Whether a front of lane (`j`, `dir`) on its way to layer `i` meets
    /// a block's port: it crosses a block between them, or it heads into a
    /// port first and comes back. Its block's part may then come out up to
    /// [`Blocks::margin`] earlier than the layers' transits say.
    #[inline]
    pub(crate) fn answers(&self, i: usize, j: usize, dir: Direction) -> bool {
        let (lo, hi) = (i.min(j), i.max(j));
        let towards = (dir == Direction::Up) == (j < i);
        self.list.iter().any(|b| {
            let between = lo < b.lower && b.upper < hi;
            let into = match dir {
                Direction::Up => j + 1 == b.lower,
                Direction::Down => j == b.upper + 1,
            };
            between || (!towards && into)
        })
    }

    /// Indexes `list` for a rod of `n` layers.
    pub(crate) fn new(list: Vec<Block<R>>, n: usize) -> Self {
        let mut port_at = vec![None; n + 1];
        let mut key_of = vec![None; n];
        let mut margin = R::zero();
        for (bi, block) in list.iter().enumerate() {
            for (o, port) in block.ports.iter().enumerate() {
                port_at[port.boundary] = Some((bi, o));
                key_of[port.key_layer] = Some((bi, o));
                margin = margin.max(R::of(2.0) * port.spacing);
            }
        }
        Self {
            list,
            port_at,
            key_of,
            spawns: Vec::new(),
            late: Late::default(),
            margin,
        }
    }
}

//! A block within the block: the trace's fastest layer answered by its
//! own response.
//!
//! A block's fastest layer holds most of what its trace follows: a lane
//! holds about as many lattice points a transit whatever the transit, so
//! a layer ten times faster than the others has ten times their points
//! (54 to 94 % of the traced fronts on the layer survey's trace-bound
//! rods, 86 % on the fast-bottom draw's rod 29, ARCHITECTURE.md). Between
//! the block's slower layers it often rings out within a few dozen round
//! trips, a sliver of the run, while the block as a whole rings through
//! it. Inside the trace that layer is then a block of its own
//! (`block.rs`), between neighbours that are the trace's lanes: what
//! arrives at it from its two sides is put on those lanes' lattices, and
//! its short response, traced once, is delivered into them at every step's
//! end; the trace's own large fronts go through it at their exact times
//! (a second copy of its response, with its large fronts apart). The
//! trace stays the same
//! lattice model, its nested layer answered as the run answers a block,
//! and the ladder measures both with the rest.
//!
//! The trace's steps leave room for it: a delivery may be born up to two
//! of its lane's spacings before the arrival that caused it (the arrival
//! and the response are each split onto the lattice, `Blocks::margin`),
//! so the two lanes it feeds take a step no longer than their transit
//! less two spacings. The trace is done only once what the inner block
//! may still deliver counts too.

use super::{Shape, Trace};
use crate::block::choice::NS_PER_ADD;
use crate::block::partitioned::adds_per_point;
use crate::block::{Block, FRONT_ADDS, Nesting};
use crate::real::Real;

/// Each neighbour of the nested layer is at least this many times slower.
pub(crate) const NEST_SLOWER: f64 = 4.0;

/// The nested layer's round trip between the block's layers keeps at most
/// this share of a front (`|R_below R_above|`): its response then rings
/// out, under `1e-13`, within about 300 round trips. Seed 3's rod 32, whose
/// fastest layer keeps 0.984 (1,844 round trips), would pay more for the
/// sums than the fronts it saves.
pub(crate) const NEST_RINGS: f64 = 0.9;

/// A lane nesting feeds holds at most this share of its transit a cell,
/// so that its step, the transit less two cells, keeps half of it.
const NEST_COARSEST: f64 = 0.25;

/// What a traced front costs, in nanoseconds: 17 on layer survey rod 20's
/// finest trace, 30 on the fast-bottom draw's rod 29 (ARCHITECTURE.md).
const NS_PER_FRONT: f64 = 20.0;

/// What nesting costs, in nanoseconds, measured on layer survey rod 20's
/// second level (`perf` of the `layer_events` example): an arrival at the
/// nested block (put on both ports' lattices), a delivered point (its
/// bookkeeping and placing), and each input's sum for it beside its
/// multiply-adds (28 ns for about 61 taps).
const NS_PER_ARRIVAL: f64 = 35.0;
const NS_PER_DELIVERY: f64 = 25.0;
const NS_PER_SUM: f64 = 10.0;

/// Nesting must save this many times its price: the prices come from one
/// rod, and on the fast-bottom draw's rod 29, priced at 0.47, 0.61 and
/// 0.89 of what they save at the ladder's three levels, its levels took
/// 0.79, 0.80 and 1.37 of the time (the `layer_events` example, nested
/// and not). Seed 3's rod 27 of the layer survey, priced at 0.07 to
/// 0.08, took a fifth.
const NEST_MARGIN: f64 = 3.0;

/// The layer of a block to answer by its own response, if one pays: the
/// layer inside the block (not at a port) with the most lattice points
/// a unit of time, more than all the others together, each neighbour
/// [`NEST_SLOWER`] times slower and ringing at most [`NEST_RINGS`], where
/// the fronts it would no longer follow cost more than the arrivals at
/// it and its sums. The sums grow as the square of the lattices' density
/// (points to deliver, each summing a response as many taps long), the
/// fronts saved only with it, so a finer level may not nest what a
/// coarser one does: rod 20 of the layer survey (neighbours 4.4 and 5.9
/// times slower, a response of about 45 transits) paid at a fifth of
/// each transit and lost at a twentieth (1.08 s against 0.70 s).
pub(crate) fn nested_layer<R: Real>(shape: &Shape<R>) -> Option<usize> {
    let n = shape.layers.len();
    if n < 3 {
        return None;
    }
    let rate = |m: usize| 1.0 / shape.spacing[m].to_f64();
    let transit = |m: usize| shape.layers[m].transit_time.to_f64();
    let f = (1..n - 1).max_by(|&a, &b| rate(a).total_cmp(&rate(b)))?;
    let others: f64 = (0..n).filter(|&m| m != f).map(rate).sum();
    let rings = (shape.inner[f - 1].down_reflected * shape.inner[f].up_reflected)
        .abs()
        .to_f64();
    let coarse = |m: usize| shape.spacing[m].to_f64() > NEST_COARSEST * transit(m);
    let fits = rate(f) > others
        && NEST_SLOWER * transit(f) <= transit(f - 1).min(transit(f + 1))
        && rings <= NEST_RINGS
        && !coarse(f - 1)
        && !coarse(f + 1);
    if !fits {
        return None;
    }
    // nanoseconds a unit of time: the nested layer's two lanes traced,
    // against its arrivals and its ports' sums over a response of
    // `trips` round trips (until what it holds falls under `REST`)
    let trips = if rings > 0.0 {
        (super::REST.ln() / rings.ln()).ceil().max(1.0)
    } else {
        1.0
    };
    let length = (2.0 * trips + 1.0) * transit(f);
    let traced = NS_PER_FRONT * 2.0 * rate(f);
    let ports = [f - 1, f + 1];
    let arrivals: f64 = ports.iter().map(|&m| NS_PER_ARRIVAL * rate(m)).sum();
    let deliveries: f64 = ports
        .iter()
        .map(|&out| {
            let sums: f64 = ports
                .iter()
                .map(|&m| NS_PER_SUM + NS_PER_ADD * adds_per_point(length * rate(m)))
                .sum();
            rate(out) * (NS_PER_DELIVERY + sums)
        })
        .sum();
    (NEST_MARGIN * (arrivals + deliveries) < traced).then_some(f)
}

/// The nested layer's block, with room kept between steps.
#[derive(Debug, Clone)]
pub(crate) struct Inner<R> {
    /// The nested layer (in the block's own count).
    pub layer: usize,
    /// The block the lattice points arriving are answered by: its
    /// response wholly on its ports' lattices.
    block: Box<Block<R>>,
    /// The same layer's response with its large fronts apart, traced to
    /// its end, for the trace's large fronts: they keep their timing
    /// through the nested layer as through any other (a first build put
    /// them on the lattice too, and missed the exact engine by up to
    /// `4.4e-4`, a hundred times the trace's own error, on rods whose first
    /// fronts through the block decide contacts).
    large: Box<Block<R>>,
    due: Vec<(R, R)>,
    late: crate::block::Late<R>,
}

impl<R: Real> Inner<R> {
    /// Layer `f` of `shape` as a block between its neighbours' lanes.
    pub(crate) fn new(shape: &Shape<R>, f: usize) -> Self {
        let spacing = |m: usize, _| shape.spacing[m];
        let block = Block::new(
            &shape.layers,
            &shape.inner,
            (f, f),
            &spacing,
            (Nesting::Inside, false),
        );
        let mut large = Block::new(
            &shape.layers,
            &shape.inner,
            (f, f),
            &spacing,
            (Nesting::Never, false),
        );
        for trace in &mut large.traces {
            trace.extend(&large.shape, 0, i64::MAX / 4);
        }
        Self {
            layer: f,
            block: Box::new(block),
            large: Box::new(large),
            due: Vec::new(),
            late: crate::block::Late::default(),
        }
    }
}

impl<R: Real> Trace<R> {
    /// The step a trace with layer `f` nested may take: no front born
    /// within it arrives within it, deliveries born up to two cells early
    /// included.
    pub(super) fn nested_step(shape: &Shape<R>, f: usize) -> R {
        (0..shape.layers.len())
            .filter(|&m| m != f)
            .map(|m| {
                let cells = if m + 1 == f || m == f + 1 { 2.0 } else { 1.0 };
                shape.layers[m].transit_time - R::of(cells) * shape.spacing[m]
            })
            .fold(-R::neg_infinity(), |a, b| a.min(b))
    }

    /// Whether a front of layer `m` going up (`up`) or down arrives at the
    /// nested layer: the input it enters by.
    #[inline]
    pub(super) fn nested_input(&self, m: usize, up: bool) -> Option<usize> {
        let f = self.inner.as_ref()?.layer;
        match up {
            true if m + 1 == f => Some(0),
            false if m == f + 1 => Some(1),
            _ => None,
        }
    }

    /// What a front of layer `m` going up (`up`) or down reflects where it
    /// meets the nested layer.
    #[inline]
    pub(super) fn reflected_before_nested(shape: &Shape<R>, m: usize, up: bool) -> R {
        if up {
            shape.inner[m].up_reflected
        } else {
            shape.inner[m - 1].down_reflected
        }
    }

    /// Jumps `d` arriving at the nested layer by `input` at `at`; what
    /// they add to points already delivered is placed now.
    pub(super) fn arrive_nested(&mut self, shape: &Shape<R>, input: usize, arrivals: &[(R, R)]) {
        let Some(inner) = self.inner.as_mut() else {
            return;
        };
        let mut late = std::mem::take(&mut inner.late);
        late.clear();
        let mut work = 0;
        for &(at, d) in arrivals {
            work += inner.block.arrive(input, at, d, &mut late).0;
        }
        // (a nested block folds nothing: its large fronts are followed)
        debug_assert!(late.deposited.is_empty());
        self.followed += work / FRONT_ADDS;
        for &(o, born, jump) in &late.spawned {
            self.place_delivery(shape, o, born, jump);
        }
        if let Some(inner) = self.inner.as_mut() {
            inner.late = late;
        }
    }

    /// The nested block's deliveries due by `end` into its two lanes.
    pub(super) fn deliver_nested(&mut self, shape: &Shape<R>, end: R) {
        for o in 0..2 {
            let Some(inner) = self.inner.as_mut() else {
                return;
            };
            let mut due = std::mem::take(&mut inner.due);
            due.clear();
            let (_, work, on_lattice) = inner.block.due(o, end, &mut due);
            if let Some((velocity, force, _)) = inner.block.take_rest() {
                self.dropped.0 += R::of(velocity);
                self.dropped.1 += R::of(force);
            }
            self.followed += work / FRONT_ADDS;
            let (m, up) = self.nested_lane(o);
            for (n, &(born, jump)) in due.iter().enumerate() {
                if n < on_lattice {
                    self.place_delivery(shape, o, born, jump);
                } else {
                    self.enter(shape, m, up, born, jump, true);
                }
            }
            if let Some(inner) = self.inner.as_mut() {
                inner.due = due;
            }
        }
    }

    /// A large front `d` arriving at the nested layer by `input` at `at`:
    /// its response's large fronts followed at their times, the rest put
    /// on the lanes' lattices now, as births to come (the arrival split
    /// between its two lattice points, each point's response from there).
    pub(super) fn arrive_nested_large(&mut self, shape: &Shape<R>, input: usize, at: R, d: R) {
        let Some(inner) = self.inner.take() else {
            return;
        };
        let trace = &inner.large.traces[input];
        for o in 0..2 {
            let (m, up) = Self::lane_of(inner.layer, o);
            for &(delay, jump) in &trace.exact[o] {
                self.enter(shape, m, up, at + delay, d * jump, true);
            }
            let h = shape.spacing[m];
            let (k, lo, hi) = super::split(at, h);
            let k = k.to_f64() as i64;
            for (i, &tap) in trace.taps[o].iter().enumerate() {
                for (point, share) in [(k + i as i64, lo), (k + 1 + i as i64, hi)] {
                    let jump = d * share * tap;
                    if jump != R::zero() {
                        self.place_on(shape, (m, up), R::of(point as f64) * h, jump);
                    }
                }
            }
            self.followed += trace.taps[o].len() as u64;
        }
        self.inner = Some(inner);
    }

    /// The lane port `o` of the block nesting layer `f` delivers into.
    fn lane_of(f: usize, o: usize) -> (usize, bool) {
        if o == 0 {
            (f - 1, false)
        } else {
            (f + 1, true)
        }
    }

    /// The lane port `o` of the nested block delivers into.
    fn nested_lane(&self, o: usize) -> (usize, bool) {
        Self::lane_of(self.inner.as_ref().map_or(1, |i| i.layer), o)
    }

    /// A delivery of port `o` on its lane's lattice point at `born`.
    fn place_delivery(&mut self, shape: &Shape<R>, o: usize, born: R, jump: R) {
        let lane = self.nested_lane(o);
        self.place_on(shape, lane, born, jump);
    }

    /// A jump born at `born` in lane (`m`, up or down): on its lattice
    /// point if it is born on one, else split as any birth.
    fn place_on(&mut self, shape: &Shape<R>, (m, up): (usize, bool), born: R, jump: R) {
        let k = (born * shape.per_spacing[m]).round();
        if k * shape.spacing[m] == born {
            let l = &shape.layers[m];
            if (jump * l.wave_speed).abs() < self.tiny {
                self.dropped.0 += (jump * l.wave_speed).abs();
                self.dropped.1 += (jump * l.modulus).abs();
            } else {
                self.lanes[2 * m + usize::from(!up)].add(k.to_f64() as i64, jump);
            }
        } else {
            self.push(shape, m, up, born, jump);
        }
    }

    /// The most velocity the nested block may still deliver (`sum |d| c`),
    /// zero without one; infinite while a response is still traced.
    pub(super) fn nested_pending(&self) -> R {
        self.inner
            .as_ref()
            .map_or(R::zero(), |inner| inner.block.pending())
    }
}

//! The bottom group stepped (merged runs only): a few fast layers at the
//! wall, under a much slower layer, followed in steps instead of event by
//! event.
//!
//! A block's response (`block.rs`) cannot hold the layers at the wall:
//! the wall's decisions (separation, landing) need the group's state, and
//! a response keeps none. But between decisions the group is linear, and
//! its fronts sit on their lanes' lattices, so it can be taken as a block's
//! trace is (`block/response.rs`): in steps no front born within can cross
//! (a step is shorter than every group layer's transit less its spacing),
//! each lane's due lattice points at once, with the same scattering, the
//! same lattices and the same rules for the large fronts kept where they
//! are born and the small ones dropped as the loop's lanes. The state is
//! kept, so the loop can take the fronts back at any step's end: where the
//! next step could hold a wall decision (a tensile or nearly grazing wall
//! strain in contact, a landing in flight, both seen ahead from the fronts
//! already on their way to the wall), and when the run stops. On layer
//! survey seed 3's rod 23 (its third lattice's 39.5 M loop events all in
//! its bottom group) a front of the loop cost about 100 ns, one taken in
//! a step 50 to 60 ns.
//!
//! What the group sends up is spawned into the layer above at the times
//! it leaves, no later than the loop's present (the group is brought up
//! to it whenever a front arrives from above, and at every step's end,
//! which its layer-0 queue key schedules), so the loop sees every front in
//! order. The layer above does not leap while the group is stepped (a leap
//! would not see the group's fronts coming), and a leap further up ends
//! where they could reach it.

use crate::engine::LayerConst;
use crate::lane::{Front, LatticePoints};
use crate::real::Real;
use crate::window::Window;
use impact_model::InterfaceCoefficients;

mod step;
mod turns;

/// A birth this close to a lattice point (in cells) is checked for
/// sitting on it.
const ON_POINT: f64 = 1e-9;

/// How many times slower than each group layer the layer above must be.
pub(crate) const SLOWER: f64 = 8.0;

/// A front followed at its own time: the large ones kept where they were
/// born, as a lattice lane keeps them, and those the loop's lanes held off
/// their lattice (a leap's merged fronts) when the group was taken over.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Exact<R> {
    pub born: R,
    pub jump: R,
    pub lane: usize,
    /// Counted against the lane's `keep_at_most` (a kept front).
    pub kept: bool,
    /// Ahead of a lattice front born at the same instant in the loop's
    /// lane: born before that lattice point took its first deposit (a lane
    /// holds fronts born together in the order they came). With `order`,
    /// the loop's order among fronts arriving together.
    pub ahead: bool,
    pub order: u64,
}

/// The dropped fronts' sums, as `Tracer::drop_front` keeps them.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Dropped {
    pub fronts: u64,
    /// `sum |d| c`, in internal units.
    pub velocity: f64,
    pub force: f64,
    pub force_time: f64,
}

/// Layers `0..top` stepped, and what the loop needs back.
#[derive(Debug, Clone)]
pub(crate) struct Group<R> {
    /// The slow layer just above: the group's layers are `0..top`.
    pub(crate) top: usize,
    /// Whether the group's fronts are here (stepped) or in the loop's lanes.
    pub(crate) active: bool,
    /// Per lane of the group (`Lane::index`): births on lattice points.
    points: Vec<LatticePoints<R>>,
    exact: Vec<Exact<R>>,
    /// Per lane: kept fronts held.
    kept: Vec<usize>,
    layers: Vec<LayerConst<R>>,
    /// The group's interfaces and the one with the layer above (`top`).
    interfaces: Vec<InterfaceCoefficients<R>>,
    spacing: Vec<R>,
    per_spacing: Vec<R>,
    keep_above: Vec<R>,
    keep_at_most: usize,
    /// Every front arriving before this has been followed.
    pub(crate) reached: R,
    /// The longest step.
    step: R,
    /// Per lane: the jumps born since the loop's bases last took them.
    born_sums: Vec<R>,
    dropped: Dropped,
    /// Fronts followed since the loop last counted them.
    followed: u64,
    /// Fronts sent into the layer above, `(born, jump)`, for the loop.
    sent: Vec<(R, R)>,
    /// No try to take the group over before this many loop events.
    retry: u64,
    /// The leaps' thresholds of layers `0..=top`, while stepped.
    saved_leap_after: Vec<R>,
    /// Exact fronts made so far (their `order`).
    made: u64,
    /// Lattice points a kept front was born on after they took a deposit:
    /// `(lane, point, bucket)`. The loop's lane holds that point's later
    /// deposits as another front, behind the kept one (a lane merges a
    /// deposit into its newest front born there only if it is not kept),
    /// here an exact front (`bucket`, its `order`; 0 until the first).
    behind_kept: Vec<(usize, i64, u64)>,
    /// Per lane, which points of `behind_kept` it holds, by the point's
    /// number modulo 64: every deposit asks, and nearly none is one (a
    /// scan of the list at every deposit: seed 7's rod 15 of the layer
    /// survey ran 0.78x without it, its results the same to the bit).
    behind_mask: Vec<u64>,
    /// Whether the births under way come of an event a front going up
    /// started: at one instant the loop takes an up lane's arrival before
    /// its layer's down lane's, and a lower layer's before a higher one's,
    /// so such births come before a kept front of their lane leaves at that
    /// instant, and the others after.
    from_up: bool,
    /// The loop's next front from above while a step runs, and whether the
    /// step took it (an arrival from below took it into its event).
    input: Option<(R, R)>,
    input_taken: bool,
    /// Which arrivals at one boundary are one event (the loop's window).
    window: Window<R>,
    /// Scratch: due exact fronts, a boundary's arrivals from each side.
    due: Vec<Exact<R>>,
    below: Vec<(R, R)>,
    above: Vec<(R, R)>,
    /// Scratch: a lane's fronts sorted in its order; the wall's ahead.
    tagged: Vec<Tagged<R>>,
    wall: Vec<(R, R)>,
}

/// Lattice point `k`'s bit in a lane's `behind_mask`.
#[inline(always)]
fn point_bit(k: i64) -> u64 {
    1 << (k & 63)
}

/// A front of a lane with what sorts fronts arriving together as the
/// loop's lane holds them: birth, then exact fronts born ahead of a
/// lattice point's front, the point's, the others, each in birth order.
#[derive(Debug, Clone, Copy)]
struct Tagged<R> {
    arrives: R,
    born: R,
    /// 0: an exact front ahead of the point's, 1: the point's, 2: behind.
    rank: u8,
    order: u64,
    jump: R,
}

impl<R: Real> Tagged<R> {
    fn on_point(arrives: R, born: R, jump: R) -> Self {
        let (rank, order) = (1, 0);
        Self {
            arrives,
            born,
            rank,
            order,
            jump,
        }
    }

    fn exact(e: &Exact<R>, transit: R) -> Self {
        let rank = if e.ahead { 0 } else { 2 };
        let (born, order, jump) = (e.born, e.order, e.jump);
        Self {
            arrives: born + transit,
            born,
            rank,
            order,
            jump,
        }
    }
}

/// Sorts a lane's fronts as the loop's lane takes them (see [`Tagged`]).
fn in_lane_order<R: Real>(fronts: &mut [Tagged<R>]) {
    use std::cmp::Ordering::Equal;
    fronts.sort_by(|a, b| {
        a.arrives
            .partial_cmp(&b.arrives)
            .unwrap_or(Equal)
            .then(a.born.partial_cmp(&b.born).unwrap_or(Equal))
            .then(a.rank.cmp(&b.rank))
            .then(a.order.cmp(&b.order))
    });
}

/// A layer whose neighbours are all this many times slower leaps well on
/// its own (`leap.rs`), and a group holding one is left to the loop: seed
/// 7's rod 12 of the layer survey (a bottom of transit `1.3e-5` under one
/// of `7.4e-4`, 57 times slower) leapt its bottom 22,663 times at its
/// third lattice and ran 6.8 s; stepped with that layer, 11 s.
pub(crate) const LEAPS_ON_ITS_OWN: f64 = 16.0;

/// The bottom group of a rod with these transit times: `top`, when layers
/// `0..top` (two at least: one fast bottom leaps) are each [`SLOWER`]
/// times faster than layer `top`, the largest such group; none where a
/// block (`lowest_block`, its lowest layer) would hold one of its layers
/// or the layer above it, or where one of its layers leaps well on its
/// own ([`LEAPS_ON_ITS_OWN`]).
pub(crate) fn bottom_group(transits: &[f64], lowest_block: Option<usize>) -> Option<usize> {
    let mut slowest_inside = 0.0f64;
    let mut best = None;
    for top in 1..transits.len() {
        slowest_inside = slowest_inside.max(transits[top - 1]);
        if top >= 2 && transits[top] >= SLOWER * slowest_inside {
            best = Some(top);
        }
    }
    let leaps_alone = |m: usize| {
        let below = m.checked_sub(1).map_or(f64::INFINITY, |j| transits[j]);
        below.min(transits[m + 1]) >= LEAPS_ON_ITS_OWN * transits[m]
    };
    best.filter(|&top| lowest_block.is_none_or(|b| b > top))
        .filter(|&top| !(0..top).any(leaps_alone))
}

impl<R: Real> Group<R> {
    /// The group `0..top` of a run's layers; `lattice` gives a lane's
    /// spacing, its large fronts' threshold and how many it keeps.
    pub(crate) fn new(
        layers: &[LayerConst<R>],
        interfaces: &[InterfaceCoefficients<R>],
        top: usize,
        window: Window<R>,
        lattice: &dyn Fn(usize) -> (R, R, usize),
    ) -> Self {
        let lanes = 2 * top;
        let spacing: Vec<R> = (0..top).map(|m| lattice(2 * m).0).collect();
        let step = (0..top)
            .map(|m| layers[m].transit_time - spacing[m])
            .fold(-R::neg_infinity(), |a, b| a.min(b));
        Self {
            top,
            active: false,
            points: vec![LatticePoints::default(); lanes],
            exact: Vec::new(),
            kept: vec![0; lanes],
            layers: layers[..top].to_vec(),
            interfaces: interfaces[..top].to_vec(),
            per_spacing: spacing.iter().map(|&s| R::one() / s).collect(),
            spacing,
            keep_above: (0..lanes).map(|i| lattice(i).1).collect(),
            keep_at_most: lattice(0).2,
            reached: R::zero(),
            step,
            born_sums: vec![R::zero(); lanes],
            dropped: Dropped::default(),
            followed: 0,
            sent: Vec::new(),
            retry: 0,
            saved_leap_after: Vec::new(),
            made: 0,
            behind_kept: Vec::new(),
            behind_mask: vec![0; lanes],
            from_up: false,
            input: None,
            input_taken: false,
            window,
            due: Vec::new(),
            below: Vec::new(),
            above: Vec::new(),
            tagged: Vec::new(),
            wall: Vec::new(),
        }
    }

    /// When lattice point `k` of lane `i` arrives at its far end.
    #[inline(always)]
    fn arrival(&self, i: usize, k: i64) -> R {
        let m = i / 2;
        R::of(k as f64) * self.spacing[m] + self.layers[m].transit_time
    }

    /// A front of the loop's lane `i` taken over at `now`: on its lattice
    /// point, or followed at its own time.
    pub(crate) fn take(&mut self, i: usize, f: &Front<R>) {
        let m = i / 2;
        let k = (f.born * self.per_spacing[m]).round();
        if !f.kept && k * self.spacing[m] == f.born {
            self.add_on_point(i, k.to_f64() as i64, f.jump);
        } else {
            self.follow(i, f.born, f.jump, f.kept);
        }
    }

    /// A front of lane `i` followed at its own time: a kept one, or one
    /// the loop held off its lattice. Where it is born on a lattice point
    /// that already holds a deposit, it comes behind that point's front in
    /// the loop's lane, and so do the point's later deposits.
    fn follow(&mut self, i: usize, born: R, jump: R, kept: bool) {
        let m = i / 2;
        let k = (born * self.per_spacing[m]).round();
        let point = k.to_f64() as i64;
        let on_point = k * self.spacing[m] == born;
        let taken = self.points[i].get(point).is_some()
            || self.behind_kept.iter().any(|r| r.0 == i && r.1 == point);
        if kept {
            self.kept[i] += 1;
            if on_point && taken {
                self.behind_kept.retain(|r| !(r.0 == i && r.1 == point));
                self.behind_kept.push((i, point, 0));
                self.behind_mask[i] |= point_bit(point);
            }
        }
        self.made += 1;
        self.exact.push(Exact {
            born,
            jump,
            lane: i,
            kept,
            ahead: on_point && !taken,
            order: self.made,
        });
    }

    /// `behind_mask` anew, after entries of `behind_kept` went.
    pub(crate) fn remask_behind_kept(&mut self) {
        self.behind_mask.fill(0);
        for &(i, k, _) in &self.behind_kept {
            self.behind_mask[i] |= point_bit(k);
        }
    }

    /// Adds `d` on lattice point `k` of lane `i`, or to the front behind a
    /// kept one born there (see `behind_kept`).
    #[inline(always)]
    fn add_on_point(&mut self, i: usize, k: i64, d: R) {
        if self.behind_mask[i] & point_bit(k) != 0
            && let Some(r) = self.behind_kept.iter().position(|r| r.0 == i && r.1 == k)
        {
            self.add_behind_kept(r, d);
        } else {
            self.points[i].add(k, d);
        }
    }

    #[inline(never)]
    fn add_behind_kept(&mut self, r: usize, d: R) {
        let (i, k, bucket) = self.behind_kept[r];
        if let Some(e) = self
            .exact
            .iter_mut()
            .find(|e| bucket != 0 && e.order == bucket)
        {
            e.jump += d;
            return;
        }
        self.made += 1;
        self.behind_kept[r].2 = self.made;
        self.exact.push(Exact {
            born: R::of(k as f64) * self.spacing[i / 2],
            jump: d,
            lane: i,
            kept: false,
            ahead: false,
            order: self.made,
        });
    }

    /// Lane `i`'s fronts for the loop, in birth order (its lattice points
    /// born where the loop's deposits put them, `k * spacing`), into
    /// `fronts`; the group's hold on them let go.
    pub(crate) fn give_back(&mut self, i: usize, fronts: &mut Vec<Front<R>>) {
        let s = self.spacing[i / 2];
        let lane = &mut self.points[i];
        let mut all: Vec<(R, u8, u64, Front<R>)> = Vec::new();
        for (j, &jump) in lane.points.iter().enumerate() {
            if jump != R::zero() {
                let born = R::of((lane.base + j as i64) as f64) * s;
                all.push((
                    born,
                    1,
                    0,
                    Front {
                        born,
                        jump,
                        id: 0,
                        kept: false,
                    },
                ));
            }
        }
        lane.points.clear();
        for e in self.exact.iter().filter(|e| e.lane == i) {
            let front = Front {
                born: e.born,
                jump: e.jump,
                id: 0,
                kept: e.kept,
            };
            all.push((e.born, if e.ahead { 0 } else { 2 }, e.order, front));
        }
        self.exact.retain(|e| e.lane != i);
        self.behind_kept.retain(|r| r.0 != i);
        self.behind_mask[i] = 0;
        self.kept[i] = 0;
        // the loop's order among fronts born together (see `Exact::ahead`)
        all.sort_by(|a, b| {
            a.0.partial_cmp(&b.0)
                .unwrap_or(std::cmp::Ordering::Equal)
                .then(a.1.cmp(&b.1))
                .then(a.2.cmp(&b.2))
        });
        fronts.clear();
        fronts.extend(all.iter().map(|a| a.3));
    }

    /// A front born at `at` in lane `i` with jump `d`, as a lattice lane of
    /// the loop takes it: dropped below the layer's threshold, kept where
    /// it is born if large and the lane then holds fewer than
    /// `keep_at_most` kept fronts, else deposited on the two lattice
    /// points around its birth, jump and first moment kept. A lane's
    /// births come from one boundary (the wall for the bottom's up lane),
    /// whose events a step takes in time order, so each lane's births come
    /// in the loop's order; the kept fronts of the step under way (`due`)
    /// still count until they arrive.
    #[inline(always)]
    pub(crate) fn birth(&mut self, i: usize, at: R, d: R) {
        let l = &self.layers[i / 2];
        if d.abs() < l.drop_strain {
            if d != R::zero() {
                let force = (l.modulus * d.abs()).to_f64();
                self.dropped.fronts += 1;
                self.dropped.velocity += (d.abs() * l.wave_speed).to_f64();
                self.dropped.force += force;
                self.dropped.force_time += force * at.to_f64();
            }
            return;
        }
        self.born_sums[i] += d;
        if d.abs() >= self.keep_above[i] && self.keeps(i, at) {
            self.follow(i, at, d, true);
        } else {
            self.deposit(i, at, d);
        }
    }

    /// Whether lane `i` keeps one more large front born at `at`.
    #[inline(never)]
    fn keeps(&self, i: usize, at: R) -> bool {
        let transit = self.layers[i / 2].transit_time;
        let still = self
            .due
            .iter()
            .filter(|e| {
                let arrives = e.born + transit;
                e.kept && e.lane == i && (arrives > at || (self.from_up && arrives == at))
            })
            .count();
        self.kept[i] + still < self.keep_at_most
    }

    /// A birth on lane `i`'s lattice: split between the points around it.
    #[inline(always)]
    fn deposit(&mut self, i: usize, at: R, d: R) {
        // (births are at or after the impact: truncation is the floor,
        // without the call `floor` is on the baseline x86-64; and a
        // reciprocal, where two divisions were a fifth of a step)
        let m = i / 2;
        let x = at * self.per_spacing[m];
        let mut k = x.to_f64() as i64;
        let mut f = x - R::of(k as f64);
        if f < R::of(ON_POINT) || f > R::one() - R::of(ON_POINT) {
            // a birth on a lattice point, as the loop's division finds it:
            // all of it there, nothing on the next point (whose front
            // would otherwise exist, and order fronts born together)
            let s = self.spacing[m];
            if R::of((k + 1) as f64) * s == at {
                (k, f) = (k + 1, R::zero());
            } else if R::of(k as f64) * s == at {
                f = R::zero();
            }
        }
        let (lo, hi) = (d * (R::one() - f), d * f);
        if lo != R::zero() {
            self.add_on_point(i, k, lo);
        }
        if hi != R::zero() {
            self.add_on_point(i, k + 1, hi);
        }
    }

    /// The wall's arrivals before `to` (bottom's down lane), `(time,
    /// jump)`, in the order a step takes them (`step.rs`, `arrivals`):
    /// fronts arriving together in the lane's order, as the loop's wall
    /// events take them one by one.
    pub(crate) fn wall_ahead(&mut self, to: R) -> Vec<(R, R)> {
        let transit = self.layers[0].transit_time;
        let lane = &self.points[1];
        let ahead = &mut self.tagged;
        ahead.clear();
        for (j, &x) in lane.points.iter().enumerate() {
            let born = R::of((lane.base + j as i64) as f64) * self.spacing[0];
            if born + transit >= to {
                break;
            }
            if x != R::zero() {
                ahead.push(Tagged::on_point(born + transit, born, x));
            }
        }
        let exact = self
            .exact
            .iter()
            .filter(|e| e.lane == 1 && e.born + transit < to);
        ahead.extend(exact.map(|e| Tagged::exact(e, transit)));
        in_lane_order(ahead);
        let mut wall = std::mem::take(&mut self.wall);
        wall.clear();
        wall.extend(ahead.iter().map(|a| (a.arrives, a.jump)));
        wall
    }

    /// Hands back the vector [`Group::wall_ahead`] lent.
    pub(crate) fn return_wall(&mut self, wall: Vec<(R, R)>) {
        self.wall = wall;
    }

    /// How many fronts the group holds.
    pub(crate) fn len(&self) -> usize {
        self.exact.len() + self.points.iter().map(|l| l.points.len()).sum::<usize>()
    }
}

#[cfg(test)]
mod tests;

//! A merged run's leap takes in the arrivals its neighbours already hold.
//!
//! A fast layer between two lattice lanes hears from them every lattice
//! cell: a neighbour of transit `t_n` on a lattice of `p t_n` sends a
//! front every `p t_n`. Stopping a leap at each of them left leaps of a
//! few transits, or none: on the layer survey's rod 17 (a layer of
//! `6.8e-6` under one of `5.1e-4`) halving the lattice from `0.2` to `0.1`
//! of a transit stopped every leap (34,757 leaps, then one) and took the
//! run from 2.3 to 10.7 million steps.
//!
//! Yet those fronts are known when the leap starts: a front in a
//! neighbour's lane going towards the layer arrives when it arrives,
//! whatever the layer does meanwhile. Nothing the layer sends can reach it
//! before the neighbour's round trip, and nothing from farther away before
//! the bound [`Tracer::first_from_outside`] gives with those lanes left
//! out. So the leap takes every such front that arrives before that bound:
//! its transmission into the layer rings as one more phase (the ringing is
//! linear), its reflection goes back into the neighbour as a single front,
//! as the event at the interface would send them. The window then grows to
//! about a neighbour's transit (about 75 of the layer's transits there).
//!
//! The bottom takes them too. Its wall decisions are found in closed form
//! over the fronts it holds when the leap begins, and an arrival's ringing
//! can move the wall's strain (or the bottom's velocity) only so far, of
//! its own sign ([`Tracer::arrivals_slack`]): the decisions are sought
//! with that much taken off, so a leap that takes arrivals stops before
//! any decision they could bring, and falls back on the window without
//! them where the bound comes too near. The loop still takes every
//! decision. A fast bottom under a lattice lane hears from it every cell:
//! before this it rang in the loop (layer survey seed 3's rod 31, a bottom
//! of `1.3e-5` under `2.9e-4`: 8 M of the third level's 13 M loop steps).
//!
//! Only merged runs take arrivals by default: an exact run's neighbours
//! are not lattices, so its trains are spawned front by front and a
//! longer window saves nothing. [`LeapArrivals::Always`] makes exact runs
//! take them too, which tests the bookkeeping, and the bottom's bound,
//! against the event loop to rounding (`tests/leaps.rs`).

use super::{Ends, Phase};
use crate::config::LeapArrivals;
use crate::engine::Tracer;
use crate::error::WaveError;
use crate::lane::{Direction, Lane, MergeRule};
use crate::leap::Train;
use crate::real::Real;
use crate::wall::ContactState;

/// How many times the loop's work a leap that takes arrivals must save: a
/// leap's unit of work takes longer than a loop event, and a leap has its
/// fixed costs (survey rod 12, whose layer of `2.8e-6` under one of
/// `3.4e-5` took five arrivals into leaps of twelve transits, estimated at
/// a third of the loop's work, ran 1.4 times slower leaping).
const WORTH: f64 = 4.0;

/// A leap's work a phase, besides the cells its trains fill together.
const PER_PHASE: f64 = 3.0;

/// What the arrivals taken into a leap added to it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Taken<R> {
    /// Interface events they stood for.
    pub(super) events: u64,
    /// Jumps spawned into the layer's up and down lanes (its bases).
    pub(super) up: R,
    pub(super) down: R,
}

impl<R: Real> Default for Taken<R> {
    fn default() -> Self {
        Self {
            events: 0,
            up: R::zero(),
            down: R::zero(),
        }
    }
}

impl<R: Real> Tracer<R> {
    /// Whether a leap may take its neighbours' arrivals.
    pub(super) fn takes_arrivals(&self) -> bool {
        match self.leap_arrivals {
            LeapArrivals::Never => false,
            LeapArrivals::Merged => self.merged,
            LeapArrivals::Always => true,
        }
    }

    /// The most the arrivals a leap of the bottom would take in before
    /// `horizon` can move the wall towards a decision, whatever else rings
    /// there. An arrival's transmitted jump `d` reaches the wall at
    /// `s + t_0` and returns with `d q^k`: the wall sees the partial sums
    /// `d (1 + q + ... + q^k)`, each of the sign of `d` and at most
    /// `|d| / (1 - q)` for `q > 0`, `|d|` for `q <= 0`. In contact a
    /// tensile `d` adds at most twice that to the strain; in flight a
    /// downward `d` takes at most twice that, times the bottom's wave
    /// speed, off the velocity, from its arrival to the horizon. With this
    /// subtracted, [`Tracer::wall_stop`] finds the decisions of the
    /// bottom's own fronts as before, so a leap that takes arrivals never
    /// passes one (it falls back on the window without them where the
    /// bound comes too near).
    ///
    /// Scanning stops once the slack reaches `limit` (what the wall has
    /// now: the contact strain's distance from a decision, the height):
    /// then no leap can take them. Returns the slack (at least `limit`
    /// where it stopped) and how many fronts were looked at (a failed try
    /// holds off the next for that many loop events).
    pub(super) fn arrivals_slack(&self, horizon: R, ti: R, q: R, limit: R) -> (R, usize) {
        let Some(from) = self.from_above.get(1).copied().flatten() else {
            return (R::zero(), 0);
        };
        let lane = &self.lanes[from];
        let k = self.interfaces[0];
        let two = R::of(2.0);
        let most = if q > R::zero() {
            R::one() / (R::one() - q)
        } else {
            R::one()
        };
        let in_contact = matches!(self.contact, ContactState::InContact { .. });
        let c0 = self.layers[0].wave_speed;
        // (a lattice lane's fronts are in birth order but for a lattice
        // cell: none born after `horizon` plus a cell arrives before it)
        let last = match lane.rule {
            MergeRule::Lattice { spacing, .. } => horizon + spacing + spacing,
            MergeRule::Simultaneous { .. } => horizon,
        } - lane.transit;
        let (mut slack, mut scanned) = (R::zero(), 0);
        for f in lane.fronts() {
            if f.born > last || slack >= limit {
                break;
            }
            scanned += 1;
            let at = lane.arrival_of(f.born);
            let d = k.down_transmitted * lane.delivered(f.jump);
            slack = if at >= horizon {
                slack
            } else if in_contact && d > R::zero() {
                slack + two * d * most
            } else if !in_contact && d < R::zero() {
                let left = horizon - (at + ti);
                let left = if left > R::zero() { left } else { R::zero() };
                slack - two * c0 * d * most * left
            } else {
                slack
            };
        }
        (slack, scanned)
    }

    /// Whether a leap of layer `i` over `window` (from now) pays for
    /// taking arrivals. A leap costs a few units of work a phase (the
    /// layer's `m` fronts and the `a` arrivals: their tails, a cell or two)
    /// and one for every lattice cell its trains fill in a neighbour, the
    /// trains taken together (`together.rs`; or every front, where the
    /// round trip is longer than a cell). The loop would take about
    /// `window / t_i` events for each of the layer's fronts, and half that
    /// for each arrival (on average it rings half the window), but no more
    /// than the layer's lattice holds (the loop merges the arrivals into
    /// its cells, a leap rings each until it ends). The leap is taken where
    /// the loop would cost [`WORTH`] times more. Without the arrivals'
    /// count, survey rod 0 (stiff layers between soft ones on lattices of
    /// `4e-3` of the longest transit) took 500 arrivals into each leap and
    /// 3.7 times the loop's work.
    pub(super) fn worth_taking(&self, i: usize, window: R) -> bool {
        let ti = self.layers[i].transit_time;
        let period = ti + ti;
        let end = self.now + window;
        let own = self.lanes[Lane::<R>::index(i, Direction::Up)].len()
            + self.lanes[Lane::<R>::index(i, Direction::Down)].len();
        let mut arrivals = 0;
        let mut cells = R::one();
        for j in [i.checked_sub(1), Some(i + 1)].into_iter().flatten() {
            let towards = match j < i {
                true => Some(Lane::<R>::index(j, Direction::Up)),
                false => self.from_above.get(j).copied().flatten(),
            };
            let Some(towards) = towards else {
                continue;
            };
            let MergeRule::Lattice { spacing, .. } = self.lanes[towards].rule else {
                return false;
            };
            arrivals += self.lanes[towards].arriving_before(end);
            let step = if spacing > period { spacing } else { period };
            cells += window / step;
        }
        // the loop's lanes hold at most their lattice's cells
        let lane = &self.lanes[Lane::<R>::index(i, Direction::Up)];
        let capacity = match lane.rule {
            MergeRule::Lattice { spacing, .. } => R::of(2.0) * (ti / spacing + R::one()),
            MergeRule::Simultaneous { .. } => return false,
        };
        let (own, arrivals) = (R::of(own as f64), R::of(arrivals as f64));
        let leap = R::of(PER_PHASE) * (own + arrivals) + cells;
        let rounds = window / ti;
        let ringing = own + R::of(0.5) * arrivals;
        let by_loop = if ringing < capacity {
            ringing
        } else {
            capacity
        } * rounds
            + arrivals;
        by_loop > R::of(WORTH) * leap
    }

    /// Takes into the leap of layer `i` every front of its neighbours'
    /// lanes going towards it (a folded top's fronts all are) that arrives before `horizon`: each becomes a
    /// phase of the layer (or a front for the rebuilt lane, if its first
    /// crossing ends past the horizon), and its reflection is emitted into
    /// the neighbour. The fronts are taken out of their lanes and the
    /// neighbours put back in the queue.
    pub(super) fn take_arrivals(
        &mut self,
        i: usize,
        horizon: R,
        ti: R,
        ends: Ends<R>,
        phases: &mut Vec<Phase<R>>,
    ) -> Result<Taken<R>, WaveError> {
        let thr = self.layers[i].drop_strain();
        let period = ti + ti;
        let mut taken = Taken::default();
        // from above: down fronts of layer i + 1 reaching the layer's top
        if let Some(from) = self.from_above.get(i + 1).copied().flatten() {
            let back = Lane::<R>::index(i + 1, Direction::Up);
            let k = self.interfaces[i];
            while let Some((s, a)) = self.take_before(from, horizon) {
                taken.events += 1;
                self.emit_single(back, s, k.down_reflected * a, period)?;
                let d = k.down_transmitted * a;
                if d.abs() < thr {
                    self.drop_front(i, s, d);
                    continue;
                }
                taken.down += d;
                phases.push(Phase {
                    tau: s + ti,
                    amp: d,
                    top: None,
                });
            }
            self.reschedule_layer(i + 1)?;
        }
        // from below: up fronts of layer i - 1 reaching the layer's bottom
        if i > 0 {
            let from = Lane::<R>::index(i - 1, Direction::Up);
            let back = Lane::<R>::index(i - 1, Direction::Down);
            let k = self.interfaces[i - 1];
            while let Some((s, a)) = self.take_before(from, horizon) {
                taken.events += 1;
                self.emit_single(back, s, k.up_reflected * a, period)?;
                let d = k.up_transmitted * a;
                if d.abs() < thr {
                    self.drop_front(i, s, d);
                    continue;
                }
                taken.up += d;
                phases.push(Phase {
                    tau: s + period,
                    amp: ends.top * d,
                    top: Some((s + ti, d)),
                });
            }
            self.reschedule_layer(i - 1)?;
        }
        self.arrivals_taken += taken.events;
        Ok(taken)
    }

    /// The head of lane `index` if it arrives before `horizon`: when, and
    /// the jump it delivers (a folded top's, reflected at the free end).
    fn take_before(&mut self, index: usize, horizon: R) -> Option<(R, R)> {
        let at = self.lanes[index].head_arrival().filter(|&a| a < horizon)?;
        Some((at, self.pop_delivered(index)?))
    }

    /// One front born at `born` into `lane`, as a train of one (deposited
    /// on the lattice as the interface event would spawn it).
    fn emit_single(&mut self, lane: usize, born: R, jump: R, period: R) -> Result<(), WaveError> {
        self.emit(
            lane,
            Train {
                start: born,
                period,
                c: jump,
                q: R::zero(),
                count: 1,
            },
        )
    }
}

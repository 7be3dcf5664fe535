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
//! Only merged runs take arrivals by default, and only above the bottom
//! layer: an exact run's neighbours are not lattices, so its trains are
//! spawned front by front and a longer window saves nothing; the bottom's
//! wall decisions are found over the phases present when the leap begins.
//! [`LeapArrivals::Always`] makes exact runs take them too, which tests
//! the bookkeeping against the event loop to rounding
//! (`tests/leaps.rs`).

use super::{Ends, Phase};
use crate::config::LeapArrivals;
use crate::engine::Tracer;
use crate::error::WaveError;
use crate::lane::{Direction, Lane, MergeRule};
use crate::leap::Train;
use crate::real::Real;

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
    /// Whether a leap of layer `i` may take its neighbours' arrivals.
    pub(super) fn takes_arrivals(&self, i: usize) -> bool {
        i > 0
            && match self.leap_arrivals {
                LeapArrivals::Never => false,
                LeapArrivals::Merged => self.merged,
                LeapArrivals::Always => true,
            }
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

//! The event loop of the exact engine: the tracer's state, and each event
//! as the fronts meet a boundary. Setting a run up (`setup.rs`), the rod as one
//! body (`motion.rs`: the wall's ledger, flight, landing and escape), what a
//! run accounts for (`ledger.rs`) and what it tells its caller
//! (`observe.rs`) are the submodules.
//!
//! Everything here runs in internal units (see `impact_model::units`): the
//! rod's length, mean density and stiffness and the impact speed are all of
//! order one, whatever units the scene was written in. Times, strains and
//! heights are converted back to the scene's units, exactly (the scales are
//! powers of two), only where they leave the engine.

use crate::config::{LeapArrivals, Record, StopRule};
use crate::error::WaveError;
use crate::lane::{Direction, Lane, Pushed};
use crate::queue::{EventInPast, EventKey, EventQueue};
use crate::real::Real;
use crate::record::Recording;
use crate::wall::{self, ContactState};
use crate::window::Window;
use impact_model::escape::EscapeBound;
use impact_model::{ContactHistory, InterfaceCoefficients, StopReason, Units};

/// Instants this many ulps apart (of the time, plus the shortest transit)
/// are one: rounding alone could have split them (see [`Window`]). A gap
/// this small is rounding, not a use of the simultaneity window: the error
/// estimate's rounding part covers it.
pub(crate) const TIE_ULPS: f64 = 64.0;

/// A contact decision within this margin of going the other way (relative
/// to the impact's strain or speed) is near grazing: a run that takes one
/// is repeated in double-double (`solve.rs`), and a leap leaves it to the
/// loop.
pub(crate) const NEAR_GRAZING: f64 = 1e-7;

mod ledger;
mod motion;
mod observe;
pub use observe::BlockResponse;
mod setup;

pub use ledger::Decisions;
pub(crate) use ledger::Ledger;
pub(crate) use motion::WallLedger;

/// What one call of [`Tracer::step`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    /// When, in the scene's units.
    pub time: f64,
    /// Which event it was.
    pub kind: StepKind,
}

/// The kind of event processed by a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepKind {
    /// Fronts reached interface `b` (between layers `b - 1` and `b`).
    Interface(usize),
    /// Fronts reached the free top.
    Top,
    /// Fronts reached the wall; `separated` when the rod left it there.
    Wall {
        /// Whether the rod left the wall at this arrival (the wall strain would have turned tensile).
        separated: bool,
    },
    /// The free bottom landed on the wall.
    Reconnected,
    /// Layer `layer`'s ringing was advanced in closed form over a quiet
    /// window, standing for `events` boundary events.
    Leap {
        /// Index of the leapt layer, bottom first.
        layer: usize,
        /// The boundary events of its ringing that the leap replaced.
        events: u64,
    },
    /// The bottom group's fronts were followed in steps (taken over from
    /// the loop, or stepped on), `fronts` of them.
    Stepped {
        /// Fronts followed, each a boundary event.
        fronts: u64,
    },
    /// The run is over.
    Stopped(StopReason),
}

/// One layer's constants in internal units.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LayerConst<R> {
    pub bottom: R,
    pub top: R,
    pub length: R,
    pub modulus: R,
    pub wave_speed: R,
    pub impedance: R,
    pub transit_time: R,
    /// Fronts with `|jump|` below this are dropped.
    pub(crate) drop_strain: R,
}

impl<R: Real> LayerConst<R> {
    /// Fronts with `|jump|` below this are dropped.
    pub(crate) fn drop_strain(&self) -> R {
        self.drop_strain
    }
}

/// The exact engine for one rod, in arithmetic `R` (`f64`, or `TwoFloat` to
/// measure rounding). Build with [`Tracer::new`], then [`Tracer::run`] to the
/// end or [`Tracer::step`] one event at a time. After each step, the fields
/// are exactly those of the rod at [`Tracer::time`].
#[derive(Debug, Clone)]
pub struct Tracer<R: Real> {
    pub(crate) layers: Vec<LayerConst<R>>,
    pub(crate) interfaces: Vec<InterfaceCoefficients<R>>,
    pub(crate) lanes: Vec<Lane<R>>,
    /// For boundary `b`: the lane whose fronts arrive there from above
    /// (the layer's down lane, or the folded top lane), if any.
    pub(crate) from_above: Vec<Option<usize>>,
    /// Up-going component at the bottom of each layer, behind all its up
    /// fronts; with the lanes it gives the field anywhere (see `fields`).
    pub(crate) up_base: Vec<R>,
    /// Down-going component at the top of each layer, behind its down fronts
    /// (for a folded top lane: behind the fronts that have not yet reached the
    /// top).
    pub(crate) down_base: Vec<R>,
    pub(crate) queue: EventQueue<R>,
    pub(crate) contact: ContactState<R>,
    pub(crate) ledger: WallLedger<R>,
    pub(crate) history: ContactHistory,
    pub(crate) impact_speed: R,
    pub(crate) mass: R,
    /// The escape bound of the rod (DESIGN.md §2), in the run's arithmetic.
    escape: EscapeBound<R>,
    /// Which instants are one (see [`Window`]).
    pub(crate) window: Window<R>,
    pub(crate) grazing_strain: R,
    pub(crate) merged: bool,
    /// Whether quiet layers are leapt (see `leap.rs`).
    pub(crate) leaps: bool,
    /// Which leaps take in their neighbours' arrivals, and how many they
    /// took.
    pub(crate) leap_arrivals: LeapArrivals,
    pub(crate) arrivals_taken: u64,
    max_events: u64,
    pub(crate) max_time: R,
    stop_rule: StopRule,
    pub(crate) record: Record,
    recording: Recording,
    pub(crate) drops: Ledger,
    decisions: Decisions,
    /// Whether the front `take_head` took last was one a lattice lane
    /// keeps where it was born (not a deposit): a separation it decides is
    /// not a lattice point's (`Decisions::separations_on_lattice`).
    last_taken_kept: bool,
    pub(crate) events: u64,
    /// Reflections at a folded top whose fronts came back: events of the
    /// unfolded engine, counted so that both report the same work.
    folded_reflections: u64,
    /// Boundary events advanced in closed form by leaps.
    pub(crate) leaped: u64,
    /// What leaps did: phases advanced and lattice cells filled.
    pub(crate) leap_work: u64,
    /// Per layer: no leap before this time (a wall decision is due first).
    pub(crate) leap_after: Vec<R>,
    /// Per layer: no try to leap before this many loop events.
    pub(crate) leap_retry: Vec<u64>,
    /// No weighing of the bottom's leaps with arrivals before this many
    /// loop events (`leap.rs`: the bottom tries at every event of its own).
    pub(crate) bottom_weighs_after: u64,
    /// Lattice deposits a leap gathers before placing them: (lane, at, d).
    pub(crate) deposits: Vec<(usize, R, R)>,
    /// Trains an exact leap sends into its neighbours' lanes, spawned
    /// front by front in birth order when the leap ends.
    pub(crate) exact_trains: crate::leap::ExactTrains<R>,
    /// Geometric sums `(q, n) -> (s0, s1, s2)` in slots by `n` (`leap.rs`).
    pub(crate) sums_memo: Vec<(R, u64, (R, R, R))>,
    /// The last powers `q^k` a leap asked for (`Tracer::pow_remembered`),
    /// `(q, k, q^k)`: one per sign of the ratio.
    pub(crate) pow_memo: [(R, u64, R); 2],
    /// A leap's buffers, kept for the next.
    pub(crate) scratch: crate::leap::LeapScratch<R>,
    /// The last `(|q|, ln |q|)` a leap needed.
    pub(crate) ln_memo: Option<(R, R)>,
    /// One lane's deposits as a leap places them, kept for the next.
    pub(crate) batch: Vec<(R, R)>,
    /// A lane's deposits summed point by point (`lane::sum_on_points`).
    pub(crate) point_sums: Vec<R>,
    /// The buffers of a leap's trains deposited together, kept for the next.
    pub(crate) together: crate::leap::TogetherRoom<R>,
    /// Fronts a lane merges as a leap places them, kept for the next.
    pub(crate) spare_fronts: Vec<crate::lane::Front<R>>,
    /// Blocks of fast layers answered by their response (`block.rs`).
    pub(crate) blocks: crate::block::Blocks<R>,
    /// The bottom group, stepped between wall decisions (`group.rs`).
    pub(crate) group: Option<Box<crate::group::Group<R>>>,
    /// Fronts the bottom group's steps followed (boundary events).
    pub(crate) stepped: u64,
    pub(crate) next_id: u32,
    pub(crate) now: R,
    stopped: Option<StopReason>,
    pub(crate) units: Units,
    transit_times: Vec<f64>,
}

/// The exact engine in double precision.
pub type WaveEngine = Tracer<f64>;

pub(crate) fn past(e: EventInPast) -> WaveError {
    WaveError::EventInPast {
        now: e.now,
        requested: e.requested,
    }
}

impl<R: Real> Tracer<R> {
    /// Adds a front born at `t` at the start of the lane of (`layer`, `dir`).
    /// Inlined, as are `take_head` and `boundary_event`: out of line, their
    /// calls (saved registers, spilled arguments) were a quarter of an
    /// event's instructions at the hard corner (callgrind).
    #[inline(always)]
    pub(crate) fn spawn(
        &mut self,
        layer: usize,
        dir: Direction,
        t: R,
        jump: R,
        parents: &[u32],
    ) -> Result<(), WaveError> {
        self.spawn_by(layer, dir, t, jump, parents, Lane::push)
    }

    /// [`Tracer::spawn`] deposited on a lattice lane whatever its size
    /// ([`Lane::push_deposited`]).
    pub(crate) fn spawn_deposited(
        &mut self,
        layer: usize,
        dir: Direction,
        t: R,
        jump: R,
    ) -> Result<(), WaveError> {
        self.spawn_by(layer, dir, t, jump, &[], Lane::push_deposited)
    }

    /// [`Tracer::spawn`] with the lane's `push`.
    #[inline(always)]
    fn spawn_by(
        &mut self,
        layer: usize,
        dir: Direction,
        t: R,
        jump: R,
        parents: &[u32],
        push: impl FnOnce(&mut Lane<R>, R, R, u32) -> Pushed<R>,
    ) -> Result<(), WaveError> {
        if jump == R::zero() {
            return Ok(());
        }
        if jump.abs() < self.layers[layer].drop_strain {
            self.drop_front(layer, t, jump);
            return Ok(());
        }
        match dir {
            Direction::Up => self.up_base[layer] += jump,
            Direction::Down => self.down_base[layer] += jump,
        }
        let index = Lane::<R>::index(layer, dir);
        let id = self.next_id;
        let lane = &mut self.lanes[index];
        match push(lane, t, jump, id) {
            Pushed::New { was_empty } => {
                if self.record.fronts {
                    let arrives = lane.arrival_of(t);
                    self.record_front(id, (layer, dir), (t, arrives), jump, parents);
                }
                self.next_id += 1;
                if was_empty {
                    self.reschedule_layer(layer)?;
                }
            }
            Pushed::Merged {
                id,
                moved_head,
                beyond_simultaneity,
                gap,
            } => {
                if gap > R::zero() {
                    // (a leap spawns fronts born after now)
                    self.note_combined(gap, t);
                }
                if beyond_simultaneity {
                    self.drops.truncation.merged_fronts += 1;
                }
                if moved_head {
                    self.reschedule_layer(layer)?;
                }
                if self.record.fronts {
                    self.record_merge(id, jump, parents);
                }
            }
        }
        Ok(())
    }

    /// Takes the head of lane `index` if it arrives by `deadline`: its
    /// delivered jump and id.
    #[inline(always)]
    fn take_head(&mut self, index: usize, deadline: R) -> Result<Option<(R, u32)>, WaveError> {
        let lane = &mut self.lanes[index];
        match lane.head_arrival() {
            Some(t) if t <= deadline => {
                if t > self.now {
                    let gap = t - self.now;
                    self.note_combined(gap, t);
                }
            }
            _ => return Ok(None),
        }
        let lane = &mut self.lanes[index];
        let Some(front) = lane.pop() else {
            return Ok(None);
        };
        let jump = lane.delivered(front.jump);
        self.last_taken_kept = front.kept;
        if lane.folded {
            // the front reflected at the top on its way: that reflection is
            // an event of the unfolded engine, and moves the top's base
            self.folded_reflections += 1;
            self.down_base[lane.layer] -= front.jump;
        }
        // the layer's first arrival now: this lane's new head, or its
        // sibling's (lanes of a layer are `2 i` and `2 i + 1`)
        let (layer, next) = (lane.layer, lane.head_arrival());
        let other = self.lanes[index ^ 1].head_arrival();
        let first = match (next, other) {
            (Some(a), Some(b)) => Some(if b < a { b } else { a }),
            (a, b) => a.or(b),
        };
        let key = EventKey::Layer(layer as u32);
        match first {
            Some(at) => self.queue.schedule(key, at, self.now).map_err(past)?,
            None => self.queue.cancel(key),
        }
        Ok(Some((jump, front.id)))
    }

    /// Takes the head of lane `index` without an event (a leap takes it
    /// in): the jump it delivers. A folded lane's front reflected at the
    /// top on its way, an event of the unfolded engine counted as
    /// [`Tracer::take_head`] counts it. The caller puts the layer back in
    /// the queue.
    pub(crate) fn pop_delivered(&mut self, index: usize) -> Option<R> {
        let lane = &mut self.lanes[index];
        let front = lane.pop()?;
        let jump = lane.delivered(front.jump);
        if lane.folded {
            self.folded_reflections += 1;
            self.down_base[lane.layer] -= front.jump;
        }
        Some(jump)
    }

    /// The lane of `layer` whose head arrives first (the up lane on a tie,
    /// the order of the lanes' indices), and when.
    #[inline]
    fn first_lane(&self, layer: usize) -> Option<(usize, R)> {
        let up = Lane::<R>::index(layer, Direction::Up);
        let down = Lane::<R>::index(layer, Direction::Down);
        match (
            self.lanes[up].head_arrival(),
            self.lanes[down].head_arrival(),
        ) {
            (Some(u), Some(d)) if d < u => Some((down, d)),
            (Some(u), _) => Some((up, u)),
            (None, d) => d.map(|d| (down, d)),
        }
    }

    /// Puts `layer`'s first arrival in the queue (or takes the layer out).
    #[inline]
    pub(crate) fn reschedule_layer(&mut self, layer: usize) -> Result<(), WaveError> {
        let key = EventKey::Layer(layer as u32);
        match self.first_lane(layer) {
            Some((_, t)) => self.queue.schedule(key, t, self.now).map_err(past),
            None => {
                self.queue.cancel(key);
                Ok(())
            }
        }
    }

    /// Processes the next event. Arrivals at the same boundary within the
    /// simultaneity window are combined into one event first.
    pub fn step(&mut self) -> Result<Step, WaveError> {
        let to_scene = |t: R, u: &Units| t.to_f64() * u.time;
        if let Some(reason) = self.stopped {
            return Ok(Step {
                time: self.time(),
                kind: StepKind::Stopped(reason),
            });
        }
        if self.steps() >= self.max_events {
            return Err(WaveError::EventLimit {
                events: self.steps(),
                time: self.time(),
            });
        }
        let Some((key, t)) = self.queue.next_event() else {
            // Nothing left can happen (every front dropped): the rod is free
            // for good only if it moves away; otherwise this is a limit case.
            return Err(WaveError::TimeLimit { time: self.time() });
        };
        if t > self.max_time {
            return Err(WaveError::TimeLimit {
                time: to_scene(t, &self.units),
            });
        }
        self.events += 1;
        self.now = t;
        let kind = match key {
            EventKey::Layer(layer) => {
                let layer = layer as usize;
                // (`leap_after` checked here too: most layers never leap,
                // and the call alone cost a small point a sixth of its time)
                if self.leaps
                    && t >= self.leap_after[layer]
                    && self.events >= self.leap_retry[layer]
                    && let Some(events) = self.leap(layer)?
                {
                    // the arrival that started the leap is among the events
                    // it counts: the loop's iteration is work, not an event
                    self.events -= 1;
                    self.leap_work += 1;
                    StepKind::Leap { layer, events }
                } else if let Some(&Some((bi, o))) = self.blocks.key_of.get(layer) {
                    // a block layer's key: its port's deliveries
                    self.block_delivery(bi, o)?
                } else if layer == 0 && self.group_active() {
                    // the stepped group's key
                    self.group_tick()?
                } else if self.group.as_deref().is_some_and(|g| layer < g.top)
                    && self.try_group()?
                {
                    StepKind::Stepped { fronts: 0 }
                } else {
                    // a layer is in the queue exactly while one of its lanes
                    // holds a front (spawn, take_head and leaps keep it so)
                    let (lane, _) = self
                        .first_lane(layer)
                        .expect("a scheduled layer holds a front");
                    let boundary = self.lanes[lane].target();
                    self.boundary_event(boundary, t)?
                }
            }
            EventKey::Reconnection => {
                self.queue.pop();
                let wall_lane = self.from_above[0];
                if wall_lane.is_some_and(|i| {
                    self.lanes[i]
                        .head_arrival()
                        .is_some_and(|a| a <= t + self.window.at(t))
                }) {
                    // A front reaches the bottom as it lands: one event. It
                    // reflects off the still-free bottom first; if the bottom
                    // still moves down it lands at once (the landing is
                    // rescheduled at t), else the flight goes on. Either
                    // order gives the same state; this one gives no
                    // zero-length contact.
                    self.landing_arrival()?
                } else {
                    self.reconnect(t)?;
                    StepKind::Reconnected
                }
            }
            EventKey::Escape => {
                self.queue.pop();
                if self.group_active() {
                    // the field's check needs the group's fronts
                    self.release_group()?;
                }
                if self.merged && !self.escape_confirmed()? {
                    StepKind::Wall { separated: false }
                } else {
                    self.finish(t, StopReason::Escaped)
                }
            }
            EventKey::Horizon => {
                self.queue.pop();
                if self.group_active() {
                    self.release_group()?;
                }
                let reason = StopReason::at_horizon(self.history.in_contact());
                self.finish(t, reason)
            }
        };
        Ok(Step {
            time: to_scene(t, &self.units),
            kind,
        })
    }

    fn finish(&mut self, t: R, reason: StopReason) -> StepKind {
        self.advance_wall(t);
        self.stopped = Some(reason);
        StepKind::Stopped(reason)
    }

    /// Spawns a front with no recorded parents (for leaps).
    pub(crate) fn spawn_front(
        &mut self,
        layer: usize,
        dir: Direction,
        t: R,
        jump: R,
    ) -> Result<(), WaveError> {
        self.spawn(layer, dir, t, jump, &[])
    }

    /// A front reaching the free bottom as it lands: the wall's boundary
    /// event, out of line (rare; the event loop inlines the common one).
    #[inline(never)]
    fn landing_arrival(&mut self) -> Result<StepKind, WaveError> {
        self.boundary_event(0, self.now)
    }

    /// All fronts reaching boundary `b` within the simultaneity window of
    /// `t`, as one event.
    #[inline(always)]
    fn boundary_event(&mut self, b: usize, t: R) -> Result<StepKind, WaveError> {
        let deadline = t + self.window.at(t);
        let n = self.layers.len();
        let mut parents = [0u32; 2];
        let mut count = 0;
        let mut from_below = R::zero();
        let mut from_above = R::zero();
        if b > 0
            && let Some((d, id)) =
                self.take_head(Lane::<R>::index(b - 1, Direction::Up), deadline)?
        {
            from_below = d;
            parents[count] = id;
            count += 1;
        }
        if let Some(lane) = self.from_above[b]
            && let Some((d, id)) = self.take_head(lane, deadline)?
        {
            from_above = d;
            parents[count] = id;
            count += 1;
        }
        let parents = &parents[..count];
        if b == 0 {
            self.advance_wall(t);
            let c0 = self.layers[0].wave_speed;
            if let ContactState::InContact { strain } = self.contact {
                let scale = self.impact_speed / c0;
                let rigid = strain + R::of(2.0) * from_above;
                self.note_decision(rigid / scale);
                if rigid != R::zero() && rigid.abs() <= self.grazing_strain {
                    self.decisions.within_tolerance += 1;
                    self.decisions.grazed += 1;
                }
            }
            let r = wall::reflect(self.contact, from_above, c0, t, self.grazing_strain);
            self.contact = r.state;
            if r.separated {
                if !self.last_taken_kept
                    && self.from_above[0].is_some_and(|lane| self.lanes[lane].lattice_arrival(t))
                {
                    self.decisions.separations_on_lattice += 1;
                }
                self.history.separate(t.to_f64() * self.units.time);
                self.drops.at_separation =
                    (self.drops.dropped_force, self.drops.dropped_force_time);
                self.schedule_escape(t)?;
            }
            self.schedule_landing()?;
            self.spawn(0, Direction::Up, t, r.reflected, parents)?;
            self.record_wall();
            Ok(StepKind::Wall {
                separated: r.separated,
            })
        } else if b == n {
            self.spawn(n - 1, Direction::Down, t, -from_below, parents)?;
            Ok(StepKind::Top)
        } else {
            if let Some(&Some(port)) = self.blocks.port_at.get(b) {
                return self.block_boundary(b, t, (from_below, from_above), port, parents);
            }
            if self
                .group
                .as_deref()
                .is_some_and(|g| g.active && g.top == b)
            {
                debug_assert!(from_below == R::zero());
                return self.group_input(t, from_above, parents);
            }
            let k = self.interfaces[b - 1];
            let down = k.up_reflected * from_below + k.down_transmitted * from_above;
            let up = k.up_transmitted * from_below + k.down_reflected * from_above;
            self.spawn(b - 1, Direction::Down, t, down, parents)?;
            self.spawn(b, Direction::Up, t, up, parents)?;
            Ok(StepKind::Interface(b))
        }
    }
}

//! The event loop of the exact engine.
//!
//! Everything here runs in internal units (see `impact_model::units`): the
//! rod's length, mean density and stiffness and the impact speed are all of
//! order one, whatever units the scene was written in. Times, strains and
//! heights are converted back to the scene's units, exactly (the scales are
//! powers of two), only where they leave the engine.

use crate::config::{LeapArrivals, Record, Resolution, StopRule, WaveConfig};
use crate::error::WaveError;
use crate::lane::{Direction, Lane, MergeRule, Pushed};
use crate::queue::{EventInPast, EventKey, EventQueue};
use crate::real::Real;
use crate::record::{FrontRecord, Recording, WallSample};
use crate::wall::{self, ContactState};
use crate::window::Window;
use impact_model::escape::{EscapeBound, Margin, internal_energy};
use impact_model::{
    ContactHistory, EngineKind, InterfaceCoefficients, Outcome, Rod, StopReason, Truncation, Units,
    WaveConstants,
};

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

/// The merge rule of a lane, from its layer's transit time and wave speed.
type LaneRule<R> = dyn Fn(f64, f64) -> MergeRule<R>;
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
    /// The run is over.
    Stopped(StopReason),
}

/// Wall impulse bookkeeping: everything the wall does to the rod is the force
/// `-E0 eps0` while in contact, so the centre of mass is known exactly.
#[derive(Debug, Clone, Copy)]
pub(crate) struct WallLedger<R> {
    /// Time of the last update.
    pub(crate) at: R,
    /// `I = integral(eps0 dt)`.
    pub(crate) impulse: R,
    /// `W = integral(I dt)`, for the centre-of-mass displacement.
    pub(crate) moment: R,
}

/// Fronts whose velocity jump is at least this fraction of the impact speed
/// stay where they were born in a merged lane...
const KEEP_ABOVE: f64 = 1e-2;
/// ...up to this many per lane: the few large fronts whose exact timing
/// decides contacts (the impact front, a landing's front), while the many
/// small ones they shed are deposited on the lattice.
const KEEP_AT_MOST: usize = 8;

/// The escape bound's margins ([`impact_model::escape`]). A margin only
/// makes a run stop later (a few more events), never wrongly, so each is
/// set well above what it covers. Relative, on the energy balance: the
/// dropped fronts may leave the true internal energy a hair above the
/// balance `M (v_b^2 - v^2) / 2` used to schedule the stop.
const BALANCE_MARGIN: f64 = 1e-9;
/// Absolute, in impact-speed-times-`sum(t_i)`: above the rounding of the
/// centre-of-mass displacement, so a rod with no internal energy left
/// (`D = 0`) still stops only once it has risen clear of it.
const ROUNDING_MARGIN: f64 = 1e-12;
/// Relative, when the bound is checked on a merged field: the merged
/// field's energy and the bottom's offset are those of the deposited fronts,
/// which differ a little from the exact balance; a failed check reschedules.
const MERGED_FIELD_MARGIN: f64 = 1e-6;

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

/// How close the run's nonlinear decisions came to going the other way:
/// where rounding can be amplified.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Decisions {
    /// Contact decisions and landings taken.
    pub count: u64,
    /// Those within `1e-7` (relative to the impact's strain or speed) of
    /// the other outcome.
    pub near_grazing: u64,
    /// The smallest relative margin met.
    pub smallest_margin: f64,
    /// Settled by a tolerance rather than by the arithmetic: arrivals (or
    /// births) more than rounding apart combined by the simultaneity
    /// window, and wall strains within the grazing tolerance of zero taken
    /// as zero. Each moved the run by up to the tolerance; the solver
    /// measures what they did to `e` by a rerun with tighter tolerances.
    pub within_tolerance: u64,
    /// Of those, the wall strains taken as zero.
    pub grazed: u64,
}

/// Drops and merges, with what the error estimate needs of them.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct Ledger {
    pub(crate) truncation: Truncation,
    /// `sum E |d|` over dropped fronts (force mismatch they leave), and
    /// `sum E |d| s` with `s` their birth times.
    pub(crate) dropped_force: f64,
    pub(crate) dropped_force_time: f64,
    /// Those sums at the last separation (only drops before the last
    /// separation can change the wall impulse).
    pub(crate) at_separation: (f64, f64),
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
    /// Lattice deposits a leap gathers before placing them: (lane, at, d).
    pub(crate) deposits: Vec<(usize, R, R)>,
    /// Trains an exact leap sends into its neighbours' lanes, spawned
    /// front by front in birth order when the leap ends.
    pub(crate) exact_trains: crate::leap::ExactTrains<R>,
    /// Geometric sums `(q, n) -> (s0, s1, s2)` in slots by `n` (`leap.rs`).
    pub(crate) sums_memo: Vec<(R, u64, (R, R, R))>,
    /// A leap's buffers, kept for the next.
    pub(crate) scratch: crate::leap::LeapScratch<R>,
    /// The last `(|q|, ln |q|)` a leap needed.
    pub(crate) ln_memo: Option<(R, R)>,
    /// One lane's deposits as a leap places them, kept for the next.
    pub(crate) batch: Vec<(R, R)>,
    /// Fronts a lane merges as a leap places them, kept for the next.
    pub(crate) spare_fronts: Vec<crate::lane::Front<R>>,
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
    /// Prepares a run: the impact happens at `t = 0`, launching the
    /// compression front `-v_b / c0` from the wall. A tracer runs one
    /// resolution: `Exact` and `Auto` both mean exact here (choosing between
    /// runs is [`crate::simulate`]'s job), `Merged` merges.
    pub fn new(rod: &Rod, config: WaveConfig) -> Result<Self, WaveError> {
        if let Some(i) = rod.scene().layers.iter().position(|l| l.is_viscous()) {
            return Err(WaveError::ViscousLayer { layer: i });
        }
        config.check_engine()?;
        let scaled = rod.scaled_layers();
        let units = *rod.units();
        let of = R::of;
        let vb = of(rod.scaled_impact_speed());
        let t_min = scaled
            .iter()
            .map(|l| l.transit_time)
            .fold(f64::INFINITY, f64::min);
        let t_max = scaled.iter().map(|l| l.transit_time).fold(0.0, f64::max);
        let simultaneity = of(config.simultaneity) * of(t_min);
        let window = Window {
            fixed: simultaneity,
            ulps: of(TIE_ULPS * f64::EPSILON),
            scale: of(t_min),
        };
        let (rule, merged): (Box<LaneRule<R>>, bool) = match config.resolution {
            Resolution::Exact | Resolution::Auto { .. } => (
                Box::new(move |_, _| MergeRule::Simultaneous { window }),
                false,
            ),
            Resolution::Merged {
                per_transit,
                per_longest,
            } => (
                Box::new(move |transit: f64, speed: f64| MergeRule::Lattice {
                    spacing: simultaneity.max(of((per_transit * transit).min(per_longest * t_max))),
                    keep_above: of(KEEP_ABOVE) * vb / of(speed),
                    keep_at_most: KEEP_AT_MOST,
                }),
                true,
            ),
        };
        // The layers' derived constants in the run's arithmetic, from their
        // primary quantities by the model's formulas (`WaveConstants`,
        // `InterfaceCoefficients::of_sides`): a double run gets the model's
        // numbers bit for bit, a double-double run its own. Taken from the model's doubles, they carried double
        // rounding into the double-double rerun: on the grazing line
        // `alpha = 0.1`, whose points are rerun so, `e` was 2.5 ulps from the
        // 40-digit value under a bound of 1.7 (`tests/integration/tracker.rs`).
        let layers: Vec<LayerConst<R>> = scaled
            .iter()
            .map(|l| {
                let (length, modulus) = (of(l.length), of(l.modulus));
                let waves = WaveConstants::of(length, modulus, of(l.density));
                LayerConst {
                    bottom: of(l.bottom),
                    top: of(l.top),
                    length,
                    modulus,
                    wave_speed: waves.wave_speed,
                    impedance: waves.impedance,
                    transit_time: waves.transit_time,
                    drop_strain: of(config.drop_tolerance) * vb / waves.wave_speed,
                }
            })
            .collect();
        let n = layers.len();
        // The top's lanes fold into one (its reflections carried by the
        // fronts, no events at the free end), except where fronts are
        // recorded and where a merged run may leap a fast top (a folded
        // lane is not leapt, see `leap`): a top ringing a million times
        // under a slow layer otherwise takes the loop a million steps.
        let fast_top = n >= 2
            && scaled[n - 1].transit_time * crate::leap::LEAST_TRANSITS
                < scaled[n - 2].transit_time;
        // An exact run leaps only when nothing is recorded: a recording
        // shows every event. A double-double run never does
        // (`Real::LEAPS`), but lays its lanes out as the double run it
        // checks does (a merged run's lattice lanes are its discretisation).
        let may_leap =
            config.leap_quiet_layers && (merged || !(config.record.wall || config.record.fronts));
        let leaps = R::LEAPS && may_leap;
        let fold = !(config.record.fronts || (may_leap && fast_top));
        let mut room = crate::room::take::<R>();
        let mut lanes: Vec<Lane<R>> = scaled
            .iter()
            .enumerate()
            .flat_map(|(i, l)| {
                let transit = layers[i].transit_time;
                [Direction::Up, Direction::Down]
                    .map(|d| Lane::new(i, d, transit, rule(l.transit_time, l.wave_speed)))
            })
            .collect();
        for (lane, kept) in lanes.iter_mut().zip(room.lanes.drain(..)) {
            lane.move_into(kept);
        }
        let top_up = Lane::<R>::index(n - 1, Direction::Up);
        lanes[top_up].folded = fold;
        let from_above = (0..=n)
            .map(|b| match b {
                b if b == n => None,
                b if fold && b == n - 1 => Some(top_up),
                b => Some(Lane::<R>::index(b, Direction::Down)),
            })
            .collect();
        let interfaces = layers
            .windows(2)
            .map(|w| {
                let side = |l: &LayerConst<R>| (l.impedance, l.modulus);
                InterfaceCoefficients::of_sides(side(&w[0]), side(&w[1]))
            })
            .collect();
        let c0 = layers[0].wave_speed;
        let transit_sum: f64 = scaled.iter().map(|l| l.transit_time).sum();
        let two = of(2.0);
        let mut engine = Self {
            interfaces,
            // At rest relative to the rod's motion at -v_b: a = v_b/2c, b = -v_b/2c.
            up_base: layers.iter().map(|l| vb / (two * l.wave_speed)).collect(),
            down_base: layers.iter().map(|l| -vb / (two * l.wave_speed)).collect(),
            queue: EventQueue::new(n),
            lanes,
            from_above,
            contact: ContactState::InContact { strain: R::zero() },
            ledger: WallLedger {
                at: R::zero(),
                impulse: R::zero(),
                moment: R::zero(),
            },
            history: ContactHistory::new(),
            impact_speed: vb,
            mass: scaled
                .iter()
                .fold(R::zero(), |m, l| m + of(l.density) * of(l.length)),
            escape: EscapeBound::new(of(rod.scaled_compliance_moment()), of(rod.scaled_mass())),
            window,
            grazing_strain: of(config.grazing_tolerance) * vb / c0,
            merged,
            leaps,
            leap_arrivals: config.leap_arrivals,
            arrivals_taken: 0,
            max_events: config.max_events,
            max_time: of(config.max_time_factor * transit_sum),
            stop_rule: config.stop,
            record: config.record,
            recording: Recording::default(),
            drops: Ledger::default(),
            decisions: Decisions {
                smallest_margin: f64::INFINITY,
                ..Decisions::default()
            },
            events: 0,
            folded_reflections: 0,
            leaped: 0,
            leap_work: 0,
            leap_after: crate::leap::first_leaps(&layers, fold),
            leap_retry: vec![0; n],
            deposits: room.deposits,
            exact_trains: room.exact_trains,
            sums_memo: Vec::new(),
            scratch: room.scratch,
            ln_memo: None,
            batch: room.batch,
            spare_fronts: room.spare_fronts,
            next_id: 0,
            now: R::zero(),
            stopped: None,
            units,
            transit_times: rod.transit_times(),
            layers,
        };
        if let StopRule::Horizon { factor } = config.stop {
            let horizon = of(factor) * of(t_max);
            engine
                .queue
                .schedule(EventKey::Horizon, horizon, R::zero())
                .map_err(past)?;
        }
        // The impact: the bottom is stopped, v: -v_b -> 0, so d = -v_b / c0.
        let first = -vb / c0;
        engine.contact = ContactState::InContact { strain: first };
        engine.spawn(0, Direction::Up, R::zero(), first, &[])?;
        engine.record_wall();
        Ok(engine)
    }

    /// Current time, in the scene's units: that of the last processed event.
    pub fn time(&self) -> f64 {
        self.now.to_f64() * self.units.time
    }

    /// The contact state in the scene's units.
    pub fn contact_state(&self) -> ContactState {
        let u = &self.units;
        self.contact
            .to_f64(u.strain(), u.displacement(), u.amplitude, u.time)
    }

    /// Boundary events so far (reflections at a folded top included).
    pub fn events(&self) -> u64 {
        self.events + self.folded_reflections + self.pending_reflections() + self.leaped
    }

    /// The run's work so far: iterations of the event loop, plus what
    /// leaps did in their stead (a phase advanced, a lattice cell filled).
    /// A leap counts as one iteration but can fill thousands of cells: a
    /// budget of iterations alone let merged ladders refine far past it.
    pub fn steps(&self) -> u64 {
        self.events + self.leap_work
    }

    /// Boundary events advanced in closed form (by leaps over quiet layers).
    pub fn leaped_events(&self) -> u64 {
        self.leaped
    }

    /// Fronts of a folded top lane that have reached the top but not come
    /// back yet.
    fn pending_reflections(&self) -> u64 {
        self.lanes
            .iter()
            .filter(|l| l.folded)
            .map(|l| l.count_born_by(|born| born + l.transit <= self.now))
            .sum()
    }

    /// Why the run stopped, once it has.
    pub fn stopped(&self) -> Option<StopReason> {
        self.stopped
    }

    /// What was recorded (empty unless asked in the config).
    pub fn recording(&self) -> &Recording {
        &self.recording
    }

    /// Fronts of neighbouring lanes that leaps took in (`leap/arrivals.rs`).
    pub fn arrivals_taken(&self) -> u64 {
        self.arrivals_taken
    }

    /// What was dropped and merged so far.
    pub fn truncation(&self) -> Truncation {
        self.drops.truncation
    }

    /// How close the contact decisions came to grazing.
    pub fn decisions(&self) -> Decisions {
        self.decisions
    }

    /// Fronts alive now, over all lanes (the run's memory).
    pub fn live_fronts(&self) -> usize {
        self.lanes.iter().map(Lane::len).sum()
    }

    /// A first-order bound on how far dropped fronts moved `e`: each left a
    /// force mismatch `E |d|` at its boundary from its birth on, whose
    /// impulse until the last separation changes the wall impulse at most
    /// twice over.
    pub fn dropped_error_bound(&self) -> f64 {
        let (force, force_time) = if self.history.in_contact() {
            (self.drops.dropped_force, self.drops.dropped_force_time)
        } else {
            self.drops.at_separation
        };
        let tc = self.history.contact_time(self.time()) / self.units.time;
        let impulse = (force * tc - force_time).max(0.0);
        2.0 * impulse / (self.mass.to_f64() * self.impact_speed.to_f64())
    }

    /// Centre-of-mass velocity in internal units, exact from the wall
    /// impulse: `M dv/dt = -E0 eps0`.
    pub(crate) fn centre_of_mass_velocity(&self) -> R {
        let impulse = self.impulse_at(self.now);
        -self.impact_speed - self.layers[0].modulus / self.mass * impulse
    }

    /// The restitution so far.
    pub fn restitution(&self) -> f64 {
        (self.centre_of_mass_velocity() / self.impact_speed).to_f64()
    }

    fn impulse_at(&self, t: R) -> R {
        match self.contact {
            ContactState::InContact { strain } => {
                self.ledger.impulse + strain * (t - self.ledger.at)
            }
            ContactState::Free { .. } => self.ledger.impulse,
        }
    }

    /// Centre-of-mass displacement since the impact.
    fn centre_of_mass_displacement(&self) -> R {
        -self.impact_speed * self.now - self.layers[0].modulus / self.mass * self.ledger.moment
    }

    /// Brings the wall ledger (and a free bottom's height) up to time `t`.
    pub(crate) fn advance_wall(&mut self, t: R) {
        let dt = t - self.ledger.at;
        let half = R::of(0.5);
        match &mut self.contact {
            ContactState::InContact { strain } => {
                self.ledger.moment += self.ledger.impulse * dt + half * *strain * dt * dt;
                self.ledger.impulse += *strain * dt;
            }
            ContactState::Free {
                height,
                velocity,
                at,
            } => {
                self.ledger.moment += self.ledger.impulse * dt;
                *height += *velocity * (t - *at);
                *at = t;
            }
        }
        self.ledger.at = t;
    }

    /// Adds a front born at `t` at the start of the lane of (`layer`, `dir`).
    /// Inlined, as are `take_head` and `boundary_event`: out of line, their
    /// calls (saved registers, spilled arguments) were a quarter of an
    /// event's instructions at the hard corner (callgrind).
    #[inline(always)]
    fn spawn(
        &mut self,
        layer: usize,
        dir: Direction,
        t: R,
        jump: R,
        parents: &[u32],
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
        match lane.push(t, jump, id) {
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

    /// Counts a front too small to keep: what it carried goes into the
    /// error estimate (see [`Tracer::dropped_error_bound`]). Rare, so kept
    /// out of the event loop's hot path.
    #[cold]
    pub(crate) fn drop_front(&mut self, layer: usize, born: R, jump: R) {
        let l = self.layers[layer];
        let d = &mut self.drops;
        d.truncation.dropped_fronts += 1;
        d.truncation.dropped_velocity += (jump.abs() * l.wave_speed / self.impact_speed).to_f64();
        let force = (l.modulus * jump.abs()).to_f64();
        d.dropped_force += force;
        d.dropped_force_time += force * born.to_f64();
    }

    /// Records a new front (only when fronts are recorded).
    #[cold]
    fn record_front(
        &mut self,
        id: u32,
        (layer, direction): (usize, Direction),
        (born, arrives): (R, R),
        jump: R,
        parents: &[u32],
    ) {
        let u = &self.units;
        self.recording.fronts.push(FrontRecord {
            id,
            layer,
            direction,
            born: born.to_f64() * u.time,
            arrives: arrives.to_f64() * u.time,
            jump: jump.to_f64() * u.strain(),
            parents: parents.to_vec(),
        });
    }

    /// Adds a merged front's jump and parents to its record.
    #[cold]
    fn record_merge(&mut self, id: u32, jump: R, parents: &[u32]) {
        if let Some(rec) = self.recording.fronts.get_mut(id as usize) {
            rec.jump += jump.to_f64() * self.units.strain();
            rec.parents.extend_from_slice(parents);
        }
    }

    /// Counts a combination of two instants `gap > 0` apart, the later at
    /// `at`, if the gap is more than rounding (a few ulps of the time and
    /// of the shortest transit): a tie that rounding split is no use of the
    /// tolerance.
    #[cold]
    pub(crate) fn note_combined(&mut self, gap: R, at: R) {
        // the window's rounding part, and the rounding of the deadline
        // `t + window` itself (an ulp of `t`)
        let w = self.window;
        let now = at.abs();
        let rounding = w.ulps * (now + w.scale) + R::of(2.0 * f64::EPSILON) * now;
        if gap > rounding {
            self.decisions.within_tolerance += 1;
        }
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
                events: self.events(),
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
                if self.merged && !self.escape_confirmed()? {
                    StepKind::Wall { separated: false }
                } else {
                    self.finish(t, StopReason::Escaped)
                }
            }
            EventKey::Horizon => {
                self.queue.pop();
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

    /// Counts decisions a leap took without coming near grazing.
    pub(crate) fn note_decisions(&mut self, count: u64) {
        self.decisions.count += count;
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

    /// Notes how close a decision came to going the other way.
    fn note_decision(&mut self, margin: R) {
        let m = margin.abs().to_f64();
        self.decisions.count += 1;
        if m < NEAR_GRAZING {
            self.decisions.near_grazing += 1;
        }
        self.decisions.smallest_margin = self.decisions.smallest_margin.min(m);
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
            let k = self.interfaces[b - 1];
            let down = k.up_reflected * from_below + k.down_transmitted * from_above;
            let up = k.up_transmitted * from_below + k.down_reflected * from_above;
            self.spawn(b - 1, Direction::Down, t, down, parents)?;
            self.spawn(b, Direction::Up, t, up, parents)?;
            Ok(StepKind::Interface(b))
        }
    }

    /// After a separation with the centre of mass moving up, schedules the
    /// time from which no reconnection is possible
    /// ([`impact_model::escape`]), from the exact energy balance: the rod's
    /// energy is still `M v_b^2 / 2`, so `E_int = M (v_b^2 - v^2) / 2`.
    fn schedule_escape(&mut self, t: R) -> Result<(), WaveError> {
        if self.stop_rule != StopRule::Escape {
            return Ok(());
        }
        let v = self.centre_of_mass_velocity();
        let of = R::of;
        let internal = (of(0.5) * self.mass * (self.impact_speed.powi(2) - v * v)).max(R::zero());
        let transits: R = self
            .layers
            .iter()
            .fold(R::zero(), |s, l| s + l.length / l.wave_speed);
        let margin = Margin {
            relative: BALANCE_MARGIN,
            absolute: of(ROUNDING_MARGIN) * self.impact_speed * transits,
        };
        let reach = self.escape.reach(internal, margin);
        let rise = self.centre_of_mass_displacement();
        let Some(at) = EscapeBound::escape_time(t, reach, rise, v) else {
            return Ok(());
        };
        self.queue
            .schedule(EventKey::Escape, at, self.now)
            .map_err(past)
    }

    /// With merged fronts, energy and momentum are those of the merged
    /// field, which may differ a little from the exact balance the escape
    /// time was computed from. Checks the bound on the field itself (the
    /// bottom's offset from the centre of mass can never exceed `D`) and
    /// reschedules when it does not hold yet.
    fn escape_confirmed(&mut self) -> Result<bool, WaveError> {
        let t = self.now;
        self.advance_wall(t);
        let ContactState::Free { height: h, .. } = self.contact else {
            return Ok(false);
        };
        let fields = self.field_state();
        let v = fields.momentum / self.mass;
        let internal = internal_energy(fields.energy, self.mass, v);
        let reach = self
            .escape
            .reach(internal, Margin::relative(MERGED_FIELD_MARGIN));
        // height of the centre of mass above the wall
        let rise = h + fields.bottom_below_centre;
        if rise > reach && v > R::zero() {
            return Ok(true);
        }
        if let Some(at) = EscapeBound::escape_time(t, reach, rise, v) {
            self.queue
                .schedule(EventKey::Escape, at + self.window.at(at), self.now)
                .map_err(past)?;
        }
        Ok(false)
    }

    /// Keeps the landing (reconnection) event in step with the free bottom.
    pub(crate) fn schedule_landing(&mut self) -> Result<(), WaveError> {
        match self.contact {
            ContactState::Free {
                height,
                velocity,
                at,
            } => match wall::landing_time(height, velocity, at) {
                Some(land) => self
                    .queue
                    .schedule(EventKey::Reconnection, land.max(self.now), self.now)
                    .map_err(past),
                None => {
                    self.queue.cancel(EventKey::Reconnection);
                    Ok(())
                }
            },
            ContactState::InContact { .. } => {
                self.queue.cancel(EventKey::Reconnection);
                Ok(())
            }
        }
    }

    fn reconnect(&mut self, t: R) -> Result<(), WaveError> {
        self.advance_wall(t);
        let ContactState::Free { velocity, .. } = self.contact else {
            return Ok(());
        };
        self.note_decision(velocity / self.impact_speed);
        let (jump, state) = wall::reconnect(velocity, self.layers[0].wave_speed);
        self.contact = state;
        self.history.reconnect(t.to_f64() * self.units.time);
        self.queue.cancel(EventKey::Escape);
        self.spawn(0, Direction::Up, t, jump, &[])?;
        self.record_wall();
        Ok(())
    }

    pub(crate) fn record_wall(&mut self) {
        if !self.record.wall {
            return;
        }
        let state = self.contact_state();
        let (strain, height, velocity) = match state {
            ContactState::InContact { strain } => (strain, 0.0, 0.0),
            ContactState::Free {
                height, velocity, ..
            } => (0.0, height, velocity),
        };
        self.recording.wall.push(WallSample {
            time: self.time(),
            strain,
            height,
            velocity,
        });
    }

    /// Steps until the run stops.
    pub fn run(&mut self) -> Result<Outcome, WaveError> {
        while self.stopped.is_none() {
            self.step()?;
        }
        Ok(self.outcome())
    }

    /// The observables at the current time.
    pub fn outcome(&self) -> Outcome {
        let mut o = Outcome::from_history(
            EngineKind::Wave,
            self.restitution(),
            &self.history,
            &self.transit_times,
            self.time(),
            self.stopped.unwrap_or(StopReason::HorizonInContact),
        );
        o.events = Some(self.events());
        o.truncation = Some(self.drops.truncation);
        o
    }
}

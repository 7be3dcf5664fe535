//! What a run tells its caller: time, work, drops, decisions and the
//! outcome, in the scene's units.

use super::{Decisions, Tracer};
use crate::error::WaveError;
use crate::lane::Lane;
use crate::real::Real;
use crate::record::Recording;
use crate::wall::ContactState;
use impact_model::{EngineKind, Outcome, StopReason, Truncation};

impl<R: Real> Tracer<R> {
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
        self.events
            + self.folded_reflections
            + self.pending_reflections()
            + self.leaped
            + self.stepped
    }

    /// The run's work so far: iterations of the event loop, plus what
    /// leaps did in their stead (a phase advanced, a lattice cell filled).
    /// A leap counts as one iteration but can fill thousands of cells: a
    /// budget of iterations alone let merged ladders refine far past it.
    pub fn steps(&self) -> u64 {
        self.events + self.leap_work + self.stepped
    }

    /// Boundary events advanced in closed form (by leaps over quiet layers).
    pub fn leaped_events(&self) -> u64 {
        self.leaped
    }

    /// Fronts of a folded top lane that have reached the top but not come
    /// back yet.
    pub(super) fn pending_reflections(&self) -> u64 {
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

    /// The blocks of fast layers this run answers by their response
    /// (`WaveConfig::fast_blocks`): the bottom and top layer of each.
    pub fn answered_blocks(&self) -> Vec<(usize, usize)> {
        self.blocks
            .list
            .iter()
            .map(|b| (b.lower, b.upper))
            .collect()
    }

    /// A diagnostic: each answered block's response to a unit jump at each
    /// input port (its lower port, then its upper one), at each output
    /// port, traced to `length` (in the scene's time units) after the
    /// input or until it is done, per block, per input, per output. The
    /// traces go further than a run may need them, and a run counts only
    /// the tracing it asks for: run a fresh tracer, not this one, for the
    /// outcome.
    pub fn block_responses(&mut self, length: f64) -> Vec<Vec<Vec<BlockResponse>>> {
        let unit = self.units.time;
        let length = R::of(length / unit);
        self.blocks
            .list
            .iter_mut()
            .map(|b| {
                b.responses(length)
                    .into_iter()
                    .map(|ports| {
                        ports
                            .into_iter()
                            .map(|(h, taps, exact)| BlockResponse {
                                spacing: h.to_f64() * unit,
                                taps: taps.iter().map(|x| x.to_f64()).collect(),
                                exact: exact
                                    .iter()
                                    .map(|&(t, d)| (t.to_f64() * unit, d.to_f64()))
                                    .collect(),
                            })
                            .collect()
                    })
                    .collect()
            })
            .collect()
    }

    /// Which of those blocks are traced on one lattice
    /// (`WaveConfig::one_lattice_blocks`), in the same order.
    pub fn blocks_on_one_lattice(&self) -> Vec<bool> {
        self.blocks
            .list
            .iter()
            .map(|b| b.on_one_lattice())
            .collect()
    }

    /// The layers inside those blocks whose traces answer them by their
    /// own response (`WaveConfig::nest_blocks`).
    pub fn nested_layers(&self) -> Vec<usize> {
        self.blocks.list.iter().filter_map(|b| b.nested()).collect()
    }

    /// The bottom group this run followed in steps
    /// (`WaveConfig::step_bottom_group`), its first and last layer, and
    /// the fronts the steps followed; none if it never stepped.
    pub fn stepped_group(&self) -> Option<((usize, usize), u64)> {
        let g = self.group.as_deref()?;
        (self.stepped > 0).then_some(((0, g.top - 1), self.stepped))
    }

    /// The restitution so far.
    pub fn restitution(&self) -> f64 {
        (self.centre_of_mass_velocity() / self.impact_speed).to_f64()
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

/// A block's response at one output port to a unit strain jump arriving
/// at one input port ([`Tracer::block_responses`]): what the port delivers
/// per unit of the input's jump.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockResponse {
    /// The port's lattice spacing, in the scene's time units: tap `k`
    /// is delivered `k` spacings after the input.
    pub spacing: f64,
    /// The small fronts, deposited on the port's lattice.
    pub taps: Vec<f64>,
    /// The large ones, at their exact delays (scene units) in the order
    /// they leave, `(delay, jump)`.
    pub exact: Vec<(f64, f64)>,
}

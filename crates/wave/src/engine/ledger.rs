//! What a run accounts for besides its fields: fronts dropped, instants
//! combined by a tolerance, how close each contact decision came to going
//! the other way, and the records a caller asked for.

use super::{NEAR_GRAZING, Tracer};
use crate::lane::Direction;
use crate::real::Real;
use crate::record::{FrontRecord, WallSample};
use crate::wall::ContactState;
use impact_model::Truncation;

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
    /// Separations decided at the arrival of a lattice deposit (merged
    /// runs; not a kept front, though one born at a lattice point, as a
    /// front born a whole number of the bottom's transits after the impact
    /// is on lattices of a fifth, a tenth, ... of that transit): their
    /// instant is a lattice point's, and a finer lattice that
    /// holds the same point may decide at the same instant (see
    /// `ladder.rs`, shared decisions).
    pub separations_on_lattice: u64,
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

impl<R: Real> Tracer<R> {
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

    /// Counts what arrivals left in a block beyond its traced response
    /// (`block/response.rs`): the velocity and force they could carry, and
    /// the force times their arrival, as for dropped fronts.
    pub(crate) fn drop_rest(&mut self, velocity: f64, force: f64, force_time: f64) {
        let d = &mut self.drops;
        d.truncation.dropped_velocity += velocity / self.impact_speed.to_f64();
        d.dropped_force += force;
        d.dropped_force_time += force_time;
    }

    /// Records a new front (only when fronts are recorded).
    #[cold]
    pub(super) fn record_front(
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
    pub(super) fn record_merge(&mut self, id: u32, jump: R, parents: &[u32]) {
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

    /// Counts decisions a leap took without coming near grazing.
    pub(crate) fn note_decisions(&mut self, count: u64) {
        self.decisions.count += count;
    }

    /// Notes how close a decision came to going the other way.
    pub(crate) fn note_decision(&mut self, margin: R) {
        let m = margin.abs().to_f64();
        self.decisions.count += 1;
        if m < NEAR_GRAZING {
            self.decisions.near_grazing += 1;
        }
        self.decisions.smallest_margin = self.decisions.smallest_margin.min(m);
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
}

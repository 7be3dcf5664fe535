//! The rod as one body: the wall's ledger and the centre of mass it gives
//! exactly, a free bottom's flight and landing, and the escape bound the
//! run stops on.

use super::{Tracer, past};
use crate::config::StopRule;
use crate::error::WaveError;
use crate::lane::Direction;
use crate::queue::EventKey;
use crate::real::Real;
use crate::wall::{self, ContactState};
use impact_model::escape::{EscapeBound, Margin, internal_energy};

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

impl<R: Real> Tracer<R> {
    /// Centre-of-mass velocity in internal units, exact from the wall
    /// impulse: `M dv/dt = -E0 eps0`.
    pub(crate) fn centre_of_mass_velocity(&self) -> R {
        let impulse = self.impulse_at(self.now);
        -self.impact_speed - self.layers[0].modulus / self.mass * impulse
    }

    pub(super) fn impulse_at(&self, t: R) -> R {
        match self.contact {
            ContactState::InContact { strain } => {
                self.ledger.impulse + strain * (t - self.ledger.at)
            }
            ContactState::Free { .. } => self.ledger.impulse,
        }
    }

    /// Centre-of-mass displacement since the impact.
    pub(super) fn centre_of_mass_displacement(&self) -> R {
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

    /// After a separation with the centre of mass moving up, schedules the
    /// time from which no reconnection is possible
    /// ([`impact_model::escape`]), from the exact energy balance: the rod's
    /// energy is still `M v_b^2 / 2`, so `E_int = M (v_b^2 - v^2) / 2`.
    pub(super) fn schedule_escape(&mut self, t: R) -> Result<(), WaveError> {
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
    pub(super) fn escape_confirmed(&mut self) -> Result<bool, WaveError> {
        let t = self.now;
        self.advance_wall(t);
        let ContactState::Free { height: h, .. } = self.contact else {
            return Ok(false);
        };
        if !self.blocks.list.is_empty() {
            // what a block holds is not in the lanes (`block.rs`): the
            // field would leave it out, so the balance the stop was
            // scheduled from stands
            return Ok(true);
        }
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

    pub(super) fn reconnect(&mut self, t: R) -> Result<(), WaveError> {
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
}

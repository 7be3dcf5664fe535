//! Why the exact engine could not run or finish. Messages speak of the
//! physics and of the settings by their field names; which command-line
//! flag sets a field is the binary's business.

use impact_model::{Outcome, SettingError};
use thiserror::Error;

/// Why the exact engine could not run or finish.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum WaveError {
    /// A viscous layer: its fronts would decay and spread, which the exact engine cannot trace.
    #[error(
        "layers[{layer}] is viscous: the exact engine handles elastic layers only (the chain engine handles viscous ones)"
    )]
    ViscousLayer {
        /// Index of the first viscous layer, bottom first.
        layer: usize,
    },
    /// A numerical setting outside its range.
    #[error("invalid engine setting: {0}")]
    Setting(#[from] SettingError),
    /// The event budget `max_events` was spent before the rod left for good.
    #[error(
        "run stopped after {events} events at t = {time:.6e} without the rod leaving for good: fronts multiply in this scene; use the automatic or merged resolution, or allow more events"
    )]
    EventLimit {
        /// The work counted against `max_events`: the loop's events, and
        /// what leaps and blocks did in their stead.
        events: u64,
        /// Time reached, in the scene's units.
        time: f64,
    },
    /// A merged run needed for the error bound spent `max_events` before the
    /// rod left for good: merging bounds the fronts a lane holds, not how
    /// long the contact lasts, and the fastest layers ring through all of it.
    #[error(
        "the merged run on the lattice of {per_transit} of each transit stopped after {events} events at t = {time:.6e}, before the rod left for good (about {:.1e} events per unit of time), and the error bound needs that run: merging bounds the fronts each lane holds, not how long the fastest layers ring through a long contact; allow more events",
        *events as f64 / time
    )]
    LatticeLimit {
        /// The work counted against `max_events`: the loop's events, and
        /// what leaps and blocks did in their stead.
        events: u64,
        /// Time reached, in the scene's units.
        time: f64,
        /// The lattice spacing, as a fraction of each transit.
        per_transit: f64,
    },
    /// The time limit `max_time_factor * sum(t_i)` was passed before the rod left for good.
    #[error(
        "run reached t = {time:.6e} (the time limit) without the rod leaving for good; raise the time limit or stop at a horizon"
    )]
    TimeLimit {
        /// Time reached, in the scene's units.
        time: f64,
    },
    /// The stop rule is a horizon and the rod still touched the wall there: `t_c` and `e` are not final.
    #[error(
        "the horizon t = {time:.6e} was reached while the rod still touched the wall: t_c and e are not final (the partial restitution so far is {partial:.6}); stop later or use the exact stop rule"
    )]
    Unfinished {
        /// The horizon, in the scene's units.
        time: f64,
        /// Restitution from the wall impulse up to the horizon.
        partial: f64,
        /// The outcome up to the horizon, for callers that want it anyway.
        outcome: Box<Outcome>,
    },
    /// An event scheduled before the current time: a bug in the engine, never the scene's fault.
    #[error("internal error: event scheduled at {requested:e} before the current time {now:e}")]
    EventInPast {
        /// Current time, in internal units.
        now: f64,
        /// Time the event was scheduled for, in internal units.
        requested: f64,
    },
}

impl WaveError {
    /// A merged run's event limit as [`WaveError::LatticeLimit`] on the
    /// lattice `per_transit`; any other error as it is.
    pub(crate) fn on_lattice(self, per_transit: f64) -> Self {
        match self {
            WaveError::EventLimit { events, time } => WaveError::LatticeLimit {
                events,
                time,
                per_transit,
            },
            e => e,
        }
    }
}

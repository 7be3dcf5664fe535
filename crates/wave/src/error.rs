//! Why the exact engine could not run or finish. Messages speak of the
//! physics and of the settings by their field names; which command-line
//! flag sets a field is the binary's business.

use impact_model::{Outcome, SettingError};
use thiserror::Error;

/// Why the exact engine could not run or finish.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum WaveError {
    #[error(
        "layers[{layer}] is viscous: the exact engine handles elastic layers only (the chain engine handles viscous ones)"
    )]
    ViscousLayer { layer: usize },
    #[error("invalid engine setting: {0}")]
    Setting(#[from] SettingError),
    #[error(
        "run stopped after {events} events at t = {time:.6e} without the rod leaving for good: fronts multiply in this scene; use the automatic or merged resolution, or allow more events"
    )]
    EventLimit { events: u64, time: f64 },
    #[error(
        "run reached t = {time:.6e} (the time limit) without the rod leaving for good; raise the time limit or stop at a horizon"
    )]
    TimeLimit { time: f64 },
    #[error(
        "the horizon t = {time:.6e} was reached while the rod still touched the wall: t_c and e are not final (the partial restitution so far is {partial:.6}); stop later or use the exact stop rule"
    )]
    Unfinished {
        time: f64,
        partial: f64,
        outcome: Box<Outcome>,
    },
    #[error("internal error: event scheduled at {requested:e} before the current time {now:e}")]
    EventInPast { now: f64, requested: f64 },
}

//! Why the exact engine could not run or finish. Messages speak of the
//! physics and of the settings by their field names; which command-line
//! flag sets a field is the binary's business.

use crate::config::{Resolution, StopRule, WaveConfig};
use impact_model::Outcome;
use thiserror::Error;

/// Why the exact engine could not run or finish.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum WaveError {
    #[error(
        "layers[{layer}] is viscous: the exact engine handles elastic layers only (the chain engine handles viscous ones)"
    )]
    ViscousLayer { layer: usize },
    #[error("invalid engine setting: {field} must be {allowed} (got {value})")]
    Setting {
        field: &'static str,
        allowed: &'static str,
        value: f64,
    },
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

/// Checks the numerical settings (the engines' own guard; the binary
/// validates flags before they get here).
pub(crate) fn check_settings(config: &WaveConfig) -> Result<(), WaveError> {
    let nonneg = "a finite number >= 0";
    let positive = "a finite number > 0";
    let mut checks = vec![
        ("drop_tolerance", config.drop_tolerance, nonneg, true),
        ("simultaneity", config.simultaneity, nonneg, true),
        ("grazing_tolerance", config.grazing_tolerance, nonneg, true),
        ("max_time_factor", config.max_time_factor, positive, false),
    ];
    if let StopRule::Horizon { factor } = config.stop {
        checks.push(("horizon", factor, positive, false));
    }
    if let Resolution::Auto { target, .. } = config.resolution {
        checks.push(("target", target, positive, false));
    }
    if let Resolution::Merged {
        per_transit,
        per_longest,
    } = config.resolution
    {
        checks.push(("merge window per transit", per_transit, nonneg, true));
        checks.push((
            "merge window per longest transit",
            per_longest,
            nonneg,
            true,
        ));
        if per_transit > crate::solve::COARSEST {
            return Err(WaveError::Setting {
                field: "merge window per transit",
                allowed: "at most 0.5 (a coarser lattice could deposit a front that arrives before it was born)",
                value: per_transit,
            });
        }
    }
    for (field, value, allowed, zero_ok) in checks {
        let ok = value.is_finite() && (value > 0.0 || (zero_ok && value == 0.0));
        if !ok {
            return Err(WaveError::Setting {
                field,
                allowed,
                value,
            });
        }
    }
    if config.max_events == 0 {
        return Err(WaveError::Setting {
            field: "max_events",
            allowed: "at least 1",
            value: 0.0,
        });
    }
    Ok(())
}

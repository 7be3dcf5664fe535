use thiserror::Error;

/// Why the exact engine could not run or finish.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum WaveError {
    #[error(
        "layers[{layer}] is viscous: the wave engine is exact for elastic layers only; use the chain engine (--engine chain)"
    )]
    ViscousLayer { layer: usize },
    #[error("invalid engine setting: {field} must be {allowed} (got {value})")]
    Setting {
        field: &'static str,
        allowed: &'static str,
        value: f64,
    },
    #[error(
        "run stopped after {events} events at t = {time:.6e} without the rod leaving for good: fronts multiply in this scene; set a merge window (e.g. --merge-window 1e-3), raise --max-events, or use the chain engine"
    )]
    EventLimit { events: u64, time: f64 },
    #[error(
        "run reached t = {time:.6e} (the time limit) without the rod leaving for good; raise the time limit or use the paper's horizon"
    )]
    TimeLimit { time: f64 },
    #[error("internal error: event scheduled at {requested:e} before the current time {now:e}")]
    EventInPast { now: f64, requested: f64 },
}

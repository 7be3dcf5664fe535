use impact_model::SettingError;
use thiserror::Error;

/// Why the chain could not run or finish.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ChainError {
    #[error(
        "the chain needs at least one mass per layer: masses must be >= {layers} (got {masses})"
    )]
    TooFewMasses { masses: usize, layers: usize },
    #[error("invalid chain setting: {0}")]
    Setting(#[from] SettingError),
    #[error(
        "chain stopped at its step limit, {steps} steps, at t = {time:.6e} while still able to touch the wall"
    )]
    StepLimit { steps: u64, time: f64 },
    #[error(
        "chain state became non-finite at t = {time:.6e} (mass {mass}): the time step is too long"
    )]
    NonFinite { time: f64, mass: usize },
}

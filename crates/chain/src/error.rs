use thiserror::Error;

/// Why the chain could not run or finish.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ChainError {
    #[error("the chain needs at least one mass per layer: --n must be >= {layers} (got {masses})")]
    TooFewMasses { masses: usize, layers: usize },
    #[error("invalid chain setting: {field} must be {allowed} (got {value})")]
    Setting {
        field: &'static str,
        allowed: &'static str,
        value: f64,
    },
    #[error(
        "chain stopped after {steps} steps at t = {time:.6e} while still able to touch the wall; raise --max-steps or use --horizon"
    )]
    StepLimit { steps: u64, time: f64 },
    #[error("chain state became non-finite at t = {time:.6e} (mass {mass}); lower --dt-factor")]
    NonFinite { time: f64, mass: usize },
}

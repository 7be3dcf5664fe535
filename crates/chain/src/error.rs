use impact_model::SettingError;
use thiserror::Error;

/// Why the chain could not run or finish.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum ChainError {
    /// Fewer masses than layers: every layer needs at least one.
    #[error(
        "the chain needs at least one mass per layer: masses must be >= {layers} (got {masses})"
    )]
    TooFewMasses {
        /// Masses asked for.
        masses: usize,
        /// Layers in the rod.
        layers: usize,
    },
    /// A numerical setting outside its range.
    #[error("invalid chain setting: {0}")]
    Setting(#[from] SettingError),
    /// The step limit `max_steps` was reached while the rod could still touch the wall.
    #[error(
        "chain stopped at its step limit, {steps} steps, at t = {time:.6e} while still able to touch the wall"
    )]
    StepLimit {
        /// Steps taken.
        steps: u64,
        /// Time reached, in the scene's units.
        time: f64,
    },
    /// A displacement or velocity became infinite or NaN: the integration blew up.
    #[error(
        "chain state became non-finite at t = {time:.6e} (mass {mass}): the time step is too long"
    )]
    NonFinite {
        /// Time at which it was found, in the scene's units.
        time: f64,
        /// Index of the first mass whose velocity is non-finite, bottom first.
        mass: usize,
    },
}

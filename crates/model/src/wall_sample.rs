//! One sample of the wall's state, the same for every engine.

use serde::{Deserialize, Serialize};

/// The wall state at one time: the exact engine samples it just after each
/// wall event, the chain every few steps.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct WallSample {
    /// Time of the sample, in the scene's units.
    pub time: f64,
    /// Wall strain `eps0` (compression negative; zero when free).
    pub strain: f64,
    /// Bottom height above the wall (zero in contact).
    pub height: f64,
    /// Bottom velocity (positive upward).
    pub velocity: f64,
}

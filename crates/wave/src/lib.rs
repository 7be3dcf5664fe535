//! Exact front-tracing engine for elastic layered rods hitting a rigid wall.
//!
//! In every layer the strain and velocity fields are piecewise constant in
//! `(y, t)`, with jumps carried by straight fronts (DESIGN.md §2). The whole
//! state is therefore a set of fronts plus the wall state, and the solution
//! advances from one boundary event to the next, exactly: no time step, no
//! mesh. Restitution comes from the exact wall impulse (paper Eq. 6).
//!
//! Architecture invariant: this crate knows nothing about output formats,
//! plotting or the command line.

mod config;
mod engine;
mod error;
mod fields;
mod lane;
pub mod queue;
mod record;
mod wall;

pub use config::{Record, StopRule, WaveConfig};
pub use engine::{Step, StepKind, WaveEngine};
pub use error::WaveError;
pub use fields::{FieldSample, FieldTotals};
pub use lane::Direction;
pub use record::{FrontRecord, Recording, WallSample};
pub use wall::ContactState;

use impact_model::{Outcome, Rod};

/// Runs one impact to the end with the given settings.
pub fn simulate(rod: &Rod, config: &WaveConfig) -> Result<Outcome, WaveError> {
    let mut engine = WaveEngine::new(rod, config.clone())?;
    engine.run()
}

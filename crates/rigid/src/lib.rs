//! The rigid-bottom limit, a model of its own: the bottom layer is a rigid
//! mass that rebounds elastically and instantly from the wall; the layers
//! above are elastic and act on it through d'Alembert's solution, waves
//! returning from the top included; it rests on the wall while the stack
//! pushes it down. The paper's Appendix C is this model with a one-layer
//! stack, followed until `2 t2`.
//!
//! It is the limit of the exact engine as the bottom's transit time goes to
//! zero at a fixed mass (DESIGN.md §6), and is computed exactly: every
//! velocity and wave is piecewise `P(s) + Q(s) exp(-lambda s)` (see
//! [`exppoly`]).
//!
//! Architecture invariant: this crate knows nothing about the other engines,
//! output formats or the command line.

#![warn(missing_docs)]

mod engine;
pub mod exppoly;
mod stack;

pub use engine::{RigidBottom, RigidConfig, RigidError, RigidStop};

use impact_model::{Outcome, Rod};

/// Runs the model to the end.
pub fn simulate(rod: &Rod, config: &RigidConfig) -> Result<Outcome, RigidError> {
    let mut outcome = RigidBottom::new(rod, config)?.run()?;
    outcome.wall_contact = rod.wall_contact();
    Ok(outcome)
}

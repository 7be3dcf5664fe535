//! The paper's discrete method (Sec. III): `N` masses joined by springs with
//! parallel dashpots (Kelvin-Voigt), a one-sided spring against the wall, and
//! Beeman integration. It is the reference that validates the exact engine,
//! and the only engine for viscous layers.
//!
//! Any scene is mapped onto the chain in the scene's units (DESIGN.md §3):
//! `l0 = L_i / N_i`, `m = rho l0`, `k = E / l0`, `k' = eta / l0`, so its
//! outcomes compare directly with the exact engine's.
//!
//! Architecture invariant: this crate knows nothing about the exact engine,
//! output formats, plotting or the command line.

#![warn(missing_docs)]

pub mod calibrate;
mod config;
mod damping;
mod engine;
mod error;
mod implicit;
mod layout;
mod verlet;
mod viscous;
pub use verlet::VerletChain;

pub use config::{ChainConfig, ChainRecord, ChainStop, ViscousKernel};
pub use engine::{ChainEngine, ChainRecording, RasterFrame};
pub use error::ChainError;
pub use layout::ChainLayout;

use impact_model::{Outcome, Rod};

/// Runs one impact to the end with the given settings.
pub fn simulate(rod: &Rod, config: &ChainConfig) -> Result<Outcome, ChainError> {
    let mut engine = ChainEngine::new(rod, config.clone())?;
    engine.run()
}

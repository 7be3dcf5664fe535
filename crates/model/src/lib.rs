//! Shared model of a layered elastic projectile hitting a rigid wall.
//!
//! This crate knows nothing about how a rod is simulated. It holds:
//! - [`Scene`]: what a user writes (layers bottom to top, impact speed), and its
//!   validation into a [`Rod`] with every derived quantity (wave speeds,
//!   impedances, transit times, interface positions);
//! - [`interface`]: reflection/transmission of strain fronts at an interface, as
//!   pure functions of the two layers;
//! - [`theory`]: the paper's closed-form results (Sec. VI, Appendix B);
//! - [`Outcome`]: what every engine returns, with the paper's bounce filter;
//! - [`numerics`]: the numerical routines the studies share (Richardson
//!   extrapolation, bisection, fits, rank correlation, Pareto fronts).
//!
//! Conventions (see `shared/DESIGN.md` §1): `y` points up from the wall, layer 0
//! touches the wall, unit cross-section, strain is positive in tension.

#![warn(missing_docs)]

pub mod bilayer;
pub mod calibration;
pub mod contact;
pub mod escape;
pub mod interface;
pub mod materials;
pub mod numerics;
pub mod outcome;
pub mod rigid_bottom;
pub mod scene;
pub mod setting;
pub mod theory;
pub mod timed;
pub mod units;
pub mod wall_contact;
pub mod wall_sample;

pub use bilayer::Bilayer;
pub use contact::ContactHistory;
pub use interface::InterfaceCoefficients;
pub use outcome::{
    EngineKind, ErrorEstimate, LadderStop, Outcome, SetAsideLadder, StopReason, Truncation,
};
pub use scene::{Layer, LayerProps, Rod, Scene, SceneError, WaveConstants};
pub use setting::{Allowed, SettingError};
pub use timed::Timed;
pub use units::Units;
pub use wall_contact::WallContact;
pub use wall_sample::WallSample;

//! The numerical routines the layers above the engines share, each written
//! once and tested once against answers derived by hand:
//! - [`richardson`]: extrapolation of a quantity computed at growing sizes,
//!   with its observed order (any spacing of the sizes) and error estimate;
//! - [`bisect`]: a root bracketed by a sign test;
//! - [`fit`]: least-squares straight lines, power laws (log-log) and
//!   exponentials (log-linear);
//! - [`rank`]: Spearman's rank correlation;
//! - [`lagrange`]: the Lagrange polynomial through a few points, evaluated
//!   outside them (extrapolation to a limit);
//! - [`pareto`]: the Pareto front of a cost/error trade.
//!
//! Why here: copies of these had drifted apart (one Richardson assumed
//! evenly spaced sizes after the others were fixed), so the model crate,
//! which every layer already depends on, holds the one version.

pub mod bisect;
pub mod fit;
pub mod lagrange;
pub mod pareto;
pub mod rank;
pub mod richardson;

pub use bisect::{bisect, bisect_to};
pub use fit::{Line, PowerLaw, exponential_fit, least_squares, power_fit};
pub use lagrange::{lagrange_extrapolate, lagrange_weights};
pub use pareto::pareto_front;
pub use rank::{ranks, spearman};
pub use richardson::{Extrapolation, extrapolate, richardson_step, self_consistent_order};

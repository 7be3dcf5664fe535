//! Exact front-tracing engine for elastic layered rods hitting a rigid wall.
//!
//! In every layer the strain and velocity fields are piecewise constant in
//! `(y, t)`, with jumps carried by straight fronts (DESIGN.md §2). The whole
//! state is therefore a set of fronts plus the wall state, and the solution
//! advances from one boundary event to the next, exactly: no time step, no
//! mesh. Restitution comes from the exact wall impulse (paper Eq. 6).
//!
//! [`simulate`] finishes every valid scene: exactly when the fronts stay
//! few, otherwise with fronts merged under an event budget and the merge
//! error measured by a second run; either way the outcome carries an error
//! estimate (see [`solve`](crate::solve())).
//!
//! Architecture invariant: this crate knows nothing about output formats,
//! plotting or the command line.

#![warn(missing_docs)]

mod block;
mod config;
mod convergence;
mod engine;
mod error;
mod exact_again;
mod fields;
mod geometric;
mod group;
mod ladder;
mod lane;
mod leap;
pub mod queue;
mod real;
mod record;
mod room;
mod runs;
mod solve;
#[cfg(test)]
mod test_random;
mod twins;
mod wall;
mod window;

pub use config::{LeapArrivals, Precision, Record, Resolution, StopRule, WaveConfig};
pub use convergence::SLOWEST_ORDER;
pub use engine::{BlockResponse, Decisions, Step, StepKind, Tracer, WaveEngine};
pub use error::WaveError;
pub use fields::{FieldSample, FieldTotals};
pub use lane::Direction;
pub use real::{DoubleDouble, Real};
pub use record::{FrontRecord, Recording, WallSample};
pub use solve::{LadderProgress, Solution, simulate, solve, solve_observed};
pub use wall::ContactState;

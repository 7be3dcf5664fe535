//! Space-time diagrams of an impact (paper Figs. 1c and 3): height in the
//! rod against time, the strain field in colour (compression red, tension
//! blue, zero white), the fronts, the interfaces, the contact events, the
//! path of the wave that triggers the final takeoff, and the wall strain
//! below.
//!
//! The exact field is drawn as exact polygons: in layer `i` the strain is
//! `A(t - (y - y_b)/c) + B(t - (y_t - y)/c)`, step functions of the birth times
//! of the up- and down-going characteristics, so it is constant on
//! parallelograms whose corners are front crossings ([`ExactField`]).

#![warn(missing_docs)]

mod field;
mod figure;
mod html;
mod runs;
mod takeoff;

pub use field::{ExactField, FieldError};
pub use figure::{ChainPicture, Diagram, DiagramOptions, Picture};
pub use html::page;
pub use runs::{MAX_DRAWN_EVENTS, Run, chain_run, chain_run_within, exact_run};
pub use takeoff::takeoff_path;

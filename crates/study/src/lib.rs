//! Studies over many impacts: `(x, alpha)` grids, parallel sweeps with a
//! deterministic row order, and their CSV / JSONL output.
//!
//! Architecture invariant: nothing here draws progress bars or parses flags;
//! the binary passes a progress callback and validated settings.

#![warn(missing_docs)]

pub mod grid;
pub mod journal;
pub mod limit;
mod lock;
pub mod runner;
pub mod sweep;

pub use grid::{Axis, Grid, GridError};
pub use journal::{Journal, JournalError, JournalHeader, Shard};
pub use limit::{ChainLimit, LimitSettings, chain_limit};
pub use runner::{Finished, JournalPlan, Progress, par_map, run_journaled};
pub use sweep::{BilayerViscosity, Engine, Row, RowFormat, sweep, sweep_row};

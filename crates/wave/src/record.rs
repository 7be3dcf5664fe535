//! Optional records: wall history and front paths. Kept only when a caller asks
//! (see [`crate::Record`]); a plain run allocates none of this.

use crate::lane::Direction;
use serde::Serialize;

pub use impact_model::WallSample;

/// The path of one front, from birth to arrival, and where it came from.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrontRecord {
    /// Identifier, in order of birth; `parents` refer to it.
    pub id: u32,
    /// Index of the layer it crosses, bottom first.
    pub layer: usize,
    /// Up (away from the wall) or down.
    pub direction: Direction,
    /// Birth time, at the bottom (up) or top (down) of its layer.
    pub born: f64,
    /// Arrival time at the other end of the layer.
    pub arrives: f64,
    /// Strain jump (including everything merged into it).
    pub jump: f64,
    /// Fronts whose arrival produced this one (empty for the impact front and
    /// for fronts launched by a reconnection).
    pub parents: Vec<u32>,
}

/// Everything recorded during a run.
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct Recording {
    /// The wall's state after each wall event.
    pub wall: Vec<WallSample>,
    /// Every front born during the run.
    pub fronts: Vec<FrontRecord>,
}

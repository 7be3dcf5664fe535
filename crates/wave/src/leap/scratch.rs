//! The buffers a leap fills, kept by the tracer from one leap to the next
//! (allocating them afresh was a tenth of a short leap's work) and, emptied,
//! from one run to the next (`crate::room`).

use super::{Phase, Train};
use crate::lane::Front;

/// Buffers a leap fills, kept by the tracer from one leap to the next.
#[derive(Debug, Clone)]
pub(crate) struct LeapScratch<R> {
    pub(super) phases: Vec<Phase<R>>,
    /// The layer's fronts when the leap ends, going up and down.
    pub(super) up: Vec<Front<R>>,
    pub(super) down: Vec<Front<R>>,
    /// At the wall: `(first arrival, jump, count)` of each phase.
    pub(super) bottom_arrivals: Vec<(R, R, u64)>,
    /// Ringing trains into lattice lanes, deposited together
    /// (`together.rs`).
    pub(super) ringing: Vec<(usize, Train<R>)>,
    /// Room for sorting phases and fronts (`runs.rs`).
    pub(super) phases_run: Vec<Phase<R>>,
    pub(super) fronts_run: Vec<Front<R>>,
}

impl<R> LeapScratch<R> {
    /// Emptied, its room kept ([`crate::room`]).
    pub(crate) fn emptied(mut self) -> Self {
        self.phases.clear();
        self.up.clear();
        self.down.clear();
        self.bottom_arrivals.clear();
        self.ringing.clear();
        self.phases_run.clear();
        self.fronts_run.clear();
        self
    }

    /// The bytes its room holds.
    pub(crate) fn bytes(&self) -> usize {
        use crate::room::vec_bytes;
        vec_bytes(&self.phases)
            + vec_bytes(&self.up)
            + vec_bytes(&self.down)
            + vec_bytes(&self.bottom_arrivals)
            + vec_bytes(&self.ringing)
            + vec_bytes(&self.phases_run)
            + vec_bytes(&self.fronts_run)
    }
}

impl<R> Default for LeapScratch<R> {
    fn default() -> Self {
        Self {
            phases: Vec::new(),
            up: Vec::new(),
            down: Vec::new(),
            bottom_arrivals: Vec::new(),
            ringing: Vec::new(),
            phases_run: Vec::new(),
            fronts_run: Vec::new(),
        }
    }
}

//! The buffers a leap fills, kept by the tracer from one leap to the next
//! (allocating them afresh was a tenth of a short leap's work) and, emptied,
//! from one run to the next (`crate::room`).

use super::together::Member;
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

/// The buffers of trains taken together, kept by the tracer from one leap
/// to the next (and, emptied, from one run to the next: `crate::room`).
/// Sorting the held trains by lane, gathering each lane's and each call's
/// five vectors allocated afresh were about a tenth of the profile samples
/// of survey rods 22 and 26 (perf); kept, rod 26 takes 7 % fewer
/// instructions (callgrind of `impact run`).
#[derive(Debug, Clone)]
pub(crate) struct TogetherRoom<R> {
    /// The lanes the held trains go to, and one lane's trains.
    pub(super) lanes: Vec<usize>,
    pub(super) group: Vec<Train<R>>,
    pub(super) work: Work<R>,
}

/// What `Tracer::emit_ringing` and `Tracer::deposit_together` fill
/// (`together.rs`).
#[derive(Debug, Clone)]
pub(crate) struct Work<R> {
    pub(super) same: Vec<Train<R>>,
    pub(super) members: Vec<Member<R>>,
    pub(super) by_r: Vec<(R, usize)>,
    pub(super) by_end: Vec<(u64, R, usize)>,
    pub(super) spare_ends: Vec<(u64, R, usize)>,
    pub(super) rank: Vec<usize>,
    pub(super) sorted_r: Vec<R>,
    pub(super) tree: Vec<(R, R)>,
}

impl<R> Default for Work<R> {
    fn default() -> Self {
        Self {
            same: Vec::new(),
            members: Vec::new(),
            by_r: Vec::new(),
            by_end: Vec::new(),
            spare_ends: Vec::new(),
            rank: Vec::new(),
            sorted_r: Vec::new(),
            tree: Vec::new(),
        }
    }
}

impl<R> Default for TogetherRoom<R> {
    fn default() -> Self {
        Self {
            lanes: Vec::new(),
            group: Vec::new(),
            work: Work::default(),
        }
    }
}

impl<R> TogetherRoom<R> {
    /// Emptied, its room kept.
    pub(crate) fn emptied(mut self) -> Self {
        self.lanes.clear();
        self.group.clear();
        let w = &mut self.work;
        w.same.clear();
        w.members.clear();
        w.by_r.clear();
        w.by_end.clear();
        w.rank.clear();
        w.sorted_r.clear();
        w.tree.clear();
        self
    }

    /// The bytes its room holds.
    pub(crate) fn bytes(&self) -> usize {
        use crate::room::vec_bytes;
        let w = &self.work;
        vec_bytes(&self.lanes)
            + vec_bytes(&self.group)
            + vec_bytes(&w.same)
            + vec_bytes(&w.members)
            + vec_bytes(&w.by_r)
            + vec_bytes(&w.by_end)
            + vec_bytes(&w.rank)
            + vec_bytes(&w.sorted_r)
            + vec_bytes(&w.tree)
    }
}

//! An exact leap's trains, gathered lane by lane and kind by kind, in the
//! order `place_exact_trains` spawns them: each lane (by index) its
//! singles, then its ringing trains, each by start, equal starts in the
//! order gathered (what a stable sort by lane, kind and start gives).
//!
//! A leap gathers phase by phase, in the order of the phases' returns: a
//! single (a front that was going up as the leap began) and then a train
//! (one front, a single too, or a ringing train of two or more). Kept
//! apart by kind, each sequence comes in order of start, and putting them
//! in order is a check, or a merge of two runs (`runs.rs`). Sorting them
//! all together was a tenth of the 20 hardest points' work, once leaps
//! took the short contacts of a chattering base.

use super::Train;
use crate::real::Real;
use crate::room::vec_bytes;
use crate::runs::sort_stably;

/// A train and its place among those gathered (ties keep that order).
pub(crate) type Placed<R> = (u32, Train<R>);

/// One lane's trains, by kind: singles (ratio zero), trains of one front
/// (ratio not zero), ringing trains (two fronts or more).
#[derive(Debug, Clone)]
struct Gathered<R> {
    lane: usize,
    kinds: [Vec<Placed<R>>; 3],
}

/// The trains of one exact leap, and room for putting them in order; kept
/// by the tracer from one leap to the next.
#[derive(Debug, Clone)]
pub(crate) struct ExactTrains<R> {
    lanes: Vec<Gathered<R>>,
    /// Lanes in use (`lanes` beyond are kept for their room).
    used: usize,
    placed: u32,
    singles: Vec<Placed<R>>,
    rings: Vec<Placed<R>>,
    run: Vec<Placed<R>>,
}

impl<R> Default for ExactTrains<R> {
    fn default() -> Self {
        Self {
            lanes: Vec::new(),
            used: 0,
            placed: 0,
            singles: Vec::new(),
            rings: Vec::new(),
            run: Vec::new(),
        }
    }
}

impl<R: Real> ExactTrains<R> {
    pub(crate) fn is_empty(&self) -> bool {
        self.used == 0
    }

    /// Gathers `train` for `lane`.
    #[inline(always)]
    pub(crate) fn push(&mut self, lane: usize, train: Train<R>) {
        let slot = match self.lanes[..self.used].iter().position(|g| g.lane == lane) {
            Some(slot) => slot,
            None => {
                if self.used == self.lanes.len() {
                    self.lanes.push(Gathered {
                        lane,
                        kinds: Default::default(),
                    });
                }
                let g = &mut self.lanes[self.used];
                g.lane = lane;
                g.kinds.iter_mut().for_each(Vec::clear);
                self.used += 1;
                self.used - 1
            }
        };
        let kind = match (train.count > 1, train.q == R::zero()) {
            (true, _) => 2,
            (false, true) => 0,
            (false, false) => 1,
        };
        self.lanes[slot].kinds[kind].push((self.placed, train));
        self.placed += 1;
    }

    /// Puts the lanes gathered in order of index; how many there are.
    pub(crate) fn by_lane(&mut self) -> usize {
        self.lanes[..self.used].sort_unstable_by_key(|g| g.lane);
        self.used
    }

    /// The `k`-th lane gathered (after [`ExactTrains::by_lane`]), its
    /// singles and its ringing trains, each in order (module doc).
    pub(crate) fn in_order(&mut self, k: usize) -> (usize, &[Placed<R>], &[Placed<R>]) {
        let g = &self.lanes[k];
        let by_start = |p: &Placed<R>| (p.1.start, p.0);
        let [single, one, ringing] = &g.kinds;
        self.singles.clear();
        self.singles.extend_from_slice(single);
        self.singles.extend_from_slice(one);
        sort_stably(&mut self.singles, &mut self.run, by_start);
        self.rings.clear();
        self.rings.extend_from_slice(ringing);
        sort_stably(&mut self.rings, &mut self.run, by_start);
        (g.lane, &self.singles, &self.rings)
    }

    /// Empties it for the next leap (keeping the room).
    pub(crate) fn clear(&mut self) {
        self.used = 0;
        self.placed = 0;
    }

    /// The bytes its room holds ([`crate::room`]).
    pub(crate) fn bytes(&self) -> usize {
        let kinds: usize = self
            .lanes
            .iter()
            .flat_map(|g| g.kinds.iter())
            .map(vec_bytes)
            .sum();
        kinds
            + vec_bytes(&self.lanes)
            + vec_bytes(&self.singles)
            + vec_bytes(&self.rings)
            + vec_bytes(&self.run)
    }
}

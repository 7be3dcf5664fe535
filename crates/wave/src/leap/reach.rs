//! How soon anything from outside can reach a leaping layer: the end of
//! its quiet window.

use super::{LEAST_TRANSITS, SHORTEST_LEAP};
use crate::engine::Tracer;
use crate::lane::{Direction, Lane, MergeRule};
use crate::queue::EventKey;
use crate::real::Real;

/// How far a port's bound, the present plus a constant, may round away
/// from the constant, relative to the run's longest time: a fold of `n`
/// sums rounds by at most `n` units in the last place of its largest,
/// `1.1e-16` relative each, so this holds for rods of up to a thousand
/// layers.
const ROUNDING: f64 = 1e-12;

impl<R: Real> Tracer<R> {
    /// The earliest any front outside layer `i` can reach it: one going
    /// towards it after crossing the layers between, one going away after
    /// a reflection at its own layer's far end as well (at an interface,
    /// the free top or the wall; any other path is longer), and the front a
    /// landing starts at the wall. Bounding only
    /// by the fronts going towards the layer let a neighbour's front,
    /// reflected at its far end, come back inside the leap: the layer had
    /// already been advanced past it (an exact lane then took a front
    /// born before its newest; a three-layer rod lost a third of its
    /// energy, `tests/conservation.rs`).
    /// With `taking`, also the earliest with the fronts of the neighbours'
    /// lanes going towards the layer left out (the leap would take them
    /// in, `arrivals.rs`); else that is the first.
    pub(super) fn first_from_outside(&self, i: usize, taking: bool) -> (Option<R>, Option<R>) {
        let transit = |m: usize| self.lanes[Lane::<R>::index(m, Direction::Up)].transit;
        let earlier = |e: Option<R>, at: R| Some(e.map_or(at, |e| if at < e { at } else { e }));
        let reach = |j: usize, towards: bool, head: R| self.reach(i, j, towards, head);
        let (mut earliest, mut others) = (None, None);
        for lane in &self.lanes {
            let j = lane.layer;
            let Some(head) = lane.head_arrival().filter(|_| j != i) else {
                continue;
            };
            // a folded top lane's arrivals are already its returns
            let towards = lane.folded || (lane.direction == Direction::Up) == (j < i);
            let mut at = reach(j, towards, head);
            if self.blocks.answers(
                i,
                j,
                if lane.folded {
                    Direction::Down
                } else {
                    lane.direction
                },
            ) {
                at -= self.blocks.margin;
            }
            earliest = earlier(earliest, at);
            if !(taking && towards && j.abs_diff(i) == 1) {
                others = earlier(others, at);
            }
        }
        // a block's ports may deliver from a little before now on (an
        // arrival and its response are each split onto the port's
        // lattice), and whatever passes a block may come out that much
        // earlier than the layers' transits say (`block.rs`)
        if !self.blocks.list.is_empty() {
            let margin = self.blocks.margin;
            for block in &self.blocks.list {
                for port in &block.ports {
                    let (j, dir) = port.out;
                    let towards = (dir == Direction::Up) == (j < i);
                    let at = reach(j, towards, self.now + transit(j));
                    earliest = earlier(earliest, at - margin);
                    others = earlier(others, at - margin);
                }
            }
        }
        // a stepped bottom group sends fronts into the layer above it from
        // where its steps reached on, each put on that lane's lattice as
        // much as a cell earlier (`group.rs`)
        if let Some(g) = self.group.as_deref().filter(|g| g.active && g.top < i) {
            let lane = &self.lanes[Lane::<R>::index(g.top, Direction::Up)];
            let cell = match lane.rule {
                MergeRule::Lattice { spacing, .. } => spacing,
                MergeRule::Simultaneous { .. } => R::zero(),
            };
            let at = reach(g.top, true, g.reached + transit(g.top)) - cell - cell;
            earliest = earlier(earliest, at);
            others = earlier(others, at);
        }
        // a landing bottom starts a front at the wall (its other fronts
        // reach the wall as a lane's fronts going down, counted above)
        if i > 0
            && let Some(land) = self.queue.time_of(EventKey::Reconnection)
        {
            let at = (0..i).fold(land, |at, m| at + transit(m));
            earliest = earlier(earliest, at);
            others = earlier(others, at);
        }
        (earliest, others)
    }

    /// When a front of layer `j` arriving at its lane's end at `head`
    /// could reach layer `i`: across the layers between, after a
    /// reflection at `j`'s far end if it goes away from `i`.
    #[inline]
    fn reach(&self, i: usize, j: usize, towards: bool, head: R) -> R {
        let transit = |m: usize| self.lanes[Lane::<R>::index(m, Direction::Up)].transit;
        let between = if j < i { j + 1..i } else { i + 1..j };
        let at = between.fold(head, |at, m| at + transit(m));
        if towards { at } else { at + transit(j) }
    }

    /// Rules out the leaps of every layer that a block's port reaches, at
    /// any moment, sooner than the layer's shortest leap: the port's bound
    /// in [`Tracer::first_from_outside`] is the present plus a constant
    /// (the layers' transits between, less the blocks' margin), so each
    /// try of such a layer would end at that bound, and it tried at every
    /// event of its own (layer survey seed 71's rod 27: 2.8 M tries in
    /// 2.9 M loop events, about a third of the run's instructions, and no
    /// leap). Its tries left nothing behind but a `leap_after` in the
    /// past; the run is the same to the bit. A constant under the shortest
    /// leap by less than the rounding of the present's sums is left to the
    /// tries.
    pub(crate) fn rule_out_leaps_blocks_forbid(&mut self) {
        if self.blocks.list.is_empty() {
            return;
        }
        let transit = |m: usize| self.lanes[Lane::<R>::index(m, Direction::Up)].transit;
        let margin = self.blocks.margin;
        for i in 0..self.layers.len() {
            if self.leap_after[i] == -R::neg_infinity() {
                continue;
            }
            let shortest = if self.merged {
                R::of(LEAST_TRANSITS)
            } else {
                R::of(SHORTEST_LEAP)
            } * transit(i);
            // the port's bound less the present (`first_from_outside`)
            let mut soonest = self.blocks.list.iter().flat_map(|b| &b.ports).map(|port| {
                let (j, dir) = port.out;
                let towards = (dir == Direction::Up) == (j < i);
                self.reach(i, j, towards, transit(j)) - margin
            });
            let rounding = R::of(ROUNDING) * (self.max_time + margin);
            if soonest.any(|at| at + rounding < shortest) {
                self.leap_after[i] = -R::neg_infinity();
            }
        }
    }
}

#[cfg(test)]
mod tests;

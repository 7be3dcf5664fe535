//! Lanes: the fronts of one layer moving in one direction.
//!
//! All fronts of a lane move at the layer's wave speed, so they reach the far
//! boundary in the order they were born: a lane is a FIFO, and only its head
//! needs a place in the event queue.
//!
//! The top layer's two lanes are folded into one when nobody records front
//! paths: the free top reflects every front `d -> -d` and nothing else
//! happens there, so a front born going up at the layer's bottom simply comes
//! back to it, negated, after two transits. That removes every event at the
//! top (a third of all events at the paper's hard corner) without changing a
//! single operation of the arithmetic: the arrival time is still
//! `(born + t) + t`, as when the reflection was an event of its own.

use crate::real::Real;
use crate::window::Window;
use serde::Serialize;
use std::collections::VecDeque;

mod fifo;
mod given;
mod lattice;
mod points;
mod trains;

pub(crate) use fifo::Fifo;
pub(crate) use lattice::sum_on_points;
pub(crate) use points::LatticePoints;

pub(crate) use given::{Given, foresee};
pub(crate) use trains::{Ring, Trains};

/// Direction of travel of a front.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    /// Travelling up, away from the wall.
    Up,
    /// Travelling down, towards the wall.
    Down,
}

/// A straight front: born at one end of its layer at time `born`, it carries the
/// strain jump `jump` (value behind minus value ahead).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Front<R> {
    pub born: R,
    pub jump: R,
    /// Index into the front records (meaningful only when fronts are recorded).
    pub id: u32,
    /// A large front a lattice lane keeps where it was born.
    pub kept: bool,
}

/// How fronts born close together in a lane are merged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MergeRule<R> {
    /// Fronts born within the simultaneity window (at their birth) of the
    /// newest are one front: they started at the same instant.
    Simultaneous { window: Window<R> },
    /// Fronts are deposited on the lattice of birth times `k * spacing`,
    /// each split between the two nearest points in the proportions that
    /// keep the jump and its first moment `d t` exact: the lane's momentum
    /// is kept, its energy can only decrease (a step shared by two nearby
    /// steps carries less), and the lane holds at most `t / spacing + 2`
    /// lattice fronts. Up to `keep_at_most` fronts with `|d| >= keep_above`
    /// stay where they were born: the few large fronts whose exact timing
    /// decides contacts.
    Lattice {
        spacing: R,
        keep_above: R,
        keep_at_most: usize,
    },
}

/// Fronts of one layer and direction, oldest first.
#[derive(Debug, Clone)]
pub struct Lane<R> {
    pub layer: usize,
    pub direction: Direction,
    pub transit: R,
    /// True for the top layer's folded lane: fronts go up, reflect at the
    /// free top and come back down to the layer's bottom, negated. Set
    /// while the lane is empty (arrivals are computed as fronts enter).
    pub folded: bool,
    pub rule: MergeRule<R>,
    /// Private: every change goes through the methods that keep `head_at`.
    fronts: Fifo<Front<R>>,
    /// A leap's trains waiting in an exact lane, in lane order among the
    /// deque's fronts (`trains.rs`); usually none.
    trains: VecDeque<Trains<R>>,
    /// Fronts pushed into and popped from the deque while trains wait
    /// (counted from when the first came): where the trains sit among them.
    pushed: u64,
    popped: u64,
    /// Whether the newest front is in the waiting trains: a push then may
    /// merge into their last (one flag, read on every push).
    newest_waiting: bool,
    /// When the head front arrives, kept beside the fronts: the event loop
    /// asks for it several times an event, the lane changes its head about
    /// once.
    head_at: Option<R>,
    /// Kept (not deposited) fronts in a lattice lane.
    pub kept: usize,
}

/// What happened to a pushed front.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Pushed<R> {
    /// It became the lane's newest front (`was_empty`: and its head).
    New { was_empty: bool },
    /// It was added into the newest front. `moved_head`: that front was the
    /// head and its birth time changed; `beyond_simultaneity`: a real merge,
    /// not a tie.
    Merged {
        id: u32,
        moved_head: bool,
        beyond_simultaneity: bool,
        /// How far apart the two births were, within the simultaneity
        /// window (zero for an exact tie or a lattice merge).
        gap: R,
    },
}

impl<R: Real> Lane<R> {
    pub fn new(layer: usize, direction: Direction, transit: R, rule: MergeRule<R>) -> Self {
        Self {
            layer,
            direction,
            transit,
            folded: false,
            rule,
            fronts: Fifo::default(),
            trains: VecDeque::new(),
            newest_waiting: false,
            pushed: 0,
            popped: 0,
            head_at: None,
            kept: 0,
        }
    }

    /// Replaces the fronts (a leap's rebuilt lanes, in birth order). On a
    /// lattice the fronts of each cell are merged onto the cell's first
    /// and last birth (each split between the two in proportion to where
    /// it sits, so jump and first moment are kept and energy can only
    /// decrease, as for a deposit), the large ones excepted as in
    /// [`Lane::push`]. Without this a leap's fronts, shifted by whole round
    /// trips, sit off the lattice and never merge: a ringing layer then
    /// carried a thousand fronts through every leap (measured on a
    /// four-layer rod, `t2/t1 = 70`), and a leap costs one train per front.
    /// The merged fronts move only within a cell, and never earlier than
    /// the cell's first birth, so no arrival moves into the past.
    /// `spare` is a buffer the caller keeps from one leap to the next (not
    /// one a lane: a larger lane slowed every event of small runs by 15 %).
    pub fn set_fronts(&mut self, fronts: &[Front<R>], spare: &mut Vec<Front<R>>) {
        self.fronts.clear();
        self.trains.clear();
        self.newest_waiting = false;
        self.kept = 0;
        let MergeRule::Lattice {
            spacing,
            keep_above,
            keep_at_most,
        } = self.rule
        else {
            // an exact lane: fronts born together are one, as `push` makes
            // them (a leap's phases are separate fronts however close)
            for f in fronts {
                self.push(f.born, f.jump, f.id);
            }
            self.refresh_head();
            return;
        };
        let cell = spare;
        cell.clear();
        let mut cell_index = R::neg_infinity();
        for &f in fronts {
            let keep = f.jump.abs() >= keep_above && self.kept < keep_at_most;
            let index = (f.born / spacing).floor();
            if keep || index != cell_index {
                self.flush_cell(cell);
                cell_index = index;
            }
            if keep {
                self.kept += 1;
                self.fronts.push_back(Front { kept: true, ..f });
                cell_index = R::neg_infinity();
            } else {
                cell.push(f);
            }
        }
        self.flush_cell(cell);
        self.refresh_head();
    }

    /// Replaces the fronts by `fronts` as they are (in birth order, kept
    /// ones flagged): a stepped group's given back (`group.rs`).
    pub(crate) fn restore(&mut self, fronts: &[Front<R>]) {
        self.fronts.clear();
        self.trains.clear();
        self.newest_waiting = false;
        self.kept = fronts.iter().filter(|f| f.kept).count();
        self.fronts.extend(fronts.iter().copied());
        self.refresh_head();
    }

    #[inline(always)]
    fn refresh_head(&mut self) {
        let born = match self.trains_head_born() {
            Some(born) => Some(born),
            None => self.fronts.front().map(|f| f.born),
        };
        self.head_at = born.map(|born| self.arrival_of(born));
    }

    /// Index of the lane of `layer` moving in `direction`.
    pub fn index(layer: usize, direction: Direction) -> usize {
        2 * layer + usize::from(direction == Direction::Down)
    }

    /// The boundary a front of this lane arrives at (boundary `b` sits at the
    /// bottom of layer `b`; boundary 0 is the wall).
    pub fn target(&self) -> usize {
        match (self.direction, self.folded) {
            (Direction::Up, false) => self.layer + 1,
            _ => self.layer,
        }
    }

    /// When a front born at `born` reaches this lane's end (for a folded
    /// lane: comes back down to the layer's bottom).
    #[inline]
    pub fn arrival_of(&self, born: R) -> R {
        let far = born + self.transit;
        if self.folded { far + self.transit } else { far }
    }

    /// Whether a front arriving at `t` was born on this lane's lattice
    /// (a deposit, not a kept front): its birth within a millionth of a
    /// cell of a lattice point. Never in a lane without a lattice.
    pub fn lattice_arrival(&self, t: R) -> bool {
        match self.rule {
            MergeRule::Lattice { spacing, .. } => {
                let trip = if self.folded {
                    self.transit + self.transit
                } else {
                    self.transit
                };
                let cells = ((t - trip) / spacing).to_f64();
                (cells - cells.round()).abs() <= 1e-6
            }
            MergeRule::Simultaneous { .. } => false,
        }
    }

    /// Arrival time of the head front.
    #[inline]
    pub fn head_arrival(&self) -> Option<R> {
        debug_assert_eq!(
            self.head_at,
            self.fronts().next().map(|f| self.arrival_of(f.born))
        );
        self.head_at
    }

    /// The jump a front delivers when it arrives (a folded lane's fronts
    /// come back reflected by the free top).
    #[inline]
    pub fn delivered(&self, jump: R) -> R {
        if self.folded { -jump } else { jump }
    }

    /// How many fronts arrive before `h` (fronts are in birth order; with
    /// trains waiting, all of them, an upper bound).
    pub(crate) fn arriving_before(&self, h: R) -> usize {
        if !self.trains.is_empty() {
            return self.len();
        }
        self.fronts.partition_point(|f| self.arrival_of(f.born) < h)
    }

    /// Takes the head front.
    #[inline(always)]
    pub fn pop(&mut self) -> Option<Front<R>> {
        if let Some(t) = self.trains.front()
            && t.after == self.popped
        {
            return Some(self.take_from_trains());
        }
        let f = self.fronts.pop_front()?;
        self.popped += 1;
        if f.kept {
            self.kept -= 1;
        }
        self.refresh_head();
        Some(f)
    }

    /// Adds a front born at `born` (not earlier than any front born before
    /// it, but lattice fronts may sit later).
    #[inline]
    pub fn push(&mut self, born: R, jump: R, id: u32) -> Pushed<R> {
        match self.rule {
            MergeRule::Simultaneous { window } => self.push_on_exact(born, jump, id, window),
            MergeRule::Lattice {
                spacing,
                keep_above,
                keep_at_most,
            } => self.push_on_lattice(born, jump, id, spacing, keep_above, keep_at_most),
        }
    }

    /// [`Lane::push`], but never kept apart on a lattice: deposited
    /// whatever its size, as the many small fronts it stands for would
    /// each have been (a block's folded deliveries, `block/folded.rs`).
    pub fn push_deposited(&mut self, born: R, jump: R, id: u32) -> Pushed<R> {
        match self.rule {
            MergeRule::Simultaneous { window } => self.push_on_exact(born, jump, id, window),
            MergeRule::Lattice {
                spacing,
                keep_above,
                ..
            } => self.push_on_lattice(born, jump, id, spacing, keep_above, 0),
        }
    }

    /// Keeps the (empty) lane's fronts in `room`, a vector another run
    /// grew ([`crate::room`]).
    pub(crate) fn move_into(&mut self, room: Vec<Front<R>>) {
        debug_assert!(self.fronts.is_empty());
        self.fronts = Fifo::in_room(room);
    }

    /// The room of the lane's fronts, emptied, for another run; the lane
    /// is left empty.
    pub(crate) fn take_room(&mut self) -> Vec<Front<R>> {
        self.trains.clear();
        self.head_at = None;
        std::mem::take(&mut self.fronts).into_room()
    }

    /// Makes room for `more` fronts (a leap's trains, pushed at once).
    pub fn reserve(&mut self, more: usize) {
        self.fronts.reserve(more);
    }

    /// [`Lane::push`] on an exact lane, its `window` given (a leap's
    /// thousands of fronts take it once): `None` when the front is new,
    /// else the gap to the newest front it was merged into, and that
    /// front's id.
    #[inline(always)]
    pub fn push_exact(&mut self, born: R, jump: R, id: u32, window: Window<R>) -> Option<(R, u32)> {
        match self.push_on_exact(born, jump, id, window) {
            Pushed::Merged { gap, id, .. } => Some((gap, id)),
            Pushed::New { .. } => None,
        }
    }

    /// [`Lane::push`] under [`MergeRule::Simultaneous`].
    #[inline(always)]
    fn push_on_exact(&mut self, born: R, jump: R, id: u32, window: Window<R>) -> Pushed<R> {
        debug_assert_eq!(
            self.newest_waiting,
            self.trains.back().is_some_and(|t| t.after == self.pushed)
        );
        let merged = |gap, id| Pushed::Merged {
            id,
            moved_head: false,
            beyond_simultaneity: false,
            gap,
        };
        if self.newest_waiting {
            return match self.push_after_trains(born, jump, id, window) {
                Some((gap, id)) => merged(gap, id),
                None => Pushed::New { was_empty: false },
            };
        }
        // (with no trains newest, an empty deque is an empty lane)
        let was_empty = match self.fronts.back_mut() {
            Some(last) => {
                let gap = born - last.born;
                if gap <= window.at(born) {
                    last.jump += jump;
                    return merged(gap, last.id);
                }
                false
            }
            None => {
                self.head_at = Some(self.arrival_of(born));
                true
            }
        };
        self.fronts.push_back(Front {
            born,
            jump,
            id,
            kept: false,
        });
        self.pushed += 1;
        Pushed::New { was_empty }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arrivals_of_lattice_deposits_are_told_from_kept_fronts() {
        let rule = MergeRule::Lattice {
            spacing: 0.1,
            keep_above: 1.0,
            keep_at_most: 4,
        };
        let mut lane = Lane::new(0, Direction::Down, 2.0, rule);
        // born at the lattice's points 7 and 2,000,000
        assert!(lane.lattice_arrival(2.0 + 0.7));
        assert!(lane.lattice_arrival(2.0 + 200_000.0));
        // born between them, a millionth of a cell off
        assert!(!lane.lattice_arrival(2.0 + 0.75));
        assert!(!lane.lattice_arrival(2.0 + 0.7 + 2e-7));
        // a folded lane's fronts come back after two transits
        lane.folded = true;
        assert!(lane.lattice_arrival(4.0 + 0.7));
        assert!(!lane.lattice_arrival(2.0 + 0.75));
        let exact = Lane::new(
            0,
            Direction::Down,
            2.0,
            MergeRule::Simultaneous {
                window: Window::fixed(1e-9),
            },
        );
        assert!(!exact.lattice_arrival(2.0));
    }

    #[test]
    fn fronts_born_together_merge() {
        let mut lane = Lane::new(
            0,
            Direction::Up,
            2.0,
            MergeRule::Simultaneous {
                window: Window::fixed(1e-9),
            },
        );
        assert_eq!(lane.push(1.0, 0.5, 0), Pushed::New { was_empty: true });
        assert!(matches!(
            lane.push(1.0 + 1e-12, 0.25, 1),
            Pushed::Merged { id: 0, .. }
        ));
        assert_eq!(lane.push(1.5, 1.0, 2), Pushed::New { was_empty: false });
        assert_eq!(lane.fronts.len(), 2);
        assert_eq!(lane.fronts[0].jump, 0.75);
        assert_eq!(lane.head_arrival(), Some(3.0));
        assert_eq!(lane.target(), 1);
    }

    #[test]
    fn a_folded_lane_returns_negated_after_two_transits() {
        let mut lane = Lane::new(
            2,
            Direction::Up,
            0.75,
            MergeRule::Simultaneous {
                window: Window::fixed(0.0),
            },
        );
        lane.folded = true;
        lane.push(1.0, 0.5, 0);
        assert_eq!(lane.head_arrival(), Some((1.0 + 0.75) + 0.75));
        assert_eq!(lane.delivered(0.5), -0.5);
        assert_eq!(lane.target(), 2);
    }
}

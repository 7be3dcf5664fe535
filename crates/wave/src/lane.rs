//! Lanes: the fronts of one layer moving in one direction.
//!
//! All fronts of a lane move at the layer's wave speed, so they reach the far
//! boundary in the order they were born: a lane is a FIFO, and only its head
//! needs a place in the event queue.

use serde::Serialize;
use std::collections::VecDeque;

/// Direction of travel of a front.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    Up,
    Down,
}

/// A straight front: born at one end of its layer at time `born`, it carries the
/// strain jump `jump` (value behind minus value ahead).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Front {
    pub born: f64,
    pub jump: f64,
    /// Index into the front records (meaningful only when fronts are recorded).
    pub id: u32,
}

/// Fronts of one layer and direction, oldest first.
#[derive(Debug, Clone)]
pub struct Lane {
    pub layer: usize,
    pub direction: Direction,
    pub transit: f64,
    pub fronts: VecDeque<Front>,
}

/// What happened to a pushed front.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Pushed {
    /// It became the lane's newest front (`was_empty`: and its head).
    New { was_empty: bool },
    /// It was added into the newest front, born within the merge window.
    Merged { id: u32 },
}

impl Lane {
    pub fn new(layer: usize, direction: Direction, transit: f64) -> Self {
        Self {
            layer,
            direction,
            transit,
            fronts: VecDeque::new(),
        }
    }

    /// Index of the lane of `layer` moving in `direction`.
    pub fn index(layer: usize, direction: Direction) -> usize {
        2 * layer + usize::from(direction == Direction::Down)
    }

    /// The boundary a front of this lane arrives at (boundary `b` sits at the
    /// bottom of layer `b`; boundary 0 is the wall).
    pub fn target(&self) -> usize {
        match self.direction {
            Direction::Up => self.layer + 1,
            Direction::Down => self.layer,
        }
    }

    /// Arrival time of the head front.
    pub fn head_arrival(&self) -> Option<f64> {
        self.fronts.front().map(|f| f.born + self.transit)
    }

    /// Adds a front born at `born` (not earlier than any front of the lane).
    pub fn push(&mut self, born: f64, jump: f64, id: u32, merge_window: f64) -> Pushed {
        if let Some(last) = self.fronts.back_mut()
            && born - last.born <= merge_window
        {
            last.jump += jump;
            return Pushed::Merged { id: last.id };
        }
        let was_empty = self.fronts.is_empty();
        self.fronts.push_back(Front { born, jump, id });
        Pushed::New { was_empty }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fronts_born_together_merge() {
        let mut lane = Lane::new(0, Direction::Up, 2.0);
        assert_eq!(
            lane.push(1.0, 0.5, 0, 1e-9),
            Pushed::New { was_empty: true }
        );
        assert_eq!(
            lane.push(1.0 + 1e-12, 0.25, 1, 1e-9),
            Pushed::Merged { id: 0 }
        );
        assert_eq!(
            lane.push(1.5, 1.0, 2, 1e-9),
            Pushed::New { was_empty: false }
        );
        assert_eq!(lane.fronts.len(), 2);
        assert_eq!(lane.fronts[0].jump, 0.75);
        assert_eq!(lane.head_arrival(), Some(3.0));
        assert_eq!(lane.target(), 1);
    }
}

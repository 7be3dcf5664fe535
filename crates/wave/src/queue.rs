//! The event queue: a keyed priority queue ordered by time, knowing nothing of
//! the physics.
//!
//! Each key is scheduled at most once (rescheduling moves it). Equal times come
//! out in the order of the keys (`EventKey`'s declaration order, then lane
//! index), so simultaneous events are processed in a fixed, documented order:
//! reconnection first, then lane heads by lane index, then the escape check,
//! then the horizon. Scheduling before the current time is refused.

use ordered_float::OrderedFloat;
use priority_queue::PriorityQueue;
use std::cmp::Reverse;

/// What an entry of the queue stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum EventKey {
    /// The free bottom returns to the wall.
    Reconnection,
    /// The head front of a lane reaches the end of its layer.
    Lane(u32),
    /// The rod can no longer reach the wall: stop.
    Escape,
    /// The requested horizon.
    Horizon,
}

/// An attempt to schedule an event before the current time.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EventInPast {
    pub now: f64,
    pub requested: f64,
}

/// Time-ordered keyed queue; ties broken by key.
#[derive(Debug, Clone, Default)]
pub struct EventQueue {
    heap: PriorityQueue<EventKey, Reverse<(OrderedFloat<f64>, EventKey)>>,
    now: f64,
}

impl EventQueue {
    pub fn new() -> Self {
        Self::default()
    }

    /// The time of the last event taken with [`EventQueue::advance`].
    pub fn now(&self) -> f64 {
        self.now
    }

    /// Schedules `key` at `time`, replacing any earlier schedule of it.
    pub fn schedule(&mut self, key: EventKey, time: f64) -> Result<(), EventInPast> {
        if time < self.now || time.is_nan() {
            return Err(EventInPast {
                now: self.now,
                requested: time,
            });
        }
        self.heap.push(key, Reverse((OrderedFloat(time), key)));
        Ok(())
    }

    /// Removes `key` if scheduled.
    pub fn cancel(&mut self, key: EventKey) {
        self.heap.remove(&key);
    }

    /// The earliest event, without removing it.
    pub fn peek(&self) -> Option<(EventKey, f64)> {
        self.heap.peek().map(|(k, p)| (*k, (p.0).0.0))
    }

    /// Time at which `key` is scheduled, if it is.
    pub fn time_of(&self, key: EventKey) -> Option<f64> {
        self.heap.get_priority(&key).map(|p| (p.0).0.0)
    }

    /// Removes and returns the earliest event, moving the clock to its time.
    pub fn pop(&mut self) -> Option<(EventKey, f64)> {
        let (key, p) = self.heap.pop()?;
        let time = (p.0).0.0;
        self.now = time;
        Some((key, time))
    }

    /// Moves the clock to `time` (an event taken out of band, e.g. a lane head
    /// popped together with a simultaneous one).
    pub fn advance(&mut self, time: f64) {
        self.now = self.now.max(time);
    }

    pub fn len(&self) -> usize {
        self.heap.len()
    }

    pub fn is_empty(&self) -> bool {
        self.heap.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::collections::{BTreeMap, HashMap};

    /// A trivially correct model: a map from key to time, and a sorted set.
    #[derive(Default)]
    struct Model {
        by_key: HashMap<EventKey, f64>,
        sorted: BTreeMap<(OrderedFloat<f64>, EventKey), ()>,
    }

    impl Model {
        fn schedule(&mut self, k: EventKey, t: f64) {
            if let Some(old) = self.by_key.insert(k, t) {
                self.sorted.remove(&(OrderedFloat(old), k));
            }
            self.sorted.insert((OrderedFloat(t), k), ());
        }
        fn cancel(&mut self, k: EventKey) {
            if let Some(old) = self.by_key.remove(&k) {
                self.sorted.remove(&(OrderedFloat(old), k));
            }
        }
        fn pop(&mut self) -> Option<(EventKey, f64)> {
            let (&(t, k), _) = self.sorted.iter().next()?;
            self.sorted.remove(&(t, k));
            self.by_key.remove(&k);
            Some((k, t.0))
        }
    }

    fn key(i: u8) -> EventKey {
        match i % 8 {
            0 => EventKey::Reconnection,
            6 => EventKey::Escape,
            7 => EventKey::Horizon,
            n => EventKey::Lane(u32::from(n)),
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        /// Random schedule / cancel / pop sequences give the same pops as the model.
        #[test]
        fn matches_a_sorted_map(ops in proptest::collection::vec((0u8..3, 0u8..8, 0u16..50), 1..400)) {
            let mut q = EventQueue::new();
            let mut m = Model::default();
            for (op, k, dt) in ops {
                let k = key(k);
                // coarse times make many exact ties
                let t = q.now() + f64::from(dt) * 0.25;
                match op {
                    0 => { q.schedule(k, t).unwrap(); m.schedule(k, t); }
                    1 => { q.cancel(k); m.cancel(k); }
                    _ => prop_assert_eq!(q.pop(), m.pop()),
                }
                prop_assert_eq!(q.len(), m.by_key.len());
            }
            while let Some(e) = m.pop() {
                prop_assert_eq!(q.pop(), Some(e));
            }
            prop_assert!(q.is_empty());
        }
    }

    #[test]
    fn ties_follow_the_documented_order() {
        let mut q = EventQueue::new();
        for k in [
            EventKey::Horizon,
            EventKey::Lane(3),
            EventKey::Escape,
            EventKey::Lane(1),
            EventKey::Reconnection,
        ] {
            q.schedule(k, 1.0).unwrap();
        }
        let order: Vec<_> = std::iter::from_fn(|| q.pop().map(|e| e.0)).collect();
        assert_eq!(
            order,
            [
                EventKey::Reconnection,
                EventKey::Lane(1),
                EventKey::Lane(3),
                EventKey::Escape,
                EventKey::Horizon
            ]
        );
    }

    #[test]
    fn the_past_is_refused() {
        let mut q = EventQueue::new();
        q.schedule(EventKey::Lane(0), 2.0).unwrap();
        q.pop();
        assert_eq!(
            q.schedule(EventKey::Lane(0), 1.0),
            Err(EventInPast {
                now: 2.0,
                requested: 1.0
            })
        );
        assert!(q.schedule(EventKey::Lane(0), f64::NAN).is_err());
    }
}

//! The event queue: a keyed priority queue ordered by time, knowing nothing of
//! the physics.
//!
//! Each key is scheduled at most once (rescheduling moves it). Equal times come
//! out in the order of the keys, so simultaneous events are processed in a
//! fixed, documented order: reconnection first, then lane heads by lane index,
//! then the escape check, then the horizon. Scheduling before the current
//! time (the engine's clock, passed in: there is one clock) is refused.
//!
//! Keys are small dense integers, so the queue's index map hashes them with
//! the identity (`nohash-hasher`) instead of SipHash: at most `2L + 3` keys
//! ever exist, and hashing was a third of the cost of an event.

use crate::real::Real;
use nohash_hasher::BuildNoHashHasher;
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
    /// Current time.
    pub now: f64,
    /// Time the event was to be scheduled for, earlier than `now`.
    pub requested: f64,
}

/// Lane-indexed heap: keys are small dense integers, so they need no
/// hashing beyond themselves.
type Heap<R> = PriorityQueue<u32, Reverse<(<R as Real>::Key, u32)>, BuildNoHashHasher<u32>>;

/// Time-ordered keyed queue for a rod with `lanes` lanes; ties broken by key.
#[derive(Debug, Clone)]
pub struct EventQueue<R: Real> {
    heap: Heap<R>,
    lanes: u32,
}

impl<R: Real> EventQueue<R> {
    /// An empty queue for `lanes` lanes and the rod's other events (reconnection, escape, horizon).
    pub fn new(lanes: usize) -> Self {
        Self {
            heap: PriorityQueue::with_capacity_and_hasher(lanes + 3, Default::default()),
            lanes: lanes as u32,
        }
    }

    /// The dense code of a key; codes sort in the documented tie order.
    #[inline]
    fn code(&self, key: EventKey) -> u32 {
        match key {
            EventKey::Reconnection => 0,
            EventKey::Lane(i) => 1 + i,
            EventKey::Escape => 1 + self.lanes,
            EventKey::Horizon => 2 + self.lanes,
        }
    }

    #[inline]
    fn key(&self, code: u32) -> EventKey {
        match code {
            0 => EventKey::Reconnection,
            c if c <= self.lanes => EventKey::Lane(c - 1),
            c if c == 1 + self.lanes => EventKey::Escape,
            _ => EventKey::Horizon,
        }
    }

    /// Schedules `key` at `time`, replacing any earlier schedule of it;
    /// refused if `time` is before `now`.
    #[inline]
    pub fn schedule(&mut self, key: EventKey, time: R, now: R) -> Result<(), EventInPast> {
        if time < now || time.is_nan() {
            return Err(EventInPast {
                now: now.to_f64(),
                requested: time.to_f64(),
            });
        }
        let code = self.code(key);
        self.heap.push(code, Reverse((time.key(), code)));
        Ok(())
    }

    /// Removes `key` if scheduled.
    #[inline]
    pub fn cancel(&mut self, key: EventKey) {
        let code = self.code(key);
        self.heap.remove(&code);
    }

    /// The earliest event, without removing it.
    #[inline]
    pub fn peek(&self) -> Option<(EventKey, R)> {
        self.heap
            .peek()
            .map(|(c, p)| (self.key(*c), R::from_key((p.0).0)))
    }

    /// Time at which `key` is scheduled, if it is.
    pub fn time_of(&self, key: EventKey) -> Option<R> {
        let code = self.code(key);
        self.heap.get_priority(&code).map(|p| R::from_key((p.0).0))
    }

    /// Removes and returns the earliest event.
    pub fn pop(&mut self) -> Option<(EventKey, R)> {
        let (code, p) = self.heap.pop()?;
        Some((self.key(code), R::from_key((p.0).0)))
    }

    /// Number of scheduled events.
    pub fn len(&self) -> usize {
        self.heap.len()
    }

    /// Whether nothing is scheduled.
    pub fn is_empty(&self) -> bool {
        self.heap.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ordered_float::OrderedFloat;
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
            n => EventKey::Lane(u32::from(n) - 1),
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        /// Random schedule / cancel / pop sequences give the same pops as the model.
        #[test]
        fn matches_a_sorted_map(ops in proptest::collection::vec((0u8..3, 0u8..8, 0u16..50), 1..400)) {
            let mut q = EventQueue::<f64>::new(5);
            let mut m = Model::default();
            let mut now = 0.0;
            for (op, k, dt) in ops {
                let k = key(k);
                // coarse times make many exact ties
                let t = now + f64::from(dt) * 0.25;
                match op {
                    0 => { q.schedule(k, t, now).unwrap(); m.schedule(k, t); }
                    1 => { q.cancel(k); m.cancel(k); }
                    _ => {
                        let popped = q.pop();
                        prop_assert_eq!(popped, m.pop());
                        if let Some((_, t)) = popped { now = t; }
                    }
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
        let mut q = EventQueue::<f64>::new(4);
        for k in [
            EventKey::Horizon,
            EventKey::Lane(3),
            EventKey::Escape,
            EventKey::Lane(1),
            EventKey::Reconnection,
        ] {
            q.schedule(k, 1.0, 0.0).unwrap();
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
        let mut q = EventQueue::<f64>::new(1);
        assert_eq!(
            q.schedule(EventKey::Lane(0), 1.0, 2.0),
            Err(EventInPast {
                now: 2.0,
                requested: 1.0
            })
        );
        assert!(q.schedule(EventKey::Lane(0), f64::NAN, 0.0).is_err());
    }
}

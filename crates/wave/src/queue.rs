//! The event queue: a keyed priority queue ordered by time, knowing nothing of
//! the physics.
//!
//! Each key is scheduled at most once (rescheduling moves it). Equal times come
//! out in the order of the keys, so simultaneous events are processed in a
//! fixed, documented order: reconnection first, then layers by index (a
//! layer's key stands for the earlier of its two lanes' heads), then the
//! escape check, then the horizon. Scheduling before the current time (the
//! engine's clock, passed in: there is one clock) is refused.
//!
//! Keys are small dense integers, so the queue's index map hashes them with
//! the identity (`nohash-hasher`) instead of SipHash: at most `L + 3` keys
//! ever exist, and hashing was a third of the cost of an event.
//!
//! **The ringing key.** Most of a hard run is one layer ringing: a thin stiff
//! base under a soft top rings thousands of times between two events of any
//! other key, and each ring moves its key in the heap (a lookup, a sift up
//! and a sift down, about 180 instructions, a quarter of an event). So one
//! key at a time lives beside the heap instead of in it: the key that came
//! out of the heap first three times running, with no event of the ringing
//! key between (the ringing key then fired less often than this one).
//! Taking a key in costs a heap removal and, for the key it replaces, a
//! heap push: at two events running, layers ringing in turn (`A A B B A
//! A`, as in a merged run of six layers, four of them fast) swapped at
//! every other event and the queue took 30 % of a run's instructions; at
//! three, with a run broken by the ringing key's own events, they do not
//! swap at all, and that run (rod 20 of the layer survey) is 17 % faster
//! with the same events. Moving the ringing key costs one comparison; every question
//! (`peek`, `pop`, `time_of`) asks both places, and ties between the two are
//! broken by the key's code exactly as the heap breaks them, so the order of
//! events is the same as with the heap alone (the sweep outputs are
//! byte-identical).

use crate::real::Real;
use nohash_hasher::BuildNoHashHasher;
use priority_queue::PriorityQueue;
use std::cmp::Reverse;

/// What an entry of the queue stands for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum EventKey {
    /// The free bottom returns to the wall.
    Reconnection,
    /// The earlier head front of a layer's two lanes reaches its end.
    Layer(u32),
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

/// An entry's place in the order: its time, then its key's code.
type Order<R> = (<R as Real>::Key, u32);

/// Code-indexed heap: keys are small dense integers, so they need no
/// hashing beyond themselves.
type Heap<R> = PriorityQueue<u32, Reverse<Order<R>>, BuildNoHashHasher<u32>>;

/// How many times running a key must come out of the heap first to be
/// taken in as the ringing key (see the module's documentation).
const RUN_TO_RING: u32 = 3;

/// Time-ordered keyed queue for a rod of `layers` layers; ties broken by key.
#[derive(Debug, Clone)]
pub struct EventQueue<R: Real> {
    heap: Heap<R>,
    /// The ringing key, kept beside the heap (never in it at the same time).
    ringing: Option<Order<R>>,
    /// The code that came out of the heap first at the last `next_event`
    /// (since the ringing key last fired), and how many times running.
    last_from_heap: Option<(u32, u32)>,
    /// Per code: scheduled (in the heap or ringing). Cancelling what is not
    /// scheduled (the landing, at every wall event in contact) is then a
    /// load, not a hash lookup.
    queued: Vec<bool>,
    layers: u32,
}

impl<R: Real> EventQueue<R> {
    /// An empty queue for `layers` layers and the rod's other events (reconnection, escape, horizon).
    pub fn new(layers: usize) -> Self {
        Self {
            heap: PriorityQueue::with_capacity_and_hasher(layers + 3, Default::default()),
            ringing: None,
            last_from_heap: None,
            queued: vec![false; layers + 3],
            layers: layers as u32,
        }
    }

    /// The dense code of a key; codes sort in the documented tie order.
    #[inline]
    fn code(&self, key: EventKey) -> u32 {
        match key {
            EventKey::Reconnection => 0,
            EventKey::Layer(i) => 1 + i,
            EventKey::Escape => 1 + self.layers,
            EventKey::Horizon => 2 + self.layers,
        }
    }

    #[inline]
    fn key(&self, code: u32) -> EventKey {
        match code {
            0 => EventKey::Reconnection,
            c if c <= self.layers => EventKey::Layer(c - 1),
            c if c == 1 + self.layers => EventKey::Escape,
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
        let was_queued = std::mem::replace(&mut self.queued[code as usize], true);
        match &mut self.ringing {
            Some(ringing) if ringing.1 == code => ringing.0 = time.key(),
            _ => {
                let order = Reverse((time.key(), code));
                // (a block's port reschedules its next delivery at every
                // arrival, nearly always to the same time: a lookup then,
                // not the heap's sift)
                if was_queued && self.heap.get_priority(&code) == Some(&order) {
                    return Ok(());
                }
                self.heap.push(code, order);
            }
        }
        Ok(())
    }

    /// Removes `key` if scheduled.
    #[inline]
    pub fn cancel(&mut self, key: EventKey) {
        let code = self.code(key);
        if !std::mem::take(&mut self.queued[code as usize]) {
            return;
        }
        match self.ringing {
            Some((_, c)) if c == code => self.ringing = None,
            _ => {
                self.heap.remove(&code);
            }
        }
    }

    /// The earliest entry, and whether it is the ringing key.
    #[inline]
    fn first(&self) -> Option<(Order<R>, bool)> {
        let heap = self.heap.peek().map(|(_, p)| p.0);
        match (self.ringing, heap) {
            (Some(r), Some(h)) if h < r => Some((h, false)),
            (Some(r), _) => Some((r, true)),
            (None, h) => h.map(|h| (h, false)),
        }
    }

    /// The earliest event, without removing it.
    #[inline]
    pub fn peek(&self) -> Option<(EventKey, R)> {
        self.first()
            .map(|((time, code), _)| (self.key(code), R::from_key(time)))
    }

    /// The earliest event, without removing it, for the event loop: a key
    /// that comes out of the heap first twice running is taken out of the
    /// heap and becomes the ringing key (the previous one goes back in).
    #[inline]
    pub fn next_event(&mut self) -> Option<(EventKey, R)> {
        let ((time, code), ringing) = self.first()?;
        if ringing {
            self.last_from_heap = None;
        } else {
            let run = match self.last_from_heap {
                Some((last, run)) if last == code => run + 1,
                _ => 1,
            };
            if run >= RUN_TO_RING {
                self.heap.remove(&code);
                if let Some(old) = self.ringing.replace((time, code)) {
                    self.heap.push(old.1, Reverse(old));
                }
                self.last_from_heap = None;
            } else {
                self.last_from_heap = Some((code, run));
            }
        }
        Some((self.key(code), R::from_key(time)))
    }

    /// Time at which `key` is scheduled, if it is.
    pub fn time_of(&self, key: EventKey) -> Option<R> {
        let code = self.code(key);
        // (what is not scheduled is answered without the heap's hash
        // lookup: a leap's try asks for the landing, the escape and the
        // horizon, mostly unscheduled; 1.3 % of survey rod 20)
        if !self.queued[code as usize] {
            return None;
        }
        match self.ringing {
            Some((time, c)) if c == code => Some(R::from_key(time)),
            _ => self.heap.get_priority(&code).map(|p| R::from_key((p.0).0)),
        }
    }

    /// Removes and returns the earliest event.
    pub fn pop(&mut self) -> Option<(EventKey, R)> {
        let ((time, code), ringing) = self.first()?;
        self.queued[code as usize] = false;
        if ringing {
            self.ringing = None;
        } else {
            self.heap.pop();
        }
        Some((self.key(code), R::from_key(time)))
    }

    /// Number of scheduled events.
    pub fn len(&self) -> usize {
        self.heap.len() + usize::from(self.ringing.is_some())
    }

    /// Whether nothing is scheduled.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
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
        fn peek(&self) -> Option<(EventKey, f64)> {
            self.sorted.keys().next().map(|&(t, k)| (k, t.0))
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
            n => EventKey::Layer(u32::from(n) - 1),
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(200))]
        /// Random schedule / cancel / next / pop sequences give the same
        /// events as the model, whichever key is the ringing one (`next_event`
        /// moves keys out of the heap and back).
        #[test]
        fn matches_a_sorted_map(ops in proptest::collection::vec((0u8..5, 0u8..8, 0u16..50), 1..400)) {
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
                    2 | 3 => {
                        prop_assert_eq!(q.next_event(), m.peek());
                        prop_assert_eq!(q.peek(), m.peek());
                        prop_assert_eq!(q.time_of(k), m.by_key.get(&k).copied());
                    }
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
            EventKey::Layer(3),
            EventKey::Escape,
            EventKey::Layer(1),
            EventKey::Reconnection,
        ] {
            q.schedule(k, 1.0, 0.0).unwrap();
        }
        let order: Vec<_> = std::iter::from_fn(|| q.pop().map(|e| e.0)).collect();
        assert_eq!(
            order,
            [
                EventKey::Reconnection,
                EventKey::Layer(1),
                EventKey::Layer(3),
                EventKey::Escape,
                EventKey::Horizon
            ]
        );
    }

    /// A ringing key (out of the heap) still yields to a tie with a smaller
    /// code, and goes first in a tie with a larger one.
    #[test]
    fn ties_follow_the_documented_order_with_a_ringing_key() {
        let mut q = EventQueue::<f64>::new(4);
        q.schedule(EventKey::Layer(2), 0.5, 0.0).unwrap();
        for _ in 0..RUN_TO_RING {
            assert_eq!(q.next_event(), Some((EventKey::Layer(2), 0.5)));
        }
        assert_eq!(q.ringing.map(|r| r.1), Some(3), "Layer(2) rings");
        for k in [EventKey::Layer(3), EventKey::Layer(1), EventKey::Layer(2)] {
            q.schedule(k, 1.0, 0.5).unwrap();
        }
        assert_eq!(q.heap.len(), 2, "the ringing key stays out of the heap");
        let order: Vec<_> = std::iter::from_fn(|| q.pop().map(|e| e.0)).collect();
        assert_eq!(
            order,
            [EventKey::Layer(1), EventKey::Layer(2), EventKey::Layer(3)]
        );
    }

    /// Two keys that fire in turn, twice each, do not swap places: the
    /// ringing key keeps its place while it fires between the other's runs
    /// (swapping at every other event made the queue 30 % of a merged run).
    #[test]
    fn keys_ringing_in_turn_do_not_swap() {
        let (a, b) = (EventKey::Layer(0), EventKey::Layer(1));
        let mut q = EventQueue::<f64>::new(2);
        let mut now = 0.0;
        let mut fire = |q: &mut EventQueue<f64>, key: EventKey| {
            // `key` next, the other one just after
            let other = if key == a { b } else { a };
            q.schedule(key, now + 1.0, now).unwrap();
            q.schedule(other, now + 1.5, now).unwrap();
            assert_eq!(q.next_event(), Some((key, now + 1.0)));
            now += 1.0;
        };
        for _ in 0..RUN_TO_RING {
            fire(&mut q, a);
        }
        assert_eq!(q.ringing.map(|r| r.1), Some(1), "Layer(0) rings");
        for _ in 0..10 {
            fire(&mut q, b);
            fire(&mut q, b);
            fire(&mut q, a);
            fire(&mut q, a);
            assert_eq!(q.ringing.map(|r| r.1), Some(1), "Layer(0) still rings");
        }
        // a longer run of the other key takes its place
        for _ in 0..RUN_TO_RING {
            fire(&mut q, b);
        }
        assert_eq!(q.ringing.map(|r| r.1), Some(2), "Layer(1) rings");
    }

    #[test]
    fn the_past_is_refused() {
        let mut q = EventQueue::<f64>::new(1);
        assert_eq!(
            q.schedule(EventKey::Layer(0), 1.0, 2.0),
            Err(EventInPast {
                now: 2.0,
                requested: 1.0
            })
        );
        assert!(q.schedule(EventKey::Layer(0), f64::NAN, 0.0).is_err());
    }
}

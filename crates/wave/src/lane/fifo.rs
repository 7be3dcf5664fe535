//! A lane's fronts, oldest first: a vector read from a moving head.
//!
//! Fronts are pushed at the back and taken from the front, and a leap reads
//! them all in order. `std::collections::VecDeque` did this first; its ring
//! arithmetic on every access and its out-of-line `push_back` were a fifth
//! of an event's instructions in the flight after the last separation,
//! where the 20 hardest points of the paper's grid spend a quarter of
//! their time (callgrind). Here a push is a vector's push, a pop moves the
//! head, and the taken fronts are dropped from the vector (one move of the
//! rest) once they are at least half of it and [`COMPACT_FROM`] or more: a
//! front is moved at most once on average, and the vector holds at most
//! twice the lane's fronts (plus `COMPACT_FROM`).

use std::ops::{Index, IndexMut, RangeFrom, RangeTo};

/// Taken fronts are dropped from the vector from this many on.
const COMPACT_FROM: usize = 256;

/// Items in first-in, first-out order, with the access a lane needs.
#[derive(Debug, Clone)]
pub struct Fifo<T> {
    items: Vec<T>,
    /// Items before `head` were taken.
    head: usize,
}

impl<T> Default for Fifo<T> {
    fn default() -> Self {
        Self {
            items: Vec::new(),
            head: 0,
        }
    }
}

impl<T: Copy> Fifo<T> {
    /// Empty, in the room of `items` (emptied first).
    pub fn in_room(mut items: Vec<T>) -> Self {
        items.clear();
        Self { items, head: 0 }
    }

    /// The room, emptied.
    pub fn into_room(mut self) -> Vec<T> {
        self.items.clear();
        self.items
    }

    pub fn len(&self) -> usize {
        self.items.len() - self.head
    }

    pub fn is_empty(&self) -> bool {
        self.items.len() == self.head
    }

    pub fn clear(&mut self) {
        self.items.clear();
        self.head = 0;
    }

    pub fn reserve(&mut self, more: usize) {
        self.items.reserve(more);
    }

    /// The items, oldest first.
    #[inline(always)]
    pub fn as_slice(&self) -> &[T] {
        &self.items[self.head..]
    }

    /// The items, oldest first, to change in place.
    #[inline(always)]
    pub fn as_mut_slice(&mut self) -> &mut [T] {
        &mut self.items[self.head..]
    }

    #[inline(always)]
    pub fn iter(&self) -> std::slice::Iter<'_, T> {
        self.as_slice().iter()
    }

    #[inline(always)]
    pub fn front(&self) -> Option<&T> {
        self.items.get(self.head)
    }

    #[inline(always)]
    pub fn back(&self) -> Option<&T> {
        if self.is_empty() {
            None
        } else {
            self.items.last()
        }
    }

    #[inline(always)]
    pub fn back_mut(&mut self) -> Option<&mut T> {
        if self.is_empty() {
            None
        } else {
            self.items.last_mut()
        }
    }

    pub fn get(&self, i: usize) -> Option<&T> {
        self.as_slice().get(i)
    }

    /// The `i`-th oldest item, if held: one comparison against the
    /// vector. `i` is at most `isize::MAX` (a lane's offset from its first
    /// point, an `i64` at or above zero), so `head + i` cannot overflow:
    /// `head` is at most the vector's length, itself at most `isize::MAX`.
    /// (A saturating or checked sum cost seed 7's rod 20 4 % more
    /// instructions than the plain one, callgrind.)
    #[inline(always)]
    pub fn get_mut(&mut self, i: usize) -> Option<&mut T> {
        debug_assert!(i <= isize::MAX as usize, "index {i} past isize::MAX");
        self.items.get_mut(self.head + i)
    }

    #[inline(always)]
    pub fn push_back(&mut self, item: T) {
        self.items.push(item);
    }

    /// Takes the oldest item.
    #[inline(always)]
    pub fn pop_front(&mut self) -> Option<T> {
        let item = *self.items.get(self.head)?;
        self.head += 1;
        if self.head == self.items.len() {
            self.clear();
        } else if self.head >= COMPACT_FROM && 2 * self.head >= self.items.len() {
            self.compact();
        }
        Some(item)
    }

    /// Takes the `n` oldest items (all of them, if fewer).
    #[inline]
    pub fn skip(&mut self, n: usize) {
        self.head += n.min(self.len());
        if self.head == self.items.len() {
            self.clear();
        } else if self.head >= COMPACT_FROM && 2 * self.head >= self.items.len() {
            self.compact();
        }
    }

    /// Drops the taken items from the vector.
    #[cold]
    fn compact(&mut self) {
        self.items.drain(..self.head);
        self.head = 0;
    }

    /// Takes the newest item.
    pub fn pop_back(&mut self) -> Option<T> {
        if self.is_empty() {
            return None;
        }
        let item = self.items.pop();
        if self.is_empty() {
            self.clear();
        }
        item
    }

    /// Inserts `item` at position `i` among the items (`0`: the oldest).
    pub fn insert(&mut self, i: usize, item: T) {
        assert!(i <= self.len(), "insertion index {i} beyond {}", self.len());
        if i == 0 && self.head > 0 {
            // before the oldest, where a taken item was: no move
            self.head -= 1;
            self.items[self.head] = item;
        } else {
            self.items.insert(self.head + i, item);
        }
    }

    pub fn extend(&mut self, items: impl IntoIterator<Item = T>) {
        self.items.extend(items);
    }

    /// The items from position `from` on, taken out.
    pub fn drain(&mut self, from: RangeFrom<usize>) -> std::vec::Drain<'_, T> {
        let start = self.head + from.start.min(self.len());
        self.items.drain(start..)
    }

    /// The items before position `to`.
    pub fn range(&self, to: RangeTo<usize>) -> std::slice::Iter<'_, T> {
        self.as_slice()[to].iter()
    }

    /// The number of items (oldest first) for which `pred` holds, where it
    /// holds for a prefix.
    pub fn partition_point(&self, pred: impl FnMut(&T) -> bool) -> usize {
        self.as_slice().partition_point(pred)
    }
}

impl<T> Index<usize> for Fifo<T> {
    type Output = T;
    fn index(&self, i: usize) -> &T {
        &self.items[self.head + i]
    }
}

impl<T> IndexMut<usize> for Fifo<T> {
    fn index_mut(&mut self, i: usize) -> &mut T {
        &mut self.items[self.head + i]
    }
}

#[cfg(test)]
mod tests {
    use super::Fifo;
    use std::collections::VecDeque;

    /// Against `VecDeque` over a long pseudo-random mix of every operation
    /// (pushes outnumbering pops, so that the head compacts many times):
    /// the same items, in the same order, after each.
    #[test]
    fn it_holds_what_a_deque_holds() {
        let mut fifo = Fifo::default();
        let mut deque = VecDeque::new();
        let mut next = crate::test_random::xorshift(0x2545_f491_4f6c_dd1du64);
        for step in 0..200_000u64 {
            let r = next();
            match r % 16 {
                0..=6 => {
                    fifo.push_back(step);
                    deque.push_back(step);
                }
                7..=11 => assert_eq!(fifo.pop_front(), deque.pop_front()),
                12 => assert_eq!(fifo.pop_back(), deque.pop_back()),
                13 => {
                    // (before the oldest half the time: into a taken slot
                    // where the head has moved)
                    let i = match next() % 2 {
                        0 => 0,
                        _ => (next() as usize) % (deque.len() + 1),
                    };
                    fifo.insert(i, step);
                    deque.insert(i, step);
                }
                14 => {
                    if let (Some(a), Some(b)) = (fifo.back_mut(), deque.back_mut()) {
                        *a += 1;
                        *b += 1;
                    }
                    let at = (next() as usize) % (deque.len() + 1);
                    let taken: Vec<u64> = fifo.drain(at..).collect();
                    let expected: Vec<u64> = deque.drain(at..).collect();
                    assert_eq!(taken, expected);
                    fifo.extend(taken);
                    deque.extend(expected);
                }
                _ => {
                    if !deque.is_empty() {
                        let i = (next() as usize) % deque.len();
                        assert_eq!(fifo[i], deque[i]);
                        assert_eq!(fifo.get(i), deque.get(i));
                        assert_eq!(fifo.get_mut(i), deque.get_mut(i));
                    }
                    // (past the end, and as far past it as an index goes:
                    // nothing)
                    let past = [deque.len(), isize::MAX as usize - (r as usize % 4)];
                    for i in past {
                        assert_eq!(fifo.get_mut(i), None, "{i}");
                    }
                }
            }
            assert_eq!(fifo.len(), deque.len());
            assert_eq!(fifo.front(), deque.front());
            assert_eq!(fifo.back(), deque.back());
            if step % 1_000 == 0 {
                assert!(fifo.iter().eq(deque.iter()), "step {step}");
                let to = deque.len() / 2;
                assert!(fifo.range(..to).eq(deque.range(..to)));
            }
        }
        // (the mix leaves thousands of items: the head compacted on the way)
        assert!(deque.len() > 1_000, "{}", deque.len());
    }

    /// On items in order (a lane's births), the number before a value,
    /// as the deque counts it, with the head anywhere.
    #[test]
    fn partition_point_counts_the_items_before_a_value() {
        for taken in [0, 1, 255, 256, 257, 700, 999] {
            let mut fifo = Fifo::default();
            let mut deque = VecDeque::new();
            for v in 0..1_000u64 {
                fifo.push_back(2 * v);
                deque.push_back(2 * v);
            }
            for _ in 0..taken {
                assert_eq!(fifo.pop_front(), deque.pop_front());
            }
            for x in [0, 1, 2, 511, 512, 1_400, 1_997, 1_998, 1_999, 5_000] {
                assert_eq!(
                    fifo.partition_point(|&v| v < x),
                    deque.partition_point(|&v| v < x),
                    "taken {taken}, x {x}"
                );
            }
        }
    }
}

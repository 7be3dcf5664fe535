//! Trains a leap sent into an exact lane, kept as trains until their fronts
//! arrive.
//!
//! A leap of a quiet layer sends each of its ringing fronts into a
//! neighbour as a train: `c q^k` born at `start + k P`. Spawned front by
//! front, the trains of one leap at the paper's hard corner are 8,400
//! fronts of the soft top, born in a few microseconds and never reached:
//! the run ends before they come back. Making them was a fifth of the
//! point's time and most of its memory (its page faults were another
//! fifth of a sweep's first pass). Here they wait as trains, and a front
//! is made only when it becomes the lane's head.
//!
//! Nothing changes but when the arithmetic is done: the fronts come out in
//! the order, with the births (`start + k P`) and the jumps (one product a
//! round) that spawning them one by one gave (`leap::trains`), merged as
//! the lane merged them. The leap keeps trains waiting only where what
//! spawning would do is foreseen (`lane::given`): no front dropped, none
//! merged into the lane's newest; otherwise, and for short trains, it
//! spawns them as before (`Tracer::place_exact_trains`).

use super::{Front, Given, Lane};
use crate::real::Real;
use crate::window::Window;

/// One train of fronts: the next one it gives is born at
/// `start + round P` with `jump`; it gives `count` in all.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ring<R> {
    pub start: R,
    pub period: R,
    pub q: R,
    pub count: u64,
    pub jump: R,
}

/// Trains of one leap waiting in a lane, given round by round: round `k`
/// of every train still ringing, by start, then round `k + 1` (their
/// starts lie within one period, so that is birth order). Their fronts
/// are merged as the lane merges fronts pushed one by one: one born within
/// the simultaneity window of the newest is added into it (at the hard
/// corner two trains ring `2.5e-14` apart, a tie split by rounding).
#[derive(Debug, Clone)]
pub(crate) struct Trains<R> {
    /// They sit after this many fronts pushed into the lane's deque.
    pub(super) after: u64,
    /// The trains still ringing in the current round, by start.
    rings: Vec<Ring<R>>,
    round: u64,
    next: usize,
    /// The lane's simultaneity window.
    window: Window<R>,
    /// Fronts left as the lane holds them (merged) and as the trains give
    /// them; the id of the next, and the birth of the last.
    left: u64,
    given: u64,
    id: u32,
    last_born: R,
    /// The births of the fronts given that merge into the one before, in
    /// order, and how many of them are taken.
    merging: Vec<R>,
    merged: usize,
}

impl<R: Real> Trains<R> {
    /// The trains `rings` (sorted by start, all with one period) in a lane
    /// of simultaneity `window`, giving `given` (ids from `id`).
    pub(crate) fn new(rings: Vec<Ring<R>>, window: Window<R>, given: Given<R>, id: u32) -> Self {
        let mut trains = Self {
            after: 0,
            rings,
            round: 0,
            next: 0,
            window,
            left: given.held,
            given: given.given,
            id,
            last_born: given.last_born,
            merging: given.merging,
            merged: 0,
        };
        trains.rings.retain(|r| r.count > 0);
        trains
    }

    fn head_born(&self) -> R {
        let r = &self.rings[self.next];
        r.start + R::of(self.round as f64) * r.period
    }

    /// How many of the fronts left are born while `born_by` holds (see
    /// [`Lane::count_born_by`]): for each train, the first round it fails,
    /// by bisection on the births as [`Trains::give`] computes them.
    fn count_born_by(&self, born_by: &impl Fn(R) -> bool) -> u64 {
        let born = |r: &Ring<R>, k: u64| r.start + R::of(k as f64) * r.period;
        let given: u64 = self
            .rings
            .iter()
            .enumerate()
            .map(|(j, r)| {
                // rounds this train still gives: from the current one, or
                // the next if it has given the current one
                let (mut lo, mut hi) = (self.round + u64::from(j < self.next), r.count);
                let first = lo;
                while lo < hi {
                    let mid = lo + (hi - lo) / 2;
                    if born_by(born(r, mid)) {
                        lo = mid + 1;
                    } else {
                        hi = mid;
                    }
                }
                lo - first
            })
            .sum();
        // a front merging into the one before is not one of the lane's
        // (births only grow: if it is born by then, so is the one before)
        let merging = self.merging[self.merged..].partition_point(|&b| born_by(b));
        given - merging as u64
    }

    /// The next front as the lane holds it: the next one given, and those
    /// after it born within the window of it added in order, as
    /// `Lane::push_exact` adds them.
    fn take(&mut self) -> Front<R> {
        let (born, mut jump) = self.give();
        while self.given > 0 {
            let next = self.head_born();
            if next - born > self.window.at(next) {
                break;
            }
            jump += self.give().1;
            self.merged += 1;
        }
        let front = Front {
            born,
            jump,
            id: self.id,
            kept: false,
        };
        self.id = self.id.wrapping_add(1);
        self.left -= 1;
        front
    }

    /// The next front given: its birth and jump.
    fn give(&mut self) -> (R, R) {
        let round = self.round;
        let r = &mut self.rings[self.next];
        let given = (r.start + R::of(round as f64) * r.period, r.jump);
        r.jump = r.jump * r.q;
        self.given -= 1;
        self.next += 1;
        if self.next == self.rings.len() {
            self.round += 1;
            self.rings.retain(|r| r.count > round + 1);
            self.next = 0;
        }
        given
    }
}

impl<R: Real> Iterator for Trains<R> {
    type Item = Front<R>;

    fn next(&mut self) -> Option<Front<R>> {
        (self.left > 0).then(|| self.take())
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = usize::try_from(self.left).unwrap_or(usize::MAX);
        (n, Some(n))
    }
}

/// A lane's fronts in order, its waiting trains expanded as they come.
pub struct Fronts<'a, R> {
    /// The deque's alone, when no trains wait.
    plain: Option<std::slice::Iter<'a, Front<R>>>,
    lane: &'a Lane<R>,
    /// Next front of the deque, next trains, the trains being expanded.
    index: usize,
    trains: usize,
    expanding: Option<Trains<R>>,
}

impl<R: Real> Iterator for Fronts<'_, R> {
    type Item = Front<R>;

    #[inline]
    fn next(&mut self) -> Option<Front<R>> {
        if let Some(plain) = &mut self.plain {
            return plain.next().copied();
        }
        loop {
            if let Some(t) = &mut self.expanding {
                if let Some(f) = t.next() {
                    return Some(f);
                }
                self.expanding = None;
                self.trains += 1;
            }
            let lane = self.lane;
            if let Some(t) = lane.trains.get(self.trains)
                && t.after == lane.popped + self.index as u64
            {
                self.expanding = Some(t.clone());
                continue;
            }
            let f = lane.fronts.get(self.index)?;
            self.index += 1;
            return Some(*f);
        }
    }

    /// The deque's own `fold` when no trains wait (a leap gathers its
    /// layer's fronts so: a call a front was a tenth of a leap).
    fn fold<B, F: FnMut(B, Front<R>) -> B>(mut self, init: B, mut f: F) -> B {
        if let Some(plain) = self.plain.take() {
            return plain.fold(init, |acc, front| f(acc, *front));
        }
        let mut acc = init;
        for front in self {
            acc = f(acc, front);
        }
        acc
    }
}

impl<R: Real> Lane<R> {
    /// The fronts, oldest first.
    pub fn fronts(&self) -> Fronts<'_, R> {
        Fronts {
            plain: self.trains.is_empty().then(|| self.fronts.iter()),
            lane: self,
            index: 0,
            trains: 0,
            expanding: None,
        }
    }

    /// How many fronts the lane holds.
    pub fn len(&self) -> usize {
        let waiting: u64 = self.trains.iter().map(|t| t.left).sum();
        self.fronts.len() + usize::try_from(waiting).unwrap_or(usize::MAX)
    }

    /// Whether the lane holds no front.
    #[inline(always)]
    pub fn is_empty(&self) -> bool {
        self.fronts.is_empty() && self.trains.is_empty()
    }

    /// The birth of the newest front, if any.
    pub(crate) fn newest_born(&self) -> Option<R> {
        if self.newest_waiting {
            self.newest_born_waiting()
        } else {
            self.fronts.back().map(|f| f.born)
        }
    }

    /// The birth of the newest waiting trains' last front.
    fn newest_born_waiting(&self) -> Option<R> {
        self.trains.back().map(|t| t.last_born)
    }

    /// Puts a leap's trains behind the newest front (an exact lane's; the
    /// caller has checked that none of their fronts would be dropped or
    /// merged into the newest).
    pub(crate) fn add_trains(&mut self, mut trains: Trains<R>) {
        debug_assert!(matches!(self.rule, super::MergeRule::Simultaneous { .. }));
        if trains.left == 0 {
            return;
        }
        if self.trains.is_empty() {
            // the counts matter only while trains wait
            self.pushed = self.fronts.len() as u64;
            self.popped = 0;
        }
        trains.after = self.pushed;
        let was_empty = self.is_empty();
        self.trains.push_back(trains);
        self.newest_waiting = true;
        if was_empty {
            self.refresh_head();
        }
    }

    /// How many fronts were born by the time `born_by` turns false (a
    /// predicate of the birth, true up to some birth and false after): the
    /// deque's and the waiting trains' by bisection
    /// (a run stopped with a leap's trains in a folded top counts the
    /// reflections they made at the top).
    pub(crate) fn count_born_by(&self, born_by: impl Fn(R) -> bool) -> u64 {
        // (births only grow along the deque: a bisection)
        let deque = self.fronts.partition_point(|f| born_by(f.born)) as u64;
        let waiting: u64 = self.trains.iter().map(|t| t.count_born_by(&born_by)).sum();
        deque + waiting
    }

    /// The waiting trains' next front, if it is the lane's head.
    #[inline(always)]
    pub(super) fn trains_head_born(&self) -> Option<R> {
        match self.trains.front() {
            Some(t) if t.after == self.popped => Some(t.head_born()),
            _ => None,
        }
    }

    /// Takes the head from the waiting trains (cold: a leap's trains are
    /// rarely reached).
    #[cold]
    #[inline(never)]
    pub(super) fn take_from_trains(&mut self) -> Front<R> {
        let (front, done) = match self.trains.front_mut() {
            Some(t) => (t.take(), t.left == 0),
            None => unreachable!("the lane's head is in its trains"),
        };
        if done {
            self.trains.pop_front();
            // (the newest too, if none wait now)
            self.newest_waiting &= !self.trains.is_empty();
        }
        self.refresh_head();
        front
    }

    /// [`Lane::push_exact`] when the newest front is in the waiting trains:
    /// behind them, or merged into their last (first made a front of the
    /// deque) if born within the window of it.
    #[cold]
    #[inline(never)]
    pub(super) fn push_after_trains(
        &mut self,
        born: R,
        jump: R,
        id: u32,
        window: Window<R>,
    ) -> Option<(R, u32)> {
        let within = |last: R| born - last <= window.at(born);
        self.newest_waiting = false;
        if !self.newest_born_waiting().is_some_and(within) {
            self.push_behind(born, jump, id);
            return None;
        }
        if let Some(trains) = self.trains.pop_back() {
            self.pushed += trains.left;
            self.fronts.extend(trains);
        }
        match self.fronts.back_mut() {
            Some(last) => {
                last.jump += jump;
                Some((born - last.born, last.id))
            }
            None => unreachable!("the trains' fronts are in the deque"),
        }
    }

    fn push_behind(&mut self, born: R, jump: R, id: u32) {
        self.pushed += 1;
        self.fronts.push_back(Front {
            born,
            jump,
            id,
            kept: false,
        });
    }
}

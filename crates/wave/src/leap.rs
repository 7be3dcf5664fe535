//! Leaping a quiet layer: its ringing advanced in closed form.
//!
//! Between two arrivals from outside, the fronts in a layer only bounce
//! between its two ends: a front arriving at the bottom with jump `a` comes
//! back one round trip `P = 2 t_i` later with `a q`, `q` the product of the
//! two reflections, and leaves `c a q^k` into a neighbour each time. So
//! `n` round trips of `m` fronts, `2 n m` events of the step-by-step loop,
//! are a few geometric sums per front: the wall impulse and height, the
//! fronts deposited on the neighbours' lattices (jump and first moment, as a
//! deposit one by one would give), the drops. A stiff base under a soft
//! stack rings thousands of times between two arrivals from the stack: its
//! cost no longer grows with `t_soft / t_stiff`.
//!
//! The wall's decisions stay exact: in contact the wall strain after the
//! `k`-th return of front `p` is `C0 + C_p q^k`, monotone in `k` for each
//! parity, so the first return that would make it tensile (or grazing) is
//! found in closed form and the leap stops just before it; in flight the
//! bottom's velocity takes only values `V_inf + W_p q^k`, so its lowest
//! value bounds the height from below and the leap stops before the bottom
//! could land. The event loop then takes the decision itself.
//!
//! A merged run's neighbours take the deposits on their lattices in bulk;
//! an exact run's take every front, spawned in birth order when the leap
//! ends (a leap's trains interleave). An exact leap leaves to the loop any
//! return whose contact decision comes within [`NEAR_GRAZING`] of going the
//! other way, so the loop still counts them (they decide the double-double
//! repeat). What it changes is rounding only: a front's jump after `k`
//! round trips is `a q^k` instead of `k` products, its birth `tau + k P`
//! instead of `2 k` sums, and the wall impulse a geometric sum.

use crate::engine::{NEAR_GRAZING, Tracer};
use crate::error::WaveError;
use crate::geometric::sums;
use crate::lane::{Direction, Front, Lane, MergeRule};
use crate::queue::EventKey;
use crate::real::Real;
use crate::wall::ContactState;
use crate::window::Window;
use std::cmp::Ordering;

/// Leaps shorter than this many transits of the layer are not worth it.
pub(crate) const LEAST_TRANSITS: f64 = 8.0;

/// When each layer may first try to leap: never (infinity) where a
/// neighbour's round trip is under [`LEAST_TRANSITS`] of the layer's own
/// transits (what a leap sends it would come back too soon) or the layer is
/// a folded top; else from the start. Without this every boundary event of
/// such a layer tried, at a tenth of a small point's time.
pub(crate) fn first_leaps<R: Real>(transits: &[R], folded_top: bool) -> Vec<R> {
    let n = transits.len();
    (0..n)
        .map(|i| {
            let least = R::of(LEAST_TRANSITS) * transits[i];
            let neighbours = [i.checked_sub(1), (i + 1 < n).then_some(i + 1)];
            let too_soon = neighbours
                .into_iter()
                .flatten()
                .any(|j| transits[j] + transits[j] < least);
            if n < 2 || too_soon || (folded_top && i == n - 1) {
                -R::neg_infinity()
            } else {
                R::neg_infinity()
            }
        })
        .collect()
}

/// A front ringing in the leaping layer.
#[derive(Debug, Clone, Copy)]
struct Phase<R> {
    /// Next arrival at the layer's bottom, and the strain jump it brings.
    tau: R,
    amp: R,
    /// For a front going up as the leap starts: when it reaches the top and
    /// with which jump (its reflection is the phase).
    top: Option<(R, R)>,
}

/// What the layer's two ends do to a front.
#[derive(Debug, Clone, Copy)]
struct Ends<R> {
    /// Reflection of an arriving down front at the bottom.
    bottom: R,
    /// Lane and transmission into the layer below (none at the wall).
    below: Option<(usize, R)>,
    /// Reflection of an arriving up front at the top.
    top: R,
    /// Lane and transmission into the layer above (none at a free top).
    above: Option<(usize, R)>,
}

/// A train of fronts: `c q^k` born at `start + k period`, `k < count`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Train<R> {
    start: R,
    period: R,
    c: R,
    q: R,
    count: u64,
}

/// The smallest `k < kmax` with `c0 + cp q^k >= threshold`, `0 <= q < 1`.
fn first_crossing_positive<R: Real>(c0: R, cp: R, q: R, kmax: u64, threshold: R) -> Option<u64> {
    if kmax == 0 {
        return None;
    }
    let at = |k: u64| c0 + cp * q.powi(k.min(i32::MAX as u64) as i32);
    if at(0) >= threshold {
        return Some(0);
    }
    if q == R::zero() {
        return (kmax > 1 && c0 >= threshold).then_some(1);
    }
    // cp >= 0: decreasing from at(0) < threshold: never
    if cp >= R::zero() || c0 < threshold {
        return None;
    }
    // increasing towards c0 >= threshold: q^k <= (c0 - threshold) / (-cp)
    let x = (c0 - threshold) / (-cp);
    let mut k = if x >= R::one() {
        0
    } else {
        let v = (x.ln() / q.ln()).ceil().to_f64();
        if !(v.is_finite()) || v > kmax as f64 {
            return None;
        }
        v.max(0.0) as u64
    };
    while k > 0 && at(k - 1) >= threshold {
        k -= 1;
    }
    while k < kmax && at(k) < threshold {
        k += 1;
    }
    (k < kmax).then_some(k)
}

/// The smallest `k < kmax` with `c0 + cp q^k >= threshold`, `|q| < 1`.
fn first_crossing<R: Real>(c0: R, cp: R, q: R, kmax: u64, threshold: R) -> Option<u64> {
    if q >= R::zero() {
        return first_crossing_positive(c0, cp, q, kmax, threshold);
    }
    // even k = 2j: c0 + cp Q^j; odd k = 2j + 1: c0 + cp q Q^j, Q = q^2
    let big_q = q * q;
    let even = first_crossing_positive(c0, cp, big_q, kmax.div_ceil(2), threshold).map(|j| 2 * j);
    let odd = first_crossing_positive(c0, cp * q, big_q, kmax / 2, threshold).map(|j| 2 * j + 1);
    match (even, odd) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// The first `k < kmax` with `f0 + b k + c (q^k - 1) <= 0`, `|q| < 1`.
fn first_nonpositive<R: Real>(f0: R, b: R, c: R, q: R, kmax: u64) -> Option<u64> {
    if kmax == 0 {
        return None;
    }
    if f0 <= R::zero() {
        return Some(0);
    }
    if q >= R::zero() {
        return first_nonpositive_positive(f0, b, c, q, kmax);
    }
    // parity: k = 2j + r, q^k - 1 = q^r (Q^j - 1) + (q^r - 1), Q = q^2
    let big_q = q * q;
    let even = first_nonpositive_positive(f0, b + b, c, big_q, kmax.div_ceil(2)).map(|j| 2 * j);
    let odd_f0 = f0 + b + c * (q - R::one());
    let odd = if kmax >= 2 {
        first_nonpositive_positive(odd_f0, b + b, c * q, big_q, kmax / 2).map(|j| 2 * j + 1)
    } else {
        None
    };
    match (even, odd) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// [`first_nonpositive`] for `0 <= q < 1`: the differences
/// `b + c q^k (q - 1)` change sign at most once, so the function has at most
/// two monotone pieces; each is searched by bisection.
fn first_nonpositive_positive<R: Real>(f0: R, b: R, c: R, q: R, kmax: u64) -> Option<u64> {
    let ln_q = q.ln();
    let f = |k: u64| f0 + b * R::of(k as f64) + c * (ln_q * R::of(k as f64)).exp_m1();
    if kmax == 0 {
        return None;
    }
    if f(0) <= R::zero() {
        return Some(0);
    }
    // where the differences change sign: q^k = -b / (c (q - 1))
    let x = -b / (c * (q - R::one()));
    let turn = if q > R::zero() && x > R::zero() && x < R::one() {
        let k = (x.ln() / ln_q).to_f64();
        if k.is_finite() && k > 0.0 {
            (k.floor() as u64).min(kmax - 1)
        } else {
            0
        }
    } else {
        0
    };
    for (lo, hi) in [(0, turn), (turn, kmax - 1)] {
        if hi < lo || f(hi) > R::zero() {
            continue;
        }
        // monotone on [lo, hi], positive at lo (else found before), not at hi
        if f(lo) <= R::zero() {
            return Some(lo);
        }
        let (mut a, mut z) = (lo, hi);
        while z - a > 1 {
            let mid = a + (z - a) / 2;
            if f(mid) <= R::zero() {
                z = mid;
            } else {
                a = mid;
            }
        }
        return Some(z);
    }
    None
}

/// `q^k`, for any `k`.
fn pow<R: Real>(q: R, k: u64) -> R {
    if k <= i32::MAX as u64 {
        q.powi(k as i32)
    } else {
        q.powf(R::of(k as f64))
    }
}

/// How many `k >= 0` have `start + k period < end`.
fn count_before<R: Real>(start: R, period: R, end: R) -> u64 {
    if start >= end {
        return 0;
    }
    let mut n = ((end - start) / period).ceil().to_f64().max(1.0) as u64;
    while n > 0 && start + R::of((n - 1) as f64) * period >= end {
        n -= 1;
    }
    while start + R::of(n as f64) * period < end {
        n += 1;
    }
    n
}

/// Fronts going into one exact lane at the end of a leap, as
/// [`Tracer::spawn_front`] would take them: what it drops and the merges
/// it notes are kept for the tracer's ledgers.
struct Into<'a, R> {
    lane: &'a mut Lane<R>,
    window: Window<R>,
    thr: R,
    id: u32,
    /// The jumps added (the layer's base moves by them).
    total: R,
    dropped: Vec<(R, R)>,
    /// Merges of births more than zero apart: `(gap, born)`.
    merges: Vec<(R, R)>,
}

impl<R: Real> Into<'_, R> {
    #[inline(always)]
    fn put(&mut self, born: R, jump: R) {
        if jump.abs() < self.thr {
            if jump != R::zero() {
                self.dropped.push((born, jump));
            }
            return;
        }
        self.total += jump;
        match self.lane.push_exact(born, jump, self.id, self.window) {
            None => self.id += 1,
            Some(gap) => {
                if gap > R::zero() {
                    self.merges.push((gap, born));
                }
            }
        }
    }
}

/// The births of ringing trains round by round: round `k` of every train
/// (sorted by start), then round `k + 1`; jumps by one product a round.
fn rounds<R: Real>(rings: &[(usize, Train<R>)], mut put: impl FnMut(R, R)) {
    let count = rings.iter().map(|t| t.1.count).max().unwrap_or(0);
    let mut jumps: Vec<R> = rings.iter().map(|t| t.1.c).collect();
    for k in 0..count {
        let kk = R::of(k as f64);
        for ((_, t), jump) in rings.iter().zip(jumps.iter_mut()) {
            if k < t.count {
                put(t.start + kk * t.period, *jump);
                *jump = *jump * t.q;
            }
        }
    }
}

/// Whether the singles then [`rounds`] come in birth order: singles (sorted)
/// before the first ring, and rings (sorted, one period) whose starts lie
/// within a period by more than rounding, so that the rounded births of
/// round `k` stay before those of round `k + 1`.
fn in_rounds<R: Real>(singles: &[(usize, Train<R>)], rings: &[(usize, Train<R>)]) -> bool {
    let (Some(first), Some(last)) = (rings.first(), rings.last()) else {
        return true;
    };
    let period = first.1.period;
    let end = rings
        .iter()
        .map(|t| t.1.start + R::of(t.1.count as f64) * period)
        .fold(R::zero(), |m, x| if x > m { x } else { m });
    let rounding = R::of(8.0 * f64::EPSILON) * (end.abs() + period);
    singles.last().is_none_or(|s| s.1.start <= first.1.start)
        && rings.iter().all(|t| t.1.period == period)
        && last.1.start - first.1.start + rounding < period
}

impl<R: Real> Tracer<R> {
    /// Tries to leap layer `i` from now over its quiet window; the number
    /// of boundary events it stood for, or `None` when the layer is not
    /// quiet long enough (or the run is exact).
    pub(crate) fn leap(&mut self, i: usize) -> Result<Option<u64>, WaveError> {
        let n = self.layers.len();
        if !self.leaps || self.record.fronts || n < 2 {
            return Ok(None);
        }
        let up = Lane::<R>::index(i, Direction::Up);
        let t = self.now;
        // A folded top lane is not leapt: leaping it was found to gain
        // energy (e = 1.33 on a four-layer rod with a fast top,
        // `tests/finishes.rs`). A merged run does not fold a fast top (see
        // `Tracer::new`): it leaps as any layer, its free end reflecting.
        if self.lanes[up].folded || t < self.leap_after[i] {
            return Ok(None);
        }
        let has_above = i + 1 < n;
        let ti = self.lanes[up].transit;
        let period = ti + ti;
        let least = R::of(LEAST_TRANSITS) * ti;
        // the quiet window: until something arrives from outside, or the
        // run's own stops; what the leap itself sends into a neighbour
        // comes back after the neighbour's round trip at the earliest (a
        // layer that round trip alone keeps from leaping never tries, see
        // `first_leaps`)
        let mut horizon = self.max_time;
        let mut bound = |a: Option<R>| {
            if let Some(a) = a {
                horizon = horizon.min(a);
            }
        };
        if i > 0 {
            let below = self.lanes[Lane::<R>::index(i - 1, Direction::Up)].transit;
            bound(Some(t + below + below));
        }
        if has_above {
            let above = self.lanes[Lane::<R>::index(i + 1, Direction::Up)].transit;
            bound(Some(t + above + above));
        }
        // (the bottom's own landing is found in closed form below)
        if let Some(outside) = self.first_from_outside(i) {
            if outside - t < least {
                // no leap before that arrival: fronts born from now on
                // reach the layer no earlier than the self-sent bound
                self.leap_after[i] = outside;
                return Ok(None);
            }
            bound(Some(outside));
        }
        for key in [EventKey::Escape, EventKey::Horizon] {
            bound(self.queue.time_of(key));
        }
        if horizon - t < least {
            return Ok(None);
        }
        let ends = self.ends(i);
        let mut phases = self.phases(i, ti, ends);
        if phases.is_empty() {
            return Ok(None);
        }
        phases.sort_by(|a, b| a.tau.partial_cmp(&b.tau).unwrap_or(Ordering::Equal));
        let q = ends.bottom * ends.top;
        if i == 0 {
            self.advance_wall(t);
            horizon = horizon.min(self.wall_stop(&phases, q, period, horizon));
            if horizon - t < least {
                // a decision is near: no leap until the loop has taken it,
                // and no try before the loop has done as many events as
                // this one cost (a try is a pass over the phases and
                // follows every decision; an exact run's chattering base
                // holds thousands of phases, and tries took nine tenths of
                // its time: aluminium under silicone, 47 ms -> 0.44 s)
                self.leap_after[i] = horizon;
                self.leap_retry[i] = self.events + phases.len() as u64;
                return Ok(None);
            }
        }
        let thr = self.layers[i].drop_strain();
        let mut events = 0u64;
        let mut fronts: (Vec<Front<R>>, Vec<Front<R>>) = (Vec::new(), Vec::new());
        let mut bottom_arrivals: Vec<(R, R, u64)> = Vec::new();
        let (mut up_sum, mut down_sum) = (R::zero(), R::zero());
        for p in &phases {
            // the pending arrival at the top of a front going up
            if let Some((u, d)) = p.top {
                if u >= horizon {
                    fronts.0.push(self.front(u - ti, d));
                    continue;
                }
                events += 1;
                if let Some((lane, c)) = ends.above {
                    self.emit(
                        lane,
                        Train {
                            start: u,
                            period,
                            c: c * d,
                            q: R::zero(),
                            count: 1,
                        },
                    )?;
                }
                if p.amp.abs() < thr {
                    self.drop_front(i, u, p.amp);
                    continue;
                }
                down_sum += p.amp;
            }
            // round trips: bottom arrivals k < nb, top arrivals k < nt
            let life_down = self.life(p.amp, q, thr, 1);
            let life_up = self.life(ends.bottom * p.amp, q, thr, 0);
            let nb = count_before(p.tau, period, horizon)
                .min(life_down)
                .min(life_up + 1);
            if nb == 0 {
                fronts.1.push(self.front(p.tau - ti, p.amp));
                continue;
            }
            let nt = count_before(p.tau + ti, period, horizon)
                .min(nb)
                .min(life_up);
            events += nb + nt;
            bottom_arrivals.push((p.tau, p.amp, nb));
            let (s0_t, _, _) = self.sums_cached(q, nt);
            up_sum += ends.bottom * p.amp * self.sums_cached(q, nb.min(life_up)).0;
            down_sum += p.amp * q * s0_t;
            if let Some((lane, c)) = ends.below {
                self.emit(
                    lane,
                    Train {
                        start: p.tau,
                        period,
                        c: c * p.amp,
                        q,
                        count: nb,
                    },
                )?;
            }
            if let Some((lane, c)) = ends.above {
                self.emit(
                    lane,
                    Train {
                        start: p.tau + ti,
                        period,
                        c: c * ends.bottom * p.amp,
                        q,
                        count: nt,
                    },
                )?;
            }
            // where the front is when the leap ends
            let last = p.tau + R::of((nb - 1) as f64) * period;
            let arriving = p.amp * pow(q, nb - 1);
            let going_up = ends.bottom * arriving;
            if nt == nb {
                let back = q * arriving;
                if back.abs() < thr {
                    self.drop_front(i, last + ti, back);
                } else {
                    fronts.1.push(self.front(last + ti, back));
                }
            } else if going_up.abs() < thr {
                self.drop_front(i, last, going_up);
            } else {
                fronts.0.push(self.front(last, going_up));
            }
        }
        if i == 0 {
            self.wall_after(&bottom_arrivals, q, period);
            self.schedule_landing()?;
        }
        self.leap_work += phases.len() as u64;
        self.up_base[i] += up_sum;
        self.down_base[i] += down_sum;
        self.place_deposits()?;
        self.place_exact_trains()?;
        self.rebuild(i, fronts)?;
        self.leaped += events;
        Ok(Some(events))
    }

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
    fn first_from_outside(&self, i: usize) -> Option<R> {
        let transit = |m: usize| self.lanes[Lane::<R>::index(m, Direction::Up)].transit;
        let mut earliest: Option<R> = None;
        for lane in &self.lanes {
            let j = lane.layer;
            let Some(head) = lane.head_arrival().filter(|_| j != i) else {
                continue;
            };
            // a folded top lane's arrivals are already its returns
            let towards = lane.folded || (lane.direction == Direction::Up) == (j < i);
            let between = if j < i { j + 1..i } else { i + 1..j };
            let mut at = between.fold(head, |at, m| at + transit(m));
            if !towards {
                at += transit(j);
            }
            earliest = Some(earliest.map_or(at, |e| if at < e { at } else { e }));
        }
        // a landing bottom starts a front at the wall (its other fronts
        // reach the wall as a lane's fronts going down, counted above)
        if i > 0
            && let Some(land) = self.queue.time_of(EventKey::Reconnection)
        {
            let at = (0..i).fold(land, |at, m| at + transit(m));
            earliest = Some(earliest.map_or(at, |e| if at < e { at } else { e }));
        }
        earliest
    }

    /// Geometric sums, remembered within a leap: the fronts of a quiet
    /// layer mostly return the same number of times.
    fn sums_cached(&mut self, q: R, n: u64) -> (R, R, R) {
        if let Some(&(_, _, s)) = self.sums_memo.iter().find(|m| m.0 == q && m.1 == n) {
            return s;
        }
        let s = sums(q, n);
        if self.sums_memo.len() >= 8 {
            self.sums_memo.remove(0);
        }
        self.sums_memo.push((q, n, s));
        s
    }

    /// The reflections and transmissions at the ends of layer `i`.
    fn ends(&self, i: usize) -> Ends<R> {
        let n = self.layers.len();
        let (bottom, below) = if i == 0 {
            let sign = match self.contact {
                ContactState::InContact { .. } => R::one(),
                ContactState::Free { .. } => -R::one(),
            };
            (sign, None)
        } else {
            let k = self.interfaces[i - 1];
            (
                k.down_reflected,
                Some((Lane::<R>::index(i - 1, Direction::Down), k.down_transmitted)),
            )
        };
        let (top, above) = if i == n - 1 {
            (-R::one(), None)
        } else {
            let k = self.interfaces[i];
            (
                k.up_reflected,
                Some((Lane::<R>::index(i + 1, Direction::Up), k.up_transmitted)),
            )
        };
        Ends {
            bottom,
            below,
            top,
            above,
        }
    }

    /// The fronts of layer `i` as phases.
    fn phases(&self, i: usize, ti: R, ends: Ends<R>) -> Vec<Phase<R>> {
        // (a folded lane is never leapt)
        let up = &self.lanes[Lane::<R>::index(i, Direction::Up)];
        let down = &self.lanes[Lane::<R>::index(i, Direction::Down)];
        down.fronts()
            .iter()
            .map(|f| Phase {
                tau: f.born + ti,
                amp: f.jump,
                top: None,
            })
            .chain(up.fronts().iter().map(|f| {
                let u = f.born + ti;
                Phase {
                    tau: u + ti,
                    amp: ends.top * f.jump,
                    top: Some((u, f.jump)),
                }
            }))
            .collect()
    }

    /// A front for a rebuilt lane.
    fn front(&self, born: R, jump: R) -> Front<R> {
        Front {
            born,
            jump,
            id: 0,
            kept: false,
        }
    }

    /// How many round trips a front of jump `a` lives (counted from `from`)
    /// before it falls under the drop threshold `thr`.
    fn life(&self, a: R, q: R, thr: R, from: u64) -> u64 {
        if a.abs() < thr && from == 0 {
            return 0;
        }
        let aq = q.abs();
        if aq == R::zero() {
            return from.max(1);
        }
        if aq >= R::one() {
            return u64::MAX;
        }
        let k = ((thr / a.abs()).ln() / aq.ln()).to_f64();
        if !k.is_finite() || k < 0.0 {
            return from.max(if a.abs() >= thr { 1 } else { 0 });
        }
        // the first integer above k, unless k is so near an integer that
        // the logarithms' rounding could decide: then count with powers
        // (the common case needs none; they were half of a leap's time)
        if (k - k.round()).abs() > 1e-9 * k.max(1.0) {
            return (k.floor() as u64 + 1).max(from);
        }
        let mut k = k.floor().max(0.0) as u64;
        // the first k with |a| |q|^k < thr
        while k > 0 && a.abs() * pow(aq, k - 1) < thr {
            k -= 1;
        }
        while a.abs() * pow(aq, k) >= thr {
            k += 1;
        }
        k.max(from)
    }

    /// The earliest time the wall could decide something: in contact, the
    /// first return making the wall strain grazing or tensile; in flight,
    /// the earliest the bottom could come down, from its lowest velocity.
    fn wall_stop(&self, phases: &[Phase<R>], q: R, period: R, horizon: R) -> R {
        let two = R::of(2.0);
        let one = R::one();
        let total: R = phases.iter().fold(R::zero(), |s, p| s + p.amp);
        match self.contact {
            ContactState::InContact { strain } => {
                // S(p, k) = S0 + 2 (G sum_{j<k} q^j + L_p q^k) = C0 + C_p q^k
                let limit = total / (one - q);
                let c0 = strain + two * limit;
                let mut prefix = R::zero();
                let mut stop = horizon;
                // an exact run's loop takes the near-grazing decisions
                let threshold = if self.merged {
                    self.grazing_strain
                } else {
                    let scale = self.impact_speed / self.layers[0].wave_speed;
                    self.grazing_strain.max(R::of(NEAR_GRAZING) * scale)
                };
                // The first two returns of every phase by hand, as
                // `first_crossing` evaluates them (`C0 + C_p q^k`): in a
                // chatter the next decision comes within them, and a try
                // that fails there then costs no logarithm (an exact run's
                // ringing layer holds thousands of phases, and a try
                // follows every decision). The phases lie within one
                // period, so an earlier round holds the earlier crossing.
                for (k, qk) in [(0u64, one), (1, q)] {
                    let mut first = None;
                    let mut prefix = R::zero();
                    for p in phases {
                        prefix += p.amp;
                        if c0 + two * (prefix - limit) * qk >= -threshold
                            && count_before(p.tau, period, horizon) > k
                        {
                            let at = p.tau + R::of(k as f64) * period;
                            first = Some(first.map_or(at, |f: R| f.min(at)));
                        }
                    }
                    if let Some(at) = first {
                        return stop.min(at);
                    }
                }
                for p in phases {
                    prefix += p.amp;
                    let kmax = count_before(p.tau, period, horizon);
                    if let Some(k) = first_crossing(c0, two * (prefix - limit), q, kmax, -threshold)
                    {
                        stop = stop.min(p.tau + R::of(k as f64) * period);
                    }
                }
                stop
            }
            ContactState::Free {
                height,
                velocity,
                at,
            } => {
                // the height just before the k-th return of p is
                // f0_p + beta k + gamma_p (q^k - 1): its first zero is where
                // the bottom has landed (DESIGN: the loop then lands it)
                let c0 = self.layers[0].wave_speed;
                let gap = one - q;
                let moment: R = phases.iter().fold(R::zero(), |s, p| s + p.amp * p.tau);
                let beta = period * (velocity + two * c0 * total / gap);
                let mut stop = horizon;
                let mut prefix = R::zero();
                let mut before = R::zero(); // sum_{p' < p} a_p' (tau_p - tau_p') as it grows
                let mut last_tau = phases[0].tau;
                // (tau_p, f0_p, gamma_p)
                let mut heights = Vec::with_capacity(phases.len());
                for p in phases {
                    before += prefix * (p.tau - last_tau);
                    last_tau = p.tau;
                    let f0 = height + velocity * (p.tau - at) + two * c0 * before;
                    let m = total * p.tau - moment;
                    let gamma = two * c0 * (before - m / gap + period * total * q / (gap * gap));
                    heights.push((p.tau, f0, gamma));
                    prefix += p.amp;
                }
                // the first two returns by hand, as `first_nonpositive`
                // evaluates them (see the contact's case above)
                let ln_q = (q >= R::zero()).then(|| q.ln());
                for k in 0..2u64 {
                    let mut first = None;
                    for &(tau, f0, gamma) in &heights {
                        let f = match (k, ln_q) {
                            (0, _) => f0,
                            (_, Some(ln_q)) => f0 + beta * one + gamma * (ln_q * one).exp_m1(),
                            (_, None) => f0 + beta + gamma * (q - one),
                        };
                        if f <= R::zero() && count_before(tau, period, horizon) > k {
                            let at = tau + R::of(k as f64) * period;
                            first = Some(first.map_or(at, |f: R| f.min(at)));
                        }
                    }
                    if let Some(at) = first {
                        return stop.min(at);
                    }
                }
                for (tau, f0, gamma) in heights {
                    let kmax = count_before(tau, period, stop);
                    if kmax > 0
                        && let Some(k) = first_nonpositive(f0, beta, gamma, q, kmax)
                    {
                        stop = stop.min(tau + R::of(k as f64) * period);
                    }
                }
                stop
            }
        }
    }

    /// The wall after the bottom arrivals `(tau, a, n)`: `a q^k` at
    /// `tau + k P`, `k < n`, in contact or in flight throughout.
    fn wall_after(&mut self, arrivals: &[(R, R, u64)], q: R, period: R) {
        if arrivals.is_empty() {
            return;
        }
        let two = R::of(2.0);
        let half = R::of(0.5);
        let t0 = self.ledger.at;
        let end = arrivals.iter().fold(t0, |m, &(tau, _, n)| {
            m.max(tau + R::of((n - 1) as f64) * period)
        });
        // sum A, sum A (T - t), sum A (T - t)^2 over the arrivals
        let (mut a0, mut a1, mut a2) = (R::zero(), R::zero(), R::zero());
        for &(tau, a, n) in arrivals {
            let (s0, s1, s2) = self.sums_cached(q, n);
            let d = end - tau;
            a0 += a * s0;
            a1 += a * (d * s0 - period * s1);
            a2 += a * (d * d * s0 - two * d * period * s1 + period * period * s2);
        }
        let dt = end - t0;
        let c0 = self.layers[0].wave_speed;
        let impulse = self.ledger.impulse;
        match &mut self.contact {
            ContactState::InContact { strain } => {
                self.ledger.moment += impulse * dt + half * *strain * dt * dt + a2;
                self.ledger.impulse += *strain * dt + two * a1;
                *strain += two * a0;
            }
            ContactState::Free {
                height,
                velocity,
                at,
            } => {
                self.ledger.moment += impulse * dt;
                *height += *velocity * (end - *at) + two * c0 * a1;
                *velocity += two * c0 * a0;
                *at = end;
            }
        }
        self.ledger.at = end;
        let count: u64 = arrivals.iter().map(|a| a.2).sum();
        self.note_decisions(count);
        self.record_wall();
    }

    /// Deposits a train of fronts into `lane` as its merge rule would, one
    /// by one: the large ones kept (while the lane keeps any), the rest on
    /// its lattice with their jump and first moment, the tail under the
    /// drop threshold dropped and accounted for.
    fn emit(&mut self, lane: usize, train: Train<R>) -> Result<(), WaveError> {
        if train.count == 0 || train.c == R::zero() {
            return Ok(());
        }
        let mut deposits = std::mem::take(&mut self.deposits);
        let layer = self.lanes[lane].layer;
        let dir = self.lanes[lane].direction;
        let thr = self.layers[layer].drop_strain();
        let born = |k: u64| train.start + R::of(k as f64) * train.period;
        let amp = |k: u64| train.c * pow(train.q, k);
        // alive while above the drop threshold
        let alive = if train.q == R::zero() {
            u64::from(train.c.abs() >= thr).min(train.count)
        } else {
            self.life(train.c, train.q, thr, 0).min(train.count)
        };
        if alive < train.count {
            // the tail under the threshold, dropped as the loop would drop
            // it one by one: counted, and its force accounted in closed form
            let tail = train.count - alive;
            let aq = train.q.abs();
            let first = amp(alive).abs();
            let (s0, s1, _) = sums(aq, tail);
            let l = self.layers[layer];
            let d = &mut self.drops;
            d.truncation.dropped_fronts += tail;
            d.truncation.dropped_velocity +=
                (first * s0 * l.wave_speed / self.impact_speed).to_f64();
            let force = (l.modulus * first * s0).to_f64();
            d.dropped_force += force;
            d.dropped_force_time +=
                (l.modulus * first * (born(alive) * s0 + train.period * s1)).to_f64();
        }
        let MergeRule::Lattice {
            spacing,
            keep_above,
            keep_at_most,
        } = self.lanes[lane].rule
        else {
            self.deposits = deposits;
            self.exact_trains.push((
                lane,
                Train {
                    count: alive,
                    ..train
                },
            ));
            return Ok(());
        };
        let mut k = 0;
        while k < alive && amp(k).abs() >= keep_above && self.lanes[lane].kept < keep_at_most {
            self.spawn_front(layer, dir, born(k), amp(k))?;
            k += 1;
        }
        let mut total = R::zero();
        let mut merged = 0u64;
        // full cells hold one or two counts of fronts: their sums repeat;
        // the amplitude at a cell's first front follows by q^len
        let mut first = amp(k);
        while k < alive {
            // the fronts born in one lattice cell [j w, (j + 1) w)
            let j = (born(k) / spacing).floor();
            let (lo, hi) = (j * spacing, (j + R::one()) * spacing);
            let end = (k + count_before(born(k), train.period, hi))
                .min(alive)
                .max(k + 1);
            let len = end - k;
            self.leap_work += 1;
            let (s0, s1, _) = self.sums_cached(train.q, len);
            let step = self.sums_cached(train.q, len + 1).0 - s0; // q^len
            let jump = first * s0;
            let moment = first * (born(k) * s0 + train.period * s1);
            let at_hi = (moment - jump * lo) / spacing;
            for (at, d) in [(lo, jump - at_hi), (hi, at_hi)] {
                if d != R::zero() {
                    deposits.push((lane, at, d));
                }
            }
            total += jump;
            merged += len;
            k = end;
            first = first * step;
        }
        match dir {
            Direction::Up => self.up_base[layer] += total,
            Direction::Down => self.down_base[layer] += total,
        }
        self.drops.truncation.merged_fronts += merged;
        self.deposits = deposits;
        Ok(())
    }

    /// Places the deposits gathered by `emit` into their lanes, one pass a
    /// lane, and puts the lanes' heads in the queue.
    fn place_deposits(&mut self) -> Result<(), WaveError> {
        let all = std::mem::take(&mut self.deposits);
        // lane by lane in increasing order, each lane's deposits in the
        // order they were gathered (a leap feeds two lanes at most)
        let mut lanes: Vec<usize> = Vec::with_capacity(2);
        for &(lane, _, _) in &all {
            if !lanes.contains(&lane) {
                lanes.push(lane);
            }
        }
        lanes.sort_unstable();
        let mut batch = Vec::with_capacity(all.len());
        for lane in lanes {
            batch.clear();
            batch.extend(all.iter().filter(|d| d.0 == lane).map(|d| (d.1, d.2)));
            self.lanes[lane].place_all(&mut batch);
            self.reschedule_layer(self.lanes[lane].layer)?;
        }
        self.deposits = all;
        self.deposits.clear();
        Ok(())
    }

    /// Spawns the fronts of the trains an exact leap sent into its
    /// neighbours, lane by lane in birth order, as [`Tracer::spawn_front`]
    /// would one by one (under the drop threshold dropped, born together
    /// merged): first the single fronts (from fronts that were going up
    /// as the leap began), then the ringing trains round by round. That is
    /// birth order when their starts lie within one period, as a leap's
    /// do; otherwise (rounding at the edge) the births are sorted first.
    fn place_exact_trains(&mut self) -> Result<(), WaveError> {
        if self.exact_trains.is_empty() {
            return Ok(());
        }
        let mut trains = std::mem::take(&mut self.exact_trains);
        trains.sort_by(|a, b| {
            (a.0, a.1.count > 1)
                .cmp(&(b.0, b.1.count > 1))
                .then(a.1.start.partial_cmp(&b.1.start).unwrap_or(Ordering::Equal))
        });
        let mut rest = &trains[..];
        while let Some(&(lane, _)) = rest.first() {
            let len = rest.iter().take_while(|t| t.0 == lane).count();
            let (group, next) = rest.split_at(len);
            rest = next;
            let singles = group.partition_point(|t| t.1.count <= 1);
            let (singles, rings) = group.split_at(singles);
            let births = singles.len() as u64 + rings.iter().map(|t| t.1.count).sum::<u64>();
            self.leap_work += births;
            let layer = self.lanes[lane].layer;
            let MergeRule::Simultaneous { window } = self.lanes[lane].rule else {
                unreachable!("a merged run's leaps deposit on lattices")
            };
            let mut into = Into {
                lane: &mut self.lanes[lane],
                window,
                thr: self.layers[layer].drop_strain,
                id: self.next_id,
                total: R::zero(),
                dropped: Vec::new(),
                merges: Vec::new(),
            };
            into.lane.reserve(births as usize);
            if in_rounds(singles, rings) {
                for t in singles {
                    into.put(t.1.start, t.1.c);
                }
                rounds(rings, |born, jump| into.put(born, jump));
            } else {
                let mut all: Vec<(R, R)> = singles.iter().map(|t| (t.1.start, t.1.c)).collect();
                rounds(rings, |born, jump| all.push((born, jump)));
                all.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(Ordering::Equal));
                for (born, jump) in all {
                    into.put(born, jump);
                }
            }
            let Into {
                id,
                total,
                dropped,
                merges,
                ..
            } = into;
            self.next_id = id;
            match self.lanes[lane].direction {
                Direction::Up => self.up_base[layer] += total,
                Direction::Down => self.down_base[layer] += total,
            }
            for (born, jump) in dropped {
                self.drop_front(layer, born, jump);
            }
            for (gap, at) in merges {
                self.note_combined(gap, at);
            }
            self.reschedule_layer(layer)?;
        }
        trains.clear();
        self.exact_trains = trains;
        Ok(())
    }

    /// Replaces layer `i`'s fronts after a leap: `(up, down)` fronts.
    fn rebuild(
        &mut self,
        i: usize,
        (mut up, mut down): (Vec<Front<R>>, Vec<Front<R>>),
    ) -> Result<(), WaveError> {
        let by_birth =
            |a: &Front<R>, b: &Front<R>| a.born.partial_cmp(&b.born).unwrap_or(Ordering::Equal);
        up.sort_by(by_birth);
        down.sort_by(by_birth);
        let ui = Lane::<R>::index(i, Direction::Up);
        let di = Lane::<R>::index(i, Direction::Down);
        for (index, fronts) in [(ui, up), (di, down)] {
            self.lanes[index].set_fronts(fronts);
            self.reschedule_layer(i)?;
        }
        if self.lanes[ui].folded {
            // a folded top has no down lane: its fronts all went up
            debug_assert!(self.lanes[di].fronts().is_empty());
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {

    /// The height just before each return, by brute force, against the
    /// closed form used to find the landing.
    #[test]
    fn the_height_closed_form_matches_a_brute_force_flight() {
        let (height, velocity, at) = (0.3, -0.05, 0.0);
        let c0 = 1.7;
        let period = 0.2;
        let q: f64 = 0.93;
        let phases = [(0.01, 0.02), (0.05, -0.01), (0.12, 0.005), (0.17, -0.03)];
        let total: f64 = phases.iter().map(|p| p.1).sum();
        let moment: f64 = phases.iter().map(|p| p.1 * p.0).sum();
        let gap = 1.0 - q;
        let beta = period * (velocity + 2.0 * c0 * total / gap);
        // brute force: arrivals in time order
        let mut arrivals = vec![];
        for k in 0..40u64 {
            for &(tau, a) in &phases {
                arrivals.push((tau + k as f64 * period, a * q.powi(k as i32), k));
            }
        }
        arrivals.sort_by(|x, y| x.0.total_cmp(&y.0));
        let (mut z, mut v, mut t) = (height, velocity, at);
        let mut prefix = 0.0;
        let mut before = 0.0;
        let mut last_tau = phases[0].0;
        let mut expected = vec![];
        for (i, &(tau, a)) in phases.iter().enumerate() {
            before += prefix * (tau - last_tau);
            last_tau = tau;
            let f0 = height + velocity * (tau - at) + 2.0 * c0 * before;
            let m = total * tau - moment;
            let gamma = 2.0 * c0 * (before - m / gap + period * total * q / (gap * gap));
            expected.push((i, f0, gamma));
            prefix += a;
        }
        for (time, amp, k) in arrivals {
            z += v * (time - t);
            t = time;
            let p = phases
                .iter()
                .position(|ph| (ph.0 + k as f64 * period - time).abs() < 1e-12)
                .unwrap();
            let (_, f0, gamma) = expected[p];
            let closed = f0 + beta * k as f64 + gamma * (q.powi(k as i32) - 1.0);
            assert!(
                (closed - z).abs() < 1e-9,
                "p = {p}, k = {k}: {closed} vs {z}"
            );
            v += 2.0 * c0 * amp;
        }
    }
}

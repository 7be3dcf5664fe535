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
//! could land. The event loop then takes the decision itself. A leap of
//! the bottom that takes its neighbour's arrivals finds them the same way,
//! with the most those could move the wall taken off (`arrivals.rs`).
//!
//! A merged run's neighbours take the deposits on their lattices in bulk;
//! an exact run's take every front, spawned in birth order when the leap
//! ends (a leap's trains interleave). An exact leap leaves to the loop any
//! return whose contact decision comes within `NEAR_GRAZING` of going the
//! other way, so the loop still counts them (they decide the double-double
//! repeat). What it changes is rounding only: a front's jump after `k`
//! round trips is `a q^k` instead of `k` products, its birth `tau + k P`
//! instead of `2 k` sums, and the wall impulse a geometric sum.

use crate::config::LeapArrivals;
use crate::engine::{LayerConst, Tracer};
use crate::error::WaveError;
use crate::geometric::sums;
use crate::lane::{Direction, Front, Lane};
use crate::queue::EventKey;
use crate::real::Real;
use crate::runs::sort_stably;
use crate::wall::ContactState;

mod arrivals;
mod crossing;
mod exact;
mod life;
mod reach;
mod scratch;
mod together;
mod trains;
mod wall;

use arrivals::Taken;
use crossing::count_before_near;
pub(crate) use exact::ExactTrains;
pub(crate) use scratch::LeapScratch;
pub(crate) use scratch::TogetherRoom;

/// A layer leaps only where its neighbours' round trips are at least this
/// many of its transits (what a leap sends them would come back too
/// soon), and a top this much faster than the layer under it is not
/// folded in a merged run (see `Tracer::new`).
pub(crate) const LEAST_TRANSITS: f64 = 8.0;

/// An exact run's leaps shorter than this many transits of the layer are
/// not worth it. A leap costs a few loop events a front (its phases, what
/// it sends out, the rebuilt lanes), the loop two a front a round trip. A
/// chattering stiff base is in contact for two round trips at a time: at
/// eight transits no contact was leapt and the loop took them front by
/// front, 80 % of the 20 hardest points' loop events (at one transit the
/// tries cost more than they save; two and three were the best,
/// callgrind). A merged run's leaps keep [`LEAST_TRANSITS`]: its leaps
/// deposit on lattices, and leaping more often moved merged results
/// within their bounds (layer survey rod 12: `e` by 1e-3, 14 s -> 26 s).
pub(crate) const SHORTEST_LEAP: f64 = 2.0;

/// Geometric sums a tracer remembers, in slots by their number of terms.
/// A merged run's leap that takes in its neighbours' arrivals counts its
/// phases' returns over a dozen different numbers, phase after phase in
/// the same order: the eight sums kept first in first out before missed
/// every one of them (survey rod 26: 1.9 million sums, 4 % of its
/// instructions).
const SUMS_REMEMBERED: usize = 64;

/// When each layer may first try to leap: never (infinity) where a
/// neighbour's round trip is under [`LEAST_TRANSITS`] of the layer's own
/// transits (what a leap sends it would come back too soon) or the layer is
/// a folded top; else from the start. Without this every boundary event of
/// such a layer tried, at a tenth of a small point's time.
pub(crate) fn first_leaps<R: Real>(layers: &[LayerConst<R>], folded_top: bool) -> Vec<R> {
    let n = layers.len();
    let transits = |i: usize| layers[i].transit_time;
    (0..n)
        .map(|i| {
            let least = R::of(LEAST_TRANSITS) * transits(i);
            let neighbours = [i.checked_sub(1), (i + 1 < n).then_some(i + 1)];
            let too_soon = neighbours
                .into_iter()
                .flatten()
                .any(|j| transits(j) + transits(j) < least);
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

/// A leap's quiet window and the layer's times.
#[derive(Debug, Clone, Copy)]
struct Quiet<R> {
    /// Now, the layer's transit and round trip, the shortest leap worth
    /// taking, and the end of the window.
    t: R,
    ti: R,
    period: R,
    least: R,
    horizon: R,
    /// The end of the window without the neighbours' arrivals.
    alone: R,
    /// Whether the leap takes in its neighbours' arrivals.
    taking: bool,
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
        let least = if self.merged {
            R::of(LEAST_TRANSITS) * ti
        } else {
            R::of(SHORTEST_LEAP) * ti
        };
        if i == 0 && !self.merged && self.wall_decides_now(t, least) {
            return Ok(None);
        }
        // the quiet window: until something arrives from outside, or the
        // run's own stops; what the leap itself sends into a neighbour
        // comes back after the neighbour's round trip at the earliest (a
        // layer that round trip alone keeps from leaping never tries, see
        // `first_leaps`)
        let mut horizon = self.max_time;
        if i > 0 {
            let below = self.lanes[Lane::<R>::index(i - 1, Direction::Up)].transit;
            horizon = horizon.min(t + below + below);
        }
        if has_above {
            let above = self.lanes[Lane::<R>::index(i + 1, Direction::Up)].transit;
            horizon = horizon.min(t + above + above);
        }
        // (the bottom's own landing is found in closed form below). A
        // merged run's leap may take in what its neighbours' lanes send
        // the layer (`arrivals.rs`), where the longer window pays for it.
        // Worth weighing only where it at least doubles the window: the
        // weighing costs a pass over two lanes, and a layer in a block of
        // fast layers tries at nearly every event of its own (weighing at
        // each made survey rod 20 15 % slower).
        let takes = self.takes_arrivals() && (i > 0 || self.events >= self.bottom_weighs_after);
        let (mut outside, taken) = self.first_from_outside(i, takes);
        let end = |o: Option<R>| o.map_or(horizon, |o| if o < horizon { o } else { horizon });
        let (window, longer) = (end(outside) - t, end(taken) - t);
        let taking = takes
            && longer >= least
            && (self.leap_arrivals == LeapArrivals::Always
                || longer > window + window && self.worth_taking(i, longer));
        if i == 0 && takes && !taking && longer >= least {
            // the bottom tries at every event of its own, and weighing each
            // time was a fifth of a run with a fast bottom (survey seed 3's
            // rod 36, against a tenth): no weighing again for a round trip
            // of its fronts (holding off the tries instead stopped leaps
            // without arrivals: seed 3's rod 39, 376 k loop events at the
            // bottom -> 490 k)
            let own = self.lanes[up].len() + self.lanes[Lane::<R>::index(0, Direction::Down)].len();
            self.bottom_weighs_after = self.events + own as u64;
        }
        // the window without the arrivals: a bottom's leap falls back on
        // it where what they could do at the wall is too near a decision
        let mut alone = end(outside);
        if taking {
            outside = taken;
        }
        if let Some(outside) = outside {
            if outside - t < least {
                // no leap before that arrival: fronts born from now on
                // reach the layer no earlier than the self-sent bound
                self.leap_after[i] = outside;
                return Ok(None);
            }
            horizon = horizon.min(outside);
        }
        // (after the arrivals: most tries end there, and a key's time is a
        // lookup in the queue's map)
        for key in [EventKey::Escape, EventKey::Horizon] {
            if let Some(at) = self.queue.time_of(key) {
                horizon = horizon.min(at);
                alone = alone.min(at);
            }
        }
        if horizon - t < least {
            return Ok(None);
        }
        let ends = self.ends(i);
        // the leap's buffers are kept from one leap to the next (allocating
        // them afresh was a tenth of a short leap's work)
        let mut scratch = std::mem::take(&mut self.scratch);
        let quiet = Quiet {
            t,
            ti,
            period,
            least,
            horizon,
            alone,
            taking,
        };
        let leapt = self.leap_over(i, quiet, ends, &mut scratch);
        self.scratch = scratch;
        leapt
    }

    /// The leap itself, over the quiet window found by [`Tracer::leap`].
    fn leap_over(
        &mut self,
        i: usize,
        quiet: Quiet<R>,
        ends: Ends<R>,
        scratch: &mut LeapScratch<R>,
    ) -> Result<Option<u64>, WaveError> {
        let Quiet {
            t,
            ti,
            period,
            least,
            mut horizon,
            alone,
            mut taking,
        } = quiet;
        let LeapScratch {
            phases,
            up: fronts_up,
            down: fronts_down,
            bottom_arrivals,
            ringing,
            phases_run,
            fronts_run,
        } = scratch;
        self.phases(i, ti, ends, phases);
        if phases.is_empty() && !taking {
            return Ok(None);
        }
        let q = ends.bottom * ends.top;
        if i == 0 {
            // the wall's next decision, found over the bottom's own fronts
            // (`wall.rs`) and what the arrivals it would take could add
            sort_stably(phases, phases_run, |p| p.tau);
            self.advance_wall(t);
            let mut stop = horizon;
            if taking {
                let limit = match self.contact {
                    ContactState::InContact { strain } => -strain - self.leap_threshold(),
                    ContactState::Free { height, .. } => height,
                };
                let (slack, scanned) = self.arrivals_slack(horizon, ti, q, limit);
                if slack < limit {
                    stop = self.wall_stop(phases, q, period, horizon, slack);
                }
                // (a leap without them goes at least as far where the
                // bound stops this one before the first arrival beyond it)
                if slack >= limit || stop - t < least || stop <= alone {
                    // no weighing again before the loop has done as many
                    // events as this try cost
                    (taking, horizon) = (false, alone);
                    self.bottom_weighs_after = self.events + (phases.len() + scanned) as u64;
                    if alone - t < least {
                        self.leap_after[i] = alone;
                        return Ok(None);
                    }
                }
            }
            if !taking {
                if phases.is_empty() {
                    return Ok(None);
                }
                stop = self.wall_stop(phases, q, period, horizon, R::zero());
            }
            horizon = horizon.min(stop);
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
        let taken = if taking {
            self.take_arrivals(i, horizon, ti, ends, phases)?
        } else {
            Taken::default()
        };
        if phases.is_empty() && taken.events == 0 {
            return Ok(None);
        }
        sort_stably(phases, phases_run, |p| p.tau);
        let thr = self.layers[i].drop_strain();
        let mut events = taken.events;
        fronts_up.clear();
        fronts_down.clear();
        bottom_arrivals.clear();
        ringing.clear();
        let (mut up_sum, mut down_sum) = (taken.up, taken.down);
        let mut last_within = 0;
        for p in phases.iter() {
            // the pending arrival at the top of a front going up
            if let Some((u, d)) = p.top {
                if u >= horizon {
                    fronts_up.push(self.front(u - ti, d));
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
            // (phases start within a period of one another: their counts
            // differ by one at most)
            let within = count_before_near(p.tau, period, horizon, last_within);
            last_within = within;
            let life_down = self.life_within(p.amp, q, thr, 1, within);
            let life_up = self.life_within(ends.bottom * p.amp, q, thr, 0, within);
            let nb = within.min(life_down).min(life_up + 1);
            if nb == 0 {
                fronts_down.push(self.front(p.tau - ti, p.amp));
                continue;
            }
            let nt = count_before_near(p.tau + ti, period, horizon, within)
                .min(nb)
                .min(life_up);
            events += nb + nt;
            bottom_arrivals.push((p.tau, p.amp, nb));
            let (s0_t, _, _) = self.sums_cached(q, nt);
            up_sum += ends.bottom * p.amp * self.sums_cached(q, nb.min(life_up)).0;
            down_sum += p.amp * q * s0_t;
            if let Some((lane, c)) = ends.below {
                let train = Train {
                    start: p.tau,
                    period,
                    c: c * p.amp,
                    q,
                    count: nb,
                };
                self.emit_or_hold(lane, train, ringing)?;
            }
            if let Some((lane, c)) = ends.above {
                let train = Train {
                    start: p.tau + ti,
                    period,
                    c: c * ends.bottom * p.amp,
                    q,
                    count: nt,
                };
                self.emit_or_hold(lane, train, ringing)?;
            }
            // where the front is when the leap ends
            let last = p.tau + R::of((nb - 1) as f64) * period;
            let arriving = p.amp * self.pow_remembered(q, nb - 1);
            let going_up = ends.bottom * arriving;
            if nt == nb {
                let back = q * arriving;
                if back.abs() < thr {
                    self.drop_front(i, last + ti, back);
                } else {
                    fronts_down.push(self.front(last + ti, back));
                }
            } else if going_up.abs() < thr {
                self.drop_front(i, last, going_up);
            } else {
                fronts_up.push(self.front(last, going_up));
            }
        }
        if i == 0 {
            self.wall_after(bottom_arrivals, q, period);
            self.schedule_landing()?;
        }
        self.emit_held(ringing)?;
        self.leap_work += phases.len() as u64;
        self.up_base[i] += up_sum;
        self.down_base[i] += down_sum;
        self.place_deposits()?;
        self.place_exact_trains()?;
        self.rebuild(i, fronts_up, fronts_down, fronts_run)?;
        self.leaped += events;
        Ok(Some(events))
    }

    /// Geometric sums, remembered within a leap: the fronts of a quiet
    /// layer mostly return the same number of times.
    #[inline(always)]
    fn sums_cached(&mut self, q: R, n: u64) -> (R, R, R) {
        // one or two terms, as `sums` adds them (a leap over a short
        // contact returns each front once or twice; the search cost more)
        match n {
            0 => (R::zero(), R::zero(), R::zero()),
            1 => (R::one(), R::zero(), R::zero()),
            2 => (R::one() + q, q, q),
            _ => self.sums_remembered(q, n),
        }
    }

    /// [`Tracer::sums_cached`] of three terms or more, remembered in
    /// [`SUMS_REMEMBERED`] slots by the number of terms (a slot keeps the
    /// last ratio and count that fell on it).
    fn sums_remembered(&mut self, q: R, n: u64) -> (R, R, R) {
        if self.sums_memo.is_empty() {
            // (counts of zero terms are never stored: an empty slot)
            self.sums_memo =
                vec![(R::zero(), 0, (R::zero(), R::zero(), R::zero())); SUMS_REMEMBERED];
        }
        let slot = &mut self.sums_memo[(n % SUMS_REMEMBERED as u64) as usize];
        if slot.1 == n && slot.0 == q {
            return slot.2;
        }
        let s = sums(q, n);
        *slot = (q, n, s);
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
    fn phases(&self, i: usize, ti: R, ends: Ends<R>, phases: &mut Vec<Phase<R>>) {
        // (a folded lane is never leapt)
        let up = &self.lanes[Lane::<R>::index(i, Direction::Up)];
        let down = &self.lanes[Lane::<R>::index(i, Direction::Down)];
        phases.clear();
        phases.reserve(down.len() + up.len());
        // (`for_each`: the lanes' own `fold`)
        down.fronts().for_each(|f| {
            phases.push(Phase {
                tau: f.born + ti,
                amp: f.jump,
                top: None,
            });
        });
        up.fronts().for_each(|f| {
            let u = f.born + ti;
            phases.push(Phase {
                tau: u + ti,
                amp: ends.top * f.jump,
                top: Some((u, f.jump)),
            });
        });
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

    /// Replaces layer `i`'s fronts after a leap: `(up, down)` fronts.
    fn rebuild(
        &mut self,
        i: usize,
        up: &mut [Front<R>],
        down: &mut [Front<R>],
        run: &mut Vec<Front<R>>,
    ) -> Result<(), WaveError> {
        sort_stably(up, run, |f| f.born);
        sort_stably(down, run, |f| f.born);
        let ui = Lane::<R>::index(i, Direction::Up);
        let di = Lane::<R>::index(i, Direction::Down);
        let mut spare = std::mem::take(&mut self.spare_fronts);
        for (index, fronts) in [(ui, &*up), (di, &*down)] {
            self.lanes[index].set_fronts(fronts, &mut spare);
        }
        self.spare_fronts = spare;
        self.reschedule_layer(i)?;
        if self.lanes[ui].folded {
            // a folded top has no down lane: its fronts all went up
            debug_assert!(self.lanes[di].is_empty());
        }
        Ok(())
    }
}

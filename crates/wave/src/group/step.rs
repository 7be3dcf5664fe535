//! The group's steps: every front arriving before a step's end, lane by
//! lane, the wall's in the order they come.

use super::{Group, Tagged, in_lane_order};
use crate::engine::Tracer;
use crate::error::WaveError;
use crate::lane::Direction;
use crate::real::Real;
use crate::wall::ContactState;

impl<R: Real> Group<R> {
    #[inline(always)]
    fn emit(&mut self, to: Option<usize>, at: R, d: R) {
        match to {
            Some(j) => self.birth(j, at, d),
            None if d != R::zero() => self.sent.push((at, d)),
            None => {}
        }
    }

    /// Lane `i`'s fronts arriving before `end`, taken out into `into` in
    /// the order they arrive, `(time, jump)`: its lattice points', and its
    /// exact fronts' among them (`due` holds the step's). Each point's
    /// arrival is found once, in the one pass that finds where the due
    /// points end (a pass to find the end, a copy of the due points and a
    /// second pass cost 6.5 % of the instructions of layer survey seed 3's
    /// rod 23, whose time is its bottom group's steps).
    fn arrivals(&mut self, i: usize, end: R, into: &mut Vec<(R, R)>) {
        let m = i / 2;
        let (s, transit) = (self.spacing[m], self.layers[m].transit_time);
        let lane = &self.points[i];
        let first = lane.base;
        into.clear();
        let mut n = 0;
        for (j, &x) in lane.points.iter().enumerate() {
            let at = self.arrival(i, first + j as i64);
            if at >= end {
                break;
            }
            n = j + 1;
            if x != R::zero() {
                into.push((at, x));
            }
        }
        // fronts arriving together in the loop's lane order: a lattice
        // point after the exact fronts ahead of it, before the others
        // (births apart may arrive together after rounding: birth order
        // first, as the lane holds them)
        if self.due.iter().any(|e| e.lane == i) {
            let mut tagged = std::mem::take(&mut self.tagged);
            tagged.clear();
            for (j, &x) in lane.points.as_slice()[..n].iter().enumerate() {
                if x != R::zero() {
                    let born = R::of((first + j as i64) as f64) * s;
                    tagged.push(Tagged::on_point(born + transit, born, x));
                }
            }
            let exact = self.due.iter().filter(|e| e.lane == i);
            tagged.extend(exact.map(|e| Tagged::exact(e, transit)));
            in_lane_order(&mut tagged);
            into.clear();
            into.extend(tagged.iter().map(|t| (t.arrives, t.jump)));
            self.tagged = tagged;
        }
        let lane = &mut self.points[i];
        lane.points.skip(n);
        lane.base += n as i64;
        self.followed += into.len() as u64;
    }

    /// The fronts reaching boundary `b` (`1..=top`) before `end`, from
    /// below (`from_below`) and above (`from_above`, none at the top: what
    /// comes from the layer above arrives through the loop), as the loop
    /// takes them: an event at each arrival, with the other side's first
    /// arrival within the simultaneity window taken with it, and what it
    /// sends each way born at the event.
    fn boundary(&mut self, b: usize, end: R, from_below: &[(R, R)], from_above: &[(R, R)]) {
        let k = self.interfaces[b - 1];
        let down = 2 * (b - 1) + 1;
        let up = (b < self.top).then_some(2 * b);
        let (mut i, mut j) = (0, 0);
        while i < from_below.len() || j < from_above.len() {
            let t = match (from_below.get(i), from_above.get(j)) {
                (Some(x), Some(y)) => x.0.min(y.0),
                (Some(x), None) => x.0,
                (None, Some(y)) => y.0,
                (None, None) => break,
            };
            let deadline = t + self.window.at(t);
            // (past the step's end only what an event just before it takes)
            let beyond = deadline >= end;
            self.from_up = from_below.get(i).is_some_and(|x| x.0 == t);
            let below = self.side(from_below, &mut i, beyond.then_some(2 * (b - 1)), deadline);
            let above = if b < self.top {
                self.side(from_above, &mut j, beyond.then_some(2 * b + 1), deadline)
            } else if beyond {
                self.take_input(deadline)
            } else {
                R::zero()
            };
            self.emit(
                Some(down),
                t,
                k.up_reflected * below + k.down_transmitted * above,
            );
            self.emit(up, t, k.up_transmitted * below + k.down_reflected * above);
        }
    }

    /// One side's arrival at an event whose window ends at `deadline`: its
    /// next in the step's `arrivals`, or, when the step holds no more, its
    /// lane's first beyond the step (an event just before a step's end
    /// takes what the loop would take with it); zero if none is due.
    fn side(&mut self, arrivals: &[(R, R)], n: &mut usize, lane: Option<usize>, deadline: R) -> R {
        match (arrivals.get(*n), lane) {
            (Some(&(at, d)), _) if at <= deadline => {
                *n += 1;
                d
            }
            (None, Some(i)) => self.take_beyond(i, deadline).map_or(R::zero(), |a| a.1),
            _ => R::zero(),
        }
    }

    /// The loop's next front from above (`input`), if it arrives by
    /// `deadline`: taken, for the loop to let go of.
    fn take_input(&mut self, deadline: R) -> R {
        match self.input {
            Some((at, d)) if at <= deadline && !self.input_taken => {
                self.input_taken = true;
                d
            }
            _ => R::zero(),
        }
    }

    /// Lane `i`'s first front not yet taken, if it arrives by `deadline`:
    /// taken out, its arrival and jump.
    pub(crate) fn take_beyond(&mut self, i: usize, deadline: R) -> Option<(R, R)> {
        let transit = self.layers[i / 2].transit_time;
        let lane = &self.points[i];
        let point = lane
            .points
            .iter()
            .position(|&x| x != R::zero())
            .map(|j| (self.arrival(i, lane.base + j as i64), j));
        // the lane's first among its exact fronts: by arrival, then birth
        // order
        let exact = self
            .exact
            .iter()
            .enumerate()
            .filter(|(_, e)| e.lane == i)
            .min_by(|(_, a), (_, b)| {
                (a.born + transit)
                    .partial_cmp(&(b.born + transit))
                    .unwrap_or(std::cmp::Ordering::Equal)
                    .then(a.order.cmp(&b.order))
            })
            .map(|(n, e)| (e.born + transit, n, e.ahead));
        // (a lattice point before an exact front arriving with it, unless
        // that one is ahead of it in the lane)
        let lattice_first = match (point, exact) {
            (Some(p), Some(e)) => p.0 < e.0 || (p.0 == e.0 && !e.2),
            (p, _) => p.is_some(),
        };
        if lattice_first {
            let (at, j) = point?;
            if at > deadline {
                return None;
            }
            let x = &mut self.points[i].points[j];
            let d = *x;
            *x = R::zero();
            self.followed += 1;
            Some((at, d))
        } else {
            let (at, n, _) = exact?;
            if at > deadline {
                return None;
            }
            let e = self.exact.swap_remove(n);
            if e.kept {
                self.kept[i] -= 1;
            }
            self.followed += 1;
            Some((at, e.jump))
        }
    }

    /// The exact fronts arriving before `end`, taken out into `due` (a
    /// kept one no longer counts against its lane).
    fn take_due_exact(&mut self, end: R) {
        self.due.clear();
        if !self.behind_kept.is_empty() {
            let (spacing, layers) = (&self.spacing, &self.layers);
            let held = self.behind_kept.len();
            self.behind_kept.retain(|&(i, k, _)| {
                R::of(k as f64) * spacing[i / 2] + layers[i / 2].transit_time >= end
            });
            // (the mask anew only where an entry went, not at every step)
            if self.behind_kept.len() < held {
                self.remask_behind_kept();
            }
        }
        let mut n = 0;
        while n < self.exact.len() {
            let e = self.exact[n];
            if e.born + self.layers[e.lane / 2].transit_time < end {
                self.exact.swap_remove(n);
                if e.kept {
                    self.kept[e.lane] -= 1;
                }
                self.due.push(e);
            } else {
                n += 1;
            }
        }
    }
}

impl<R: Real> Tracer<R> {
    /// Follows the group's fronts arriving before `end`, step by step, and
    /// hands the loop what they did: the fronts sent up, the jumps born
    /// (the lanes' bases), the drops and the work.
    pub(crate) fn step_group(&mut self, end: R) -> Result<(), WaveError> {
        self.step_group_taking(end, None).map(|_| ())
    }

    /// [`Tracer::step_group`], with the loop's front from above that an
    /// arrival from below just before `end` may take into its event:
    /// `taken`, one the loop has already taken out of its lane (its
    /// arrival, the jump it delivers), else the lane's next. Whether it
    /// was taken.
    pub(crate) fn step_group_taking(
        &mut self,
        end: R,
        taken: Option<(R, R)>,
    ) -> Result<bool, WaveError> {
        let Some(mut g) = self.group.take() else {
            return Ok(false);
        };
        // (a folded top's one lane brings its fronts back down)
        let from_above = self.from_above[g.top];
        let mut took = false;
        while g.reached < end {
            let until = (g.reached + g.step).min(end);
            g.input = taken.filter(|_| !took).or_else(|| {
                from_above.and_then(|index| {
                    let lane = &self.lanes[index];
                    lane.fronts()
                        .next()
                        .map(|f| (lane.arrival_of(f.born), lane.delivered(f.jump)))
                })
            });
            g.input_taken = false;
            self.group_step(&mut g, until);
            g.reached = until;
            if g.input_taken {
                if taken.is_some() && !took {
                    took = true;
                } else if let Some(index) = from_above {
                    self.pop_delivered(index);
                    self.reschedule_layer(g.top)?;
                }
            }
        }
        let result = self.settle_group(&mut g);
        self.group = Some(g);
        result.map(|_| took)
    }

    /// One step, to `end`: the wall's arrivals in the order they come
    /// (its state changes at each), then each boundary's.
    fn group_step(&mut self, g: &mut Group<R>, end: R) {
        g.take_due_exact(end);
        let (mut below, mut above) = (std::mem::take(&mut g.below), std::mem::take(&mut g.above));
        g.arrivals(1, end, &mut above);
        g.from_up = false;
        for &(at, d) in &above {
            let reflected = self.group_wall(at, d);
            g.birth(0, at, reflected);
        }
        for b in 1..=g.top {
            g.arrivals(2 * (b - 1), end, &mut below);
            if b < g.top {
                g.arrivals(2 * b + 1, end, &mut above);
            } else {
                above.clear();
            }
            g.boundary(b, end, &below, &above);
        }
        (g.below, g.above) = (below, above);
        g.due.clear();
    }

    /// A front of jump `d` reaching the wall at `at` while the group is
    /// stepped, where the step was seen to hold no decision: in contact
    /// the wall strain stays compressive, free the bottom does not land.
    /// The reflected jump.
    fn group_wall(&mut self, at: R, d: R) -> R {
        self.advance_wall(at);
        let two = R::of(2.0);
        match self.contact {
            ContactState::InContact { strain } => {
                let rigid = strain + two * d;
                let scale = self.impact_speed / self.layers[0].wave_speed;
                self.note_decision(rigid / scale);
                self.contact = ContactState::InContact { strain: rigid };
                d
            }
            ContactState::Free {
                height, velocity, ..
            } => {
                self.contact = ContactState::Free {
                    height,
                    velocity: velocity + two * self.layers[0].wave_speed * d,
                    at,
                };
                -d
            }
        }
    }

    /// What the group's steps did, handed to the loop.
    fn settle_group(&mut self, g: &mut Group<R>) -> Result<(), WaveError> {
        for (i, sum) in g.born_sums.iter_mut().enumerate() {
            if *sum != R::zero() {
                match i % 2 {
                    0 => self.up_base[i / 2] += *sum,
                    _ => self.down_base[i / 2] += *sum,
                }
                *sum = R::zero();
            }
        }
        let dropped = std::mem::take(&mut g.dropped);
        if dropped.fronts > 0 {
            let d = &mut self.drops;
            d.truncation.dropped_fronts += dropped.fronts;
            d.truncation.dropped_velocity += dropped.velocity / self.impact_speed.to_f64();
            d.dropped_force += dropped.force;
            d.dropped_force_time += dropped.force_time;
        }
        self.stepped += g.followed;
        g.followed = 0;
        let mut sent = std::mem::take(&mut g.sent);
        sent.sort_by(|a, b| a.0.partial_cmp(&b.0).unwrap_or(std::cmp::Ordering::Equal));
        let top = g.top;
        let result = sent
            .iter()
            .try_for_each(|&(born, jump)| self.spawn(top, Direction::Up, born, jump, &[]));
        sent.clear();
        g.sent = sent;
        result
    }
}

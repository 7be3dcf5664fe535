//! When the group is stepped and when the loop takes it back: the wall
//! seen a step ahead, the group taken over and given back, its key's
//! events and the fronts that reach it from above.

use super::{Group, bottom_group};
use crate::engine::{NEAR_GRAZING, StepKind, Tracer, past};
use crate::error::WaveError;
use crate::lane::{Direction, Lane, MergeRule};
use crate::queue::EventKey;
use crate::real::Real;
use crate::wall::ContactState;

impl<R: Real> Tracer<R> {
    /// Sets the rod's bottom group up, if it has one (`group.rs`); after
    /// the blocks are chosen.
    pub(crate) fn find_group(&mut self) {
        let transits: Vec<f64> = self
            .layers
            .iter()
            .map(|l| l.transit_time.to_f64())
            .collect();
        let lowest_block = self.blocks.list.iter().map(|b| b.lower).min();
        // (a double-double run follows every front in the loop, the
        // reference, as it does not leap)
        let Some(top) = bottom_group(&transits, lowest_block).filter(|_| R::LEAPS) else {
            return;
        };
        let lattice = |i: usize| match self.lanes[i].rule {
            MergeRule::Lattice {
                spacing,
                keep_above,
                keep_at_most,
            } => (spacing, keep_above, keep_at_most),
            MergeRule::Simultaneous { .. } => (R::zero(), R::zero(), 0),
        };
        if (0..2 * top).any(|i| lattice(i).0 == R::zero()) {
            return;
        }
        let group = Group::new(&self.layers, &self.interfaces, top, self.window, &lattice);
        self.group = Some(Box::new(group));
    }

    /// Whether the wall takes no decision over the arrivals `wall` (time
    /// and jump, in time order) before `to`: in contact every wall strain
    /// stays compressive by more than the grazing tolerance and the margin
    /// of a near-grazing decision (those decide the double-double repeat:
    /// the loop takes them); free, the bottom stays above the wall.
    fn wall_quiet(&self, wall: impl Iterator<Item = (R, R)>, to: R) -> bool {
        let two = R::of(2.0);
        let c0 = self.layers[0].wave_speed;
        match self.contact {
            ContactState::InContact { strain } => {
                let scale = self.impact_speed / c0;
                let least = self.grazing_strain.max(R::of(2.0 * NEAR_GRAZING) * scale);
                let mut strain = strain;
                for (_, d) in wall {
                    strain += two * d;
                    if strain >= -least {
                        return false;
                    }
                }
                true
            }
            ContactState::Free {
                height,
                velocity,
                at,
            } => {
                let above = R::of(NEAR_GRAZING) * self.impact_speed * (to - at);
                let (mut height, mut velocity, mut at) = (height, velocity, at);
                for (t, d) in wall {
                    height += velocity * (t - at);
                    if height <= above {
                        return false;
                    }
                    at = t;
                    velocity += two * c0 * d;
                }
                height + velocity * (to - at) > above
            }
        }
    }

    /// At an event of the group's layers: takes the group over, if a step
    /// from now holds no wall decision (the loop's fronts then go to the
    /// group, the one arriving now among them).
    pub(crate) fn try_group(&mut self) -> Result<bool, WaveError> {
        let Some(g) = self.group.as_deref() else {
            return Ok(false);
        };
        if g.active || self.events < g.retry {
            return Ok(false);
        }
        let (top, to) = (g.top, self.now + g.step);
        let wall = &self.lanes[Lane::<R>::index(0, Direction::Down)];
        let arrivals = wall
            .fronts()
            .map(|f| (wall.arrival_of(f.born), f.jump))
            .take_while(|&(t, _)| t < to);
        if !self.wall_quiet(arrivals, to) {
            let held = self.lanes[0].len() + self.lanes[1].len();
            if let Some(g) = self.group.as_deref_mut() {
                g.retry = self.events + held as u64 + 16;
            }
            return Ok(false);
        }
        let Some(mut g) = self.group.take() else {
            return Ok(false);
        };
        let mut spare = std::mem::take(&mut self.spare_fronts);
        for i in 0..2 * top {
            for f in self.lanes[i].fronts() {
                g.take(i, &f);
            }
            self.lanes[i].set_fronts(&[], &mut spare);
        }
        self.spare_fronts = spare;
        for m in 0..top {
            self.queue.cancel(EventKey::Layer(m as u32));
        }
        self.queue.cancel(EventKey::Reconnection);
        g.saved_leap_after = self.leap_after[..=top].to_vec();
        for after in &mut self.leap_after[..=top] {
            *after = -R::neg_infinity();
        }
        g.reached = self.now;
        g.active = true;
        let tick = self.now + g.step;
        self.group = Some(g);
        self.queue
            .schedule(EventKey::Layer(0), tick, self.now)
            .map_err(past)?;
        // (an iteration of the loop, counted as work, not as an event: the
        // arrival that started it is the group's now)
        self.events -= 1;
        self.leap_work += 1;
        Ok(true)
    }

    /// Whether the group is stepped now.
    #[inline]
    pub(crate) fn group_active(&self) -> bool {
        self.group.as_deref().is_some_and(|g| g.active)
    }

    /// The group's key (layer 0's, while stepped): steps to now, then on
    /// for another step if it holds no wall decision, else the loop takes
    /// the group back.
    pub(crate) fn group_tick(&mut self) -> Result<StepKind, WaveError> {
        let before = self.stepped;
        self.step_group(self.now)?;
        let quiet = match self.group.as_deref_mut() {
            // a group that holds nothing goes back to the loop, whose
            // queue then says whether anything is left to happen
            Some(g) if g.len() > 0 => {
                let to = self.now + g.step;
                let wall = g.wall_ahead(to);
                let quiet = self.wall_quiet(wall.iter().copied(), to);
                if let Some(g) = self.group.as_deref_mut() {
                    g.return_wall(wall);
                }
                quiet.then_some(to)
            }
            _ => None,
        };
        match quiet {
            Some(to) => self
                .queue
                .schedule(EventKey::Layer(0), to, self.now)
                .map_err(past)?,
            None => self.release_group()?,
        }
        // (an iteration of the loop, counted as work, not as an event)
        self.events -= 1;
        self.leap_work += 1;
        Ok(StepKind::Stepped {
            fronts: self.stepped - before,
        })
    }

    /// The loop takes the group's fronts back (stepped to now).
    pub(crate) fn release_group(&mut self) -> Result<(), WaveError> {
        self.step_group(self.now)?;
        let Some(mut g) = self.group.take() else {
            return Ok(());
        };
        let top = g.top;
        let held = g.len();
        let mut fronts = std::mem::take(&mut self.spare_fronts);
        for i in 0..2 * top {
            g.give_back(i, &mut fronts);
            self.lanes[i].restore(&fronts);
        }
        self.spare_fronts = fronts;
        self.leap_after[..=top].copy_from_slice(&g.saved_leap_after);
        g.active = false;
        // the loop does a few rounds of the group's work before the next try
        g.retry = self.events + 4 * held as u64 + 64;
        self.group = Some(g);
        for m in 0..top {
            self.reschedule_layer(m)?;
        }
        self.schedule_landing()
    }

    /// Fronts reaching the group's top boundary from above while it is
    /// stepped: reflected as at any interface, the rest born in the group.
    pub(crate) fn group_input(
        &mut self,
        t: R,
        from_above: R,
        parents: &[u32],
    ) -> Result<StepKind, WaveError> {
        // (an arrival from below just before `t` takes it into its event)
        if self.step_group_taking(t, Some((t, from_above)))? {
            return Ok(StepKind::Interface(
                self.group.as_deref().map_or(0, |g| g.top),
            ));
        }
        let Some(mut g) = self.group.take() else {
            return Ok(StepKind::Interface(0));
        };
        let top = g.top;
        let k = self.interfaces[top - 1];
        // an arrival from below within the window is one event with it
        let deadline = t + self.window.at(t);
        let (from_below, up) =
            match g.take_beyond(Lane::<R>::index(top - 1, Direction::Up), deadline) {
                Some((at, d)) => (d, at == t),
                None => (R::zero(), false),
            };
        g.from_up = up;
        g.birth(
            Lane::<R>::index(top - 1, Direction::Down),
            t,
            k.up_reflected * from_below + k.down_transmitted * from_above,
        );
        self.group = Some(g);
        // (the born jump into the group's base)
        self.step_group(t)?;
        self.spawn(
            top,
            Direction::Up,
            t,
            k.up_transmitted * from_below + k.down_reflected * from_above,
            parents,
        )?;
        Ok(StepKind::Interface(top))
    }
}

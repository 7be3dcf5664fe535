//! The rigid-bottom model's event loop.
//!
//! The bottom layer is a rigid mass `m` (its mass per unit area); the layers
//! above are elastic (see `stack`). The mass feels the stack through
//! `m dV/dt = Z1 (2 beta - V)` while it flies; it rebounds from the wall
//! elastically and instantly (`V -> -V`); it rests on the wall (`V = 0`,
//! the wall pushing `-2 Z1 beta`) once a landing is too slow to matter
//! while the stack pushes it down, and lifts off when the stack pulls
//! (`beta > 0`). This generalises the paper's Appendix C (a one-layer stack
//! followed only up to `2 t2`) and is the limit the exact engine approaches
//! as the bottom stiffens at a fixed mass.

use crate::exppoly::ExpPoly;
use crate::stack::{Lane, scatter};
use impact_model::escape::{EscapeBound, Margin, internal_energy};
use impact_model::{
    Allowed, ContactHistory, EngineKind, ErrorEstimate, Outcome, Rod, SettingError, StopReason,
};
use thiserror::Error;

/// The escape bound's margins ([`impact_model::escape`]), as the exact
/// engine's: relative on the energy balance, and an absolute floor of this
/// many impact-speed-times-`sum(t_i)` above the rounding of the
/// centre-of-mass displacement. A margin only makes the model stop later.
const BALANCE_MARGIN: f64 = 1e-9;
const ROUNDING_MARGIN: f64 = 1e-12;

/// When to stop.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RigidStop {
    /// When the rod is free and can provably never touch the wall again.
    Escape,
    /// At `factor * max(t_i)` (the paper's 20).
    Horizon {
        /// The multiple of the longest transit time `max(t_i)` at which to stop.
        factor: f64,
    },
}

/// Settings of the rigid-bottom model.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct RigidConfig {
    /// When the run ends. Default: the escape bound.
    pub stop: RigidStop,
    /// A landing slower than `rest_ratio` times the speed scale of the push
    /// (`2 |beta|`, the speed at which drag and push balance) while the
    /// stack pushes the mass down ends the chatter: the mass rests. The
    /// exact model bounces on forever, each bounce losing `(2/3) lambda V^2
    /// / g` with `g = 2 lambda |beta|`: the speeds decay like
    /// `exp(-lambda t / 3)` (the paper's `exp(-t / 3 tau)`, Appendix C),
    /// while the mean wall force is that of rest. Taking rest early moves
    /// the mass's momentum by at most `m V exp(-lambda T / 3)` when it lifts
    /// off after `T`, which is reported. Default `1e-3`. The speeds
    /// fall as `V_n ~ 1/n` within a chatter (`dV = -(2/3) V^2 / (2 |beta|)`
    /// per bounce), so a chatter ends after `1.5 / rest_ratio` bounces: 1500
    /// (measured on every real pair in `data/scenes`).
    pub rest_ratio: f64,
    /// Give up after this many events.
    pub max_events: u64,
}

impl RigidConfig {
    /// The settings' ranges, checked once, here: by the model, and by a
    /// caller that wants to refuse bad settings before running anything.
    pub fn check(&self) -> Result<(), SettingError> {
        if let RigidStop::Horizon { factor } = self.stop {
            Allowed::Positive.check("horizon", factor)?;
        }
        Allowed::UnitFraction.check("rest_ratio", self.rest_ratio)?;
        Ok(())
    }
}

impl Default for RigidConfig {
    fn default() -> Self {
        Self {
            stop: RigidStop::Escape,
            rest_ratio: 1e-3,
            max_events: 20_000_000,
        }
    }
}

/// Why the model could not run or finish.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RigidError {
    /// A viscous layer: the model's stack is elastic and its bottom rigid.
    #[error("layers[{layer}] is viscous: the rigid-bottom model has elastic layers only")]
    ViscousLayer {
        /// Index of the first viscous layer, bottom first.
        layer: usize,
    },
    /// A numerical setting outside its range.
    #[error("invalid setting: {0}")]
    Setting(#[from] SettingError),
    /// The event budget `max_events` was spent before the rod left for good.
    #[error(
        "the rigid-bottom model stopped after {events} events at t = {time:.6e} without the rod leaving for good"
    )]
    EventLimit {
        /// Events processed.
        events: u64,
        /// Time reached, in the scene's units.
        time: f64,
    },
    /// The stop rule is a horizon and the mass still touched the wall there.
    #[error(
        "the horizon t = {time:.6e} was reached while the mass still touched the wall: t_c and e are not final"
    )]
    Unfinished {
        /// The horizon, in the scene's units.
        time: f64,
    },
}

/// What the mass is doing.
#[derive(Debug, Clone)]
enum Motion {
    /// Flying since `t0`: `v(s)`, `z(s)` with `s = t - t0`.
    Flying { t0: f64, v: ExpPoly, z: ExpPoly },
    /// Resting on the wall since `t0`, the wall pushing `force(s)`.
    Resting { t0: f64, force: ExpPoly },
}

/// The model for one rod.
pub struct RigidBottom {
    lambda: f64,
    mass: f64,
    total_mass: f64,
    impact_speed: f64,
    /// Impedances of the stack layers (index 0: the mass, unused).
    impedance: Vec<f64>,
    /// `2 (i - 1)` up, `2 (i - 1) + 1` down, for stack layer `i`; the top's
    /// up lane is folded.
    lanes: Vec<Lane>,
    layers: usize,
    motion: Motion,
    /// Wall impulse so far (up to the current piece's start).
    impulse: f64,
    /// Centre-of-mass displacement up to the current piece's start.
    displacement: f64,
    energy: f64,
    /// The escape bound, from the stack's `integral m(s)^2 / E` (the rigid
    /// bottom adds no compliance) and the whole mass.
    escape: EscapeBound<f64>,
    /// Contacts, in the scene's units.
    history: ContactHistory,
    horizon: f64,
    stop: RigidStop,
    rest_ratio: f64,
    /// Landing speed and time of the chatter taken as rest, while resting.
    rest_from: Option<(f64, f64)>,
    max_events: u64,
    events: u64,
    now: f64,
    tolerance: f64,
    /// Sum of the transit times: the model's natural time span.
    span: f64,
    stopped: Option<StopReason>,
    /// `sum 2 m |V| / (M v_b)` over landings ended by rest.
    rest_error: f64,
    transit_times: Vec<f64>,
    time_unit: f64,
}

impl RigidBottom {
    /// The model of `rod`: its bottom layer as the rigid mass, the layers
    /// above as the elastic stack, at the moment of impact. Refuses viscous
    /// layers and settings out of range.
    pub fn new(rod: &Rod, config: &RigidConfig) -> Result<Self, RigidError> {
        if let Some(i) = rod.scene().layers.iter().position(|l| l.is_viscous()) {
            return Err(RigidError::ViscousLayer { layer: i });
        }
        config.check()?;
        let layers = rod.scaled_layers();
        let n = layers.len();
        let vb = rod.scaled_impact_speed();
        let mass = layers[0].mass();
        let impedance: Vec<f64> = layers.iter().map(|l| l.impedance).collect();
        let lambda = if n > 1 { impedance[1] / mass } else { 0.0 };
        let mut lanes = Vec::new();
        for (i, l) in layers.iter().enumerate().skip(1) {
            let top = i == n - 1;
            let delay = if top {
                2.0 * l.transit_time
            } else {
                l.transit_time
            };
            lanes.push(Lane::steady(delay, -0.5 * vb));
            lanes.push(Lane::steady(l.transit_time, -0.5 * vb));
        }
        // integral over the stack of m(s)^2 / E, m(s) the mass above s
        let mut above = 0.0;
        let mut compliance = 0.0;
        for l in layers.iter().skip(1).rev() {
            let below = above + l.mass();
            compliance +=
                (below * below * below - above * above * above) / (3.0 * l.density * l.modulus);
            above = below;
        }
        let total_mass: f64 = layers.iter().map(|l| l.mass()).sum();
        let t_max = layers.iter().map(|l| l.transit_time).fold(0.0, f64::max);
        let span: f64 = layers.iter().map(|l| l.transit_time).sum();
        let horizon = match config.stop {
            RigidStop::Escape => f64::INFINITY,
            RigidStop::Horizon { factor } => factor * t_max,
        };
        let mut model = Self {
            lambda,
            mass,
            total_mass,
            impact_speed: vb,
            impedance,
            lanes,
            layers: n,
            motion: Motion::Resting {
                t0: 0.0,
                force: ExpPoly::default(),
            },
            impulse: 0.0,
            displacement: 0.0,
            energy: 0.5 * total_mass * vb * vb,
            escape: EscapeBound::new(compliance, total_mass),
            history: ContactHistory::new(),
            horizon,
            stop: config.stop,
            rest_ratio: config.rest_ratio,
            rest_from: None,
            max_events: config.max_events,
            events: 0,
            now: 0.0,
            tolerance: 1e-15 * span,
            span,
            stopped: None,
            rest_error: 0.0,
            transit_times: rod.transit_times(),
            time_unit: rod.units().time,
        };
        // the impact: the mass rebounds at once
        model.impulse = 2.0 * mass * vb;
        model.history.separate(0.0);
        model.motion = Motion::Flying {
            t0: 0.0,
            v: ExpPoly::constant(vb),
            z: ExpPoly::constant(0.0),
        };
        if n == 1 {
            // a lone rigid body: nothing above it, it leaves at v_b
            model.stopped = Some(StopReason::Escaped);
        } else {
            model.replan(0.0);
        }
        Ok(model)
    }

    fn above_lane(&self, boundary: usize) -> usize {
        // the lane arriving at the bottom of stack layer `boundary` from above
        if boundary == self.layers - 1 {
            2 * (boundary - 1)
        } else {
            2 * (boundary - 1) + 1
        }
    }

    /// Velocity of the centre of mass.
    fn centre_velocity(&self, impulse: f64) -> f64 {
        -self.impact_speed + impulse / self.total_mass
    }

    /// Ends the current piece at `t`: the mass's state then, and the wall
    /// impulse and centre displacement brought up to `t`.
    fn close_piece(&mut self, t: f64) -> (f64, f64) {
        let l = self.lambda;
        match &self.motion {
            Motion::Flying { t0, v, z } => {
                let s = t - t0;
                self.displacement += self.centre_velocity(self.impulse) * s;
                (v.eval(s, l), z.eval(s, l).max(0.0))
            }
            Motion::Resting { t0, force } => {
                let s = t - t0;
                let j = force.integral(l);
                let jj = j.integral(l);
                self.displacement +=
                    self.centre_velocity(self.impulse) * s + jj.eval(s, l) / self.total_mass;
                self.impulse += j.eval(s, l);
                (0.0, 0.0)
            }
        }
    }

    /// Starts a new piece of the mass's motion at `t`, from velocity `v0`
    /// and height `z0` (resting if `resting`), with the stack as it arrives
    /// from `t` on; emits the wave it sends up.
    fn start_piece(&mut self, t: f64, v0: f64, z0: f64, resting: bool) {
        let l = self.lambda;
        let lane = self.above_lane(1);
        let beta = self.lanes[lane].arriving(t, l);
        let (alpha, motion) = if resting {
            let force = beta.scaled(-2.0 * self.impedance[1]);
            (beta.scaled(-1.0), Motion::Resting { t0: t, force })
        } else {
            let v = ExpPoly::driven(v0, &beta, l);
            let z = v.integral(l).combine(1.0, &ExpPoly::constant(z0), 1.0);
            (v.combine(1.0, &beta, -1.0), Motion::Flying { t0: t, v, z })
        };
        self.lanes[0].emit(t, alpha);
        self.motion = motion;
    }

    /// Closes the current piece at `t` and starts the next with the same
    /// motion (a new wave has arrived at the mass).
    fn replan(&mut self, t: f64) {
        let resting = matches!(self.motion, Motion::Resting { .. });
        let (v, z) = self.close_piece(t);
        self.start_piece(t, v, z, resting);
    }

    /// The next thing the mass does by itself (landing or lift-off) before
    /// `until`, if any.
    fn next_mass_event(&self, until: f64) -> Option<f64> {
        let l = self.lambda;
        match &self.motion {
            Motion::Flying { t0, z, .. } => {
                let span = until - t0;
                if span.is_nan() || span <= 0.0 || !span.is_finite() {
                    return None;
                }
                z.first_zero(span, l, self.tolerance).map(|s| t0 + s)
            }
            Motion::Resting { t0, force } => {
                let span = until - t0;
                if span.is_nan() || span <= 0.0 || !span.is_finite() {
                    return None;
                }
                // lift-off when the wall's push comes down to zero
                force.first_zero(span, l, self.tolerance).map(|s| t0 + s)
            }
        }
    }

    /// The escape time, if the rod flies away now.
    fn escape_time(&self) -> Option<f64> {
        if self.stop != RigidStop::Escape {
            return None;
        }
        let Motion::Flying { t0, .. } = self.motion else {
            return None;
        };
        let v = self.centre_velocity(self.impulse);
        let internal = internal_energy(self.energy, self.total_mass, v);
        let margin = Margin {
            relative: BALANCE_MARGIN,
            absolute: ROUNDING_MARGIN * self.impact_speed * self.span,
        };
        let reach = self.escape.reach(internal, margin);
        EscapeBound::escape_time(t0, reach, self.displacement, v)
    }

    /// Processes the next event; false once stopped.
    pub fn step(&mut self) -> Result<bool, RigidError> {
        if self.stopped.is_some() {
            return Ok(false);
        }
        if self.events >= self.max_events {
            return Err(RigidError::EventLimit {
                events: self.events,
                time: self.now * self.time_unit,
            });
        }
        self.events += 1;
        // the earliest lane arrival
        let arrival = self
            .lanes
            .iter()
            .enumerate()
            .filter_map(|(i, lane)| lane.next_arrival().map(|t| (t, i)))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        let until = arrival.map_or(f64::INFINITY, |a| a.0).min(self.horizon);
        let escape = self.escape_time();
        let bound = until.min(escape.unwrap_or(f64::INFINITY));
        let mass_event = self.next_mass_event(if bound.is_finite() {
            bound
        } else {
            self.now + 1e3 * self.span
        });
        if let Some(t) = mass_event
            && t <= bound
        {
            self.now = t;
            self.mass_event(t);
            return Ok(true);
        }
        if let Some(t) = escape
            && t <= until
        {
            self.now = t;
            self.close_piece(t);
            self.stopped = Some(StopReason::Escaped);
            return Ok(false);
        }
        if until >= self.horizon {
            self.now = self.horizon;
            self.close_piece(self.horizon);
            self.stopped = Some(StopReason::at_horizon(self.history.in_contact()));
            return Ok(false);
        }
        let Some((t, lane)) = arrival else {
            // nothing arrives any more and the mass does nothing by itself
            self.stopped = Some(StopReason::Escaped);
            return Ok(false);
        };
        self.now = t;
        self.lanes[lane].advance(t);
        self.boundary(lane, t);
        Ok(true)
    }

    /// A landing or a lift-off at `t`.
    fn mass_event(&mut self, t: f64) {
        let resting = matches!(self.motion, Motion::Resting { .. });
        let (v, _) = self.close_piece(t);
        let scene_t = t * self.time_unit;
        if resting {
            self.end_rest(t);
            self.history.separate(scene_t);
            self.start_piece(t, 0.0, 0.0, false);
            return;
        }
        let arriving = self.lanes[self.above_lane(1)].arriving(t, self.lambda);
        let beta = arriving.eval(0.0, self.lambda);
        // the push just after `t`, which decides at zero speed
        let beta_after = arriving.eval(1e-9 * self.span, self.lambda);
        let speed = v.abs();
        self.history.reconnect(scene_t);
        let pushed =
            beta < 0.0 || (beta == 0.0 && beta_after <= 0.0) || (speed == 0.0 && beta_after <= 0.0);
        if pushed && speed <= self.rest_ratio * 2.0 * beta.abs().max(beta_after.abs()) {
            // too slow to matter while pushed down: the chatter ends in rest
            self.impulse += self.mass * speed;
            self.energy -= 0.5 * self.mass * speed * speed;
            self.rest_from = Some((speed, t));
            self.start_piece(t, 0.0, 0.0, true);
        } else {
            self.impulse += 2.0 * self.mass * speed;
            self.history.separate(scene_t);
            self.start_piece(t, speed, 0.0, false);
        }
    }

    /// Accounts for the chatter a rest replaced, when it ends at `t`: the
    /// bounces it stands for would still carry `m V exp(-lambda T / 3)`.
    fn end_rest(&mut self, t: f64) {
        if let Some((speed, since)) = self.rest_from.take() {
            let left = speed * (-self.lambda * (t - since) / 3.0).exp();
            self.rest_error += 2.0 * self.mass * left / (self.total_mass * self.impact_speed);
        }
    }

    /// A new piece has arrived through `lane` at its boundary at `t`.
    fn boundary(&mut self, lane: usize, t: f64) {
        let l = self.lambda;
        // lane 2 (i - 1) + d of stack layer i: up lanes arrive at the top
        // of layer i (boundary i + 1) unless folded; down lanes at its bottom
        let layer = lane / 2 + 1;
        let up = lane.is_multiple_of(2);
        let boundary = if up && layer != self.layers - 1 {
            layer + 1
        } else {
            layer
        };
        if boundary == 1 {
            self.replan(t);
            return;
        }
        let below = 2 * (boundary - 2);
        let alpha = self.lanes[below].arriving(t, l);
        let beta = self.lanes[self.above_lane(boundary)].arriving(t, l);
        let (down, upward) = scatter(
            self.impedance[boundary - 1],
            self.impedance[boundary],
            &alpha,
            &beta,
        );
        self.lanes[below + 1].emit(t, down);
        self.lanes[2 * (boundary - 1)].emit(t, upward);
    }

    /// Runs to the end.
    pub fn run(&mut self) -> Result<Outcome, RigidError> {
        while self.step()? {}
        let end = self.now;
        self.end_rest(end);
        if self.stopped == Some(StopReason::HorizonInContact) {
            return Err(RigidError::Unfinished {
                time: self.now * self.time_unit,
            });
        }
        Ok(self.outcome())
    }

    /// The observables now, with the model's error estimate.
    pub fn outcome(&self) -> Outcome {
        let e = self.centre_velocity(self.impulse) / self.impact_speed;
        let mut o = Outcome::from_history(
            EngineKind::RigidBottom,
            e,
            &self.history,
            &self.transit_times,
            self.now * self.time_unit,
            self.stopped.unwrap_or(StopReason::HorizonInContact),
        );
        o.events = Some(self.events);
        o.with_error(ErrorEstimate {
            reduced: self.rest_error,
            rounding: 4.0 * f64::EPSILON * self.events as f64,
            method: format!(
                "model: rigid bottom (the elastic engine's limit as the bottom's transit time goes to zero at fixed mass); reduced: chatter slower than {:.0e} of the push's speed scale taken as rest; rounding: 9e-16 per event",
                self.rest_ratio
            ),
            ..ErrorEstimate::default()
        })
    }
}

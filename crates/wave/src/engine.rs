//! The event loop of the exact engine.

use crate::config::{Record, StopRule, WaveConfig};
use crate::error::WaveError;
use crate::lane::{Direction, Lane, Pushed};
use crate::queue::{EventInPast, EventKey, EventQueue};
use crate::record::{FrontRecord, Recording, WallSample};
use crate::wall::{self, ContactState};
use impact_model::{
    ContactHistory, EngineKind, InterfaceCoefficients, LayerProps, Outcome, Rod, StopReason,
    Truncation,
};
use std::time::Instant;

/// What one call of [`WaveEngine::step`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Step {
    pub time: f64,
    pub kind: StepKind,
}

/// The kind of event processed by a step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepKind {
    /// Fronts reached interface `b` (between layers `b - 1` and `b`).
    Interface(usize),
    /// Fronts reached the free top.
    Top,
    /// Fronts reached the wall; `separated` when the rod left it there.
    Wall { separated: bool },
    /// The free bottom landed on the wall.
    Reconnected,
    /// The run is over.
    Stopped(StopReason),
}

/// Wall impulse bookkeeping: everything the wall does to the rod is the force
/// `-E0 eps0` while in contact, so the centre of mass is known exactly.
#[derive(Debug, Clone, Copy)]
struct WallLedger {
    /// Time of the last update.
    at: f64,
    /// `I = integral(eps0 dt)`.
    impulse: f64,
    /// `W = integral(I dt)`, for the centre-of-mass displacement.
    moment: f64,
}

/// The exact engine for one rod. Build with [`WaveEngine::new`], then
/// [`WaveEngine::run`] to the end or [`WaveEngine::step`] one event at a time.
/// After each step, the fields are exactly those of the rod at
/// [`WaveEngine::time`].
#[derive(Debug, Clone)]
pub struct WaveEngine {
    pub(crate) layers: Vec<LayerProps>,
    interfaces: Vec<InterfaceCoefficients>,
    pub(crate) lanes: Vec<Lane>,
    /// Up-going component at the bottom of each layer, behind all its up
    /// fronts; with the lanes it gives the field anywhere (see `fields`).
    pub(crate) up_base: Vec<f64>,
    /// Down-going component at the top of each layer, behind its down fronts.
    pub(crate) down_base: Vec<f64>,
    queue: EventQueue,
    pub(crate) contact: ContactState,
    ledger: WallLedger,
    history: ContactHistory,
    impact_speed: f64,
    mass: f64,
    /// Distance the centre of mass must rise above its start before a free rod
    /// can never touch the wall again (DESIGN.md §2).
    escape_margin_per_energy: f64,
    /// Drop threshold on |strain jump| in each layer.
    drop_strain: Vec<f64>,
    simultaneity: f64,
    merge_window: f64,
    grazing_strain: f64,
    max_events: u64,
    max_time: f64,
    stop_rule: StopRule,
    record: Record,
    recording: Recording,
    truncation: Truncation,
    events: u64,
    next_id: u32,
    now: f64,
    stopped: Option<StopReason>,
    transit_times: Vec<f64>,
}

fn past(e: EventInPast) -> WaveError {
    WaveError::EventInPast {
        now: e.now,
        requested: e.requested,
    }
}

impl WaveEngine {
    /// Prepares a run: the impact happens at `t = 0`, launching the
    /// compression front `-v_b / c0` from the wall.
    pub fn new(rod: &Rod, config: WaveConfig) -> Result<Self, WaveError> {
        if let Some(i) = rod.scene().layers.iter().position(|l| l.is_viscous()) {
            return Err(WaveError::ViscousLayer { layer: i });
        }
        let nonneg = "a finite number >= 0";
        for (field, value) in [
            ("drop_tolerance", config.drop_tolerance),
            ("simultaneity", config.simultaneity),
            ("merge_window", config.merge_window),
            ("grazing_tolerance", config.grazing_tolerance),
        ] {
            if !(value.is_finite() && value >= 0.0) {
                return Err(WaveError::Setting {
                    field,
                    allowed: nonneg,
                    value,
                });
            }
        }
        if let StopRule::Horizon { factor } = config.stop
            && !(factor.is_finite() && factor > 0.0)
        {
            return Err(WaveError::Setting {
                field: "horizon",
                allowed: "a finite number > 0",
                value: factor,
            });
        }
        let layers = rod.layers().to_vec();
        let vb = rod.impact_speed();
        let t_min = rod.min_transit_time();
        let lanes = layers
            .iter()
            .enumerate()
            .flat_map(|(i, l)| {
                [
                    Lane::new(i, Direction::Up, l.transit_time),
                    Lane::new(i, Direction::Down, l.transit_time),
                ]
            })
            .collect();
        let interfaces = layers
            .windows(2)
            .map(|w| InterfaceCoefficients::between(&w[0], &w[1]))
            .collect();
        let c0 = layers[0].wave_speed;
        let simultaneity = config.simultaneity * t_min;
        let mut engine = Self {
            interfaces,
            lanes,
            // At rest relative to the rod's motion at -v_b: a = v_b/2c, b = -v_b/2c.
            up_base: layers.iter().map(|l| vb / (2.0 * l.wave_speed)).collect(),
            down_base: layers.iter().map(|l| -vb / (2.0 * l.wave_speed)).collect(),
            drop_strain: layers
                .iter()
                .map(|l| config.drop_tolerance * vb / l.wave_speed)
                .collect(),
            queue: EventQueue::new(),
            contact: ContactState::InContact { strain: 0.0 },
            ledger: WallLedger {
                at: 0.0,
                impulse: 0.0,
                moment: 0.0,
            },
            history: ContactHistory::new(),
            impact_speed: vb,
            mass: rod.mass(),
            escape_margin_per_energy: rod.compliance_moment().sqrt() / rod.mass(),
            simultaneity,
            merge_window: simultaneity.max(config.merge_window * t_min),
            grazing_strain: config.grazing_tolerance * vb / c0,
            max_events: config.max_events,
            max_time: config.max_time_factor * rod.transit_times().iter().sum::<f64>(),
            stop_rule: config.stop,
            record: config.record,
            recording: Recording::default(),
            truncation: Truncation::default(),
            events: 0,
            next_id: 0,
            now: 0.0,
            stopped: None,
            transit_times: rod.transit_times(),
            layers,
        };
        if let StopRule::Horizon { factor } = config.stop {
            let horizon = factor * rod.max_transit_time();
            engine
                .queue
                .schedule(EventKey::Horizon, horizon)
                .map_err(past)?;
        }
        // The impact: the bottom is stopped, v: -v_b -> 0, so d = -v_b / c0.
        let first = -vb / c0;
        engine.contact = ContactState::InContact { strain: first };
        engine.spawn(0, Direction::Up, 0.0, first, &[])?;
        engine.record_wall();
        Ok(engine)
    }

    /// Current time: that of the last processed event.
    pub fn time(&self) -> f64 {
        self.now
    }

    pub fn contact_state(&self) -> ContactState {
        self.contact
    }

    pub fn events(&self) -> u64 {
        self.events
    }

    /// Why the run stopped, once it has.
    pub fn stopped(&self) -> Option<StopReason> {
        self.stopped
    }

    /// What was recorded (empty unless asked in the config).
    pub fn recording(&self) -> &Recording {
        &self.recording
    }

    pub fn truncation(&self) -> Truncation {
        self.truncation
    }

    /// Centre-of-mass velocity, exact from the wall impulse:
    /// `M dv/dt = -E0 eps0`.
    pub fn centre_of_mass_velocity(&self) -> f64 {
        let impulse = self.impulse_at(self.now);
        -self.impact_speed - self.layers[0].modulus / self.mass * impulse
    }

    fn impulse_at(&self, t: f64) -> f64 {
        match self.contact {
            ContactState::InContact { strain } => {
                self.ledger.impulse + strain * (t - self.ledger.at)
            }
            ContactState::Free { .. } => self.ledger.impulse,
        }
    }

    /// Centre-of-mass displacement since the impact.
    fn centre_of_mass_displacement(&self) -> f64 {
        -self.impact_speed * self.now - self.layers[0].modulus / self.mass * self.ledger.moment
    }

    /// Brings the wall ledger (and a free bottom's height) up to time `t`.
    fn advance_wall(&mut self, t: f64) {
        let dt = t - self.ledger.at;
        match &mut self.contact {
            ContactState::InContact { strain } => {
                self.ledger.moment += self.ledger.impulse * dt + 0.5 * *strain * dt * dt;
                self.ledger.impulse += *strain * dt;
            }
            ContactState::Free {
                height,
                velocity,
                at,
            } => {
                self.ledger.moment += self.ledger.impulse * dt;
                *height += *velocity * (t - *at);
                *at = t;
            }
        }
        self.ledger.at = t;
    }

    /// Adds a front born at `t` at the start of the lane of (`layer`, `dir`).
    fn spawn(
        &mut self,
        layer: usize,
        dir: Direction,
        t: f64,
        jump: f64,
        parents: &[u32],
    ) -> Result<(), WaveError> {
        if jump == 0.0 {
            return Ok(());
        }
        if jump.abs() < self.drop_strain[layer] {
            self.truncation.dropped_fronts += 1;
            self.truncation.dropped_velocity +=
                jump.abs() * self.layers[layer].wave_speed / self.impact_speed;
            return Ok(());
        }
        match dir {
            Direction::Up => self.up_base[layer] += jump,
            Direction::Down => self.down_base[layer] += jump,
        }
        let index = Lane::index(layer, dir);
        let lane = &mut self.lanes[index];
        let newest_born = lane.fronts.back().map(|f| f.born);
        match lane.push(t, jump, self.next_id, self.merge_window) {
            Pushed::New { was_empty } => {
                if self.record.fronts {
                    self.recording.fronts.push(FrontRecord {
                        id: self.next_id,
                        layer,
                        direction: dir,
                        born: t,
                        arrives: t + lane.transit,
                        jump,
                        parents: parents.to_vec(),
                    });
                }
                self.next_id += 1;
                if was_empty {
                    let arrival = t + lane.transit;
                    self.queue
                        .schedule(EventKey::Lane(index as u32), arrival)
                        .map_err(past)?;
                }
            }
            Pushed::Merged { id } => {
                if newest_born.is_some_and(|b| t - b > self.simultaneity) {
                    self.truncation.merged_fronts += 1;
                }
                if self.record.fronts
                    && let Some(rec) = self.recording.fronts.get_mut(id as usize)
                {
                    rec.jump += jump;
                    rec.parents.extend_from_slice(parents);
                }
            }
        }
        Ok(())
    }

    /// Takes the head of lane `index` if it arrives by `deadline`.
    fn take_head(&mut self, index: usize, deadline: f64) -> Result<Option<(f64, u32)>, WaveError> {
        let lane = &mut self.lanes[index];
        match lane.head_arrival() {
            Some(t) if t <= deadline => {}
            _ => return Ok(None),
        }
        let Some(front) = lane.fronts.pop_front() else {
            return Ok(None);
        };
        match lane.head_arrival() {
            Some(next) => self
                .queue
                .schedule(EventKey::Lane(index as u32), next)
                .map_err(past)?,
            None => self.queue.cancel(EventKey::Lane(index as u32)),
        }
        Ok(Some((front.jump, front.id)))
    }

    /// Processes the next event. Arrivals at the same boundary within the
    /// simultaneity window are combined into one event first.
    pub fn step(&mut self) -> Result<Step, WaveError> {
        if let Some(reason) = self.stopped {
            return Ok(Step {
                time: self.now,
                kind: StepKind::Stopped(reason),
            });
        }
        if self.events >= self.max_events {
            return Err(WaveError::EventLimit {
                events: self.events,
                time: self.now,
            });
        }
        let Some((key, t)) = self.queue.peek() else {
            // Nothing left can happen (every front dropped): the rod is free
            // for good only if it moves away; otherwise this is a limit case.
            return Err(WaveError::TimeLimit { time: self.now });
        };
        if t > self.max_time {
            return Err(WaveError::TimeLimit { time: t });
        }
        self.events += 1;
        self.queue.advance(t);
        self.now = t;
        let kind = match key {
            EventKey::Lane(index) => {
                let boundary = self.lanes[index as usize].target();
                self.boundary_event(boundary, t)?
            }
            EventKey::Reconnection => {
                self.queue.pop();
                let wall_lane = Lane::index(0, Direction::Down);
                if self.lanes[wall_lane]
                    .head_arrival()
                    .is_some_and(|a| a <= t + self.simultaneity)
                {
                    // A front reaches the bottom as it lands: one event. It
                    // reflects off the still-free bottom first; if the bottom
                    // still moves down it lands at once (the landing is
                    // rescheduled at t), else the flight goes on. Either
                    // order gives the same state; this one gives no
                    // zero-length contact.
                    self.boundary_event(0, t)?
                } else {
                    self.reconnect(t)?;
                    StepKind::Reconnected
                }
            }
            EventKey::Escape => {
                self.queue.pop();
                self.finish(t, StopReason::Escaped)
            }
            EventKey::Horizon => {
                self.queue.pop();
                let reason = if self.history.in_contact() {
                    StopReason::HorizonInContact
                } else {
                    StopReason::Horizon
                };
                self.finish(t, reason)
            }
        };
        Ok(Step { time: t, kind })
    }

    fn finish(&mut self, t: f64, reason: StopReason) -> StepKind {
        self.advance_wall(t);
        self.stopped = Some(reason);
        StepKind::Stopped(reason)
    }

    /// All fronts reaching boundary `b` by `t + simultaneity`, as one event.
    fn boundary_event(&mut self, b: usize, t: f64) -> Result<StepKind, WaveError> {
        let deadline = t + self.simultaneity;
        let n = self.layers.len();
        let mut parents = [0u32; 2];
        let mut count = 0;
        let mut from_below = 0.0;
        let mut from_above = 0.0;
        if b > 0
            && let Some((d, id)) = self.take_head(Lane::index(b - 1, Direction::Up), deadline)?
        {
            from_below = d;
            parents[count] = id;
            count += 1;
        }
        if b < n
            && let Some((d, id)) = self.take_head(Lane::index(b, Direction::Down), deadline)?
        {
            from_above = d;
            parents[count] = id;
            count += 1;
        }
        let parents = &parents[..count];
        if b == 0 {
            self.advance_wall(t);
            let c0 = self.layers[0].wave_speed;
            let r = wall::reflect(self.contact, from_above, c0, t, self.grazing_strain);
            self.contact = r.state;
            if r.separated {
                self.history.separate(t);
                self.schedule_escape(t)?;
            }
            self.schedule_landing()?;
            self.spawn(0, Direction::Up, t, r.reflected, parents)?;
            self.record_wall();
            Ok(StepKind::Wall {
                separated: r.separated,
            })
        } else if b == n {
            self.spawn(n - 1, Direction::Down, t, -from_below, parents)?;
            Ok(StepKind::Top)
        } else {
            let k = self.interfaces[b - 1];
            let down = k.up_reflected * from_below + k.down_transmitted * from_above;
            let up = k.up_transmitted * from_below + k.down_reflected * from_above;
            self.spawn(b - 1, Direction::Down, t, down, parents)?;
            self.spawn(b, Direction::Up, t, up, parents)?;
            Ok(StepKind::Interface(b))
        }
    }

    /// After a separation with the centre of mass moving up, schedules the
    /// time from which no reconnection is possible: the bottom satisfies
    /// `z0 >= w_cm - D`, `D = sqrt(integral(m^2/E)) sqrt(2 E_int) / M`.
    fn schedule_escape(&mut self, t: f64) -> Result<(), WaveError> {
        let v = self.centre_of_mass_velocity();
        if v <= 0.0 || self.stop_rule != StopRule::Escape {
            return Ok(());
        }
        let internal = (0.5 * self.mass * (self.impact_speed.powi(2) - v * v)).max(0.0);
        // 1e-9 relative margin: the dropped fronts may leave the true internal
        // energy a hair above the balance used here.
        let margin = self.escape_margin_per_energy * (2.0 * internal).sqrt() * (1.0 + 1e-9)
            + 1e-12 * self.impact_speed * self.transit_times.iter().sum::<f64>();
        let rise = margin - self.centre_of_mass_displacement();
        let at = t + rise.max(0.0) / v;
        self.queue.schedule(EventKey::Escape, at).map_err(past)
    }

    /// Keeps the landing (reconnection) event in step with the free bottom.
    fn schedule_landing(&mut self) -> Result<(), WaveError> {
        match self.contact {
            ContactState::Free {
                height,
                velocity,
                at,
            } => match wall::landing_time(height, velocity, at) {
                Some(land) => self
                    .queue
                    .schedule(EventKey::Reconnection, land.max(self.now))
                    .map_err(past),
                None => {
                    self.queue.cancel(EventKey::Reconnection);
                    Ok(())
                }
            },
            ContactState::InContact { .. } => {
                self.queue.cancel(EventKey::Reconnection);
                Ok(())
            }
        }
    }

    fn reconnect(&mut self, t: f64) -> Result<(), WaveError> {
        self.advance_wall(t);
        let ContactState::Free { velocity, .. } = self.contact else {
            return Ok(());
        };
        let (jump, state) = wall::reconnect(velocity, self.layers[0].wave_speed);
        self.contact = state;
        self.history.reconnect(t);
        self.queue.cancel(EventKey::Escape);
        self.spawn(0, Direction::Up, t, jump, &[])?;
        self.record_wall();
        Ok(())
    }

    fn record_wall(&mut self) {
        if !self.record.wall {
            return;
        }
        let (strain, height, velocity) = match self.contact {
            ContactState::InContact { strain } => (strain, 0.0, 0.0),
            ContactState::Free {
                height, velocity, ..
            } => (0.0, height, velocity),
        };
        self.recording.wall.push(WallSample {
            time: self.now,
            strain,
            height,
            velocity,
        });
    }

    /// Steps until the run stops.
    pub fn run(&mut self) -> Result<Outcome, WaveError> {
        let start = Instant::now();
        while self.stopped.is_none() {
            self.step()?;
        }
        let mut outcome = self.outcome();
        outcome.elapsed_seconds = start.elapsed().as_secs_f64();
        Ok(outcome)
    }

    /// The observables at the current time (`elapsed_seconds` left at 0).
    pub fn outcome(&self) -> Outcome {
        let mut o = Outcome::from_history(
            EngineKind::Wave,
            self.centre_of_mass_velocity() / self.impact_speed,
            &self.history,
            &self.transit_times,
            self.now,
            self.stopped.unwrap_or(StopReason::HorizonInContact),
        );
        o.events = Some(self.events);
        o.truncation = Some(self.truncation);
        o
    }
}

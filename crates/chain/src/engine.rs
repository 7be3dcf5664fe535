//! The chain's time loop: the kernel's steps, the wall's impulse and
//! contacts, the stop rules.
//!
//! An elastic chain needs positions only (the wall impulse, the contacts
//! and the escape decision depend on nothing else), so it runs
//! [`VerletChain`], Beeman's positions as Verlet's, and rebuilds Beeman's
//! velocities when they are asked for. A viscous chain runs
//! [`ImplicitChain`] (SDIRK2 on springs and dashpots together), or, asked
//! for by name, [`ViscousChain`]: Beeman's whole state (`u, v, a, a_prev`)
//! on the masses its dashpots act on, Verlet's sweep on the others, and an
//! SDIRK2 step of the dashpots after each step.

use crate::config::{ChainConfig, ChainStop, ViscousKernel};
use crate::error::ChainError;
use crate::implicit::ImplicitChain;
use crate::layout::ChainLayout;
use crate::verlet::VerletChain;
use crate::viscous::ViscousChain;
use impact_model::escape::{EscapeBound, Margin, internal_energy};
use impact_model::{ContactHistory, EngineKind, Outcome, Rod, StopReason, WallContact, WallSample};
use serde::Serialize;
use std::borrow::Cow;

/// The strain field at one time, averaged into equal-height rows (row 0 at
/// the wall).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RasterFrame {
    /// Time of the frame, in the scene's units.
    pub time: f64,
    /// Mean strain of each row, bottom first (negative in compression).
    pub strain: Vec<f64>,
}

/// What the chain recorded (only what the config asked for).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct ChainRecording {
    /// Wall samples (the same type as the exact engine's).
    pub wall: Vec<WallSample>,
    /// Strain frames for space-time diagrams.
    pub raster: Vec<RasterFrame>,
}

/// Fraction of the impact's kinetic energy under which a rod held at the
/// wall is at rest: a centre-of-mass speed of at most `1e-6 v_b`.
const REST_ENERGY: f64 = 1e-12;

/// The escape bound's margin: Beeman's discrete energy is not conserved
/// but fluctuates about the true one with the step, and the bound is
/// computed from it; 5% covers that fluctuation. A margin only makes the
/// chain stop later (a few more steps), never wrongly.
const INTEGRATOR_MARGIN: f64 = 0.05;

/// The kernel that steps the masses.
#[derive(Debug, Clone)]
enum Kernel {
    /// No dashpot anywhere: positions only.
    Elastic(VerletChain),
    /// Dashpots somewhere, the split kernel asked for: Beeman's state where
    /// they act (boxed: it holds the dashpots' factors too).
    Split(Box<ViscousChain>),
    /// Dashpots somewhere, the default: springs and dashpots implicit
    /// together (`crate::implicit`).
    Implicit(Box<ImplicitChain>),
}

/// The discrete chain for one rod.
#[derive(Debug, Clone)]
pub struct ChainEngine {
    layout: ChainLayout,
    kernel: Kernel,
    wall_contact: WallContact,
    dt: f64,
    t: f64,
    steps: u64,
    history: ContactHistory,
    /// Wall impulse so far (trapezoid on the spring force, exact for the
    /// dashpot half-steps).
    impulse: f64,
    wall_force: f64,
    total_mass: f64,
    impact_speed: f64,
    transit_times: Vec<f64>,
    stop: ChainStop,
    horizon: f64,
    escape_at: Option<f64>,
    escape: EscapeBound<f64>,
    max_steps: u64,
    config: ChainConfig,
    recording: ChainRecording,
    stopped: Option<StopReason>,
}

impl ChainEngine {
    /// Lays the rod out on `config.masses` masses, at rest and moving down at
    /// `v_b`, just touching the wall at `t = 0`; refuses settings out of range.
    pub fn new(rod: &Rod, config: ChainConfig) -> Result<Self, ChainError> {
        config.check()?;
        let layout = ChainLayout::new(rod, config.masses)?;
        let dt = layout.paper_time_step() * config.dt_factor;
        let kernel = if layout.is_viscous() && config.viscous_kernel == ViscousKernel::Implicit {
            Kernel::Implicit(Box::new(ImplicitChain::new(
                &layout,
                dt,
                rod.impact_speed(),
                rod.wall_contact(),
            )))
        } else if layout.is_viscous() {
            Kernel::Split(Box::new(ViscousChain::new(&layout, dt, rod.impact_speed())))
        } else {
            Kernel::Elastic(VerletChain::new(&layout, dt, rod.impact_speed()))
        };
        let horizon = match config.stop {
            ChainStop::Horizon { factor } => factor * rod.max_transit_time(),
            ChainStop::Escape => f64::INFINITY,
        };
        Ok(Self {
            kernel,
            escape: EscapeBound::new(layout.compliance_moment(), layout.mass.iter().sum()),
            total_mass: layout.mass.iter().sum(),
            wall_contact: rod.wall_contact(),
            dt,
            t: 0.0,
            steps: 0,
            history: ContactHistory::new(),
            impulse: 0.0,
            wall_force: 0.0,
            impact_speed: rod.impact_speed(),
            transit_times: rod.transit_times(),
            stop: config.stop,
            horizon,
            escape_at: None,
            max_steps: config.max_steps,
            recording: ChainRecording::default(),
            stopped: None,
            config,
            layout,
        })
    }

    /// Which kernel steps this chain's dashpots (`None`: an elastic chain,
    /// Verlet's positions only).
    pub fn viscous_kernel(&self) -> Option<ViscousKernel> {
        match self.kernel {
            Kernel::Elastic(_) => None,
            Kernel::Split(_) => Some(ViscousKernel::Split),
            Kernel::Implicit(_) => Some(ViscousKernel::Implicit),
        }
    }

    /// True when the dashpot kernel runs; an elastic scene never does any
    /// dashpot work.
    pub fn uses_dashpots(&self) -> bool {
        self.viscous_kernel().is_some()
    }

    /// How the rod was mapped onto masses.
    pub fn layout(&self) -> &ChainLayout {
        &self.layout
    }

    /// Current time, in the scene's units.
    pub fn time(&self) -> f64 {
        self.t
    }

    /// The time step `dt`, in the scene's units.
    pub fn time_step(&self) -> f64 {
        self.dt
    }

    /// Steps taken so far.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Why the run stopped, once it has.
    pub fn stopped(&self) -> Option<StopReason> {
        self.stopped
    }

    /// What was recorded (empty unless asked in the config).
    pub fn recording(&self) -> &ChainRecording {
        &self.recording
    }

    /// Displacements and velocities of the masses (Beeman's; an elastic
    /// chain rebuilds the velocities from its positions).
    pub fn state(&self) -> (Cow<'_, [f64]>, Cow<'_, [f64]>) {
        (self.displacement(), self.velocities())
    }

    fn displacement(&self) -> Cow<'_, [f64]> {
        match &self.kernel {
            Kernel::Elastic(k) => Cow::Borrowed(k.displacement()),
            Kernel::Split(k) => k.displacement(),
            Kernel::Implicit(k) => k.displacement(),
        }
    }

    /// Displacement of mass 0 (the wall's) now.
    fn u0(&self) -> f64 {
        match &self.kernel {
            Kernel::Elastic(k) => k.displacement()[0],
            Kernel::Split(k) => k.u0(),
            Kernel::Implicit(k) => k.u0(),
        }
    }

    fn velocities(&self) -> Cow<'_, [f64]> {
        match &self.kernel {
            Kernel::Elastic(k) => Cow::Owned(k.velocities()),
            Kernel::Split(k) => Cow::Owned(k.velocities()),
            Kernel::Implicit(k) => k.velocities(),
        }
    }

    /// Beeman's velocity of mass `j` now.
    fn velocity(&self, j: usize) -> f64 {
        match &self.kernel {
            Kernel::Elastic(k) => k.velocity(j),
            Kernel::Split(k) => k.velocity(j),
            Kernel::Implicit(k) => k.velocity(j),
        }
    }

    /// Whether the bottom mass touches the wall now (its element compressed).
    pub fn in_contact(&self) -> bool {
        self.history.in_contact()
    }

    /// At rest against the wall for good: in contact under the paper's law
    /// (whose wall can hold a viscous bottom), with a mechanical energy
    /// below `REST_ENERGY` of the impact's. The dashpots then only drain
    /// what is left; the rod would need energy to leave.
    fn rests_on_wall(&self) -> bool {
        self.wall_contact == WallContact::Paper
            && self.uses_dashpots()
            && self.history.in_contact()
            && self.stop == ChainStop::Escape
            && self.mechanical_energy()
                <= REST_ENERGY * 0.5 * self.total_mass * self.impact_speed.powi(2)
    }

    /// Kinetic energy plus spring energy (wall spring included while
    /// compressed).
    pub fn mechanical_energy(&self) -> f64 {
        let l = &self.layout;
        let (u, v) = self.state();
        let kinetic: f64 = l
            .mass
            .iter()
            .zip(v.iter())
            .map(|(m, v)| 0.5 * m * v * v)
            .sum();
        let wall = 0.5 * l.stiffness[0] * u[0].min(0.0).powi(2);
        let springs: f64 = (1..l.len())
            .map(|j| 0.5 * l.stiffness[j] * (u[j] - u[j - 1]).powi(2))
            .sum();
        kinetic + wall + springs
    }

    /// Centre-of-mass velocity from the masses.
    pub fn mean_velocity(&self) -> f64 {
        self.layout
            .mass
            .iter()
            .zip(self.velocities().iter())
            .map(|(m, v)| m * v)
            .sum::<f64>()
            / self.total_mass
    }

    fn mean_displacement(&self) -> f64 {
        self.layout
            .mass
            .iter()
            .zip(self.displacement().iter())
            .map(|(m, u)| m * u)
            .sum::<f64>()
            / self.total_mass
    }

    /// One step of `dt`; returns why the run stops here, if it does (the
    /// stop rules live here, so a caller stepping by hand stops where
    /// [`Self::run`] would). Stepping on after a stop is allowed.
    pub fn step(&mut self) -> Result<Option<StopReason>, ChainError> {
        let dt = self.dt;
        let u0_old = self.u0();
        // each kernel's wall impulse for the step: the trapezoid on the wall
        // spring (plus the split kernel's dashpot impulse), or the implicit
        // kernel's stage quadrature
        let wall_force = self.wall_force;
        let trapezoid = |force: f64| 0.5 * dt * (wall_force + force);
        let spring_force = |u0: f64| -self.layout.stiffness[0] * u0.min(0.0);
        let (force, step_impulse) = match &mut self.kernel {
            Kernel::Elastic(kernel) => {
                kernel.step();
                let force = spring_force(kernel.displacement()[0]);
                (force, trapezoid(force))
            }
            Kernel::Split(kernel) => {
                let (force, dashpot) =
                    kernel.step(&self.layout.mass, wall_force, self.wall_contact);
                (force, trapezoid(force) + dashpot)
            }
            Kernel::Implicit(kernel) => {
                let impulse = kernel.step();
                (spring_force(kernel.u0()), impulse)
            }
        };
        self.impulse += step_impulse;
        self.wall_force = force;
        self.t += dt;
        self.steps += 1;
        self.track_contact(u0_old);
        self.record();
        if self.steps.is_multiple_of(1024) && !self.u0().is_finite() {
            let mass = self
                .displacement()
                .iter()
                .position(|u| !u.is_finite())
                .unwrap_or(0);
            return Err(ChainError::NonFinite { time: self.t, mass });
        }
        if self.stopped.is_none() {
            self.stopped = self.stop_now();
        }
        Ok(self.stopped)
    }

    /// The stop rules after a step: the horizon, the escape bound, rest.
    fn stop_now(&self) -> Option<StopReason> {
        if self.t >= self.horizon {
            Some(StopReason::at_horizon(self.history.in_contact()))
        } else if self
            .escape_at
            .is_some_and(|at| self.t >= at && !self.history.in_contact())
        {
            Some(StopReason::Escaped)
        } else if self.steps.is_multiple_of(1024) && self.rests_on_wall() {
            Some(StopReason::RestsOnWall)
        } else {
            None
        }
    }

    /// Detects wall-spring crossings of zero, timed by linear interpolation
    /// within the step.
    fn track_contact(&mut self, u0_old: f64) {
        let u0 = self.u0();
        let was = self.history.in_contact();
        let now = u0 < 0.0;
        if was == now {
            return;
        }
        let frac = if u0_old != u0 {
            u0_old / (u0_old - u0)
        } else {
            1.0
        };
        let at = self.t - self.dt + self.dt * frac.clamp(0.0, 1.0);
        if now {
            self.history.reconnect(at);
            self.escape_at = None;
        } else {
            self.history.separate(at);
            self.schedule_escape();
        }
    }

    /// The escape bound ([`impact_model::escape`]) in its discrete form:
    /// the chain's compliance moment is `sum M_j^2 / k_j`, `M_j` the mass
    /// above spring `j`.
    fn schedule_escape(&mut self) {
        if self.stop != ChainStop::Escape {
            return;
        }
        let v = self.mean_velocity();
        let internal = internal_energy(self.mechanical_energy(), self.total_mass, v);
        let reach = self
            .escape
            .reach(internal, Margin::relative(INTEGRATOR_MARGIN));
        self.escape_at = EscapeBound::escape_time(self.t, reach, self.mean_displacement(), v);
    }

    fn record(&mut self) {
        let rec = self.config.record;
        if rec.record_until.is_some_and(|until| self.t > until) {
            return;
        }
        if let Some(every) = rec.wall_every
            && self.steps.is_multiple_of(every.max(1))
        {
            let u0 = self.u0();
            let velocity = self.velocity(0);
            self.recording.wall.push(WallSample {
                time: self.t,
                strain: u0.min(0.0) / self.layout.rest_length[0],
                height: u0.max(0.0),
                velocity,
            });
        }
        if let Some((every, rows)) = rec.raster
            && self.steps.is_multiple_of(every.max(1))
        {
            let frame = self.raster(rows.max(1));
            self.recording.raster.push(frame);
        }
    }

    /// The strain field averaged into `rows` equal-height rows.
    pub fn raster(&self, rows: usize) -> RasterFrame {
        let l = &self.layout;
        let u = self.displacement();
        let total = l.height.last().copied().unwrap_or(1.0);
        let mut sum = vec![0.0; rows];
        let mut weight = vec![0.0; rows];
        for j in 0..l.len() {
            // the wall element is strained only while compressed
            let stretch = if j == 0 {
                u[0].min(0.0)
            } else {
                u[j] - u[j - 1]
            };
            let strain = stretch / l.rest_length[j];
            let centre = l.height[j] - 0.5 * l.rest_length[j];
            let row = ((centre / total) * rows as f64)
                .floor()
                .clamp(0.0, rows as f64 - 1.0) as usize;
            sum[row] += strain * l.rest_length[j];
            weight[row] += l.rest_length[j];
        }
        RasterFrame {
            time: self.t,
            strain: sum
                .iter()
                .zip(&weight)
                .map(|(s, w)| if *w > 0.0 { s / w } else { 0.0 })
                .collect(),
        }
    }

    /// Steps until the stop rule says so.
    pub fn run(&mut self) -> Result<Outcome, ChainError> {
        while self.stopped.is_none() {
            if self.steps >= self.max_steps {
                return Err(ChainError::StepLimit {
                    steps: self.steps,
                    time: self.t,
                });
            }
            self.step()?;
        }
        Ok(self.outcome())
    }

    /// The observables now.
    pub fn outcome(&self) -> Outcome {
        let mut o = Outcome::from_history(
            EngineKind::Chain,
            (-self.impact_speed + self.impulse / self.total_mass) / self.impact_speed,
            &self.history,
            &self.transit_times,
            self.t,
            self.stopped.unwrap_or(StopReason::HorizonInContact),
        );
        o.restitution_from_velocity = Some(self.mean_velocity() / self.impact_speed);
        o.wall_contact = self.wall_contact;
        o.steps = Some(self.steps);
        o.viscous_kernel = self.viscous_kernel().map(|k| k.name().to_string());
        o
    }
}

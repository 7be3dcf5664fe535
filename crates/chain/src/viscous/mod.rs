//! The viscous chain's kernel: Beeman with dashpots where dashpots act,
//! Verlet's one sweep everywhere else.
//!
//! Beeman's positions are Störmer-Verlet's for any mass whose velocity only
//! Beeman's rule changes (substitute the velocity update into the position
//! update: `u(n+1) - 2 u(n) + u(n-1) = dt^2 a(u(n))`, whatever moves the
//! neighbours), and the dashpot step changes the velocities of the masses
//! of its segments alone (the runs of dashpot-joined masses, see
//! [`Dashpots`]). So the masses no dashpot touches (a viscous rod's elastic
//! layers) take the elastic kernel's sweep, `d += dt^2 a(u); u' = u + d`
//! (`crate::verlet`), and only the segments keep Beeman's state
//! (`u, v, a, a_prev`) for the dashpot solve.
//!
//! A long segment (`LANES * 64` masses or more, where the dashpot solve
//! runs in blocks) keeps its state in the blocks' lanes and takes its whole
//! step in two passes ([`blocked`]); a short one keeps it in the chain's
//! arrays, with a Beeman pass for the positions, one for the velocities and
//! the dashpot step of [`Dashpots`].
//!
//! All rules read positions only across a border, and all write the new
//! positions into a second array (swapped with `u` after the step), so the
//! order within a step is free but for one thing: Beeman's new
//! accelerations need every neighbour's new position, so the segments'
//! velocities come after the sweep (a long segment's positions are ready
//! before the step: it computes them a step ahead, and publishes its end
//! masses', the only ones its neighbours read). After the swap the second
//! array holds the last step's positions of every mass (but a long
//! segment's inner ones), from which a swept mass's Beeman velocity is
//! rebuilt when asked (`v(n) = d(n) / dt + dt (2 a(n) + a(n-1)) / 6`, as
//! the elastic kernel does).

mod blocked;

use crate::damping::{Dashpots, lane_length, segments};
use crate::layout::ChainLayout;
use crate::verlet::{Edge, Run, Sweep, edge_dt2_acceleration, restrict, spring_runs};
use blocked::Blocked;
use impact_model::WallContact;
use std::borrow::Cow;
use std::ops::Range;

/// Positions of a viscous chain, Beeman's state on its dashpot segments and
/// the last step's motion elsewhere.
#[derive(Debug, Clone)]
pub(crate) struct ViscousChain {
    /// `u(n)` (a long segment's inner masses: in the segment).
    now: Vec<f64>,
    /// `u(n+1)` while a step computes it, `u(n-1)` between steps.
    next: Vec<f64>,
    /// `d(n) = u(n) - u(n-1)` of the swept masses.
    motion: Vec<f64>,
    /// Beeman's velocities and accelerations now and one step ago (only the
    /// short segments' masses are kept up to date).
    v: Vec<f64>,
    a: Vec<f64>,
    a_prev: Vec<f64>,
    /// The swept masses' runs and edges, `dt^2 k / m`.
    swept: (Vec<Run>, Vec<Edge>),
    /// The short segments' runs and edges, `k / m`.
    beeman: (Vec<Run>, Vec<Edge>),
    short: Vec<Range<usize>>,
    /// The short segments' dashpots.
    dashpots: Dashpots,
    long: Vec<Blocked>,
    /// `k_0 / m_0`: the wall spring, acting while `u_0 < 0`.
    wall_spring: f64,
    /// `k_0` and `c_0`.
    wall_stiffness: f64,
    wall_damping: f64,
    dt: f64,
}

impl ViscousChain {
    /// The chain at rest length, every mass moving down at `impact_speed`,
    /// no force yet (Beeman's start: `a = a_prev = 0`).
    pub(crate) fn new(layout: &ChainLayout, dt: f64, impact_speed: f64) -> Self {
        let n = layout.len();
        let (mass, k, c) = (&layout.mass, &layout.stiffness, &layout.viscosity);
        let (long, short): (Vec<_>, Vec<_>) = segments(c)
            .into_iter()
            .partition(|r| lane_length(r.len()) > 0);
        // 0: swept, 1: short segment, 2: long segment
        let mut rule = vec![0u8; n];
        for (r, mark) in short
            .iter()
            .map(|r| (r, 1))
            .chain(long.iter().map(|r| (r, 2)))
        {
            rule[r.clone()].iter_mut().for_each(|s| *s = mark);
        }
        let (runs, edges) = spring_runs(layout, 1.0);
        let beeman = restrict(&runs, &edges, |j| rule[j] == 1);
        let (runs, edges) = spring_runs(layout, dt * dt);
        let swept = restrict(&runs, &edges, |j| rule[j] == 0);
        Self {
            dashpots: Dashpots::on(mass, c, dt, &short),
            long: long
                .iter()
                .map(|r| Blocked::new((mass, k, c), r.start, r.len(), dt, impact_speed))
                .collect(),
            now: vec![0.0; n],
            // u(-1) = u(0) - d(0): no spring strained, so a(-1) = 0
            next: vec![dt * impact_speed; n],
            motion: vec![-dt * impact_speed; n],
            v: vec![-impact_speed; n],
            a: vec![0.0; n],
            a_prev: vec![0.0; n],
            swept,
            beeman,
            short,
            wall_spring: k[0] / mass[0],
            wall_stiffness: k[0],
            wall_damping: c[0],
            dt,
        }
    }

    /// Displacement of mass 0 now.
    pub(crate) fn u0(&self) -> f64 {
        self.now[0]
    }

    /// Displacements now.
    pub(crate) fn displacement(&self) -> Cow<'_, [f64]> {
        if self.long.is_empty() {
            return Cow::Borrowed(&self.now);
        }
        let mut u = self.now.clone();
        for b in &self.long {
            for (q, u) in u[b.masses()].iter_mut().enumerate() {
                *u = b.position(q);
            }
        }
        Cow::Owned(u)
    }

    /// The sweep over the masses no dashpot touches.
    fn sweep(&self) -> Sweep<'_> {
        Sweep {
            runs: &self.swept.0,
            edges: &self.swept.1,
            wall: self.dt * self.dt * self.wall_spring,
        }
    }

    /// One step: Beeman's springs (Verlet's sweep off the segments), then
    /// the dashpots. `old_force` is the wall spring's force at the start of
    /// the step; returns its force at the end and the wall dashpot's
    /// impulse (upward positive) under the wall law `law`.
    pub(crate) fn step(&mut self, mass: &[f64], old_force: f64, law: WallContact) -> (f64, f64) {
        let dt = self.dt;
        let u0_old = self.now[0];
        for b in &self.long {
            b.publish(&mut self.next);
        }
        for r in &self.short {
            let r = r.clone();
            let (v, a, ap) = (
                &self.v[r.clone()],
                &self.a[r.clone()],
                &self.a_prev[r.clone()],
            );
            beeman_positions(&self.now[r.clone()], &mut self.next[r], v, a, ap, dt);
        }
        let sweep = Sweep {
            runs: &self.swept.0,
            edges: &self.swept.1,
            wall: dt * dt * self.wall_spring,
        };
        sweep.step(&self.now, &mut self.motion, &mut self.next);
        let springs = Springs {
            runs: &self.beeman.0,
            edges: &self.beeman.1,
            wall: self.wall_spring,
        };
        springs.beeman_velocities(&self.next, &mut self.v, &self.a, &mut self.a_prev, dt);
        // `a_prev` now holds the new accelerations: the shift is a swap
        std::mem::swap(&mut self.a, &mut self.a_prev);
        let u0 = self.next[0];
        let force = -self.wall_stiffness * u0.min(0.0);
        let spring_impulse = 0.5 * dt * (old_force + force);
        let compressed = compressed_fraction(u0_old, u0);
        let mut wall_impulse =
            (self.dashpots).step(mass, &mut self.v, compressed, spring_impulse, law);
        for b in &mut self.long {
            let wall = if b.masses().start == 0 {
                compressed * self.wall_damping
            } else {
                0.0
            };
            wall_impulse += b.step(&self.next, wall, spring_impulse, law);
        }
        std::mem::swap(&mut self.now, &mut self.next);
        (force, wall_impulse)
    }

    /// Beeman's velocity of mass `j` now: kept on the segments, rebuilt
    /// from the positions elsewhere.
    pub(crate) fn velocity(&self, j: usize) -> f64 {
        if let Some(b) = self.long.iter().find(|b| b.masses().contains(&j)) {
            return b.velocity(j - b.masses().start);
        }
        if self.short.iter().any(|r| r.contains(&j)) {
            return self.v[j];
        }
        let sweep = self.sweep();
        let a_now = sweep.dt2_acceleration(j, |i| self.now[i]);
        let a_before = sweep.dt2_acceleration(j, |i| self.next[i]);
        (self.motion[j] + (2.0 * a_now + a_before) / 6.0) / self.dt
    }

    /// Beeman's velocities now.
    pub(crate) fn velocities(&self) -> Vec<f64> {
        let mut v = self.v.clone();
        let (runs, edges) = &self.swept;
        let masses = runs
            .iter()
            .flat_map(|r| r.start..r.end)
            .chain(edges.iter().map(|e| e.mass));
        for j in masses {
            v[j] = self.velocity(j);
        }
        for b in &self.long {
            for (q, v) in v[b.masses()].iter_mut().enumerate() {
                *v = b.velocity(q);
            }
        }
        v
    }
}

/// The fraction of a step from `u0_old` to `u0` during which the wall
/// element was compressed (`u0 < 0`), the crossing timed by linear
/// interpolation: a wall dashpot switched on or off inside a step acts for
/// that fraction, which keeps the step second order where the contact
/// begins or ends (switching it for whole steps is first order).
fn compressed_fraction(u0_old: f64, u0: f64) -> f64 {
    match (u0_old < 0.0, u0 < 0.0) {
        (true, true) => 1.0,
        (false, false) => 0.0,
        (true, false) => u0_old / (u0_old - u0),
        (false, true) => u0 / (u0 - u0_old),
    }
}

/// Beeman positions: `u' = u + dt v + dt^2 (4 a - a_prev) / 6`.
fn beeman_positions(u: &[f64], next: &mut [f64], v: &[f64], a: &[f64], a_prev: &[f64], dt: f64) {
    let c = dt * dt / 6.0;
    for ((((next, u), v), a), ap) in next.iter_mut().zip(u).zip(v).zip(a).zip(a_prev) {
        *next = u + (dt * v + c * (4.0 * a - ap));
    }
}

/// Beeman's springs on the segments, borrowed from the kernel.
struct Springs<'a> {
    runs: &'a [Run],
    edges: &'a [Edge],
    /// `k_0 / m_0`.
    wall: f64,
}

impl Springs<'_> {
    /// New spring accelerations from the new positions, then Beeman
    /// velocities `v += dt (2 a_new + 5 a - a_prev) / 6`; `a_new` goes
    /// into `a_prev`, which the caller then swaps with `a` (one store per
    /// mass instead of two for the shift). The wall spring (element 0)
    /// pushes only while compressed.
    ///
    /// Inside a run the acceleration is `c ((u_above - u) - (u - u_below))`
    /// with one `c = k / m`: six equal-length slices and no index
    /// arithmetic, so the loop compiles to packed SIMD (`mulpd`/`subpd`)
    /// with no per-mass `k` or `1 / m` to load; the edge masses (mass 0,
    /// layer tops, the top, a segment's ends) take the general formula,
    /// outside the loop.
    fn beeman_velocities(&self, u: &[f64], v: &mut [f64], a: &[f64], a_prev: &mut [f64], dt: f64) {
        let c = dt / 6.0;
        for r in self.runs {
            let (start, end, km) = (r.start, r.end, r.c);
            let (lo, mid, hi) = (
                &u[start - 1..end - 1],
                &u[start..end],
                &u[start + 1..end + 1],
            );
            let (v, a, ap) = (&mut v[start..end], &a[start..end], &mut a_prev[start..end]);
            for (((((v, a), ap), &lo), &mid), &hi) in v
                .iter_mut()
                .zip(a)
                .zip(ap.iter_mut())
                .zip(lo)
                .zip(mid)
                .zip(hi)
            {
                let acc = km * ((hi - mid) - (mid - lo));
                *v += c * (2.0 * acc + 5.0 * a - *ap);
                *ap = acc;
            }
        }
        for e in self.edges {
            let j = e.mass;
            let acc = edge_dt2_acceleration(self.wall, e, |i| u[i]);
            v[j] += c * (2.0 * acc + 5.0 * a[j] - a_prev[j]);
            a_prev[j] = acc;
        }
    }
}

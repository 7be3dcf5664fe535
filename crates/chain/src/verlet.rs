//! The elastic chain's kernel: Beeman's positions computed as Störmer-Verlet's.
//!
//! Beeman's position and velocity updates, substituted into each other, give
//! `u(n+1) - 2 u(n) + u(n-1) = dt^2 a(u(n))` exactly: its positions are
//! Verlet's. The wall impulse, and so `e`, the contact history and the
//! escape decision, depends on positions only, so an elastic chain needs three
//! arrays instead of six (`u, v, a, a_prev, k, 1/m`). Verlet is written in
//! its summed form, `d += dt^2 a(u); u += d` with `d(n) = u(n) - u(n-1)`:
//! the three-term form `u(n+1) = 2 u(n) - u(n-1) + ...` subtracts numbers of
//! the size of `u` to get a step's motion and drifted from Beeman by `2e-10`
//! (relative) in `10^4` steps; the summed form keeps the motion in its own
//! array, as Beeman keeps `v`. Beeman's velocities, when asked for (output,
//! the escape bound), are rebuilt from the positions and the motion:
//! `v(n) = d(n) / dt + dt (2 a(n) + a(n-1)) / 6`.
//!
//! Inside a layer every mass has the same `k / m`, so a step is
//! `d += c (u_below - 2 u + u_above); u' = u + d` with one constant
//! `c = dt^2 k / m`, one sweep writing the new positions to a third array
//! (swapped with `u` after the step): a loop over five slices of equal
//! length with no index arithmetic, which the compiler turns into packed
//! SIMD with no bounds checks (`mulpd`/`addpd`/`subpd`). Each `u` and `d`
//! is loaded once per step, against twice when `u += d` was a pass of its
//! own (the kernel is bound by loads, not by the cache: a blocked two-pass
//! sweep that kept both in L1 gained nothing). The masses where `k` or `m`
//! change (the bottom, under the wall spring; the top of each layer; the
//! top of the rod) are few and take the general formula, outside the loop.

use crate::layout::ChainLayout;

/// A run of masses `start..end` of one layer whose neighbours above and
/// below are joined by springs of that layer: `c = scale k / m`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Run {
    pub(crate) start: usize,
    pub(crate) end: usize,
    pub(crate) c: f64,
}

/// A mass at a change of `k` or `m`: `scale k_below / m` and
/// `scale k_above / m` (zero at the top).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Edge {
    pub(crate) mass: usize,
    pub(crate) below: f64,
    pub(crate) above: f64,
}

/// The chain's springs as runs of one `scale k / m` and the edges between
/// them (mass 0, the top of each layer, the top of the rod), shared by
/// Verlet's kernel (`scale = dt^2`) and Beeman's (`scale = 1`).
pub(crate) fn spring_runs(layout: &ChainLayout, scale: f64) -> (Vec<Run>, Vec<Edge>) {
    let n = layout.len();
    let (k, m) = (&layout.stiffness, &layout.mass);
    let coefficient = |spring: usize, mass: usize| scale * k[spring] / m[mass];
    let mut runs: Vec<Run> = Vec::new();
    let mut edges: Vec<Edge> = Vec::new();
    for j in 0..n {
        let above = if j + 1 < n {
            coefficient(j + 1, j)
        } else {
            0.0
        };
        let below = coefficient(j, j);
        let interior = j > 0 && j + 1 < n && k[j] == k[j + 1];
        if !interior {
            edges.push(Edge {
                mass: j,
                below,
                above,
            });
            continue;
        }
        match runs.last_mut() {
            Some(r) if r.end == j && r.c == below => r.end += 1,
            _ => runs.push(Run {
                start: j,
                end: j + 1,
                c: below,
            }),
        }
    }
    (runs, edges)
}

/// Positions of the elastic chain now and the last step's motion.
#[derive(Debug, Clone)]
pub struct VerletChain {
    /// `u(n)`.
    now: Vec<f64>,
    /// `d(n) = u(n) - u(n-1)`.
    motion: Vec<f64>,
    /// `u(n+1)` while a step computes it.
    next: Vec<f64>,
    runs: Vec<Run>,
    edges: Vec<Edge>,
    /// `dt^2 k_0 / m_0`: the wall spring, acting while `u_0 < 0`.
    wall: f64,
    dt: f64,
}

impl VerletChain {
    /// The chain at rest length, every mass moving down at `impact_speed`,
    /// no force yet (Beeman's start: `a = a_prev = 0`), so
    /// `d(0) = u(0) - u(-1) = -dt impact_speed`.
    pub fn new(layout: &ChainLayout, dt: f64, impact_speed: f64) -> Self {
        let n = layout.len();
        let (runs, edges) = spring_runs(layout, dt * dt);
        Self {
            now: vec![0.0; n],
            motion: vec![-dt * impact_speed; n],
            next: vec![0.0; n],
            runs,
            edges,
            wall: dt * dt * layout.stiffness[0] / layout.mass[0],
            dt,
        }
    }

    /// Displacements now.
    pub fn displacement(&self) -> &[f64] {
        &self.now
    }

    /// One step: `d += dt^2 a(u)`, then `u += d`, in one sweep: the new
    /// positions go to a second array, which then becomes `u`, so each
    /// mass's `u` and `d` are loaded once per step (twice with `u += d` as
    /// a pass of its own). Every run and edge writes the new `u` of its own
    /// masses, and together they cover the chain.
    pub fn step(&mut self) {
        let sweep = Sweep {
            runs: &self.runs,
            edges: &self.edges,
            wall: self.wall,
        };
        sweep.step(&self.now, &mut self.motion, &mut self.next);
        std::mem::swap(&mut self.now, &mut self.next);
    }

    /// `dt^2` times the acceleration of mass `j` at positions `u(i)`.
    fn dt2_acceleration(&self, j: usize, u: impl Fn(usize) -> f64) -> f64 {
        let sweep = Sweep {
            runs: &self.runs,
            edges: &self.edges,
            wall: self.wall,
        };
        sweep.dt2_acceleration(j, u)
    }

    /// Beeman's velocities now, rebuilt from the positions and the motion:
    /// `v(n) = d(n) / dt + dt (2 a(n) + a(n-1)) / 6`.
    pub fn velocities(&self) -> Vec<f64> {
        (0..self.now.len()).map(|j| self.velocity(j)).collect()
    }

    /// Beeman's velocity of mass `j` now.
    pub fn velocity(&self, j: usize) -> f64 {
        let a_now = self.dt2_acceleration(j, |i| self.now[i]);
        let a_before = self.dt2_acceleration(j, |i| self.now[i] - self.motion[i]);
        (self.motion[j] + (2.0 * a_now + a_before) / 6.0) / self.dt
    }
}

/// Verlet's sweep over some masses: their runs and edges, with `dt^2 k / m`
/// constants (`wall`: `dt^2 k_0 / m_0`), borrowed from a kernel.
pub(crate) struct Sweep<'a> {
    pub(crate) runs: &'a [Run],
    pub(crate) edges: &'a [Edge],
    pub(crate) wall: f64,
}

impl Sweep<'_> {
    /// `d += dt^2 a(u)`, `next = u + d` for the sweep's masses: every run
    /// and edge writes the new `u` of its own masses and reads `u` alone,
    /// so masses outside the sweep may be moved by another rule, before or
    /// after, as long as they leave `u` as it was.
    pub(crate) fn step(&self, u: &[f64], d: &mut [f64], next: &mut [f64]) {
        for r in self.runs {
            layer_run(u, d, next, r.start, r.end, r.c);
        }
        for e in self.edges {
            let j = e.mass;
            d[j] += edge_dt2_acceleration(self.wall, e, |i| u[i]);
            next[j] = u[j] + d[j];
        }
    }

    /// `dt^2` times the acceleration of mass `j` (one of the sweep's) at
    /// positions `u(i)`.
    pub(crate) fn dt2_acceleration(&self, j: usize, u: impl Fn(usize) -> f64) -> f64 {
        if let Some(e) = self.edges.iter().find(|e| e.mass == j) {
            return edge_dt2_acceleration(self.wall, e, u);
        }
        let c = self
            .runs
            .iter()
            .find(|r| (r.start..r.end).contains(&j))
            .map_or(0.0, |r| r.c);
        c * ((u(j - 1) - u(j)) + (u(j + 1) - u(j)))
    }
}

/// The runs and edges of [`spring_runs`] restricted to the masses `keep`
/// selects: a run is cut where it leaves them.
pub(crate) fn restrict(
    runs: &[Run],
    edges: &[Edge],
    keep: impl Fn(usize) -> bool,
) -> (Vec<Run>, Vec<Edge>) {
    let mut kept: Vec<Run> = Vec::new();
    for r in runs {
        for j in (r.start..r.end).filter(|&j| keep(j)) {
            match kept.last_mut() {
                Some(k) if k.end == j && k.c == r.c => k.end += 1,
                _ => kept.push(Run {
                    start: j,
                    end: j + 1,
                    c: r.c,
                }),
            }
        }
    }
    let edges = edges.iter().filter(|e| keep(e.mass)).copied().collect();
    (kept, edges)
}

/// `dt^2` times the acceleration of an edge mass at positions `u(i)`.
#[inline]
pub(crate) fn edge_dt2_acceleration(wall: f64, e: &Edge, u: impl Fn(usize) -> f64) -> f64 {
    let j = e.mass;
    let below = if j == 0 {
        wall * u(0).min(0.0)
    } else {
        e.below * (u(j) - u(j - 1))
    };
    let above = if e.above != 0.0 {
        e.above * (u(j + 1) - u(j))
    } else {
        0.0
    };
    above - below
}

/// `d += c (u_below - 2 u + u_above)`, `u' = u + d` over `start..end`
/// (`start >= 1`, `end < len`): equal-length slices, so no bounds checks
/// and packed SIMD. The run's two halves go side by side in one loop (ten
/// slices, still of one length): a trip then does four masses in two
/// registers each way, so the loop's counting and branching cost half as
/// much per mass (6.75 instructions a mass instead of 7.5); an odd run's
/// last mass goes alone.
#[inline]
fn layer_run(u: &[f64], d: &mut [f64], next: &mut [f64], start: usize, end: usize, c: f64) {
    let half = (end - start) / 2;
    let (d0, d1) = d[start..end].split_at_mut(half);
    let (n0, n1) = next[start..end].split_at_mut(half);
    let (b0, b1) = u[start - 1..end - 1].split_at(half);
    let (m0, m1) = u[start..end].split_at(half);
    let (a0, a1) = u[start + 1..end + 1].split_at(half);
    let first = n0.iter_mut().zip(d0).zip(b0).zip(m0).zip(a0);
    let second = n1.iter_mut().zip(d1.iter_mut()).zip(b1).zip(m1).zip(a1);
    for (((((n, d), &b), &m), &a), ((((n1, d1), &b1), &m1), &a1)) in first.zip(second) {
        *d += c * ((b - m) + (a - m));
        *n = m + *d;
        *d1 += c * ((b1 - m1) + (a1 - m1));
        *n1 = m1 + *d1;
    }
    if (end - start) % 2 == 1 {
        let j = end - 1;
        d[j] += c * ((u[j - 1] - u[j]) + (u[j + 1] - u[j]));
        next[j] = u[j] + d[j];
    }
}

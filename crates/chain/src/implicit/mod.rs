//! The viscous chain's default kernel: SDIRK2 on springs and dashpots
//! together.
//!
//! Why not the split kernel (`crate::viscous`: a Beeman step of the
//! springs, then an SDIRK2 step of the dashpots). It is second order while
//! the step resolves how fast a dashpot stops a mass, and its splitting
//! error is large where it does not. Under the paper's wall law a viscous
//! bottom's wall dashpot can stop mass 0 within a fraction of a step
//! (`c_0 dt / m_0 = 12.6` for a homogeneous rod at `tau c / L = 1`,
//! `N = 200`). The bottom then creeps at the velocity where spring and
//! dashpot forces balance, and `e` is set by when `u_0` creeps back to
//! zero. With the springs explicit that creep is forward Euler's: measured
//! at the paper's step, `|e(dt) - e(0)| = 9.3e-5` on `e = 0.0091`, and not
//! second order until `dt` is 16 times smaller. A viscous top with stiff
//! dashpots (`x = 0.5`, `alpha = 0.05`, `tau2 = 1`) chatters on the wall and
//! lands `3.3e-4` from its limit (`6.2e-4` at `N = 400`). Taken with the
//! dashpots, implicitly, the springs' part is SDIRK2's too, stiffly
//! accurate: `1e-9` and `1.6e-5` there (`tests/dt_order.rs`).
//!
//! So a viscous chain takes whole steps of the
//! two-stage, stiffly accurate SDIRK method (`g = 1 - 1/sqrt 2`) on
//! `u' = v`, `M v' = K u + D v`, every mass alike. The stage positions
//! `U_i = u + h sum_j a_ij V_j` eliminate, leaving one tridiagonal matrix
//! `A = M - g h D - g^2 h^2 K` for both stages:
//!
//! ```text
//! A V1 = M v + g h K u
//! A V2 = M v + h K u + (1 - g) h (D + 2 g h K) V1
//! u' = u + h ((1 - g) V1 + g V2),   v' = V2.
//! ```
//!
//! It is L-stable and second order, and has the split kernel's `dt -> 0`
//! limit: the same chain, the same wall law (the stage forces of the wall
//! element act while it is compressed). For a fixed wall state it never
//! adds energy: the system is dissipative in its energy norm and SDIRK2's
//! stability function is bounded by 1 on the left half-plane (von
//! Neumann's inequality). An elastic layer of such a rod
//! takes these steps too: within `O(dt^2)` of Beeman's, as the split
//! kernel's layers are. The wall element switches on or off where `u_0`
//! crosses zero: the step is redone in two parts that meet there (timed by
//! linear interpolation), each with its own factor.
//!
//! The wall impulse is the stages' quadrature of the wall element's force,
//! `h ((1 - g) F(U1, V1) + g F(U2, V2))`, which is exactly the momentum the
//! step takes from the rod: the internal forces cancel in the sum. Under
//! the unilateral law a step whose wall impulse would pull is redone with
//! the wall giving none, as the split kernel does.
//!
//! Cost. A step is two tridiagonal solves and three stencils. Taken one
//! at a time (the stage-by-stage kernel below: each stage's forces and
//! right-hand side in a pass, the blocked sweeps of
//! `crate::damping::factor`, the positions), that is seven passes over the
//! chain's arrays, 3.7 ns per mass-step at `N = 10^4`, bound by moving the
//! arrays through the cache. A chain long enough to cut into eight blocks
//! of at least its sweeps' halo takes its steps in two passes instead
//! (`fused.rs`: the first stage solved up then down, the second down then
//! up, each sweep riding the pass that goes its way, four arrays, the
//! blocks side by side in vector registers): 0.95 ns (a viscous top) and
//! 1.13 ns (a viscous bottom) per mass-step at `N = 10^4` with AVX-512,
//! 1.28 and 1.49 with AVX2, 2.3 and 2.5 with the baseline's SSE2 (`cargo
//! bench -p impact-chain --bench chain`; the same bits from each, tested).
//! The steps where the wall switches, or would pull, are the stage-by-stage
//! kernel's. About 34 flops per mass-step stage by stage, 31 in two passes
//! (inside a layer a stencil takes one multiply).

use crate::damping::{Factor, GAMMA, Quad, lane_length};
use crate::layout::ChainLayout;
use fused::{Bottom, Fused, Isa};
use impact_model::WallContact;
use plan::{Elements, Plan};
use std::borrow::Cow;

mod fused;
mod lanes;
mod plan;

/// The chain's state and the factors of `A` for the wall element off and
/// on.
#[derive(Debug, Clone)]
pub(crate) struct ImplicitChain {
    u: Vec<f64>,
    v: Vec<f64>,
    mass: Vec<f64>,
    /// Element `j` (below mass `j`; element 0 the wall's): `k_j`, `c_j`.
    stiffness: Vec<f64>,
    viscosity: Vec<f64>,
    /// `c_j + 2 g dt k_j`: the second stage's `D + 2 g h K` at `h = dt`.
    second_stage: Vec<f64>,
    dt: f64,
    unilateral: bool,
    free: Factor,
    with_wall: Factor,
    /// Whether the wall element is compressed (it acts on mass 0).
    wall_on: bool,
    /// The state a step computes, swapped in when the step stands: a step
    /// redone finds the state it started from untouched.
    u_next: Vec<f64>,
    v_next: Vec<f64>,
    /// Scratch: `K u`, the right-hand side, the first stage's velocities,
    /// the sweeps' lanes.
    ku: Vec<f64>,
    r: Vec<f64>,
    v1: Vec<f64>,
    lanes: Vec<Quad>,
    /// The two-pass kernel of a long chain (`fused.rs`), which then holds
    /// the state: `u` and `v` above are only the stage-by-stage steps' copies.
    fused: Option<Box<FusedKernel>>,
}

/// The two-pass kernel and its plans for the wall element off and on.
#[derive(Debug, Clone)]
struct FusedKernel {
    state: Fused,
    free: Plan,
    with_wall: Plan,
}

impl ImplicitChain {
    /// The chain at rest length, every mass moving down at `impact_speed`
    /// and mass 0 touching the wall, under the wall law `law`.
    pub(crate) fn new(layout: &ChainLayout, dt: f64, impact_speed: f64, law: WallContact) -> Self {
        Self::with_isa(
            layout,
            dt,
            impact_speed,
            law,
            Some(Isa::Detected(pulp::Arch::new())),
        )
    }

    /// [`Self::new`], the two-pass kernel compiled for `isa` (`None`: the
    /// stage-by-stage kernel only, the tests' reference).
    fn with_isa(
        layout: &ChainLayout,
        dt: f64,
        impact_speed: f64,
        law: WallContact,
        isa: Option<Isa>,
    ) -> Self {
        let n = layout.len();
        let lane = lane_length(n);
        let (m, k, c) = (&layout.mass, &layout.stiffness, &layout.viscosity);
        let elements = Elements {
            mass: m,
            stiffness: k,
            viscosity: c,
            h: dt,
        };
        let u = vec![0.0; n];
        let v = vec![-impact_speed; n];
        let fused = isa.and_then(|isa| {
            let lanes = lanes::LaneLayout::new(n, elements.ghosts(n.div_ceil(lanes::LANES))?)?;
            Some(Box::new(FusedKernel {
                state: Fused::new(lanes, &u, &v, isa),
                free: elements.plan(&lanes, false),
                with_wall: elements.plan(&lanes, true),
            }))
        });
        Self {
            fused,
            u,
            v,
            mass: layout.mass.clone(),
            stiffness: k.clone(),
            viscosity: c.clone(),
            second_stage: second_stage(k, c, dt),
            dt,
            unilateral: law == WallContact::Unilateral,
            free: factor((m, k, c), dt, false, lane),
            with_wall: factor((m, k, c), dt, true, lane),
            wall_on: true,
            u_next: vec![0.0; n],
            v_next: vec![0.0; n],
            ku: vec![0.0; n],
            r: vec![0.0; n],
            v1: vec![0.0; n],
            lanes: vec![Quad::ZERO; lane],
        }
    }

    /// [`factor`] of this chain, in one piece (a part of a step).
    fn part_factor(&self, h: f64, wall: bool) -> Factor {
        factor((&self.mass, &self.stiffness, &self.viscosity), h, wall, 0)
    }

    /// Displacements now.
    pub(crate) fn displacement(&self) -> Cow<'_, [f64]> {
        match &self.fused {
            Some(f) => Cow::Owned(f.state.displacements()),
            None => Cow::Borrowed(&self.u),
        }
    }

    /// Velocities now.
    pub(crate) fn velocities(&self) -> Cow<'_, [f64]> {
        match &self.fused {
            Some(f) => Cow::Owned(f.state.velocities()),
            None => Cow::Borrowed(&self.v),
        }
    }

    /// Displacement of mass 0 now.
    pub(crate) fn u0(&self) -> f64 {
        self.fused.as_ref().map_or(self.u[0], |f| f.state.u(0))
    }

    /// Velocity of mass `j` now.
    pub(crate) fn velocity(&self, j: usize) -> f64 {
        self.fused.as_ref().map_or(self.v[j], |f| f.state.v(j))
    }

    /// One step of `dt`; returns the wall's impulse on the rod during it
    /// (upward positive).
    pub(crate) fn step(&mut self) -> f64 {
        let element = self.wall_element(self.wall_on);
        let Some(fused) = self.fused.as_mut() else {
            return self.stage_by_stage_step();
        };
        let plan = if self.wall_on {
            &fused.with_wall
        } else {
            &fused.free
        };
        let bottom = fused.state.descend(plan, self.dt);
        let impulse = wall_impulse(element, self.dt, bottom);
        let pulls = self.unilateral && self.wall_on && impulse < 0.0;
        if !pulls && (bottom.u_next < 0.0) == self.wall_on {
            fused.state.ascend(plan, self.dt);
            return impulse;
        }
        // the wall switches, or would pull: the stage-by-stage kernel takes the
        // step from the state the descending pass left untouched
        fused.state.state_into(&mut self.u, &mut self.v);
        let impulse = self.stage_by_stage_step();
        if let Some(fused) = self.fused.as_mut() {
            fused.state.set_state(&self.u, &self.v);
        }
        impulse
    }

    /// The wall element's `(k_0, c_0)`, zero while it does not act.
    fn wall_element(&self, wall: bool) -> (f64, f64) {
        let w = if wall { 1.0 } else { 0.0 };
        (w * self.stiffness[0], w * self.viscosity[0])
    }

    /// [`Self::step`] by the stage-by-stage kernel, on `u` and `v`.
    fn stage_by_stage_step(&mut self) -> f64 {
        let impulse = self.wall_step(self.dt, None);
        if (self.u_next[0] < 0.0) == self.wall_on {
            self.accept();
            return impulse;
        }
        // the wall element switched within the step: take it in two parts
        // that meet where `u_0` crossed zero
        let theta = (self.u[0] / (self.u[0] - self.u_next[0])).clamp(0.0, 1.0);
        let (before, after) = (theta * self.dt, (1.0 - theta) * self.dt);
        let mut impulse = 0.0;
        if before > 0.0 {
            impulse += self.wall_step(before, Some(self.part_factor(before, self.wall_on)));
            self.accept();
        }
        self.wall_on = !self.wall_on;
        if after > 0.0 {
            impulse += self.wall_step(after, Some(self.part_factor(after, self.wall_on)));
            self.accept();
        }
        impulse
    }

    /// A step of `h` (by `factor`, or the kept factors of `dt`) under the
    /// wall law, into `u_next`, `v_next`: the unilateral wall's step that
    /// would pull is taken again with no wall at all.
    fn wall_step(&mut self, h: f64, factor: Option<Factor>) -> f64 {
        let impulse = self.sdirk(h, self.wall_on, factor.as_ref());
        if !(self.unilateral && self.wall_on && impulse < 0.0) {
            return impulse;
        }
        let free = factor.map(|_| self.part_factor(h, false));
        self.sdirk(h, false, free.as_ref());
        0.0
    }

    /// The step just computed becomes the state.
    fn accept(&mut self) {
        std::mem::swap(&mut self.u, &mut self.u_next);
        std::mem::swap(&mut self.v, &mut self.v_next);
    }

    /// One SDIRK2 step of `h` from `u`, `v` into `u_next`, `v_next`, the
    /// wall element on or off, by `factor` (`None`: the kept one, `h =
    /// dt`); returns the wall's impulse.
    fn sdirk(&mut self, h: f64, wall: bool, factor: Option<&Factor>) -> f64 {
        let (k0, c0) = self.wall_element(wall);
        let kept = if wall { &self.with_wall } else { &self.free };
        let factor = factor.unwrap_or(kept);
        // first stage: A V1 = M v + g h K u
        let gh = GAMMA * h;
        let (m, v) = (&self.mass[..], &self.v[..]);
        forces(&self.stiffness, k0, &self.u, |j, f| {
            self.ku[j] = f;
            self.r[j] = m[j] * v[j] + gh * f;
        });
        factor.solve_into(&mut self.r, &mut self.lanes, &mut self.v1);
        let bottom_v1 = self.v1[0];
        // second stage: A V2 = M v + h K u + (1 - g) h (D + 2 g h K) V1
        let owned;
        let e = if h == self.dt {
            &self.second_stage
        } else {
            owned = second_stage(&self.stiffness, &self.viscosity, h);
            &owned
        };
        let (e0, s) = (c0 + 2.0 * gh * k0, (1.0 - GAMMA) * h);
        let ku = &self.ku[..];
        forces(e, e0, &self.v1, |j, f| {
            self.r[j] = m[j] * v[j] + h * ku[j] + s * f;
        });
        factor.solve_into(&mut self.r, &mut self.lanes, &mut self.v_next);
        let (b1, b2) = ((1.0 - GAMMA) * h, GAMMA * h);
        for (((u_next, u), v1), v2) in self
            .u_next
            .iter_mut()
            .zip(&self.u)
            .zip(&self.v1)
            .zip(&self.v_next)
        {
            *u_next = u + (b1 * v1 + b2 * v2);
        }
        let bottom = Bottom {
            u: self.u[0],
            v1: bottom_v1,
            v2: self.v_next[0],
            u_next: self.u_next[0],
        };
        wall_impulse((k0, c0), h, bottom)
    }
}

/// The wall's impulse over a step of `h` from mass 0's part of it, its
/// element `(k_0, c_0)` (zero while it does not act): the stages'
/// quadrature of its force.
fn wall_impulse((k0, c0): (f64, f64), h: f64, b: Bottom) -> f64 {
    let wall_force_1 = -(k0 * (b.u + GAMMA * h * b.v1) + c0 * b.v1);
    let wall_force_2 = -(k0 * b.u_next + c0 * b.v2);
    h * ((1.0 - GAMMA) * wall_force_1 + GAMMA * wall_force_2)
}

/// `A = M - g h D - g^2 h^2 K` of masses `m`, elements `k`, `c` (element
/// `j` below mass `j`) for a step `h`, the wall element on or off,
/// factorised in blocks of `lane` masses.
fn factor((m, k, c): (&[f64], &[f64], &[f64]), h: f64, wall: bool, lane: usize) -> Factor {
    let n = m.len();
    let (gh, g2h2) = (GAMMA * h, GAMMA * GAMMA * h * h);
    let q = |j: usize| {
        if (j == 0 && !wall) || j >= n {
            0.0
        } else {
            gh * c[j] + g2h2 * k[j]
        }
    };
    let diagonal: Vec<f64> = (0..n).map(|i| m[i] + q(i) + q(i + 1)).collect();
    let off: Vec<f64> = (0..n).map(|i| -q(i + 1)).collect();
    Factor::from_bands(&diagonal, &off, &vec![0.0; n], lane)
}

/// `c_j + 2 g h k_j`.
fn second_stage(k: &[f64], c: &[f64], h: f64) -> Vec<f64> {
    k.iter()
        .zip(c)
        .map(|(k, c)| c + 2.0 * GAMMA * h * k)
        .collect()
}

/// The elements' forces on each mass `j` for constants `s` (element `j`
/// below mass `j`, the wall element's replaced by `wall`) and
/// displacements or velocities `x`, `s_{j+1} (x_{j+1} - x_j) - s_j (x_j -
/// x_{j-1})` with the wall at `x_{-1} = 0`, each handed to `then(j, f)`,
/// which builds a stage's right-hand side from it in the same pass. The
/// inner masses go as equal-length slices, indexed within their length,
/// so the loop (with `then` inlined) compiles to packed SIMD.
#[inline(always)]
fn forces(s: &[f64], wall: f64, x: &[f64], mut then: impl FnMut(usize, f64)) {
    let n = x.len();
    if n == 1 {
        then(0, -wall * x[0]);
        return;
    }
    then(0, s[1] * (x[1] - x[0]) - wall * x[0]);
    let inner = n - 2;
    let (lo, mid, hi) = (&x[..inner], &x[1..inner + 1], &x[2..inner + 2]);
    let (below, above) = (&s[1..inner + 1], &s[2..inner + 2]);
    for j in 0..inner {
        then(
            j + 1,
            above[j] * (hi[j] - mid[j]) - below[j] * (mid[j] - lo[j]),
        );
    }
    then(n - 1, -s[n - 1] * (x[n - 1] - x[n - 2]));
}

#[cfg(test)]
mod tests;

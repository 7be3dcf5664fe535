//! A long dashpot segment's whole step in the lanes of its blocked sweeps.
//!
//! The dashpot solve sweeps a long segment as four blocks side by side, one
//! per lane of a [`Quad`] (`crate::damping::factor`). Here the segment's
//! Beeman state lives in that layout too: step `i` of the sweeps holds the
//! masses `i`, `s + i`, `2 s + i`, `3 s + i`, so a mass's neighbours are
//! the steps before and after it in every lane at once, and the whole step
//! takes two passes over the segment instead of five:
//!
//! - forward: Beeman's new accelerations and velocities (the stencil on the
//!   new positions), the right-hand side `(M + s D) v` (the stencil on
//!   those velocities) and the forward sweep, one step behind the other;
//! - backward: the backward sweep, and from its velocities the next step's
//!   positions, `u' = u + dt v + dt^2 (4 a - a_prev) / 6`: Beeman's
//!   position update needs nothing else, so a segment's positions are
//!   always one step ahead, ready when the step that needs them begins.
//!
//! No gather or scatter between the layouts, no right-hand side array, and
//! the sweeps' latency-bound recurrences get Beeman's arithmetic to overlap
//! with. Velocities are kept as `x = dt v` and accelerations as `dt^2 a /
//! 6`, so neither update multiplies by `dt` or divides by 6 (see [`Step`]).
//!
//! The block edges: above a block's last step come the next block's first
//! masses (the lanes moved down one, [`Quad::down`]), below its first step
//! the previous block's last ([`Quad::up`]), so the first and last steps'
//! velocities are computed before the loop. The segment is padded to `4 s`
//! masses by phantoms at its top (at least one): unit masses with no spring
//! and no dashpot, so `P` is the identity on them, nothing couples them to
//! the segment, and every block has `s` steps. The first phantom's position
//! holds the mass above the segment, which its top mass's spring reads; the
//! mass below the first is read from the chain (or is the wall: its spring
//! acts while `u_0 < 0`, which `k (max(u_0, 0) - u_0)` is).

use crate::damping::{Factor, GAMMA, LANES, Quad, WallFactors};
use impact_model::WallContact;

/// A step's masses' constants: springs for Beeman's stencil, masses and
/// dashpots for the right-hand side.
#[derive(Debug, Clone, Copy, Default)]
struct Coef {
    /// `dt^2 k / (6 m)` of the springs below and above (0 above the rod's
    /// top and at a phantom).
    below: Quad,
    above: Quad,
    /// `m` (1 at a phantom).
    mass: Quad,
    /// `s c` of the dashpots below and above, `s = (1 - 2 g) dt` (the wall
    /// dashpot's is set each step).
    damp_below: Quad,
    damp_above: Quad,
}

/// The state of one step's masses (one per block, in the lanes). Each pair
/// holds the quantity now and next, their roles swapped every step by the
/// parity `P` ([`Blocked::step`]): at the step being taken (from `u(n)` to
/// `u(n+1)`)
///
/// - `u[P]` is `u(n+1)` (computed a step ahead), `u[1 - P]` gets `u(n+2)`;
/// - `x[P]` is `dt v(n)` after the dashpots, then Beeman's `dt v(n+1)`
///   before them; `x[1 - P]` gets the forward sweep's `L^-1 r`, then the
///   dashpots' `dt v(n+1)` in its place;
/// - with `b = dt^2 a / 6`: `acc[P]` is `5 b(n) - b(n-1)` until the
///   forward pass puts `b(n+1)` in its place, `acc[1 - P]` is `b(n)` until
///   the backward pass puts `5 b(n+1) - b(n)` in its place.
///
/// Beeman's velocity `x + (2 b(n+1) + 5 b(n) - b(n-1))` is then two
/// additions, and its position `u + (x + 4 b(n+1) - b(n))` gives the next
/// `5 b(n+1) - b(n)` for one more.
///
/// One array of these, not seven arrays: a pass then walks one stream of
/// state (and one of the factor's), and the roles swap by the parity
/// instead of by swapping arrays; a pointer per array cost an instruction
/// per array per step. Nothing else is stored per step: the whole state of
/// a segment at `N = 10^4` fits in the core's 1 MiB L2 with the factor's.
#[derive(Debug, Clone, Copy, Default)]
struct Step {
    u: [Quad; 2],
    x: [Quad; 2],
    acc: [Quad; 2],
}

/// Beeman's new acceleration of a step's masses from positions below, at
/// and above them, `b' = dt^2 a' / 6`, and their velocity
/// `x + (2 b' + 5 b - b_prev)`, stored in place of `x` (and `b'` in place
/// of `5 b - b_prev`).
#[inline(always)]
fn beeman<const P: usize>(co: &Coef, [lo, mid, hi]: [Quad; 3], step: &mut Step) -> Quad {
    let b = co.below * (lo - mid) + co.above * (hi - mid);
    let xb = step.x[P] + ((b + b) + step.acc[P]);
    step.acc[P] = b;
    step.x[P] = xb;
    xb
}

/// The right-hand side of a step's masses,
/// `m x + s c_below (x_below - x) + s c_above (x_above - x)`: differences
/// first, which a smooth velocity field keeps small and exact.
#[inline(always)]
fn rhs(co: &Coef, [lo, mid, hi]: [Quad; 3]) -> Quad {
    co.mass * mid + co.damp_below * (lo - mid) + co.damp_above * (hi - mid)
}

/// One step of the forward sweep, `y = r - l1 y1 - l2 y2`, with `r` the
/// right-hand side of the velocities `x` below, at and above.
#[inline(always)]
fn sweep(co: &Coef, [l1, l2]: [Quad; 2], x: [Quad; 3], y1: Quad, y2: Quad) -> Quad {
    (rhs(co, x) - l2 * y2) - l1 * y1
}

/// Beeman's position update `u + (x + (4 b - b_prev))` of a step's masses
/// from the dashpots' velocities `x`, and `5 b - b_prev` for the next step
/// in place of `b_prev`.
#[inline(always)]
fn position<const P: usize>(step: &mut Step, x: Quad) {
    let b = step.acc[P];
    let d = Quad::splat(4.0) * b - step.acc[1 - P];
    step.u[1 - P] = step.u[P] + (x + d);
    step.acc[1 - P] = d + b;
}

/// [`position`] again for a step whose `x` the fix-ups changed: `5 b -
/// b_prev` is there already, and `4 b - b_prev` is found from it.
#[inline(always)]
fn position_again<const P: usize>(step: &mut Step) {
    let d = step.acc[1 - P] - step.acc[P];
    step.u[1 - P] = step.u[P] + (step.x[1 - P] + d);
}

/// The forward pass: Beeman's velocities from the positions (if
/// `with_beeman`; otherwise they are given), the right-hand side and the
/// forward sweep.
/// `below` is the position just below the segment (its spring's constant
/// is in `coef`).
fn forward<const P: usize>(
    steps: &mut [Step],
    coef: &[Coef],
    factor: &Factor,
    below: f64,
    with_beeman: bool,
) {
    let s = steps.len();
    let (coef, fwd) = (&coef[..s], &factor.forward_steps()[..s]);
    let (mut y1, mut y2) = (Quad::ZERO, Quad::ZERO);
    if !with_beeman {
        // the unilateral wall's redo: velocities given, one lane at a time
        for e in 0..s {
            let x = |i: usize| steps[i].x[P];
            let lo = if e == 0 { x(s - 1).up(0.0) } else { x(e - 1) };
            let hi = if e + 1 == s { x(0).down(0.0) } else { x(e + 1) };
            let y = sweep(&coef[e], fwd[e], [lo, x(e), hi], y1, y2);
            steps[e].x[1 - P] = y;
            (y2, y1) = (y1, y);
        }
        return;
    }
    // the first and last steps' velocities first: each block's first
    // right-hand side needs the block below's last
    let u: [Quad; 5] = [0, 1, 2, s - 2, s - 1].map(|i| steps[i].u[P]);
    let first = [u[4].up(below), u[0], u[1]];
    let last = [u[3], u[4], u[0].down(0.0)];
    let xb_first = beeman::<P>(&coef[0], first, &mut steps[0]);
    let xb_last = beeman::<P>(&coef[s - 1], last, &mut steps[s - 1]);
    let next = beeman::<P>(&coef[1], [u[0], u[1], u[2]], &mut steps[1]);
    let y = sweep(&coef[0], fwd[0], [xb_last.up(0.0), xb_first, next], y1, y2);
    steps[0].x[1 - P] = y;
    (y2, y1) = (y1, y);
    // step e's sweep beside step e + 1's velocities, e in 1..s - 2, two
    // steps a loop trip (the loop's counting and the recurrence's register
    // moves then cost half as much a step)
    let mut y = [y1, y2];
    let pairs = (s - 3) / 2;
    for pair in 0..pairs {
        let e = 1 + 2 * pair;
        y = forward_step::<P>(steps, coef, fwd, e, y);
        y = forward_step::<P>(steps, coef, fwd, e + 1, y);
    }
    if (s - 3) % 2 == 1 {
        y = forward_step::<P>(steps, coef, fwd, s - 3, y);
    }
    let [mut y1, mut y2] = y;
    // the last two steps: their velocities above are known
    for (e, next) in [(s - 2, xb_last), (s - 1, xb_first.down(0.0))] {
        let x = [steps[e - 1].x[P], steps[e].x[P], next];
        let y = sweep(&coef[e], fwd[e], x, y1, y2);
        steps[e].x[1 - P] = y;
        (y2, y1) = (y1, y);
    }
}

/// Step `e` of the forward sweep beside step `e + 1`'s Beeman velocities,
/// `y` the sweep's last two values; returns them after the step. The
/// velocities below are read back, not carried (in registers they would
/// not all fit, and spill).
#[inline(always)]
fn forward_step<const P: usize>(
    steps: &mut [Step],
    coef: &[Coef],
    fwd: &[[Quad; 2]],
    e: usize,
    [y1, y2]: [Quad; 2],
) -> [Quad; 2] {
    let stencil = [steps[e].u[P], steps[e + 1].u[P], steps[e + 2].u[P]];
    let next = beeman::<P>(&coef[e + 1], stencil, &mut steps[e + 1]);
    let x = [steps[e - 1].x[P], steps[e].x[P], next];
    let y = sweep(&coef[e], fwd[e], x, y1, y2);
    steps[e].x[1 - P] = y;
    [y, y1]
}

/// The backward sweep from `t`, its velocities into `x[1 - P]`, and from
/// them the next positions into `u[1 - P]`. `AGAIN`: the step is taken a
/// second time (the unilateral wall's redo), and the first has put
/// `5 b - b_prev` in place already.
fn backward<const P: usize, const AGAIN: bool>(steps: &mut [Step], factor: &Factor) {
    let s = steps.len();
    let (fwd, bwd) = (&factor.forward_steps()[..s], &factor.backward_steps()[..s]);
    // the forward sweep's `l1` one step up and `l2` two steps up
    let backward_step = |step: &mut Step, d: Quad, l1: Quad, l2: Quad, [z1, z2]: [Quad; 2]| {
        let z = (step.x[1 - P] * d - l2 * z2) - l1 * z1;
        step.x[1 - P] = z;
        if AGAIN {
            position_again::<P>(step);
        } else {
            position::<P>(step, z);
        }
        [z, z1]
    };
    // the top two steps (nothing above them in their blocks), then two
    // steps a loop trip, as forward
    let mut z = [Quad::ZERO; 2];
    z = backward_step(&mut steps[s - 1], bwd[s - 1], Quad::ZERO, Quad::ZERO, z);
    z = backward_step(&mut steps[s - 2], bwd[s - 2], fwd[s - 1][0], Quad::ZERO, z);
    let odd = s % 2;
    let pairs = (steps[odd..s - 2].chunks_exact_mut(2))
        .zip(bwd[odd..s - 2].chunks_exact(2))
        .zip(fwd[odd + 1..s - 1].chunks_exact(2))
        .zip(fwd[odd + 2..].chunks_exact(2));
    for (((pair, d), up1), up2) in pairs.rev() {
        z = backward_step(&mut pair[1], d[1], up1[1][0], up2[1][1], z);
        z = backward_step(&mut pair[0], d[0], up1[0][0], up2[0][1], z);
    }
    if odd == 1 {
        backward_step(&mut steps[0], bwd[0], fwd[1][0], fwd[2][1], z);
    }
    // the blocks' fix-ups, and the positions where they changed `x`
    factor.fix_backward(steps, |step| &mut step.x[1 - P], position_again::<P>);
}

/// A long run of dashpot-joined masses, stepped in the lanes of its sweeps.
#[derive(Debug, Clone)]
pub(crate) struct Blocked {
    /// The segment's first mass in the chain, and its number of masses.
    start: usize,
    len: usize,
    coef: Vec<Coef>,
    /// The padded segment's masses and dashpot constants (element `j`
    /// below mass `j`; at the wall, the wall's), for a factor built when a
    /// contact begins or ends within a step.
    mass: Vec<f64>,
    c: Vec<f64>,
    /// `P`'s factors with the wall dashpot on and off.
    factors: WallFactors,
    /// `s = (1 - 2 g) dt`, the right-hand side's dashpot factor.
    damp: f64,
    dt: f64,
    steps: Vec<Step>,
    /// Which of each [`Step`]'s pairs is now.
    parity: usize,
}

impl Blocked {
    /// Masses `start..start + len` of a chain of masses `mass`, springs
    /// `k` and dashpots `c` (element `j` below mass `j`), at rest length
    /// and moving down at `impact_speed`, stepped by `dt`; `len` must be at
    /// least `LANES * 64`, so that blocks are long enough to pay for their
    /// fix-ups.
    pub(crate) fn new(
        (mass, k, c): (&[f64], &[f64], &[f64]),
        start: usize,
        len: usize,
        dt: f64,
        impact_speed: f64,
    ) -> Self {
        let s = len / LANES + 1;
        let padded = LANES * s;
        let chain = mass.len();
        let damp = (1.0 - 2.0 * GAMMA) * dt;
        let mut coef = vec![Coef::default(); s];
        let mut pad_mass = vec![1.0; padded];
        let mut pad_c = vec![0.0; padded];
        for q in 0..padded {
            let (i, lane) = (q % s, q / s);
            let co = &mut coef[i];
            if q >= len {
                co.mass.0[lane] = 1.0;
                continue;
            }
            let j = start + q;
            let above = |x: &[f64]| if j + 1 < chain { x[j + 1] } else { 0.0 };
            co.below.0[lane] = dt * dt * k[j] / (6.0 * mass[j]);
            co.above.0[lane] = dt * dt * above(k) / (6.0 * mass[j]);
            co.mass.0[lane] = mass[j];
            co.damp_below.0[lane] = damp * c[j];
            co.damp_above.0[lane] = if q + 1 < len { damp * above(c) } else { 0.0 };
            pad_mass[q] = mass[j];
            pad_c[q] = c[j];
        }
        if start > 0 {
            // no dashpot joins the segment to the mass below
            coef[0].damp_below.0[0] = 0.0;
            pad_c[0] = 0.0;
        }
        // u(1) = u(0) + dt v(0): no force at the start; u(0) = 0
        let mut steps = vec![Step::default(); s];
        for q in 0..len {
            let step = &mut steps[q % s];
            step.u[0].0[q / s] = -dt * impact_speed;
            step.x[0].0[q / s] = -dt * impact_speed;
        }
        Self {
            start,
            len,
            coef,
            factors: WallFactors::new(&pad_mass, &pad_c, dt, s),
            mass: pad_mass,
            c: pad_c,
            damp,
            dt,
            steps,
            parity: 0,
        }
    }

    /// The segment's masses in the chain.
    pub(crate) fn masses(&self) -> std::ops::Range<usize> {
        self.start..self.start + self.len
    }

    /// Step and lane of the segment's mass `q`.
    fn at(&self, q: usize) -> (usize, usize) {
        let s = self.steps.len();
        (q % s, q / s)
    }

    /// Puts the positions of the segment's end masses at the step being
    /// taken into the chain's `next` (they were computed a step ahead):
    /// the only ones its neighbours read.
    pub(crate) fn publish(&self, next: &mut [f64]) {
        for q in [0, self.len - 1] {
            let (i, k) = self.at(q);
            next[self.start + q] = self.steps[i].u[self.parity].0[k];
        }
    }

    /// Position of the segment's mass `q` now (between steps).
    pub(crate) fn position(&self, q: usize) -> f64 {
        let (i, k) = self.at(q);
        self.steps[i].u[1 - self.parity].0[k]
    }

    /// Beeman's velocity of the segment's mass `q` now.
    pub(crate) fn velocity(&self, q: usize) -> f64 {
        let (i, k) = self.at(q);
        self.steps[i].x[self.parity].0[k] / self.dt
    }

    /// One step: Beeman's velocities at the new positions of the chain
    /// (`next`, the segment's own published), the dashpot step, the next
    /// positions. `wall` is the wall dashpot's constant for this step (0
    /// unless the segment starts at the wall), `spring_impulse` what the
    /// wall spring gave during it; returns the wall dashpot's impulse on
    /// mass 0 (upward positive) under the law `law` (see
    /// `crate::damping::Dashpots::step`).
    pub(crate) fn step(
        &mut self,
        next: &[f64],
        wall: f64,
        spring_impulse: f64,
        law: WallContact,
    ) -> f64 {
        let impulse = if self.parity == 0 {
            self.step_from::<0>(next, wall, spring_impulse, law)
        } else {
            self.step_from::<1>(next, wall, spring_impulse, law)
        };
        self.parity = 1 - self.parity;
        impulse
    }

    /// [`Blocked::step`] at the parity `P`.
    fn step_from<const P: usize>(
        &mut self,
        next: &[f64],
        wall: f64,
        spring_impulse: f64,
        law: WallContact,
    ) -> f64 {
        let (first, top) = (self.start, self.start + self.len);
        let u0 = self.steps[0].u[P].0[0];
        // the wall spring acts while compressed: k (max(u_0, 0) - u_0)
        let below = if first == 0 {
            u0.max(0.0)
        } else {
            next[first - 1]
        };
        let (i, k) = self.at(self.len);
        self.steps[i].u[P].0[k] = next.get(top).copied().unwrap_or(0.0);
        if first == 0 {
            self.coef[0].damp_below.0[0] = self.damp * wall;
        }
        let factor = self.factors.for_wall(wall, &self.mass, &self.c);
        let factor = factor.as_ref();
        let steps = &mut self.steps;
        forward::<P>(steps, &self.coef, factor, below, true);
        factor.fix_forward(steps, |step| &mut step.x[1 - P]);
        let first_stage = if wall > 0.0 {
            Self::first_stage_0::<P>(factor, steps)
        } else {
            0.0
        };
        backward::<P, false>(steps, factor);
        let v0 = steps[0].x[1 - P].0[0];
        let impulse = -wall * ((1.0 - GAMMA) * first_stage + GAMMA * v0);
        if wall == 0.0 || law == WallContact::Paper || impulse + spring_impulse >= 0.0 {
            return impulse;
        }
        // the wall would pull: the step again with no wall impulse at all
        // (`x[P]` still holds Beeman's velocities)
        self.coef[0].damp_below.0[0] = 0.0;
        steps[0].x[P].0[0] -= self.dt * spring_impulse / self.mass[0];
        forward::<P>(steps, &self.coef, &self.factors.free, below, false);
        self.factors
            .free
            .fix_forward(steps, |step| &mut step.x[1 - P]);
        backward::<P, true>(steps, &self.factors.free);
        -spring_impulse
    }

    /// `dt (A^-1 M v)_0`, the first stage's velocity of mass 0 from
    /// Beeman's velocities `x` (see `Factor::first_stage_0`).
    fn first_stage_0<const P: usize>(factor: &Factor, steps: &[Step]) -> f64 {
        let mut sum = 0.0;
        for (k, weights) in factor.first_stage_weights().chunks(steps.len()).enumerate() {
            for (w, step) in weights.iter().zip(steps) {
                sum += w * step.x[P].0[k];
            }
        }
        sum
    }
}

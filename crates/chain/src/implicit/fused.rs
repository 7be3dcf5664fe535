//! The implicit kernel's step in two passes over the chain, for long
//! chains (see [`super`] for the method).
//!
//! A step is two tridiagonal solves, each a sweep up and a sweep down,
//! plus three stencils: done one at a time, that is seven passes over the
//! chain's arrays, and the kernel was bound by moving them through the
//! cache (3.7 ns per mass-step at `N = 10^4`). Here the first stage's
//! solve goes up then down (`L D L^T`) and the second's down then up
//! (`U D' U^T`, the same matrix factorised from the top), so that:
//!
//! - the descending pass takes the first stage's downward sweep, and with
//!   each `V1` it has, the second stage's right-hand side one row above and
//!   its downward sweep;
//! - the ascending pass takes the second stage's upward sweep, the new
//!   positions and velocities, and with them the next step's first-stage
//!   right-hand side one row below and its upward sweep.
//!
//! Four arrays of rows (`u`, `v`, the sweeps' intermediate `y`, and `V1`)
//! and two passes a step. Between the passes the wall's element is known
//! (`V2_0` is the upward sweep's first value), so a step whose wall state
//! changes, or whose unilateral wall would pull, is left to the stage-by-stage
//! kernel before anything is overwritten.
//!
//! The passes are plain element-wise arithmetic on rows of
//! [`LANES`](super::lanes::LANES) doubles, compiled for the widest vector
//! instructions the processor has (`pulp` picks AVX-512, AVX2 or the
//! baseline SSE2 at run time). Every operation is a separate, correctly
//! rounded IEEE multiply, add or subtract (Rust never fuses them into
//! FMAs), so every choice gives the same bits (tested).

use super::lanes::{LaneLayout, Row};
use super::plan::{Ascent, Coefficients, Descent, Plan, Segment};
use crate::damping::GAMMA;
use pulp::{Arch, Simd, WithSimd};

/// The vector instructions a pass is compiled for.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Isa {
    /// The best this processor has.
    Detected(Arch),
    /// The baseline (SSE2 on x86-64): the tests' reference.
    #[cfg(test)]
    Baseline,
    /// AVX2 without AVX-512, where the processor has it (tests).
    #[cfg(all(test, target_arch = "x86_64"))]
    Avx2(pulp::x86::V3),
}

impl Isa {
    fn run<Op: WithSimd>(self, op: Op) -> Op::Output {
        match self {
            Isa::Detected(arch) => arch.dispatch(op),
            #[cfg(test)]
            Isa::Baseline => pulp::Scalar::new().vectorize(op),
            #[cfg(all(test, target_arch = "x86_64"))]
            Isa::Avx2(v3) => Simd::vectorize(v3, op),
        }
    }
}

/// The chain's state in blocks (see `lanes.rs`), and the sweeps' rows.
#[derive(Debug, Clone)]
pub(crate) struct Fused {
    pub(crate) layout: LaneLayout,
    pub(crate) u: Vec<Row>,
    pub(crate) v: Vec<Row>,
    /// The first stage's upward sweep of the coming step (while `primed`),
    /// then, within a step, the second stage's downward sweep.
    y: Vec<Row>,
    /// The first stage's velocities `V1`.
    w: Vec<Row>,
    /// Whether `y` holds the upward sweep for the current state and plan.
    primed: bool,
    isa: Isa,
}

/// Mass 0's part of a step, known between the passes.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Bottom {
    pub(crate) u: f64,
    pub(crate) v1: f64,
    pub(crate) v2: f64,
    pub(crate) u_next: f64,
}

impl Fused {
    /// The chain at `u`, `v` in `layout`.
    pub(crate) fn new(layout: LaneLayout, u: &[f64], v: &[f64], isa: Isa) -> Self {
        let mut fused = Self {
            layout,
            u: layout.zeros(),
            v: layout.zeros(),
            y: layout.zeros(),
            w: layout.zeros(),
            primed: false,
            isa,
        };
        fused.set_state(u, v);
        fused
    }

    /// The state is `u`, `v` (after a step the stage-by-stage kernel took).
    pub(crate) fn set_state(&mut self, u: &[f64], v: &[f64]) {
        self.layout.scatter(u, &mut self.u);
        self.layout.scatter(v, &mut self.v);
        self.primed = false;
    }

    /// The state in the chain's order.
    pub(crate) fn state_into(&self, u: &mut [f64], v: &mut [f64]) {
        self.layout.gather(&self.u, u);
        self.layout.gather(&self.v, v);
    }

    /// The step's first half, by `plan` over `h`: the descending pass (the
    /// ascending one first if the state is new), leaving the second
    /// stage's downward sweep in `y`. Returns mass 0's part of the step.
    pub(crate) fn descend(&mut self, plan: &Plan, h: f64) -> Bottom {
        let layout = self.layout;
        if !self.primed {
            self.isa.run(Prime {
                plan,
                u: &self.u,
                v: &self.v,
                y: &mut self.y,
                last: layout.ghosts + layout.rows,
            });
            layout.fill_ghosts(&mut self.y);
        }
        self.isa.run(Descend {
            plan,
            y: &mut self.y,
            w: &mut self.w,
            u: &self.u,
            v: &self.v,
            first: layout.ghosts - 1,
        });
        // the ascending pass reads both below each block and one row above
        let g = layout.ghosts;
        layout.fill_near(&mut self.y, g, 1);
        layout.fill_near(&mut self.w, g, 1);
        self.primed = false;
        // V2_0: the upward sweep's first value (U[-1][0] = 0)
        let (u, v1) = (self.u[g].0[0], self.w[g].0[0]);
        let v2 = self.y[g].0[0] * plan.bottom_inv_du;
        let (b1, b2) = ((1.0 - GAMMA) * h, GAMMA * h);
        Bottom {
            u,
            v1,
            v2,
            u_next: u + (b1 * v1 + b2 * v2),
        }
    }

    /// The step's second half: the ascending pass, which leaves the new
    /// state and the next step's upward sweep (for the same plan).
    pub(crate) fn ascend(&mut self, plan: &Plan, h: f64) {
        let layout = self.layout;
        self.isa.run(Ascend {
            plan,
            y: &mut self.y,
            w: &self.w,
            u: &mut self.u,
            v: &mut self.v,
            b: ((1.0 - GAMMA) * h, GAMMA * h),
            last: layout.ghosts + layout.rows,
        });
        // the next descending pass reads `u`, `v` and `y` above each block
        // and `u` and `y` one row below, the next ascending pass `u` below
        let g = layout.ghosts;
        layout.fill_near(&mut self.u, g, g);
        layout.fill_near(&mut self.v, 0, g);
        layout.fill_near(&mut self.y, 1, g);
        self.primed = true;
    }

    /// Displacements in the chain's order.
    pub(crate) fn displacements(&self) -> Vec<f64> {
        let mut u = vec![0.0; self.layout.n];
        self.layout.gather(&self.u, &mut u);
        u
    }

    /// Velocities in the chain's order.
    pub(crate) fn velocities(&self) -> Vec<f64> {
        let mut v = vec![0.0; self.layout.n];
        self.layout.gather(&self.v, &mut v);
        v
    }

    /// Displacement of mass `j`.
    pub(crate) fn u(&self, j: usize) -> f64 {
        self.layout.get(&self.u, j)
    }

    /// Velocity of mass `j`.
    pub(crate) fn v(&self, j: usize) -> f64 {
        self.layout.get(&self.v, j)
    }
}

/// One row of a pass, with what it carries from row to row. Always
/// inlined: the passes are compiled for the processor's vectors only
/// where they are inlined into `WithSimd::with_simd`.
trait RowStep<C> {
    /// Row `r`; `INSIDE`: the elements above and below each mass alike
    /// ([`Coefficients::Inside`]), the `below` constants unused.
    fn row<const INSIDE: bool>(&mut self, r: usize, c: &C);
}

/// Runs `op` over the stored rows `range` of `segments`, upwards or
/// (`DOWN`) downwards, with each row's coefficients. Plain loops, no
/// closures: a closure the compiler does not inline is compiled without
/// the pass's vector instructions.
#[inline(always)]
fn sweep<C: Copy, const DOWN: bool>(
    segments: &[Segment<C>],
    range: std::ops::Range<usize>,
    op: &mut impl RowStep<C>,
) {
    for k in 0..segments.len() {
        let seg = &segments[if DOWN { segments.len() - 1 - k } else { k }];
        let (start, end) = (seg.start.max(range.start), seg.end.min(range.end));
        if start >= end {
            continue;
        }
        match &seg.c {
            Coefficients::Same(c) => {
                let c = *c;
                for i in 0..end - start {
                    let r = if DOWN { end - 1 - i } else { start + i };
                    op.row::<false>(r, &c);
                }
            }
            Coefficients::Inside(c) => {
                let c = *c;
                for i in 0..end - start {
                    let r = if DOWN { end - 1 - i } else { start + i };
                    op.row::<true>(r, &c);
                }
            }
            Coefficients::ByRow(cs) => {
                for i in 0..end - start {
                    let r = if DOWN { end - 1 - i } else { start + i };
                    op.row::<false>(r, &cs[r - seg.start]);
                }
            }
        }
    }
}

/// The descending pass: at row `j`, from the top down to `first`,
/// `V1_j = y_j / d_j - L[j+1][j] V1_{j+1}`, then the second stage's
/// right-hand side at `j + 1`,
/// `r2 = m v + h K u + (1 - g) h (D + 2 g h K) V1`, and its downward sweep
/// `z_{j+1} = r2_{j+1} - U[j+1][j+2] z_{j+2}` into `y[j + 1]` (whose first
/// sweep value row `j + 1` has used).
struct Descend<'a> {
    plan: &'a Plan,
    y: &'a mut [Row],
    w: &'a mut [Row],
    u: &'a [Row],
    v: &'a [Row],
    first: usize,
}

/// What the descending pass carries: `V1` and `u` at the two rows above,
/// `z` at the row above the one it computes.
struct Descending<'a> {
    y: &'a mut [Row],
    w: &'a mut [Row],
    u: &'a [Row],
    v: &'a [Row],
    v1_1: Row,
    v1_2: Row,
    z_2: Row,
    u_1: Row,
    u_2: Row,
}

impl RowStep<Descent> for Descending<'_> {
    #[inline(always)]
    fn row<const INSIDE: bool>(&mut self, r: usize, c: &Descent) {
        let u_0 = self.u[r];
        let v1 = self.y[r] * c.inv_d - c.l_up * self.v1_1;
        let (du, dv1) = ((self.u_2 - self.u_1), (self.v1_2 - self.v1_1));
        let (ku, dv) = if INSIDE {
            (
                c.hk_above * (du - (self.u_1 - u_0)),
                c.se_above * (dv1 - (self.v1_1 - v1)),
            )
        } else {
            (
                c.hk_above * du - c.hk_below * (self.u_1 - u_0),
                c.se_above * dv1 - c.se_below * (self.v1_1 - v1),
            )
        };
        let r2 = c.mass * self.v[r + 1] + ku + dv;
        let z = r2 - c.u_up * self.z_2;
        self.w[r] = v1;
        self.y[r + 1] = z;
        (self.v1_2, self.v1_1, self.z_2) = (self.v1_1, v1, z);
        (self.u_2, self.u_1) = (self.u_1, u_0);
    }
}

impl WithSimd for Descend<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: Simd>(self, _: S) {
        let top = self.y.len() - 1;
        let mut pass = Descending {
            u_1: self.u[top],
            y: self.y,
            w: self.w,
            u: self.u,
            v: self.v,
            v1_1: Row::ZERO,
            v1_2: Row::ZERO,
            z_2: Row::ZERO,
            u_2: Row::ZERO,
        };
        sweep::<_, true>(&self.plan.descent, self.first..top, &mut pass);
    }
}

/// The ascending pass: at row `j`, from the bottom up to `last`,
/// `V2_j = z_j / d'_j - U[j-1][j] V2_{j-1}`, `u_j += (1 - g) h V1_j + g h
/// V2_j`, `v_j = V2_j`, then the next step's first right-hand side at
/// `j - 1`, `r1 = M v + g h K u`, and its upward sweep `y_{j-1} = r1_{j-1} -
/// L[j-1][j-2] y_{j-2}` into `y[j - 1]`.
struct Ascend<'a> {
    plan: &'a Plan,
    y: &'a mut [Row],
    w: &'a [Row],
    u: &'a mut [Row],
    v: &'a mut [Row],
    b: (f64, f64),
    last: usize,
}

/// What the ascending pass carries: `V2` and the new `u` at the rows
/// below, `y` at two rows below.
struct Ascending<'a> {
    y: &'a mut [Row],
    w: &'a [Row],
    u: &'a mut [Row],
    v: &'a mut [Row],
    b1: Row,
    b2: Row,
    v2_1: Row,
    un_1: Row,
    un_2: Row,
    y_2: Row,
}

impl RowStep<Ascent> for Ascending<'_> {
    #[inline(always)]
    fn row<const INSIDE: bool>(&mut self, r: usize, c: &Ascent) {
        let v2 = self.y[r] * c.inv_du - c.u_down * self.v2_1;
        let un = self.u[r] + (self.b1 * self.w[r] + self.b2 * v2);
        let ku = if INSIDE {
            c.ghk_above * ((un - self.un_1) - (self.un_1 - self.un_2))
        } else {
            c.ghk_above * (un - self.un_1) - c.ghk_below * (self.un_1 - self.un_2)
        };
        let yn = (c.mass * self.v2_1 + ku) - c.l * self.y_2;
        self.v[r] = v2;
        self.u[r] = un;
        if r >= 1 {
            self.y[r - 1] = yn;
        }
        (self.v2_1, self.un_2, self.un_1, self.y_2) = (v2, self.un_1, un, yn);
    }
}

impl WithSimd for Ascend<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: Simd>(self, _: S) {
        let (b1, b2) = self.b;
        let mut pass = Ascending {
            y: self.y,
            w: self.w,
            u: self.u,
            v: self.v,
            b1: Row::splat(b1),
            b2: Row::splat(b2),
            v2_1: Row::ZERO,
            un_1: Row::ZERO,
            un_2: Row::ZERO,
            y_2: Row::ZERO,
        };
        sweep::<_, false>(&self.plan.ascent, 0..self.last + 1, &mut pass);
    }
}

/// The ascending pass's second half alone, for a state the ascending pass
/// did not leave: the first stage's right-hand side and upward sweep. It
/// reads `u` and `v` in the ghost rows below each block, which only
/// [`Fused::set_state`] fills for `v` (the state it primes for is always
/// one set so).
struct Prime<'a> {
    plan: &'a Plan,
    u: &'a [Row],
    v: &'a [Row],
    y: &'a mut [Row],
    last: usize,
}

/// What priming carries: `v`, `u` at the rows below, `y` at two rows
/// below.
struct Priming<'a> {
    u: &'a [Row],
    v: &'a [Row],
    y: &'a mut [Row],
    v_1: Row,
    u_1: Row,
    u_2: Row,
    y_2: Row,
}

impl RowStep<Ascent> for Priming<'_> {
    #[inline(always)]
    fn row<const INSIDE: bool>(&mut self, r: usize, c: &Ascent) {
        let u_r = self.u[r];
        let ku = if INSIDE {
            c.ghk_above * ((u_r - self.u_1) - (self.u_1 - self.u_2))
        } else {
            c.ghk_above * (u_r - self.u_1) - c.ghk_below * (self.u_1 - self.u_2)
        };
        let yn = (c.mass * self.v_1 + ku) - c.l * self.y_2;
        if r >= 1 {
            self.y[r - 1] = yn;
        }
        (self.v_1, self.u_2, self.u_1, self.y_2) = (self.v[r], self.u_1, u_r, yn);
    }
}

impl WithSimd for Prime<'_> {
    type Output = ();

    #[inline(always)]
    fn with_simd<S: Simd>(self, _: S) {
        let mut pass = Priming {
            u: self.u,
            v: self.v,
            y: self.y,
            v_1: Row::ZERO,
            u_1: Row::ZERO,
            u_2: Row::ZERO,
            y_2: Row::ZERO,
        };
        sweep::<_, false>(&self.plan.ascent, 0..self.last + 1, &mut pass);
    }
}

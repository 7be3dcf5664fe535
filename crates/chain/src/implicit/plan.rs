//! What the fused kernel's two passes need at each row, computed once per
//! wall state: the two factorisations of `A = M - g h D - g^2 h^2 K`, the
//! stencils' constants, and the halo their multipliers call for.
//!
//! A step needs both an `L D L^T` factor (its sweeps go up, then down) and
//! a `U D' U^T` one (down, then up) of the same matrix: the first stage is
//! solved up-then-down and the second down-then-up, so that each sweep
//! runs in the direction the pass it shares already goes (see `fused.rs`).
//!
//! The coefficients are the same at every row inside a layer, once the
//! factors' pivots have settled a few masses from an interface or an end;
//! rows whose coefficients equal the row before's in every block are
//! gathered into one segment, so a pass keeps them in registers instead
//! of reading them from memory at every row.

use super::lanes::{LANES, LaneLayout, Row};
use crate::damping::GAMMA;

/// What a zero start leaves out of a sweep is dropped once the sweep's
/// multipliers have cut it to this fraction: far below rounding, so the
/// blocks give one solve of the whole chain's values to rounding.
pub(crate) const NEGLIGIBLE: f64 = 1e-20;

/// Coefficients of the descending pass at one row `j`: the first stage's
/// backward sweep (`V1_j`), then the second stage's right-hand side and
/// downward sweep at `j + 1`. One block's (`T = f64`) or a row's.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Descent<T = Row> {
    /// `1 / d_j` of the `L D L^T` factor.
    pub(crate) inv_d: T,
    /// `L[j+1][j]`.
    pub(crate) l_up: T,
    /// `m_{j+1}`.
    pub(crate) mass: T,
    /// `h k` of the elements above and below mass `j + 1`.
    pub(crate) hk_above: T,
    pub(crate) hk_below: T,
    /// `(1 - g) h (c + 2 g h k)` of the same two elements.
    pub(crate) se_above: T,
    pub(crate) se_below: T,
    /// `U[j+1][j+2]` of the `U D' U^T` factor.
    pub(crate) u_up: T,
}

/// Coefficients of the ascending pass at one row `j`: the second stage's
/// upward sweep (`V2_j`, the new `u_j`), then the next step's first-stage
/// right-hand side and forward sweep at `j - 1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Ascent<T = Row> {
    /// `1 / d'_j`.
    pub(crate) inv_du: T,
    /// `U[j-1][j]`.
    pub(crate) u_down: T,
    /// `m_{j-1}`.
    pub(crate) mass: T,
    /// `g h k` of the elements above and below mass `j - 1`.
    pub(crate) ghk_above: T,
    pub(crate) ghk_below: T,
    /// `L[j-1][j-2]`.
    pub(crate) l: T,
}

/// Stored rows `start..end` and their coefficients.
#[derive(Debug, Clone)]
pub(crate) struct Segment<C> {
    pub(crate) start: usize,
    pub(crate) end: usize,
    pub(crate) c: Coefficients<C>,
}

/// A segment's coefficients: one set for all its rows, or one a row (where
/// the factors' pivots are still settling).
#[derive(Debug, Clone)]
pub(crate) enum Coefficients<C> {
    Same(C),
    /// One set whose elements above and below each mass are alike (inside
    /// a layer, in every block): a stencil then takes one multiply,
    /// `k ((u_{j+1} - u_j) - (u_j - u_{j-1}))`, and a pass keeps fewer
    /// constants in registers.
    Inside(C),
    ByRow(Vec<C>),
}

/// Equal rows fewer than this go into a segment of rows apart: a
/// segment's set-up costs about what this many rows do.
const LEAST_SAME: usize = 8;

/// Both passes' segments for one wall state.
#[derive(Debug, Clone)]
pub(crate) struct Plan {
    pub(crate) descent: Vec<Segment<Descent>>,
    pub(crate) ascent: Vec<Segment<Ascent>>,
    /// Mass 0's `1 / d'`: its `V2` is the upward sweep's first value,
    /// `z_0 / d'_0`, which the step needs between the passes.
    pub(crate) bottom_inv_du: f64,
}

/// The chain's elements and the step: everything a plan is built from.
pub(crate) struct Elements<'a> {
    pub(crate) mass: &'a [f64],
    /// Element `j` below mass `j`, element 0 the wall's.
    pub(crate) stiffness: &'a [f64],
    pub(crate) viscosity: &'a [f64],
    pub(crate) h: f64,
}

/// The two factors of `A` for one wall state, by mass.
struct Factors {
    n: usize,
    /// `L[j][j-1]` (0 at `j = 0`) and `1 / d_j`.
    l: Vec<f64>,
    inv_d: Vec<f64>,
    /// `U[j][j+1]` (0 at the top) and `1 / d'_j`.
    u: Vec<f64>,
    inv_du: Vec<f64>,
}

impl Elements<'_> {
    /// Element `j`'s `(k, c)`, the wall's only while it acts, none past
    /// the chain's ends.
    fn element(&self, j: isize, wall: bool) -> (f64, f64) {
        match usize::try_from(j) {
            Ok(0) if !wall => (0.0, 0.0),
            Ok(j) if j < self.mass.len() => (self.stiffness[j], self.viscosity[j]),
            _ => (0.0, 0.0),
        }
    }

    /// `-A[j][j-1] = g h c_j + g^2 h^2 k_j`.
    fn coupling(&self, j: isize, wall: bool) -> f64 {
        let (k, c) = self.element(j, wall);
        let gh = GAMMA * self.h;
        gh * c + gh * gh * k
    }

    fn factors(&self, wall: bool) -> Factors {
        let n = self.mass.len();
        let q = |j: usize| self.coupling(j as isize, wall);
        let a = |j: usize| self.mass[j] + q(j) + q(j + 1);
        let (mut l, mut d) = (vec![0.0; n], vec![0.0; n]);
        d[0] = a(0);
        for j in 1..n {
            l[j] = -q(j) / d[j - 1];
            d[j] = a(j) + l[j] * q(j);
        }
        let (mut u, mut du) = (vec![0.0; n], vec![0.0; n]);
        du[n - 1] = a(n - 1);
        for j in (0..n - 1).rev() {
            u[j] = -q(j + 1) / du[j + 1];
            du[j] = a(j) + u[j] * q(j + 1);
        }
        Factors {
            n,
            l,
            inv_d: d.iter().map(|d| 1.0 / d).collect(),
            u,
            inv_du: du.iter().map(|d| 1.0 / d).collect(),
        }
    }

    /// Ghost rows the blocks need (`rows` own rows each): at every seam
    /// between two blocks, enough rows on either side for the sweeps'
    /// multipliers there (both factors, both wall states) to cut a zero
    /// start to [`NEGLIGIBLE`], and four more for the stencils' reach and
    /// the passes' one-row offsets. `None` if a seam needs more rows than
    /// the blocks have.
    pub(crate) fn ghosts(&self, rows: usize) -> Option<usize> {
        let n = self.mass.len();
        let factors = [self.factors(false), self.factors(true)];
        // the largest multiplier any sweep applies at mass j
        let largest = |j: usize| {
            factors
                .iter()
                .flat_map(|f| [f.l[j], f.u[j], f.l.get(j + 1).copied().unwrap_or(0.0)])
                .chain(
                    factors
                        .iter()
                        .map(|f| if j >= 1 { f.u[j - 1] } else { 0.0 }),
                )
                .fold(0.0f64, |m, x| m.max(x.abs()))
        };
        // rows from `seam` (walking by `step`) until the product is negligible
        let reach = |seam: usize, down: bool| {
            let mut product = 1.0;
            let mut j = seam;
            for taken in 0..n {
                if product <= NEGLIGIBLE {
                    return Some(taken);
                }
                product *= largest(j);
                j = if down { j.checked_sub(1)? } else { j + 1 };
                if j >= n {
                    return Some(taken + 1);
                }
            }
            None
        };
        let mut halo = 0;
        for b in 1..LANES {
            let seam = b * rows;
            if seam >= n {
                break;
            }
            let below = reach(seam - 1, true).unwrap_or(seam);
            halo = halo.max(below).max(reach(seam, false)?);
        }
        Some(halo + 4)
    }

    /// The plan for `layout`, the wall element on or off.
    pub(crate) fn plan(&self, layout: &LaneLayout, wall: bool) -> Plan {
        let f = self.factors(wall);
        let (gh, h, s) = (GAMMA * self.h, self.h, (1.0 - GAMMA) * self.h);
        let real = |j: isize| (0..f.n as isize).contains(&j);
        let at = |x: &[f64], j: isize| if real(j) { x[j as usize] } else { 0.0 };
        let hk = |j: isize| h * self.element(j, wall).0;
        let ghk = |j: isize| gh * self.element(j, wall).0;
        let se = |j: isize| {
            let (k, c) = self.element(j, wall);
            s * (c + 2.0 * GAMMA * self.h * k)
        };
        let descent = |j: isize| {
            let next = real(j + 1);
            let or_zero = |x: f64| if next { x } else { 0.0 };
            Descent {
                inv_d: at(&f.inv_d, j),
                l_up: at(&f.l, j + 1),
                mass: at(self.mass, j + 1),
                hk_above: or_zero(hk(j + 2)),
                hk_below: or_zero(hk(j + 1)),
                se_above: or_zero(se(j + 2)),
                se_below: or_zero(se(j + 1)),
                u_up: at(&f.u, j + 1),
            }
        };
        let ascent = |j: isize| {
            let below = real(j - 1);
            let or_zero = |x: f64| if below { x } else { 0.0 };
            Ascent {
                inv_du: at(&f.inv_du, j),
                u_down: if j >= 1 { at(&f.u, j - 1) } else { 0.0 },
                mass: at(self.mass, j - 1),
                ghk_above: or_zero(ghk(j)),
                ghk_below: or_zero(ghk(j - 1)),
                l: at(&f.l, j - 1),
            }
        };
        Plan {
            descent: segments(layout, descent, Descent::side_by_side, |c| {
                c.hk_above == c.hk_below && c.se_above == c.se_below
            }),
            ascent: segments(layout, ascent, Ascent::side_by_side, |c| {
                c.ghk_above == c.ghk_below
            }),
            bottom_inv_du: f.inv_du[0],
        }
    }
}

/// Rows of `layout` with their coefficients (`one` for a mass, set side by
/// side by `widen`): runs of at least [`LEAST_SAME`] equal rows in
/// segments of their own (marked [`Coefficients::Inside`] where `inside`
/// says so), the rows between them in segments of rows apart.
fn segments<C: PartialEq, W: Copy + PartialEq>(
    layout: &LaneLayout,
    one: impl Fn(isize) -> C,
    widen: fn([C; LANES]) -> W,
    inside: fn(&W) -> bool,
) -> Vec<Segment<W>> {
    // runs of equal rows: (start, end, coefficients)
    let mut runs: Vec<(usize, usize, W)> = Vec::new();
    for r in 0..layout.stored() {
        let c = widen(std::array::from_fn(|b| one(layout.mass_at(b, r))));
        match runs.last_mut() {
            Some(last) if last.2 == c => last.1 = r + 1,
            _ => runs.push((r, r + 1, c)),
        }
    }
    let mut out: Vec<Segment<W>> = Vec::new();
    for (start, end, c) in runs {
        if end - start >= LEAST_SAME {
            out.push(Segment {
                start,
                end,
                c: if inside(&c) {
                    Coefficients::Inside(c)
                } else {
                    Coefficients::Same(c)
                },
            });
            continue;
        }
        match out.last_mut() {
            Some(Segment {
                end: last_end,
                c: Coefficients::ByRow(rows),
                ..
            }) => {
                rows.extend(std::iter::repeat_n(c, end - start));
                *last_end = end;
            }
            _ => out.push(Segment {
                start,
                end,
                c: Coefficients::ByRow(vec![c; end - start]),
            }),
        }
    }
    out
}

impl Descent {
    fn side_by_side(b: [Descent<f64>; LANES]) -> Descent {
        Descent {
            inv_d: Row(b.map(|c| c.inv_d)),
            l_up: Row(b.map(|c| c.l_up)),
            mass: Row(b.map(|c| c.mass)),
            hk_above: Row(b.map(|c| c.hk_above)),
            hk_below: Row(b.map(|c| c.hk_below)),
            se_above: Row(b.map(|c| c.se_above)),
            se_below: Row(b.map(|c| c.se_below)),
            u_up: Row(b.map(|c| c.u_up)),
        }
    }
}

impl Ascent {
    fn side_by_side(b: [Ascent<f64>; LANES]) -> Ascent {
        Ascent {
            inv_du: Row(b.map(|c| c.inv_du)),
            u_down: Row(b.map(|c| c.u_down)),
            mass: Row(b.map(|c| c.mass)),
            ghk_above: Row(b.map(|c| c.ghk_above)),
            ghk_below: Row(b.map(|c| c.ghk_below)),
            l: Row(b.map(|c| c.l)),
        }
    }
}

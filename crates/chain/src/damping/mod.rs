//! Implicit Kelvin-Voigt dashpots, second order and L-stable.
//!
//! With the paper's time step, explicit dashpots are unstable as soon as they
//! matter: the stiffest chain mode decays at `4 k'/m`, and
//! `dt 4 k'/m = 8 pi N (tau c / L) / 100` is 50 for `N = 200`,
//! `tau c / L = 1`. The chain therefore splits each step: a Beeman step of the
//! springs, then a step of the dashpot flow `M v' = D v` alone, with `D` the
//! symmetric negative semi-definite, tridiagonal dashpot matrix.
//!
//! The dashpot step is the two-stage, stiffly accurate SDIRK method with
//! `g = 1 - 1/sqrt 2`:
//!
//! ```text
//! A V1 = M v,   A V2 = M v + (1 - g) h D V1,   v' = V2,   A = M - g h D,
//! ```
//!
//! second order, L-stable (the stiff grid modes decay instead of ringing, as
//! they would under Crank-Nicolson) and never adding energy:
//! `v' = R(h M^-1 D) v` with `|R(z)| <= 1` for `z <= 0`, and `M^-1 D` is
//! self-adjoint in the `M` inner product, so `|v'|_M <= |v|_M`. A Beeman
//! step followed by it is Lie splitting, which is conjugate to Strang
//! splitting and so second order as a whole (measured in
//! `tests/dt_order.rs`); backward Euler, the first build's step, made the
//! chain first order in `dt`.
//!
//! What the wall may do. Under the paper's law the wall pulls only through
//! its dashpot, the `c_0` term of `D`: its work, `-c_0 v_0^2` per unit
//! time, is never positive, so the pull dissipates and the guarantee above
//! holds with the wall included. Under the unilateral law a step in which
//! spring plus dashpot would pull is redone with no wall impulse at all.
//! Under both, the mechanical energy never rises above its start at the
//! paper's strongest dashpots (`tests/viscous.rs`, to Beeman's `O(dt^2)`
//! wobble in the elastic parts).
//!
//! Both stages share `A`, and the two solves fold into one: `v' = P^-1 (M +
//! (1 - 2g) h D) v` with `P = A M^-1 A`, symmetric positive definite and
//! pentadiagonal, factorised once (`L D L^T`) for each wall state. A solve
//! is then one forward and one backward sweep, as backward Euler's was.
//!
//! Who runs it. [`Dashpots`] steps any segment (a run of dashpot-joined
//! masses) in the chain's arrays, a long one in blocks (`Factor::solve_into`,
//! tested here against the one-piece sweep). The chain's kernel
//! (`crate::viscous`) gives it the short segments alone: a long one it
//! steps itself in the lanes of the factor's blocked sweeps, Beeman's
//! update fused with them (`crate::viscous::blocked`), with the same
//! factors, tails and wall law.

use impact_model::WallContact;
use std::ops::Range;

mod factor;
mod quad;
mod tails;

pub(crate) use factor::{Factor, WallFactors, lane_length};
pub(crate) use quad::{LANES, Quad};

/// `g = 1 - 1/sqrt(2)`, SDIRK2's diagonal coefficient.
pub(crate) const GAMMA: f64 = 1.0 - std::f64::consts::FRAC_1_SQRT_2;

/// A run of masses `start..end` of one viscous or elastic layer: equal
/// masses `m`, equal dashpots below and above each, `s c`.
#[derive(Debug, Clone, Copy)]
struct Run {
    start: usize,
    end: usize,
    m: f64,
    sc: f64,
}

/// Where the right-hand side takes one `m` and one `c` per run.
#[derive(Debug, Clone)]
struct Stencil {
    runs: Vec<Run>,
    /// The other masses (mass 0, layer edges, the top).
    edges: Vec<usize>,
}

impl Stencil {
    /// The right-hand side `r = (M + s D) v`, the wall element's dashpot
    /// `wall`. Inside a run it is `m v + s c (v_above - 2 v + v_below)` with
    /// one `m` and one `s c`: four equal-length slices and no index
    /// arithmetic, so the loop compiles to packed SIMD; the few masses where
    /// `m` or `c` change (and mass 0, the top) take the general formula.
    fn right_hand_side(
        &self,
        mass: &[f64],
        c: &[f64],
        wall: f64,
        s: f64,
        v: &[f64],
        r: &mut [f64],
    ) {
        let n = v.len();
        for run in &self.runs {
            let (start, end, m, sc) = (run.start, run.end, run.m, run.sc);
            let (lo, mid, hi) = (
                &v[start - 1..end - 1],
                &v[start..end],
                &v[start + 1..end + 1],
            );
            for (((r, &lo), &mid), &hi) in r[start..end].iter_mut().zip(lo).zip(mid).zip(hi) {
                *r = m * mid + sc * ((hi - mid) - (mid - lo));
            }
        }
        for &i in &self.edges {
            let below = if i == 0 {
                wall * v[0]
            } else {
                c[i] * (v[i] - v[i - 1])
            };
            let above = if i + 1 < n {
                c[i + 1] * (v[i + 1] - v[i])
            } else {
                0.0
            };
            r[i] = mass[i] * v[i] + s * (above - below);
        }
    }
}

/// The runs of masses joined by dashpots (element `j`, constant `c[j]`,
/// below mass `j`; `c[0]` the wall's): the masses with a dashpot below or
/// above, each run ending where no dashpot joins a mass to the next. Only
/// their velocities does a dashpot step change.
pub(crate) fn segments(c: &[f64]) -> Vec<Range<usize>> {
    let n = c.len();
    let damped = |i: usize| c[i] != 0.0 || (i + 1 < n && c[i + 1] != 0.0);
    let mut runs: Vec<Range<usize>> = Vec::new();
    for i in (0..n).filter(|&i| damped(i)) {
        match runs.last_mut() {
            Some(r) if r.end == i && c[i] != 0.0 => r.end += 1,
            _ => runs.push(i..i + 1),
        }
    }
    runs
}

/// The dashpot step over `h`.
///
/// `P` couples two masses only through a dashpot, so the chain splits into
/// segments, each a run of masses joined by dashpots, solved on its own:
/// the masses of an elastic layer away from its viscous neighbours have no
/// dashpot at all, their step is the identity, and they are not touched
/// (two thirds of the sweeps' work in a bilayer with one viscous layer of a
/// third of the rod).
#[derive(Debug, Clone)]
pub struct Dashpots {
    /// The segments and their first masses; only one starting at mass 0
    /// feels the wall.
    segments: Vec<(usize, Segment)>,
    /// The wall element's dashpot constant, `c_0`.
    wall: f64,
    /// The velocities before a step, kept in case it must be redone.
    scratch: Vec<f64>,
}

/// One run of masses joined by dashpots, factorised for the wall dashpot
/// on and off (the same factor twice unless it starts at mass 0).
#[derive(Debug, Clone)]
struct Segment {
    factors: WallFactors,
    /// Dashpot constants (element `j` below mass `j`).
    c: Vec<f64>,
    h: f64,
    stencil: Stencil,
    /// The right-hand side, then the forward sweep's `L^-1 r`.
    rhs: Vec<f64>,
    /// The blocked sweeps' lanes.
    lanes: Vec<Quad>,
}

impl Dashpots {
    /// Dashpots of constants `c[j]` (element `j` below mass `j`) over a step
    /// `h`.
    #[cfg(test)]
    pub fn new(mass: &[f64], c: &[f64], h: f64) -> Self {
        Self::on(mass, c, h, &segments(c))
    }

    /// The dashpots of the segments `on` alone (some of [`segments`]`(c)`),
    /// over a step `h`: the velocities of the other masses are left as
    /// they are.
    pub(crate) fn on(mass: &[f64], c: &[f64], h: f64, on: &[Range<usize>]) -> Self {
        Self {
            segments: on
                .iter()
                .map(|r| (r.start, Segment::new(&mass[r.clone()], &c[r.clone()], h)))
                .collect(),
            wall: if on.iter().any(|r| r.start == 0) {
                c[0]
            } else {
                0.0
            },
            scratch: vec![0.0; mass.len()],
        }
    }

    /// One SDIRK2 step on `v` with the wall dashpot's constant `wall` (`c_0`,
    /// 0, or a fraction of `c_0` for a step in which the contact begins or
    /// ends); returns the wall dashpot's impulse on mass 0 (upward positive).
    fn flow(&mut self, mass: &[f64], v: &mut [f64], wall: f64) -> f64 {
        let mut impulse = 0.0;
        for (start, segment) in &mut self.segments {
            let range = *start..*start + segment.c.len();
            let wall = if *start == 0 { wall } else { 0.0 };
            impulse += segment.flow(&mass[range.clone()], &mut v[range], wall);
        }
        impulse
    }

    /// One dashpot step. While the wall element is compressed (for the
    /// fraction `compressed` of the step) its dashpot acts on mass 0 like
    /// any other; `spring_impulse` is what the wall spring gave during the
    /// step. Under the paper's law that is all (the wall may pull through
    /// the dashpot). Under the unilateral law the wall pushes, never pulls:
    /// if spring plus dashpot would pull, the step is redone with the wall
    /// giving no impulse at all (the dashpot cancels the spring, and the rod
    /// starts to leave). Returns the dashpot's impulse on mass 0 (upward
    /// positive).
    pub fn step(
        &mut self,
        mass: &[f64],
        v: &mut [f64],
        compressed: f64,
        spring_impulse: f64,
        law: WallContact,
    ) -> f64 {
        let wall = compressed * self.wall;
        if wall == 0.0 {
            self.flow(mass, v, 0.0);
            return 0.0;
        }
        if law == WallContact::Paper {
            return self.flow(mass, v, wall);
        }
        self.scratch.copy_from_slice(v);
        let dashpot = self.flow(mass, v, wall);
        if dashpot + spring_impulse >= 0.0 {
            return dashpot;
        }
        v.copy_from_slice(&self.scratch);
        v[0] -= spring_impulse / mass[0];
        self.flow(mass, v, 0.0);
        -spring_impulse
    }
}

impl Segment {
    /// A segment of constants `c[j]` (element `j` below mass `j`, `c[0]`
    /// the wall's for the segment at mass 0, 0 for the others) over `h`.
    fn new(mass: &[f64], c: &[f64], h: f64) -> Self {
        let n = mass.len();
        let s = (1.0 - 2.0 * GAMMA) * h;
        let mut runs: Vec<Run> = Vec::new();
        let mut edges = Vec::new();
        for i in 0..n {
            if i == 0 || i + 1 == n || c[i] != c[i + 1] {
                edges.push(i);
                continue;
            }
            let (m, sc) = (mass[i], s * c[i]);
            match runs.last_mut() {
                Some(r) if r.end == i && r.m == m && r.sc == sc => r.end += 1,
                _ => runs.push(Run {
                    start: i,
                    end: i + 1,
                    m,
                    sc,
                }),
            }
        }
        let lane = lane_length(n);
        Self {
            factors: WallFactors::new(mass, c, h, lane),
            c: c.to_vec(),
            h,
            stencil: Stencil { runs, edges },
            rhs: vec![0.0; n],
            lanes: vec![Quad::ZERO; lane],
        }
    }

    /// [`Dashpots::flow`] on this segment's masses, `wall` 0 unless it
    /// starts at mass 0.
    fn flow(&mut self, mass: &[f64], v: &mut [f64], wall: f64) -> f64 {
        let factor = self.factors.for_wall(wall, mass, &self.c);
        let s = (1.0 - 2.0 * GAMMA) * self.h;
        let r = &mut self.rhs;
        (self.stencil).right_hand_side(mass, &self.c, wall, s, v, r);
        let first_stage_0 = if wall > 0.0 {
            factor.first_stage_0(v)
        } else {
            0.0
        };
        factor.solve_into(r, &mut self.lanes, v);
        -self.h * wall * ((1.0 - GAMMA) * first_stage_0 + GAMMA * v[0])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Dense Gaussian elimination, for the oracle.
    fn dense_solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Vec<f64> {
        let n = b.len();
        for k in 0..n {
            let pivot = a[k].clone();
            for i in k + 1..n {
                let f = a[i][k] / pivot[k];
                for (x, p) in a[i].iter_mut().zip(&pivot).skip(k) {
                    *x -= f * p;
                }
                b[i] -= f * b[k];
            }
        }
        let mut x = vec![0.0; n];
        for i in (0..n).rev() {
            let s: f64 = (i + 1..n).map(|j| a[i][j] * x[j]).sum();
            x[i] = (b[i] - s) / a[i][i];
        }
        x
    }

    /// The two SDIRK2 stages written out with dense matrices: the folded
    /// pentadiagonal solve and the impulse must reproduce them.
    fn two_stages(mass: &[f64], c: &[f64], h: f64, wall: f64, v: &[f64]) -> (Vec<f64>, f64) {
        let n = mass.len();
        let mut d = vec![vec![0.0; n]; n];
        d[0][0] -= wall;
        for j in 1..n {
            d[j][j] -= c[j];
            d[j - 1][j - 1] -= c[j];
            d[j][j - 1] += c[j];
            d[j - 1][j] += c[j];
        }
        let a: Vec<Vec<f64>> = (0..n)
            .map(|i| {
                (0..n)
                    .map(|j| (if i == j { mass[i] } else { 0.0 }) - GAMMA * h * d[i][j])
                    .collect()
            })
            .collect();
        let mv: Vec<f64> = v.iter().zip(mass).map(|(v, m)| v * m).collect();
        let v1 = dense_solve(a.clone(), mv.clone());
        let rhs: Vec<f64> = (0..n)
            .map(|i| mv[i] + (1.0 - GAMMA) * h * (0..n).map(|j| d[i][j] * v1[j]).sum::<f64>())
            .collect();
        let v2 = dense_solve(a, rhs);
        let impulse = -h * wall * ((1.0 - GAMMA) * v1[0] + GAMMA * v2[0]);
        (v2, impulse)
    }

    /// Every chain length from 1 to 9 in one piece, and 8 and 9 in four
    /// blocks of 2 (the last taking the rest), soft to stiff steps, the
    /// wall dashpot on, off and in part.
    #[test]
    fn the_folded_solve_is_the_two_stage_method() {
        let all_mass = [1.0, 2.0, 0.5, 1.5, 0.7, 3.0, 0.9, 1.1, 0.4];
        let all_c = [0.3, 0.7, 0.2, 1.1, 5.0, 0.05, 2.0, 0.6, 0.0];
        let all_v = [-1.0, 0.5, 2.0, -0.25, 0.1, 1.3, -0.7, 0.0, 0.9];
        for (n, lane) in (1..=all_mass.len()).map(|n| (n, 0)).chain([(8, 2), (9, 2)]) {
            let (mass, c, v0) = (&all_mass[..n], &all_c[..n], &all_v[..n]);
            for h in [0.01, 0.4, 30.0] {
                let mut d = blocked(Dashpots::new(mass, c, h), mass, h, |_| lane);
                for wall in [c[0], 0.0, 0.37 * c[0]] {
                    let mut v = v0.to_vec();
                    let impulse = d.flow(mass, &mut v, wall);
                    let (oracle, oracle_impulse) = two_stages(mass, c, h, wall, v0);
                    for (x, y) in v.iter().zip(&oracle) {
                        assert!(
                            (x - y).abs() < 1e-12,
                            "n {n}, h {h}, wall {wall}: {x} vs {y}"
                        );
                    }
                    assert!((impulse - oracle_impulse).abs() < 1e-12);
                    // the impulse is the momentum the wall took away
                    let dp: f64 = mass
                        .iter()
                        .zip(v.iter().zip(v0))
                        .map(|(m, (a, b))| m * (a - b))
                        .sum();
                    assert!((impulse - dp).abs() < 1e-12, "{impulse} vs {dp}");
                }
            }
        }
    }

    /// `d` with each segment's sweeps cut into blocks of `lane(masses)`
    /// (one piece where that is 0 or too long for the segment).
    fn blocked(mut d: Dashpots, mass: &[f64], h: f64, lane: impl Fn(usize) -> usize) -> Dashpots {
        for (start, segment) in &mut d.segments {
            let n = segment.c.len();
            let mut l = lane(n);
            if l < 2 || LANES * l > n {
                l = 0;
            }
            let m = &mass[*start..*start + n];
            segment.lanes = vec![Quad::ZERO; l];
            segment.factors = WallFactors::new(m, &segment.c, h, l);
        }
        d
    }

    /// A layered chain: per layer `(masses, m, c)`.
    fn layered(layers: &[(usize, f64, f64)]) -> (Vec<f64>, Vec<f64>) {
        let mut mass = Vec::new();
        let mut c = Vec::new();
        for &(count, m, k) in layers {
            mass.extend(std::iter::repeat_n(m, count));
            c.extend(std::iter::repeat_n(k, count));
        }
        (mass, c)
    }

    /// Long chains: the blocked sweeps give the one-piece solve's step to
    /// `1e-12` of the velocities' size while `g h c / m <= 100`, and the
    /// cut dot product the full one to `1e-13`. Stiffer, the right-hand
    /// side `(M + s D) v` is `g h c / m` times the velocities, and any two
    /// solvers of it differ by rounding times that (measured: below
    /// `5e-15 g h c / m` up to `3e8`; the paper's `tau c / L = 1` at
    /// `N = 10^4` is 180, measured `1e-14`), so the bound is
    /// `1e-14 g h c / m` there. Soft to extremely stiff dashpots, elastic
    /// layers between viscous ones, block edges inside and between layers,
    /// the wall dashpot on, off and in part.
    #[test]
    fn the_blocked_sweeps_are_the_one_piece_solve() {
        let chains = [
            layered(&[(300, 1.0, 0.5)]),
            layered(&[(257, 1.0, 20.0)]),
            layered(&[(400, 1.0, 3.0), (600, 0.05, 0.0), (1001, 2.0, 1e3)]),
            layered(&[
                (500, 0.3, 0.0),
                (700, 1.0, 1e6),
                (1500, 4.0, 0.0),
                (300, 1.0, 1e-3),
            ]),
            layered(&[(1000, 1.0, 0.0), (999, 1.0, 40.0), (1000, 0.01, 1e4)]),
            layered(&[(3000, 1.0, 1e8)]),
        ];
        let mut worst: f64 = 0.0;
        for (mass, c) in &chains {
            let n = mass.len();
            let v0: Vec<f64> = (0..n)
                .map(|i| ((i * 7919) % 101) as f64 / 50.0 - 1.0)
                .collect();
            for h in [1e-3, 0.1, 10.0] {
                let stiffness = c
                    .iter()
                    .zip(mass)
                    .fold(0.0f64, |a, (c, m)| a.max(GAMMA * h * c / m));
                let tolerance = 1e-12f64.max(1e-14 * stiffness);
                let mut one_piece = blocked(Dashpots::new(mass, c, h), mass, h, |_| 0);
                let lanes: [fn(usize) -> usize; 5] =
                    [lane_length, |_| 2, |_| 3, |_| 61, |n| n / LANES];
                for (choice, lane) in lanes.iter().enumerate() {
                    let mut blocked = blocked(Dashpots::new(mass, c, h), mass, h, lane);
                    for wall in [c[0], 0.0, 0.37 * c[0]] {
                        let mut reference = v0.clone();
                        let impulse_0 = one_piece.flow(mass, &mut reference, wall);
                        let mut v = v0.clone();
                        let impulse = blocked.flow(mass, &mut v, wall);
                        for (i, (x, y)) in v.iter().zip(&reference).enumerate() {
                            worst = worst.max((x - y).abs());
                            assert!(
                                (x - y).abs() < tolerance,
                                "n {n}, h {h}, wall {wall}, lanes {choice}, mass {i}: {x} vs {y}"
                            );
                        }
                        let scale = h * wall * mass.iter().sum::<f64>() / mass[0];
                        assert!(
                            (impulse - impulse_0).abs() <= 1e-13 * scale.max(f64::MIN_POSITIVE),
                            "{impulse} vs {impulse_0}"
                        );
                    }
                }
                // the cut dot product against the full one
                let factor = Factor::with_lane(mass, c, h, c[0].max(1.0), 0);
                let full = {
                    let mut w = vec![0.0; n];
                    let gh = GAMMA * h;
                    w[0] = (mass[0] + gh * (c[0].max(1.0) + c[1])) / mass[0];
                    w[1] = -gh * c[1] / mass[0];
                    factor.solve(&mut w);
                    w.iter()
                        .zip(mass)
                        .zip(&v0)
                        .map(|((w, m), v)| w * m * v)
                        .sum::<f64>()
                };
                let cut = factor.first_stage_0(&v0);
                assert!((cut - full).abs() <= 1e-13 * full.abs(), "{cut} vs {full}");
            }
        }
        println!("largest gap {worst:.1e} (velocities of size 1)");
    }

    /// The tridiagonal solve of the implicit chain (`A = M - g h D - g^2
    /// h^2 K`, its blocked sweeps two masses a link) against Gaussian
    /// elimination on the dense matrix: odd and even block lengths (the
    /// sweeps' single last steps), blocks of 2 and 3, a rest above the
    /// blocks or none, soft to stiff couplings (`q / m` from `1e-3` to
    /// `1e4`, where the tails run long), to `1e-12` of the solution's size.
    #[test]
    fn the_tridiagonal_sweeps_in_pairs_are_gaussian_elimination() {
        for (n, q) in [
            (8, 1e-3),
            (9, 0.5),
            (64, 3.0),
            (257, 40.0),
            (300, 1e4),
            (301, 0.2),
        ] {
            let mass: Vec<f64> = (0..n)
                .map(|i| 1.0 + ((i * 37) % 11) as f64 / 10.0)
                .collect();
            let coupling: Vec<f64> = (0..n)
                .map(|i| q * (0.5 + ((i * 53) % 7) as f64 / 7.0))
                .collect();
            // element j below mass j (element 0 the wall's), none above the top
            let above = |i: usize| if i + 1 < n { coupling[i + 1] } else { 0.0 };
            let diagonal: Vec<f64> = (0..n).map(|i| mass[i] + coupling[i] + above(i)).collect();
            let off: Vec<f64> = (0..n).map(|i| -above(i)).collect();
            let dense: Vec<Vec<f64>> = (0..n)
                .map(|i| {
                    (0..n)
                        .map(|j| match j {
                            _ if j == i => diagonal[i],
                            _ if j == i + 1 => off[i],
                            _ if j + 1 == i => off[j],
                            _ => 0.0,
                        })
                        .collect()
                })
                .collect();
            let r: Vec<f64> = (0..n)
                .map(|i| ((i * 7919) % 101) as f64 / 50.0 - 1.0)
                .collect();
            let exact = dense_solve(dense, r.clone());
            let size = exact.iter().fold(0.0f64, |a, x| a.max(x.abs()));
            for lane in [0, 2, 3, 61, 64, n / LANES] {
                if lane != 0 && (lane < 2 || LANES * lane > n) {
                    continue;
                }
                let factor = Factor::from_bands(&diagonal, &off, &vec![0.0; n], lane);
                let (mut rhs, mut t, mut x) = (r.clone(), vec![Quad::ZERO; lane], vec![0.0; n]);
                factor.solve_into(&mut rhs, &mut t, &mut x);
                for (i, (a, b)) in x.iter().zip(&exact).enumerate() {
                    assert!(
                        (a - b).abs() <= 1e-12 * size,
                        "n {n}, q {q}, lane {lane}, mass {i}: {a} vs {b}"
                    );
                }
            }
        }
    }

    #[test]
    fn never_adds_kinetic_energy_and_keeps_momentum_off_the_wall() {
        // 50 unit masses, initial velocities spread over [-6, 6]
        let mass = vec![1.0; 50];
        let c = vec![1e6; 50]; // absurdly stiff dashpots: still stable
        let mut d = Dashpots::new(&mass, &c, 0.1);
        let mut v: Vec<f64> = (0..50).map(|i| ((i * 7919) % 13) as f64 - 6.0).collect();
        let p0: f64 = v.iter().sum();
        let e0: f64 = v.iter().map(|x| x * x).sum();
        let spread0 = 12.0;
        d.step(&mass, &mut v, 0.0, 0.0, WallContact::Unilateral);
        let e1: f64 = v.iter().map(|x| x * x).sum();
        assert!(e1 <= e0);
        assert!((v.iter().sum::<f64>() - p0).abs() < 1e-6 * p0.abs().max(1.0));
        // L-stable: stiff internal dashpots leave (almost) a rigid motion
        let spread =
            v.iter().cloned().fold(f64::MIN, f64::max) - v.iter().cloned().fold(f64::MAX, f64::min);
        assert!(spread < spread0 / 100.0, "{spread}");
    }

    /// Second order on a smooth problem: two masses, one internal dashpot,
    /// against the exact decay of their relative velocity.
    #[test]
    fn is_second_order_in_the_step() {
        let (mass, c) = ([1.0, 3.0], [0.0, 2.0]);
        // relative velocity decays at c (1/m0 + 1/m1)
        let rate = c[1] * (1.0 / mass[0] + 1.0 / mass[1]);
        let error = |steps: usize| {
            let mut d = Dashpots::new(&mass, &c, 1.0 / steps as f64);
            let mut v = [1.0, 0.0];
            for _ in 0..steps {
                d.flow(&mass, &mut v, 0.0);
            }
            ((v[0] - v[1]) - (-rate).exp()).abs()
        };
        let order = (error(40) / error(80)).log2();
        assert!((1.9..2.1).contains(&order), "order {order}");
    }
}

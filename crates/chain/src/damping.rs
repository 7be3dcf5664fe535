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

use impact_model::WallContact;

/// `g = 1 - 1/sqrt(2)`, SDIRK2's diagonal coefficient.
const GAMMA: f64 = 1.0 - std::f64::consts::FRAC_1_SQRT_2;

/// `L D L^T` factors of `P = A M^-1 A`, `A = M - g h D` for one wall
/// dashpot constant, stored for streaming sweeps.
#[derive(Debug, Clone)]
struct Factor {
    /// `L[i][i-1]`, `L[i][i-2]` (forward sweep).
    l1: Vec<f64>,
    l2: Vec<f64>,
    /// `1 / D[i]`.
    inv_d: Vec<f64>,
    /// `L[i+1][i]`, `L[i+2][i]` (backward sweep).
    u1: Vec<f64>,
    u2: Vec<f64>,
    /// Two sweep steps at once (see [`forward`]): `alpha[i] = l1[i]
    /// l1[i-1] - l2[i]`, `beta[i] = l1[i] l2[i-1]`, and backward
    /// `up_a[j] = u1[j] u1[j+1] - u2[j]`, `up_b[j] = u1[j] u2[j+1]`.
    alpha: Vec<f64>,
    beta: Vec<f64>,
    up_a: Vec<f64>,
    up_b: Vec<f64>,
    /// `M A^-1 e_0`: its dot product with `v` is the first stage's velocity
    /// of mass 0, `V1_0 = (A^-1 M v)_0`, which the wall impulse needs.
    first_stage_0: Vec<f64>,
}

impl Factor {
    /// Factorises for dashpot constants `c` (element `j` below mass `j`),
    /// the wall element's replaced by `wall`, over a step `h`.
    fn new(mass: &[f64], c: &[f64], h: f64, wall: f64) -> Self {
        let n = mass.len();
        let gh = GAMMA * h;
        let below = |i: usize| if i == 0 { wall } else { c[i] };
        let above = |i: usize| if i + 1 < n { c[i + 1] } else { 0.0 };
        // A: diagonal and super-diagonal
        let a: Vec<f64> = (0..n)
            .map(|i| mass[i] + gh * (below(i) + above(i)))
            .collect();
        let b: Vec<f64> = (0..n).map(|i| -gh * above(i)).collect();
        // P = A M^-1 A: diagonal, first and second off-diagonals
        let p0: Vec<f64> = (0..n)
            .map(|i| {
                let left = if i > 0 {
                    b[i - 1] * b[i - 1] / mass[i - 1]
                } else {
                    0.0
                };
                let right = if i + 1 < n {
                    b[i] * b[i] / mass[i + 1]
                } else {
                    0.0
                };
                a[i] * a[i] / mass[i] + left + right
            })
            .collect();
        let p1: Vec<f64> = (0..n)
            .map(|i| {
                if i + 1 < n {
                    a[i] * b[i] / mass[i] + b[i] * a[i + 1] / mass[i + 1]
                } else {
                    0.0
                }
            })
            .collect();
        let p2: Vec<f64> = (0..n)
            .map(|i| {
                if i + 2 < n {
                    b[i] * b[i + 1] / mass[i + 1]
                } else {
                    0.0
                }
            })
            .collect();
        let (mut l1, mut l2, mut d) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        for i in 0..n {
            if i >= 2 {
                l2[i] = p2[i - 2] / d[i - 2];
            }
            if i >= 1 {
                let back = if i >= 2 {
                    l2[i] * l1[i - 1] * d[i - 2]
                } else {
                    0.0
                };
                l1[i] = (p1[i - 1] - back) / d[i - 1];
            }
            let d1 = if i >= 1 {
                l1[i] * l1[i] * d[i - 1]
            } else {
                0.0
            };
            let d2 = if i >= 2 {
                l2[i] * l2[i] * d[i - 2]
            } else {
                0.0
            };
            d[i] = p0[i] - d1 - d2;
        }
        let u1: Vec<f64> = (0..n)
            .map(|i| if i + 1 < n { l1[i + 1] } else { 0.0 })
            .collect();
        let u2: Vec<f64> = (0..n)
            .map(|i| if i + 2 < n { l2[i + 2] } else { 0.0 })
            .collect();
        let mut f = Self {
            alpha: (0..n)
                .map(|i| {
                    if i >= 1 {
                        l1[i] * l1[i - 1] - l2[i]
                    } else {
                        0.0
                    }
                })
                .collect(),
            beta: (0..n)
                .map(|i| if i >= 1 { l1[i] * l2[i - 1] } else { 0.0 })
                .collect(),
            up_a: (0..n)
                .map(|j| {
                    if j + 1 < n {
                        u1[j] * u1[j + 1] - u2[j]
                    } else {
                        0.0
                    }
                })
                .collect(),
            up_b: (0..n)
                .map(|j| if j + 1 < n { u1[j] * u2[j + 1] } else { 0.0 })
                .collect(),
            u1,
            u2,
            inv_d: d.iter().map(|d| 1.0 / d).collect(),
            l1,
            l2,
            first_stage_0: vec![],
        };
        // A^-1 e_0 = P^-1 A M^-1 e_0, and A^-1 is symmetric
        let mut w = vec![0.0; n];
        w[0] = a[0] / mass[0];
        if n > 1 {
            w[1] = b[0] / mass[0];
        }
        f.solve(&mut w);
        f.first_stage_0 = w.iter().zip(mass).map(|(w, m)| w * m).collect();
        f
    }

    /// Solves `P x = r` in place, one mass at a time (set-up only; the
    /// steps use the paired sweeps, checked against this in the tests).
    fn solve(&self, x: &mut [f64]) {
        let (mut y1, mut y2) = (0.0, 0.0);
        for ((x, l1), l2) in x.iter_mut().zip(&self.l1).zip(&self.l2) {
            let y = (*x - l2 * y2) - l1 * y1;
            *x = y;
            y2 = y1;
            y1 = y;
        }
        let (mut x1, mut x2) = (0.0, 0.0);
        for (((x, d), u1), u2) in x
            .iter_mut()
            .zip(&self.inv_d)
            .zip(&self.u1)
            .zip(&self.u2)
            .rev()
        {
            let z = (*x * d - u2 * x2) - u1 * x1;
            *x = z;
            x2 = x1;
            x1 = z;
        }
    }

    /// The backward sweep, two masses at a time: both of a pair depend only
    /// on the pair above, which halves the sweep's critical path.
    fn backward(&self, x: &mut [f64]) {
        let n = x.len();
        let (d, u1, u2, ua, ub) = (
            &self.inv_d[..n],
            &self.u1[..n],
            &self.u2[..n],
            &self.up_a[..n],
            &self.up_b[..n],
        );
        // z[j+1], z[j+2] above the current top j
        let (mut z1, mut z2) = (0.0, 0.0);
        let mut j = n;
        while j >= 2 {
            let (hi, lo) = (j - 1, j - 2);
            let (g_hi, g_lo) = (x[hi] * d[hi], x[lo] * d[lo]);
            let z_hi = (g_hi - u2[hi] * z2) - u1[hi] * z1;
            let z_lo = ((g_lo - u1[lo] * g_hi) + ub[lo] * z2) + ua[lo] * z1;
            x[hi] = z_hi;
            x[lo] = z_lo;
            z1 = z_lo;
            z2 = z_hi;
            j -= 2;
        }
        if j == 1 {
            x[0] = (x[0] * d[0] - u2[0] * z2) - u1[0] * z1;
        }
    }
}

/// The right-hand side `r = (M + s D) v` and the forward sweep of `P y = r`
/// in one pass over the masses (the sweep is latency-bound, so building `r`
/// alongside is nearly free); `v` holds `y` on return. With `WALL`, also
/// returns the first stage's velocity of mass 0, `(A^-1 M v)_0`.
fn forward<const WALL: bool>(
    f: &Factor,
    mass: &[f64],
    c: &[f64],
    wall: f64,
    s: f64,
    v: &mut [f64],
) -> f64 {
    let n = v.len();
    // equal lengths, stated once, so the loop runs without bounds checks
    let (mass, c, l1, l2, w) = (
        &mass[..n],
        &c[..n],
        &f.l1[..n],
        &f.l2[..n],
        &f.first_stage_0[..n],
    );
    let (alpha, beta) = (&f.alpha[..n], &f.beta[..n]);
    let mut first_stage_0 = 0.0;
    // tension below the current mass (the wall's dashpot for mass 0)
    let mut below = wall * v[0];
    // y[i-2], y[i-1]
    let (mut ya, mut yb) = (0.0, 0.0);
    let mut i = 0;
    // pairs: y[i] from y[i-2], y[i-1]; y[i+1] from the same two (the
    // recurrence substituted into itself), so a pair costs one multiply and
    // one addition on the critical path
    while i + 2 < n {
        let (v0, v1, v2) = (v[i], v[i + 1], v[i + 2]);
        let (t0, t1) = (c[i + 1] * (v1 - v0), c[i + 2] * (v2 - v1));
        let r0 = mass[i] * v0 + s * (t0 - below);
        let r1 = mass[i + 1] * v1 + s * (t1 - t0);
        let y0 = (r0 - l2[i] * ya) - l1[i] * yb;
        let y1 = ((r1 - l1[i + 1] * r0) + beta[i + 1] * ya) + alpha[i + 1] * yb;
        if WALL {
            first_stage_0 += w[i] * v0 + w[i + 1] * v1;
        }
        v[i] = y0;
        v[i + 1] = y1;
        below = t1;
        ya = y0;
        yb = y1;
        i += 2;
    }
    while i < n {
        let vi = v[i];
        let above = if i + 1 < n {
            c[i + 1] * (v[i + 1] - vi)
        } else {
            0.0
        };
        let r = mass[i] * vi + s * (above - below);
        let y = (r - l2[i] * ya) - l1[i] * yb;
        if WALL {
            first_stage_0 += w[i] * vi;
        }
        v[i] = y;
        below = above;
        ya = yb;
        yb = y;
        i += 1;
    }
    first_stage_0
}

/// The dashpot step over `h`, factorised for the wall dashpot on and off.
#[derive(Debug, Clone)]
pub struct Dashpots {
    with_wall: Factor,
    free: Factor,
    /// Dashpot constants (element `j` below mass `j`).
    c: Vec<f64>,
    h: f64,
    /// The velocities before a step, kept in case it must be redone.
    scratch: Vec<f64>,
}

impl Dashpots {
    /// Dashpots of constants `c[j]` (element `j` below mass `j`) over a step
    /// `h`.
    pub fn new(mass: &[f64], c: &[f64], h: f64) -> Self {
        Self {
            with_wall: Factor::new(mass, c, h, c[0]),
            free: Factor::new(mass, c, h, 0.0),
            c: c.to_vec(),
            h,
            scratch: vec![0.0; mass.len()],
        }
    }

    /// One SDIRK2 step on `v` with the wall dashpot's constant `wall` (`c_0`,
    /// 0, or a fraction of `c_0` for a step in which the contact begins or
    /// ends); returns the wall dashpot's impulse on mass 0 (upward positive).
    fn flow(&mut self, mass: &[f64], v: &mut [f64], wall: f64) -> f64 {
        let built;
        let factor = if wall == 0.0 {
            &self.free
        } else if wall == self.c[0] {
            &self.with_wall
        } else {
            // a contact begins or ends: rare, factorise for the occasion
            built = Factor::new(mass, &self.c, self.h, wall);
            &built
        };
        let s = (1.0 - 2.0 * GAMMA) * self.h;
        let first_stage_0 = if wall > 0.0 {
            forward::<true>(factor, mass, &self.c, wall, s, v)
        } else {
            forward::<false>(factor, mass, &self.c, 0.0, s, v)
        };
        factor.backward(v);
        -self.h * wall * ((1.0 - GAMMA) * first_stage_0 + GAMMA * v[0])
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
        let wall = compressed * self.c[0];
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

    /// Every chain length from 1 to 9 (the paired sweeps have odd and
    /// even tails), soft to stiff steps, the wall dashpot on, off and in
    /// part.
    #[test]
    fn the_folded_solve_is_the_two_stage_method() {
        let all_mass = [1.0, 2.0, 0.5, 1.5, 0.7, 3.0, 0.9, 1.1, 0.4];
        let all_c = [0.3, 0.7, 0.2, 1.1, 5.0, 0.05, 2.0, 0.6, 0.0];
        let all_v = [-1.0, 0.5, 2.0, -0.25, 0.1, 1.3, -0.7, 0.0, 0.9];
        for n in 1..=all_mass.len() {
            let (mass, c, v0) = (&all_mass[..n], &all_c[..n], &all_v[..n]);
            for h in [0.01, 0.4, 30.0] {
                let mut d = Dashpots::new(mass, c, h);
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

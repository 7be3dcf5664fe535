//! Implicit Kelvin-Voigt dashpots.
//!
//! With the paper's time step, explicit dashpots are unstable as soon as they
//! matter: the stiffest chain mode decays at `4 k'/m`, and
//! `dt 4 k'/m = 8 pi N (tau c / L) / 100` is 50 for `N = 200`,
//! `tau c / L = 1`. The chain therefore splits each step: a Beeman step of the
//! springs, then a step of the dashpots alone, backward Euler,
//! `(M - dt D) v' = M v`, with `D` the
//! symmetric negative semi-definite, tridiagonal dashpot matrix: unconditionally
//! stable, never adding energy (`|v'|_M <= |v|_M`), and exact to O(dt) on the
//! physical (smooth) modes, whose decay per step `dt tau c^2 q^2` is tiny;
//! the grid-scale modes it over-damps are over-damped physically too.

use impact_model::WallContact;

/// Backward-Euler solver for `(M - h D) v' = M v`, factorised once (Thomas
/// algorithm) for each wall state. Each solve is two sweeps of one fused
/// multiply-add per mass.
#[derive(Debug, Clone)]
pub struct Dashpots {
    /// Factorisation with the wall dashpot acting on mass 0.
    with_wall: Factor,
    /// Factorisation with mass 0 free of the wall.
    free: Factor,
    /// Wall dashpot constant `k'_0`.
    wall: f64,
    h: f64,
    /// The velocities before a solve, kept in case it must be redone.
    scratch: Vec<f64>,
}

#[derive(Debug, Clone)]
struct Factor {
    /// Sub-diagonal multipliers.
    lower: Vec<f64>,
    /// Inverse of the modified diagonal.
    inv_diag: Vec<f64>,
    /// Super-diagonal times the inverse modified diagonal.
    upper_scaled: Vec<f64>,
}

impl Factor {
    fn new(mass: &[f64], c: &[f64], h: f64, wall_active: bool) -> Self {
        let n = mass.len();
        let mut lower = vec![0.0; n];
        let mut inv_diag = vec![0.0; n];
        let upper: Vec<f64> = (0..n)
            .map(|i| if i + 1 < n { -h * c[i + 1] } else { 0.0 })
            .collect();
        let mut prev_diag = 1.0;
        for i in 0..n {
            let below = if i == 0 {
                if wall_active { c[0] } else { 0.0 }
            } else {
                c[i]
            };
            let above = if i + 1 < n { c[i + 1] } else { 0.0 };
            let mut d = mass[i] + h * (below + above);
            if i > 0 {
                let l = upper[i - 1] / prev_diag;
                lower[i] = l;
                d -= l * upper[i - 1];
            }
            inv_diag[i] = 1.0 / d;
            prev_diag = d;
        }
        let upper_scaled = upper.iter().zip(&inv_diag).map(|(u, d)| u * d).collect();
        Self {
            lower,
            inv_diag,
            upper_scaled,
        }
    }

    /// Solves in place: `v` holds the old velocities on entry, the new on exit;
    /// `impulse0` is an extra impulse on mass 0 (added to the right-hand side).
    fn solve(&self, mass: &[f64], v: &mut [f64], impulse0: f64) {
        let n = v.len();
        // forward elimination on rhs = M v (+ impulse on mass 0)
        let mut prev = 0.0;
        for i in 0..n {
            let extra = if i == 0 { impulse0 } else { 0.0 };
            let y = mass[i] * v[i] + extra - self.lower[i] * prev;
            v[i] = y;
            prev = y;
        }
        // back substitution
        let mut next = 0.0;
        for i in (0..n).rev() {
            let x = v[i] * self.inv_diag[i] - self.upper_scaled[i] * next;
            v[i] = x;
            next = x;
        }
    }
}

impl Dashpots {
    /// Dashpots of constants `c[j]` (element `j` below mass `j`) over a step
    /// `h`.
    pub fn new(mass: &[f64], c: &[f64], h: f64) -> Self {
        Self {
            with_wall: Factor::new(mass, c, h, true),
            free: Factor::new(mass, c, h, false),
            wall: c[0],
            h,
            scratch: vec![0.0; mass.len()],
        }
    }

    /// One backward-Euler step. While the wall element is compressed its
    /// dashpot acts on mass 0 like any other; `spring_impulse` is what the
    /// wall spring gave during the step. Under the paper's law that is all
    /// (the wall may pull through the dashpot). Under the unilateral law the
    /// wall pushes, never pulls: if spring plus dashpot would pull, the step
    /// is redone with the wall giving no impulse at all (the dashpot cancels
    /// the spring, and the rod starts to leave). Returns the dashpot's
    /// impulse on mass 0 (upward positive).
    pub fn step(
        &mut self,
        mass: &[f64],
        v: &mut [f64],
        compressed: bool,
        spring_impulse: f64,
        law: WallContact,
    ) -> f64 {
        if compressed && self.wall > 0.0 {
            self.scratch.copy_from_slice(v);
            self.with_wall.solve(mass, v, 0.0);
            let dashpot = -self.h * self.wall * v[0];
            if law == WallContact::Paper || dashpot + spring_impulse >= 0.0 {
                return dashpot;
            }
            v.copy_from_slice(&self.scratch);
            self.free.solve(mass, v, -spring_impulse);
            return -spring_impulse;
        }
        self.free.solve(mass, v, 0.0);
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Dense check: (M - h D) v' = M v for a small chain.
    #[test]
    fn solves_the_tridiagonal_system() {
        let mass = [1.0, 2.0, 0.5, 1.5];
        let c = [0.3, 0.7, 0.2, 1.1];
        let h = 0.4;
        let v0 = [-1.0, 0.5, 2.0, -0.25];
        for wall in [true, false] {
            let f = Factor::new(&mass, &c, h, wall);
            let mut v = v0;
            f.solve(&mass, &mut v, 0.0);
            for i in 0..4 {
                let below = if i == 0 {
                    if wall { c[0] * v[0] } else { 0.0 }
                } else {
                    c[i] * (v[i] - v[i - 1])
                };
                let above = if i < 3 {
                    c[i + 1] * (v[i + 1] - v[i])
                } else {
                    0.0
                };
                let residual = mass[i] * v[i] - h * (above - below) - mass[i] * v0[i];
                assert!(residual.abs() < 1e-12, "{wall} {i}: {residual}");
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
        d.step(&mass, &mut v, false, 0.0, WallContact::Unilateral);
        let e1: f64 = v.iter().map(|x| x * x).sum();
        assert!(e1 <= e0);
        assert!((v.iter().sum::<f64>() - p0).abs() < 1e-6 * p0.abs().max(1.0));
        // stiff internal dashpots leave (almost) a rigid motion: the slowest
        // internal mode decays by 1 / (1 + h c lambda_min) ~ 1/400 here
        let spread =
            v.iter().cloned().fold(f64::MIN, f64::max) - v.iter().cloned().fold(f64::MAX, f64::min);
        assert!(spread < spread0 / 100.0, "{spread}");
    }
}

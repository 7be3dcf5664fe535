//! The paper's closed-form results for the canonical elastic bilayer
//! (equal densities, `alpha = E2 / (E1 + E2)`, `x = L2 / L`).
//!
//! These are oracles for the engines: each function says where the paper
//! claims it holds, and the engine tests check where it really does.

use crate::bilayer::Bilayer;

/// Eq. B1: strain reflection of a front going from `P1` up into `P2`.
/// `R12 = (sqrt(a) - sqrt(1 - a)) / (sqrt(a) + sqrt(1 - a))`.
///
/// Equal moduli (`alpha = 1/2`) reflect nothing:
/// ```
/// # use impact_model::theory::r12;
/// assert!(r12(0.5).abs() < 1e-15);
/// // a soft top (small alpha) reflects a compression as a tension
/// assert!(r12(0.005) < -0.8);
/// ```
pub fn r12(alpha: f64) -> f64 {
    let (s2, s1) = (alpha.sqrt(), (1.0 - alpha).sqrt());
    (s2 - s1) / (s2 + s1)
}

/// Eq. B1: strain transmission from `P1` into `P2`.
/// `T12 = 2 (1 - a)^(3/2) / (a sqrt(1 - a) + (1 - a) sqrt(a))`.
///
/// Force continuity at the interface, `E1 (1 + R12) = E2 T12`:
/// ```
/// # use impact_model::theory::{r12, t12};
/// for a in [0.005, 0.1, 0.5, 0.9] {
///     assert!(((1.0 - a) * (1.0 + r12(a)) - a * t12(a)).abs() < 1e-12);
/// }
/// ```
pub fn t12(alpha: f64) -> f64 {
    let b = 1.0 - alpha;
    2.0 * b.powf(1.5) / (alpha * b.sqrt() + b * alpha.sqrt())
}

/// Eq. B2: `R21 = -R12`.
pub fn r21(alpha: f64) -> f64 {
    -r12(alpha)
}

/// Eq. B2: strain transmission from `P2` down into `P1`.
/// `T21 = 2 a^(3/2) / (a sqrt(1 - a) + (1 - a) sqrt(a))`.
///
/// Force continuity going down, `E2 (1 + R21) = E1 T21`:
/// ```
/// # use impact_model::theory::{r21, t21};
/// for a in [0.005, 0.1, 0.5, 0.9] {
///     assert!((a * (1.0 + r21(a)) - (1.0 - a) * t21(a)).abs() < 1e-12);
/// }
/// ```
pub fn t21(alpha: f64) -> f64 {
    let b = 1.0 - alpha;
    2.0 * alpha.powf(1.5) / (alpha * b.sqrt() + b * alpha.sqrt())
}

/// Eq. 9 and its generalisation: `x_n = n sqrt(a) / (n sqrt(a) + sqrt(1 - a))`,
/// the composition at which `t2 = n t1` (commensurate transit times).
///
/// With equal wave speeds (`alpha = 1/2`) `t2 = n t1` when `L2 = n L1`:
/// ```
/// # use impact_model::theory::x_n;
/// assert!((x_n(1, 0.5) - 0.5).abs() < 1e-15);
/// assert!((x_n(3, 0.5) - 0.75).abs() < 1e-15);
/// ```
pub fn x_n(n: u32, alpha: f64) -> f64 {
    let s = f64::from(n) * alpha.sqrt();
    s / (s + (1.0 - alpha).sqrt())
}

/// `F_k = (1 + R12 - 2 R12^(k+1)) / (1 - R12)`: the wall strain, in units of the
/// initial strain `eps_i = -v_b / c1`, between `2k t1` and `2(k+1) t1` (Eq. 10).
///
/// Before the first echo the wall strain is the impact's, `F_0 = 1`:
/// ```
/// # use impact_model::theory::f_k;
/// assert!((f_k(0, 0.3) - 1.0).abs() < 1e-15);
/// ```
pub fn f_k(k: u32, alpha: f64) -> f64 {
    let r = r12(alpha);
    (1.0 + r - 2.0 * r.powi(k as i32 + 1)) / (1.0 - r)
}

/// Slope `a_n` and intercept `b_n` of `e(x) = a_n x + b_n` on the segment where
/// `floor(t2 / t1) = n` (after Eq. 11).
pub fn central_segment(n: u32, alpha: f64) -> (f64, f64) {
    let sum: f64 = (0..=n).map(|k| f_k(k, alpha)).sum();
    let next = f_k(n + 1, alpha);
    let nf = f64::from(n);
    let a = -2.0 * sum + 2.0 * nf * next + 2.0 * next * ((1.0 - alpha) / alpha).sqrt();
    let b = -1.0 + 2.0 * sum - 2.0 * nf * next;
    (a, b)
}

/// Eq. 11: restitution in the central region, where the rod stays in contact
/// until the first wave through `P2` returns to the wall, at `t_c = 2 t1 + 2 t2`.
///
/// The paper states it for `0.1 <= alpha <~ 0.8`. It assumes that the wall
/// stays compressed until `2 t1 + 2 t2` (every `F_k >= 0`, i.e.
/// `1 + 2 R12 >= 0`, i.e. `alpha >= 0.1`) and separates then.
/// A rod with one modulus throughout is elastic and homogeneous: `e = 1`.
/// ```
/// # use impact_model::{Bilayer, theory::central_restitution};
/// let e = central_restitution(Bilayer { x: 0.3, alpha: 0.5 });
/// assert!((e - 1.0).abs() < 1e-12, "{e}");
/// ```
pub fn central_restitution(b: Bilayer) -> f64 {
    let n = b.transit_ratio().floor() as u32;
    let (a, c) = central_segment(n, b.alpha);
    a * b.x + c
}

/// Eq. 12: composition of minimum restitution in the central region, `x_1`.
pub fn x_min(alpha: f64) -> f64 {
    x_n(1, alpha)
}

/// Eq. 14: minimum restitution in the central region,
/// `e_min = 1 - 2 (sqrt(a) - F_1 sqrt(1 - a)) / (sqrt(a) + sqrt(1 - a))`.
///
/// Eq. 14 is Eq. 11 at Eq. 12's composition (two routes, one number):
/// ```
/// # use impact_model::{Bilayer, theory::{central_restitution, e_min, x_min}};
/// for alpha in [0.2, 0.4, 0.6] {
///     let at_min = central_restitution(Bilayer { x: x_min(alpha), alpha });
///     assert!((e_min(alpha) - at_min).abs() < 1e-9, "{alpha}");
/// }
/// ```
pub fn e_min(alpha: f64) -> f64 {
    let (s2, s1) = (alpha.sqrt(), (1.0 - alpha).sqrt());
    1.0 - 2.0 * (s2 - f_k(1, alpha) * s1) / (s2 + s1)
}

/// Eq. 15: restitution in the lower region (single takeoff at `2 t1`).
///
/// The stiff bottom returns at `+v_b`, the soft top still falls at `-v_b`:
/// `e = (1 - x) - x`.
/// ```
/// # use impact_model::theory::lower_restitution;
/// assert!((lower_restitution(0.25) - 0.5).abs() < 1e-15);
/// ```
pub fn lower_restitution(x: f64) -> f64 {
    1.0 - 2.0 * x
}

/// `1 + 2 R12`: the wall strain after `2 t1` in units of `eps_i`. Negative
/// (tension, so takeoff at `2 t1`) exactly when `alpha < 1/10`.
///
/// ```
/// # use impact_model::theory::wall_strain_after_first_echo;
/// assert!(wall_strain_after_first_echo(0.1).abs() < 1e-12);
/// assert!(wall_strain_after_first_echo(0.05) < 0.0 && wall_strain_after_first_echo(0.2) > 0.0);
/// ```
pub fn wall_strain_after_first_echo(alpha: f64) -> f64 {
    1.0 + 2.0 * r12(alpha)
}

/// `1 + 2 R12 - 2 T21 T12`: the wall strain after `2 t1 + 2 t2` when `x < x_1`,
/// in units of `eps_i`. Its root near `alpha = 0.82` bounds the region where the
/// rod leaves at `2 t1 + 2 t2` (Sec. VI A).
pub fn wall_strain_after_first_return(alpha: f64) -> f64 {
    1.0 + 2.0 * r12(alpha) - 2.0 * t21(alpha) * t12(alpha)
}

/// Root of [`wall_strain_after_first_return`] in `(0.5, 1)`, by bisection.
///
/// Sec. VI A's boundary, "about 0.82":
/// ```
/// # use impact_model::theory::upper_boundary_alpha;
/// assert!((upper_boundary_alpha() - 0.82).abs() < 0.01);
/// ```
pub fn upper_boundary_alpha() -> f64 {
    // f(lo) < 0 < f(hi): the strain is tensile below the root.
    crate::numerics::bisect(0.5, 0.999_999, 200, |a| {
        wall_strain_after_first_return(a) < 0.0
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn first_echo_changes_sign_at_one_tenth() {
        assert!(wall_strain_after_first_echo(0.1).abs() < 1e-15);
        assert!(wall_strain_after_first_echo(0.099) < 0.0);
        assert!(wall_strain_after_first_echo(0.101) > 0.0);
    }

    #[test]
    fn upper_boundary_is_near_0_82() {
        let a = upper_boundary_alpha();
        assert!((a - 0.82).abs() < 0.005, "{a}");
        assert!(wall_strain_after_first_return(a).abs() < 1e-12);
    }

    #[test]
    fn segment_form_equals_eq_11_sum() {
        // Eq. 11 written as the wall-strain integral, checked against a_n x + b_n.
        for &(x, alpha) in &[(0.2, 0.3), (0.7, 0.4), (0.9, 0.15)] {
            let b = Bilayer::new(x, alpha).unwrap();
            let (t1, t2) = ((1.0 - x) / (1.0 - alpha).sqrt(), x / alpha.sqrt());
            let c1 = (1.0 - alpha).sqrt();
            let n = (t2 / t1).floor() as u32;
            let eps_i = -1.0 / c1;
            let integral: f64 = (0..=n)
                .map(|k| 2.0 * t1 * f_k(k, alpha) * eps_i)
                .sum::<f64>()
                + 2.0 * (t2 - f64::from(n) * t1) * f_k(n + 1, alpha) * eps_i;
            let e = -1.0 - c1 * c1 * integral;
            assert!((e - central_restitution(b)).abs() < 1e-12);
        }
    }

    #[test]
    fn e_min_is_the_segment_value_at_x_1() {
        for alpha in [0.15, 0.3, 0.5, 0.7] {
            let (a0, b0) = central_segment(0, alpha);
            assert!((b0 - 1.0).abs() < 1e-15, "Eq. 13: b_0 = 1");
            assert!((a0 * x_min(alpha) + b0 - e_min(alpha)).abs() < 1e-14);
        }
    }
}

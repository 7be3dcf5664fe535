//! The paper's way of giving viscosity (Sec. VII): a layer's restitution
//! `e_i` is the restitution of a homogeneous rod of the whole length made of
//! that layer alone, a function of `tau c / L` only (Sec. IV).
//!
//! The map `tau c / L -> e` depends on the wall's contact law (a viscous
//! bottom under the paper's law is pulled back by the wall as it springs
//! off), so there is one table per law, tabulated once by the chain
//! (`data/calibration/kelvin-voigt-<law>.csv`, written by
//! `impact calibrate --regenerate --wall-contact <law>`, its header says
//! how) and interpolated here, monotone and piecewise linear in
//! `(ln(tau c / L), e)`; it is never re-solved during a run.

use crate::WallContact;
use std::sync::OnceLock;

/// `(tau c / L, e)` pairs, `tau c / L` increasing, `e` decreasing.
fn table(law: WallContact) -> &'static [(f64, f64)] {
    static PAPER: OnceLock<Vec<(f64, f64)>> = OnceLock::new();
    static UNILATERAL: OnceLock<Vec<(f64, f64)>> = OnceLock::new();
    match law {
        WallContact::Paper => PAPER.get_or_init(|| {
            parse(include_str!(
                "../../../data/calibration/kelvin-voigt-paper.csv"
            ))
        }),
        WallContact::Unilateral => UNILATERAL.get_or_init(|| {
            parse(include_str!(
                "../../../data/calibration/kelvin-voigt-unilateral.csv"
            ))
        }),
    }
}

/// Parses the CSV (lines starting with `#` are comments, one header line).
pub fn parse(text: &str) -> Vec<(f64, f64)> {
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .skip(1)
        .filter_map(|l| {
            let mut cells = l.split(',').map(|c| c.trim().parse::<f64>());
            match (cells.next(), cells.next()) {
                (Some(Ok(t)), Some(Ok(e))) => Some((t, e)),
                _ => None,
            }
        })
        .collect()
}

/// The table's range: the smallest restitution it reaches, and the largest
/// `tau c / L` it covers.
pub fn range(law: WallContact) -> (f64, f64) {
    let t = table(law);
    let last = t.last().copied().unwrap_or((0.0, 1.0));
    (last.1, last.0)
}

/// The tabulated points, for reports and tests.
pub fn points(law: WallContact) -> &'static [(f64, f64)] {
    table(law)
}

/// Position of `tau` on the interpolation axis: `ln(tau)`, except on the
/// first segment, which starts at `tau = 0` and is linear in `tau`.
fn segment_fraction(a: f64, b: f64, tau: f64) -> f64 {
    if a > 0.0 {
        (tau.ln() - a.ln()) / (b.ln() - a.ln())
    } else {
        (tau - a) / (b - a)
    }
}

/// Restitution of a homogeneous Kelvin-Voigt rod with this `tau c / L`, or
/// `None` outside the table. Piecewise linear in `(ln(tau c / L), e)`.
pub fn restitution(law: WallContact, tau_c_over_l: f64) -> Option<f64> {
    let t = table(law);
    if !tau_c_over_l.is_finite() {
        return None;
    }
    let i = t
        .windows(2)
        .position(|w| w[0].0 <= tau_c_over_l && tau_c_over_l <= w[1].0)?;
    let (a, b) = (t[i], t[i + 1]);
    let s = segment_fraction(a.0, b.0, tau_c_over_l);
    Some(a.1 + s * (b.1 - a.1))
}

/// The `tau c / L` that gives this restitution, or `None` outside the table:
/// the exact inverse of [`restitution`].
pub fn tau_c_over_l(law: WallContact, restitution: f64) -> Option<f64> {
    let t = table(law);
    if !restitution.is_finite() {
        return None;
    }
    let i = t
        .windows(2)
        .position(|w| w[1].1 <= restitution && restitution <= w[0].1)?;
    let (a, b) = (t[i], t[i + 1]);
    let s = if a.1 != b.1 {
        (restitution - a.1) / (b.1 - a.1)
    } else {
        0.0
    };
    Some(if a.0 > 0.0 {
        (a.0.ln() + s * (b.0.ln() - a.0.ln())).exp()
    } else {
        a.0 + s * (b.0 - a.0)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_tables_are_monotone_and_start_elastic() {
        for law in WallContact::ALL {
            let t = points(law);
            assert!(t.len() > 20);
            assert_eq!(t[0], (0.0, 1.0));
            for w in t.windows(2) {
                assert!(w[1].0 > w[0].0 && w[1].1 < w[0].1, "{law}: {w:?}");
            }
        }
    }

    #[test]
    fn round_trip() {
        for law in WallContact::ALL {
            for e in [0.99, 0.94, 0.72, 0.4, 0.1] {
                let t = tau_c_over_l(law, e).unwrap();
                assert!((restitution(law, t).unwrap() - e).abs() < 1e-12, "{e}");
            }
            for t in [0.0, 1e-4, 0.003, 0.1, 1.0] {
                let e = restitution(law, t).unwrap();
                assert!(
                    (tau_c_over_l(law, e).unwrap() - t).abs() <= 1e-12 * t.max(1e-12),
                    "{t}"
                );
            }
            assert_eq!(tau_c_over_l(law, 1.0), Some(0.0));
            assert_eq!(restitution(law, 10.0), None);
        }
        assert_eq!(tau_c_over_l(WallContact::Unilateral, 0.001), None);
    }

    /// The laws agree where the rod is nearly elastic and part where the
    /// dashpot matters (issue 11: `e(1) = 0.15` unilateral, `0.01` paper).
    #[test]
    fn the_laws_part_as_viscosity_grows() {
        let e = |law, t| restitution(law, t).unwrap();
        assert!((e(WallContact::Paper, 1e-4) - e(WallContact::Unilateral, 1e-4)).abs() < 1e-4);
        assert!(e(WallContact::Unilateral, 1.0) > 0.1);
        assert!(e(WallContact::Paper, 1.0) < 0.05);
    }
}

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
use serde::{Deserialize, Serialize, Serializer};
use std::sync::OnceLock;

/// One line of a calibration table; the field names are the CSV header.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct TableEntry {
    /// Reduced relaxation time `tau c / L` of the homogeneous Kelvin-Voigt rod.
    #[serde(serialize_with = "shortest")]
    pub tau_c_over_l: f64,
    /// Its restitution `e`, extrapolated to the continuum (`N -> infinity`).
    #[serde(serialize_with = "shortest")]
    pub restitution: f64,
    /// The size of the Richardson correction: an estimate of the error left.
    #[serde(serialize_with = "shortest")]
    pub richardson_correction: f64,
}

/// Writes a number as `Display` does (`0`, `1`, `0.0001`): the table's
/// own form, where the `csv` crate would write `0.0`, `1.0`, `1e-4`.
fn shortest<S: Serializer>(v: &f64, s: S) -> Result<S::Ok, S::Error> {
    s.collect_str(v)
}

/// Writes a calibration table: each line of `comment` prefixed with `# `
/// (what the table is, how it was made), then the header and the entries.
pub fn write_table(
    out: &mut impl std::io::Write,
    comment: &str,
    entries: &[TableEntry],
) -> std::io::Result<()> {
    for line in comment.lines() {
        writeln!(out, "# {line}")?;
    }
    impact_output::write_csv(out, entries)
}

/// Reads a calibration table: lines starting with `#` are comments, then
/// the header; a line that is not an entry is skipped.
pub fn read_table(text: &str) -> Vec<TableEntry> {
    csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .trim(csv::Trim::All)
        .from_reader(text.as_bytes())
        .deserialize()
        .filter_map(Result::ok)
        .collect()
}

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

/// The `(tau c / L, e)` pairs of a table's text (see [`read_table`]).
pub fn parse(text: &str) -> Vec<(f64, f64)> {
    read_table(text)
        .into_iter()
        .map(|e| (e.tau_c_over_l, e.restitution))
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

/// The first table segment `(a, b)` that `holds` the looked-up value, or
/// `None` outside the table or for a value that is not finite: the lookup
/// both directions of the calibration share, so that they cannot disagree
/// on which segment a value falls in.
fn segment(
    law: WallContact,
    value: f64,
    holds: impl Fn(&[(f64, f64)]) -> bool,
) -> Option<((f64, f64), (f64, f64))> {
    let t = table(law);
    if !value.is_finite() {
        return None;
    }
    let i = t.windows(2).position(holds)?;
    Some((t[i], t[i + 1]))
}

/// Restitution of a homogeneous Kelvin-Voigt rod with this `tau c / L`, or
/// `None` outside the table. Piecewise linear in `(ln(tau c / L), e)`.
pub fn restitution(law: WallContact, tau_c_over_l: f64) -> Option<f64> {
    let (a, b) = segment(law, tau_c_over_l, |w| {
        w[0].0 <= tau_c_over_l && tau_c_over_l <= w[1].0
    })?;
    let s = segment_fraction(a.0, b.0, tau_c_over_l);
    Some(a.1 + s * (b.1 - a.1))
}

/// The `tau c / L` that gives this restitution, or `None` outside the table:
/// the exact inverse of [`restitution`].
pub fn tau_c_over_l(law: WallContact, restitution: f64) -> Option<f64> {
    let (a, b) = segment(law, restitution, |w| {
        w[1].1 <= restitution && restitution <= w[0].1
    })?;
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

    /// What `impact calibrate` writes reads back, and the shipped tables
    /// are exactly what the writer writes of what they hold.
    #[test]
    fn the_writer_reproduces_the_shipped_tables() {
        for text in [
            include_str!("../../../data/calibration/kelvin-voigt-paper.csv"),
            include_str!("../../../data/calibration/kelvin-voigt-unilateral.csv"),
        ] {
            let comment: String = text
                .lines()
                .filter_map(|l| l.strip_prefix("# "))
                .map(|l| format!("{l}\n"))
                .collect();
            let entries = read_table(text);
            assert!(entries.len() > 20);
            let mut written = Vec::new();
            write_table(&mut written, &comment, &entries).unwrap();
            assert_eq!(String::from_utf8(written).unwrap(), text);
        }
        let entry = TableEntry {
            tau_c_over_l: 0.0,
            restitution: 1.0,
            richardson_correction: -1e-7,
        };
        let mut written = Vec::new();
        write_table(&mut written, "a table\nof one", &[entry]).unwrap();
        let text = String::from_utf8(written).unwrap();
        assert_eq!(
            text,
            "# a table\n# of one\ntau_c_over_l,restitution,richardson_correction\n0,1,-0.0000001\n"
        );
        assert_eq!(read_table(&text), [entry]);
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

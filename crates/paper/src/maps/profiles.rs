//! Fig. 6(b): `e(x)` at fixed `alpha` from the exact engine, with Eq. 11
//! dashed where the paper says it holds (`alpha >= 0.1`).

use crate::claim::{csv, figure};
use crate::{PaperError, exact_bilayer};
use impact_model::{Bilayer, theory};
use impact_plot::{Axis, Colour, LinePlot, Series};

/// The alphas of the profiles: Eq. 11 is compared from 0.1 up.
const PROFILE_ALPHAS: [f64; 6] = [0.005, 0.05, 0.1, 0.2, 0.3, 0.4];

/// What the profiles wrote and how far Eq. 11 is from the engine.
pub(super) struct Profiles {
    pub figure: String,
    pub data: String,
    /// Largest `|e - Eq. 11|` over the profiles with `alpha >= 0.1`.
    pub eq11_error: f64,
}

/// Runs the profiles at every `x` of `xs`, writes `fig6b.svg`, `.png` and
/// `.csv`.
pub(super) fn run(dir: &std::path::Path, xs: &[f64]) -> Result<Profiles, PaperError> {
    let palette = [
        Colour(68, 1, 84),
        Colour(59, 82, 139),
        Colour(33, 145, 140),
        Colour(94, 201, 98),
        Colour(200, 160, 20),
        Colour::RED,
    ];
    let mut series = Vec::new();
    let mut profile_rows = Vec::new();
    let mut eq11_error: f64 = 0.0;
    for (&a, &c) in PROFILE_ALPHAS.iter().zip(&palette) {
        let pts: Vec<(f64, f64)> = xs
            .iter()
            .map(|&x| Ok((x, exact_bilayer(Bilayer { x, alpha: a })?.restitution)))
            .collect::<Result<_, PaperError>>()?;
        for &(x, ev) in &pts {
            let eq = if a >= 0.1 {
                theory::central_restitution(Bilayer { x, alpha: a })
            } else {
                f64::NAN
            };
            if a >= 0.1 {
                eq11_error = eq11_error.max((ev - eq).abs());
            }
            profile_rows.push(vec![a, x, ev, eq]);
        }
        series.push(Series::line(&format!("alpha = {a}"), pts.clone(), c));
        if a >= 0.1 {
            let eq: Vec<(f64, f64)> = xs
                .iter()
                .map(|&x| (x, theory::central_restitution(Bilayer { x, alpha: a })))
                .collect();
            series
                .push(Series::line(&format!("Eq. 11, alpha = {a}"), eq, Colour(0, 0, 0)).dashed());
        }
    }
    let data = csv(dir, "fig6b", "alpha,x,e_exact,e_eq11", profile_rows)?;
    let fig6b = LinePlot {
        title: "Fig. 6(b): e(x) at fixed alpha (dashed: Eq. 11)".into(),
        x: Axis::linear(0.0, 1.0, "x"),
        y: Axis::linear(0.0, 1.05, "e"),
        series,
    };
    Ok(Profiles {
        figure: figure(dir, "fig6b", &fig6b.to_svg())?,
        data,
        eq11_error,
    })
}

//! The maps of Figs. 4(a), 4(b), 5(a) and 6(a) with their isolines, and
//! the cut of Fig. 5(b), `N_b(x)` at the smallest alpha.

use crate::PaperError;
use crate::claim::figure;
use impact_plot::{Axis, Colour, Colourmap, Heatmap, LinePlot, Series, contour};
use impact_study::Row;
use std::path::Path;

/// The grid a map is drawn on.
struct Map<'a> {
    columns: &'a [f64],
    rows: &'a [f64],
}

impl Map<'_> {
    fn heatmap(
        &self,
        title: &str,
        label: &str,
        values: Vec<f64>,
        range: (f64, f64),
        levels: &[f64],
    ) -> Heatmap {
        let overlays = levels
            .iter()
            .flat_map(|&l| contour(self.columns, self.rows, &values, l))
            .map(|seg| (seg, Colour::INK))
            .collect();
        Heatmap {
            title: title.into(),
            x_label: "x = L2 / L".into(),
            y_label: "alpha = E2 / (E1 + E2)".into(),
            columns: self.columns.to_vec(),
            rows: self.rows.to_vec(),
            values,
            colourmap: Colourmap::Sequential,
            range,
            colourbar_label: label.into(),
            categories: None,
            overlays,
        }
    }
}

/// Writes the four maps and Fig. 5(b) from the sweep's `rows` (grid order,
/// `xs` by `alphas`); returns their stems in the paper's order.
pub(super) fn maps(
    dir: &Path,
    rows: &[Row],
    xs: &[f64],
    alphas: &[f64],
) -> Result<Vec<String>, PaperError> {
    let map = Map {
        columns: xs,
        rows: alphas,
    };
    let get = |f: fn(&Row) -> Option<f64>| {
        rows.iter()
            .map(|r| f(r).unwrap_or(f64::NAN))
            .collect::<Vec<f64>>()
    };
    let tc = get(|r| r.reduced_contact_time);
    let n1 = get(|r| r.n1);
    let nb = get(|r| r.bounces.map(f64::from));
    let e = get(|r| r.restitution);
    let max_nb = nb.iter().copied().fold(0.0, f64::max);
    let mut figures = vec![
        figure(
            dir,
            "fig4a",
            &map.heatmap(
                "Fig. 4(a): t_c / (2 t1 + 2 t2)",
                "reduced contact time",
                tc.clone(),
                (0.0, 2.0),
                &[0.5, 0.75, 0.999, 1.001, 1.25, 1.5],
            )
            .to_svg(),
        )?,
        figure(
            dir,
            "fig4b",
            &map.heatmap(
                "Fig. 4(b): n1 = (t_c - 2 t2) / t1",
                "n1",
                n1.iter().map(|v| v.clamp(-2.0, 12.0)).collect(),
                (-2.0, 12.0),
                &[2.001, 3.999, 4.001, 5.999, 6.001, 7.999],
            )
            .to_svg(),
        )?,
        figure(
            dir,
            "fig5a",
            &map.heatmap(
                "Fig. 5(a): number of bounces N_b",
                "N_b",
                nb.clone(),
                (1.0, max_nb.max(2.0)),
                &[1.5, 2.5, 3.5, 4.5, 5.5],
            )
            .to_svg(),
        )?,
        figure(
            dir,
            "fig6a",
            &map.heatmap(
                "Fig. 6(a): coefficient of restitution e",
                "e",
                e.clone(),
                (0.2, 1.0),
                &[0.3, 0.5, 0.7, 0.9, 0.99],
            )
            .to_svg(),
        )?,
    ];
    figures.push(fig5b(dir, rows, alphas[0], max_nb)?);
    Ok(figures)
}

/// Fig. 5(b): `N_b` against `x` at `alpha`.
fn fig5b(dir: &Path, rows: &[Row], alpha: f64, max_nb: f64) -> Result<String, PaperError> {
    let low: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| (r.alpha - alpha).abs() < 1e-9)
        .map(|r| (r.x, r.bounces.map_or(f64::NAN, f64::from)))
        .collect();
    let plot = LinePlot {
        title: format!("Fig. 5(b): N_b vs x at alpha = {alpha}"),
        x: Axis::linear(0.0, 1.0, "x"),
        y: Axis::linear(0.0, max_nb + 1.0, "N_b"),
        series: vec![Series::line("exact", low, Colour::BLUE)],
    };
    figure(dir, "fig5b", &plot.to_svg())
}

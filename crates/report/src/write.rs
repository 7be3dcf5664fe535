//! The report directory: `report.json`, `points.csv`, heatmaps (SVG and PNG)
//! and a self-contained `index.html`.

use crate::compare::{ComparePoint, Summary, Verdict, summarize};
use impact_plot::{Category, Colour, Colourmap, Heatmap, PlotError, write_svg_and_png};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

/// The grid the points were computed on (points in order: `alpha` outer,
/// `x` inner).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReportGrid {
    pub x: Vec<f64>,
    pub alpha: Vec<f64>,
}

#[derive(Serialize)]
struct ReportJson<'a> {
    settings: &'a serde_json::Value,
    summary: &'a Summary,
    grid: &'a ReportGrid,
    points: &'a [ComparePoint],
}

fn cell<T: ToString>(v: Option<T>) -> String {
    v.map_or_else(String::new, |v| v.to_string())
}

/// One CSV line per point, at the finest chain size.
pub fn points_csv(points: &[ComparePoint]) -> String {
    let mut s = String::from(
        "x,alpha,e_exact,e_chain,de,e_extrapolated,observed_order,reduced_tc_exact,reduced_tc_chain,n1_exact,n1_chain,bounces_exact,bounces_chain,separations_exact,separations_chain,boundary_distance,verdict,error\n",
    );
    for p in points {
        let (ex, ch) = (p.exact.as_ref(), p.finest());
        let _ = writeln!(
            s,
            "{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{},{}",
            p.x,
            p.alpha,
            cell(ex.map(|o| o.restitution)),
            cell(ch.map(|o| o.restitution)),
            cell(p.de()),
            cell(p.extrapolated_restitution),
            cell(p.observed_order),
            cell(ex.map(|o| o.reduced_contact_time)),
            cell(ch.map(|o| o.reduced_contact_time)),
            cell(ex.and_then(|o| o.n1)),
            cell(ch.and_then(|o| o.n1)),
            cell(ex.map(|o| o.bounces)),
            cell(ch.map(|o| o.bounces)),
            cell(ex.map(|o| o.separations)),
            cell(ch.map(|o| o.separations)),
            cell(p.boundary_distance),
            p.verdict.name(),
            p.error
                .as_ref()
                .map_or_else(String::new, |e| format!("\"{}\"", e.replace('"', "\"\""))),
        );
    }
    s
}

/// Heatmap of the signed `e` difference at the finest size.
pub fn de_heatmap(grid: &ReportGrid, points: &[ComparePoint], n: usize) -> Heatmap {
    let values: Vec<f64> = points.iter().map(|p| p.de().unwrap_or(f64::NAN)).collect();
    let m = values
        .iter()
        .filter(|v| v.is_finite())
        .fold(0.0f64, |a, v| a.max(v.abs()))
        .max(1e-12);
    Heatmap {
        title: format!("e(chain, N = {n}) - e(exact)"),
        x_label: "x = L2 / L".into(),
        y_label: "alpha = E2 / (E1 + E2)".into(),
        columns: grid.x.clone(),
        rows: grid.alpha.clone(),
        values,
        colourmap: Colourmap::Diverging,
        range: (-m, m),
        colourbar_label: "e difference".into(),
        categories: None,
        overlays: vec![],
    }
}

/// Categorical heatmap of bounce-count agreement.
pub fn bounces_heatmap(grid: &ReportGrid, points: &[ComparePoint], n: usize) -> Heatmap {
    let values = points
        .iter()
        .map(|p| match (p.exact.as_ref(), p.finest()) {
            (Some(e), Some(c)) if e.bounces == c.bounces => 0.0,
            (Some(e), Some(c)) if c.bounces > e.bounces => 1.0,
            (Some(_), Some(_)) => 2.0,
            _ => 3.0,
        })
        .collect();
    Heatmap {
        title: format!("N_b: chain (N = {n}) vs exact"),
        x_label: "x = L2 / L".into(),
        y_label: "alpha = E2 / (E1 + E2)".into(),
        columns: grid.x.clone(),
        rows: grid.alpha.clone(),
        values,
        colourmap: Colourmap::Sequential,
        range: (0.0, 3.0),
        colourbar_label: String::new(),
        categories: Some(vec![
            Category {
                name: "equal".into(),
                colour: Colour(230, 230, 230),
            },
            Category {
                name: "chain counts more".into(),
                colour: Colour(214, 96, 77),
            },
            Category {
                name: "chain counts fewer".into(),
                colour: Colour(67, 147, 195),
            },
            Category {
                name: "failed".into(),
                colour: Colour(40, 40, 40),
            },
        ]),
        overlays: vec![],
    }
}

/// Writes the whole report into `dir` (created if needed).
pub fn write_report(
    dir: &Path,
    settings: &serde_json::Value,
    grid: &ReportGrid,
    points: &[ComparePoint],
) -> Result<Summary, PlotError> {
    std::fs::create_dir_all(dir)?;
    let summary = summarize(points);
    let json = serde_json::to_string_pretty(&ReportJson {
        settings,
        summary: &summary,
        grid,
        points,
    })
    .map_err(std::io::Error::other)?;
    std::fs::write(dir.join("report.json"), json)?;
    std::fs::write(dir.join("points.csv"), points_csv(points))?;
    let n = points
        .iter()
        .find_map(|p| p.sizes.last().copied())
        .unwrap_or(0);
    let de = de_heatmap(grid, points, n).to_svg();
    let nb = bounces_heatmap(grid, points, n).to_svg();
    write_svg_and_png(&dir.join("heatmap-de"), &de)?;
    write_svg_and_png(&dir.join("heatmap-bounces"), &nb)?;
    std::fs::write(
        dir.join("index.html"),
        crate::html::page(settings, &summary, points, &[&de, &nb]),
    )?;
    Ok(summary)
}

/// Counts of each verdict, for tables.
pub fn verdict_counts(summary: &Summary) -> Vec<(Verdict, usize)> {
    summary.verdicts.clone()
}

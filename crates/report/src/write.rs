//! The report directory: `report.json`, `points.csv`, heatmaps (SVG and PNG)
//! and a self-contained `index.html`.

use crate::compare::{ComparePoint, Summary, Verdict, summarize};
use impact_output::{Plain, ReportDir};
use impact_plot::{Category, Colour, Colourmap, Heatmap, PlotError, write_svg_and_png};
use serde::Serialize;
use std::path::Path;

/// The grid the points were computed on (points in order: `alpha` outer,
/// `x` inner).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReportGrid {
    /// The `x` values (columns of the maps).
    pub x: Vec<f64>,
    /// The `alpha` values (rows of the maps).
    pub alpha: Vec<f64>,
}

#[derive(Serialize)]
struct ReportJson<'a> {
    settings: &'a serde_json::Value,
    summary: &'a Summary,
    grid: &'a ReportGrid,
    points: &'a [ComparePoint],
}

/// One line of `points.csv`: a point at the finest chain size. Empty cells
/// where an engine failed or a quantity does not exist.
#[derive(Serialize)]
struct PointLine<'a> {
    x: Plain<f64>,
    alpha: Plain<f64>,
    e_exact: Option<Plain<f64>>,
    e_chain: Option<Plain<f64>>,
    de: Option<Plain<f64>>,
    e_extrapolated: Option<Plain<f64>>,
    observed_order: Option<Plain<f64>>,
    reduced_tc_exact: Option<Plain<f64>>,
    reduced_tc_chain: Option<Plain<f64>>,
    n1_exact: Option<Plain<f64>>,
    n1_chain: Option<Plain<f64>>,
    bounces_exact: Option<u32>,
    bounces_chain: Option<u32>,
    separations_exact: Option<u32>,
    separations_chain: Option<u32>,
    boundary_distance: Option<Plain<f64>>,
    verdict: &'a str,
    error: Option<&'a str>,
}

impl<'a> PointLine<'a> {
    fn new(p: &'a ComparePoint) -> Self {
        let (ex, ch) = (p.exact.as_ref(), p.finest());
        Self {
            x: Plain(p.x),
            alpha: Plain(p.alpha),
            e_exact: ex.map(|o| Plain(o.restitution)),
            e_chain: ch.map(|o| Plain(o.restitution)),
            de: p.de().map(Plain),
            e_extrapolated: p.extrapolated_restitution.map(Plain),
            observed_order: p.observed_order.map(Plain),
            reduced_tc_exact: ex.map(|o| Plain(o.reduced_contact_time)),
            reduced_tc_chain: ch.map(|o| Plain(o.reduced_contact_time)),
            n1_exact: ex.and_then(|o| o.n1).map(Plain),
            n1_chain: ch.and_then(|o| o.n1).map(Plain),
            bounces_exact: ex.map(|o| o.bounces),
            bounces_chain: ch.map(|o| o.bounces),
            separations_exact: ex.map(|o| o.separations),
            separations_chain: ch.map(|o| o.separations),
            boundary_distance: p.boundary_distance.map(Plain),
            verdict: p.verdict.name(),
            error: p.error.as_deref(),
        }
    }
}

/// One CSV line per point, at the finest chain size.
pub fn points_csv(points: &[ComparePoint]) -> std::io::Result<String> {
    impact_output::to_csv(points.iter().map(PointLine::new))
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

/// Writes the whole report as `target`: staged beside it and renamed into
/// place once complete, so a failed run leaves the previous report (or
/// nothing). Files of `target` the report does not write, such as the
/// run's journal, are kept.
pub fn write_report(
    target: &Path,
    settings: &serde_json::Value,
    grid: &ReportGrid,
    points: &[ComparePoint],
) -> Result<Summary, PlotError> {
    let staged = ReportDir::create(target)?;
    let dir = staged.path();
    let summary = summarize(points);
    let json = serde_json::to_string_pretty(&ReportJson {
        settings,
        summary: &summary,
        grid,
        points,
    })
    .map_err(std::io::Error::other)?;
    std::fs::write(dir.join("report.json"), json)?;
    std::fs::write(dir.join("points.csv"), points_csv(points)?)?;
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
    staged.commit()?;
    Ok(summary)
}

/// Counts of each verdict, for tables.
pub fn verdict_counts(summary: &Summary) -> Vec<(Verdict, usize)> {
    summary.verdicts.clone()
}

//! The cost report: tables, the Pareto plot, growth plots, and a page.

use crate::CostError;
use crate::chain::{ChainCost, ChainKind, ChainStudy, Headline};
use crate::exact::ExactCost;
use crate::growth::{Growth, GrowthSweep};
use impact_model::numerics::{pareto_front, power_fit};
use impact_output::{Head, Layout, ReportDir, Stylesheet, escape};
use impact_plot::{Axis, Colour, LinePlot, Marker, Scale, Series, write_svg_and_png};
use serde::Serialize;
use std::fmt::Write as _;
use std::path::Path;

/// Everything a cost study measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CostReport {
    /// Label of the rod studied.
    pub point: String,
    /// The exact engine's `e` for it: the elastic reference.
    pub exact_e: f64,
    /// The exact engine's settings and what each cost.
    pub exact: Vec<ExactCost>,
    /// The chain's settings and what each cost, elastic and viscous.
    pub chain: Vec<ChainCost>,
    /// The viscous chain's own limit `e`, the viscous reference: Richardson in
    /// `N` from the three largest sizes when they converge monotonically.
    pub viscous_limit: f64,
    /// Exact-engine work along `x` and `alpha`.
    pub growth: Vec<Growth>,
    /// The chain's cost to reach the target error, against the exact engine's.
    pub headline: Headline,
    /// Exponent of chain time against N (expected ~2: N masses times N-long
    /// runs).
    pub chain_time_exponent: f64,
    /// Exponent of mass-steps against N.
    pub chain_work_exponent: f64,
    /// The Pareto front over both engines `(seconds, error, label)`, time
    /// increasing (usually the exact engine alone: fastest and most exact).
    pub pareto: Vec<(f64, f64, String)>,
    /// The exact engine's own front: what its settings trade.
    pub pareto_exact: Vec<(f64, f64, String)>,
    /// The chain's own front: what `N` and the time step trade.
    pub pareto_chain: Vec<(f64, f64, String)>,
}

/// Errors below this are drawn at it (the exact engine's are often 0).
pub const ERROR_FLOOR: f64 = 1e-16;

impl CostReport {
    /// Assembles a report (fits and front) from the measurements.
    pub fn new(
        point: &str,
        exact_e: f64,
        exact: Vec<ExactCost>,
        chain: Vec<ChainCost>,
        viscous_limit: f64,
        growth: Vec<Growth>,
        headline: Headline,
    ) -> Self {
        let n_study: Vec<&ChainCost> = chain
            .iter()
            .filter(|c| c.kind == ChainKind::Elastic && c.study == ChainStudy::Masses)
            .collect();
        // how a measure of the elastic N study grows with N (power-law exponent)
        let growth_in_n = |measure: fn(&ChainCost) -> f64| {
            let pts: Vec<(f64, f64)> = n_study
                .iter()
                .map(|c| (c.masses as f64, measure(c)))
                .collect();
            power_fit(&pts).exponent
        };
        let chain_time_exponent = growth_in_n(|c| c.seconds);
        let chain_work_exponent = growth_in_n(|c| c.mass_steps);
        let exact_pts: Vec<(f64, f64, String)> = exact
            .iter()
            .filter(|e| e.point == point)
            .map(|e| {
                (
                    e.seconds,
                    e.restitution_error.max(ERROR_FLOOR),
                    format!(
                        "exact, drop {:e}, merge {:e}",
                        e.drop_tolerance, e.merge_window
                    ),
                )
            })
            .collect();
        let chain_pts: Vec<(f64, f64, String)> = chain
            .iter()
            .filter(|c| c.kind == ChainKind::Elastic)
            .map(|c| {
                (
                    c.seconds,
                    c.restitution_error.max(ERROR_FLOOR),
                    format!("chain, N = {}, dt x {}", c.masses, c.dt_factor),
                )
            })
            .collect();
        let all: Vec<_> = exact_pts.iter().chain(&chain_pts).cloned().collect();
        Self {
            point: point.into(),
            exact_e,
            pareto: pareto_front(&all),
            pareto_exact: pareto_front(&exact_pts),
            pareto_chain: pareto_front(&chain_pts),
            exact,
            chain,
            viscous_limit,
            growth,
            headline,
            chain_time_exponent,
            chain_work_exponent,
        }
    }
}

/// Writes `rows` as `dir/name`, columns in the order the row type
/// declares its fields.
fn table<T: Serialize>(dir: &Path, name: &str, rows: &[T]) -> Result<(), CostError> {
    std::fs::write(dir.join(name), impact_output::to_csv(rows)?)?;
    Ok(())
}

/// Writes the report as `target`: `cost.json`, CSV tables, figures,
/// `index.html`, staged beside it and renamed into place once complete.
pub fn write_report(target: &Path, r: &CostReport) -> Result<(), CostError> {
    let staged = ReportDir::create(target)?;
    let dir = staged.path();
    std::fs::write(
        dir.join("cost.json"),
        serde_json::to_string_pretty(r).map_err(std::io::Error::other)?,
    )?;
    table(dir, "exact.csv", &r.exact)?;
    table(dir, "chain.csv", &r.chain)?;
    table(dir, "growth.csv", &r.growth)?;
    let blue = Colour::BLUE;
    let red = Colour::RED;
    let orange = Colour(230, 150, 30);
    let green = Colour(26, 152, 80);
    let grey = Colour(90, 90, 90);
    let mine = |f: &dyn Fn(&ChainCost) -> bool| {
        r.chain
            .iter()
            .filter(|c| f(c))
            .map(|c| (c.seconds, c.restitution_error.max(ERROR_FLOOR)))
            .collect::<Vec<_>>()
    };
    let exact_pts: Vec<(f64, f64)> = r
        .exact
        .iter()
        .filter(|e| e.point == r.point)
        .map(|e| (e.seconds, e.restitution_error.max(ERROR_FLOOR)))
        .collect();
    let all_pts: Vec<(f64, f64)> = exact_pts
        .iter()
        .copied()
        .chain(
            r.chain
                .iter()
                .map(|c| (c.seconds, c.restitution_error.max(ERROR_FLOOR))),
        )
        .collect();
    // one series per chain study, named and styled by what it varied: the N
    // studies are convergence paths (joined), the dt study a scatter, and
    // squares set apart what is not a plain run at the paper's step
    let purple = Colour(118, 42, 131);
    let chain_series = [
        (ChainKind::Elastic, ChainStudy::Masses, red),
        (ChainKind::Elastic, ChainStudy::TimeStep, orange),
        (ChainKind::Viscous, ChainStudy::Masses, green),
        (ChainKind::Viscous, ChainStudy::Extrapolated, purple),
    ]
    .map(|(kind, study, colour)| {
        let (varied, line, marker) = match study {
            ChainStudy::Masses => ("N varied", true, Marker::Circle),
            ChainStudy::TimeStep => ("dt varied", false, Marker::Square),
            ChainStudy::Extrapolated => ("extrapolated", true, Marker::Square),
        };
        let points = mine(&|c| c.kind == kind && c.study == study);
        Series {
            line,
            marker,
            ..Series::markers(&format!("chain, {varied} ({kind})"), points, colour)
        }
    });
    let pareto = LinePlot {
        title: format!("Error in e vs time per impact, {}", r.point),
        x: Axis::fit(
            all_pts.iter().map(|p| p.0),
            Scale::Log,
            "seconds per impact",
            0.1,
        ),
        y: Axis::fit(
            all_pts.iter().map(|p| p.1),
            Scale::Log,
            "|e - e_ref| (floor 1e-16)",
            0.1,
        ),
        series: [Series::markers(
            "exact engine (tolerances)",
            exact_pts.clone(),
            blue,
        )]
        .into_iter()
        .chain(chain_series)
        .chain([
            Series::line(
                "chain's Pareto front",
                r.pareto_chain.iter().map(|p| (p.0, p.1)).collect(),
                grey,
            )
            .dashed(),
            Series::line(
                "exact engine's Pareto front",
                r.pareto_exact.iter().map(|p| (p.0, p.1)).collect(),
                blue,
            )
            .dashed(),
        ])
        .collect(),
    };
    write_svg_and_png(&dir.join("pareto"), &pareto.to_svg())?;
    let points: Vec<String> = {
        let mut p: Vec<String> = r.exact.iter().map(|e| e.point.clone()).collect();
        p.dedup();
        p
    };
    let palette = [blue, red, green, orange];
    let tol = LinePlot {
        title: "Exact engine: error and events vs drop tolerance".into(),
        x: Axis::log(1e-17, 1e-3, "drop tolerance (velocity jump / v_b)"),
        y: Axis::fit(
            r.exact
                .iter()
                .map(|e| e.restitution_error.max(ERROR_FLOOR))
                .chain(r.exact.iter().map(|e| e.events as f64)),
            Scale::Log,
            "|de| and events",
            0.1,
        ),
        series: points
            .iter()
            .enumerate()
            .flat_map(|(i, p)| {
                let rows: Vec<&ExactCost> = r
                    .exact
                    .iter()
                    .filter(|e| &e.point == p && e.merge_window == 0.0 && e.drop_tolerance > 0.0)
                    .collect();
                let mut err = Series::markers(
                    &format!("|de|, {p}"),
                    rows.iter()
                        .map(|e| (e.drop_tolerance, e.restitution_error.max(ERROR_FLOOR)))
                        .collect(),
                    palette[i % 4],
                );
                err.line = true;
                let ev = Series::line(
                    &format!("events, {p}"),
                    rows.iter()
                        .map(|e| (e.drop_tolerance, e.events as f64))
                        .collect(),
                    palette[i % 4],
                )
                .dashed();
                [err, ev]
            })
            .collect(),
    };
    write_svg_and_png(&dir.join("tolerance"), &tol.to_svg())?;
    let n_rows: Vec<&ChainCost> = r
        .chain
        .iter()
        .filter(|c| c.kind == ChainKind::Elastic && c.study == ChainStudy::Masses)
        .collect();
    let growth = LinePlot {
        title: format!(
            "Chain cost vs N: time ~ N^{:.2}, mass-steps ~ N^{:.2}",
            r.chain_time_exponent, r.chain_work_exponent
        ),
        x: Axis::fit(n_rows.iter().map(|c| c.masses as f64), Scale::Log, "N", 0.1),
        y: Axis::fit(
            n_rows.iter().flat_map(|c| [c.seconds, c.mass_steps * 1e-9]),
            Scale::Log,
            "seconds; 10^9 mass-steps",
            0.1,
        ),
        series: vec![
            Series::markers(
                "seconds",
                n_rows
                    .iter()
                    .map(|c| (c.masses as f64, c.seconds))
                    .collect(),
                red,
            ),
            Series::markers(
                "10^9 mass-steps",
                n_rows
                    .iter()
                    .map(|c| (c.masses as f64, c.mass_steps * 1e-9))
                    .collect(),
                blue,
            ),
            Series::line(
                "N^2 (reference)",
                n_rows
                    .iter()
                    .map(|c| {
                        (
                            c.masses as f64,
                            n_rows[0].seconds * (c.masses as f64 / n_rows[0].masses as f64).powi(2),
                        )
                    })
                    .collect(),
                grey,
            )
            .dashed(),
        ],
    };
    write_svg_and_png(&dir.join("chain-growth"), &growth.to_svg())?;
    let along = |sweep: GrowthSweep| -> Vec<&Growth> {
        r.growth.iter().filter(|g| g.sweep == sweep).collect()
    };
    let (along_x, along_a) = (along(GrowthSweep::X), along(GrowthSweep::Alpha));
    let exact_growth = LinePlot {
        title: "Exact engine: events vs t2/t1".into(),
        x: Axis::fit(
            r.growth.iter().map(|g| g.transit_ratio),
            Scale::Log,
            "t2 / t1",
            0.1,
        ),
        y: Axis::fit(
            r.growth.iter().map(|g| g.events as f64),
            Scale::Log,
            "events",
            0.1,
        ),
        series: vec![
            Series::markers(
                "alpha = 0.005, x = 0.5 .. 0.995",
                along_x
                    .iter()
                    .map(|g| (g.transit_ratio, g.events as f64))
                    .collect(),
                red,
            ),
            Series::markers(
                "x = 0.5, alpha = 0.002 .. 0.99",
                along_a
                    .iter()
                    .map(|g| (g.transit_ratio, g.events as f64))
                    .collect(),
                blue,
            ),
        ],
    };
    write_svg_and_png(&dir.join("exact-growth"), &exact_growth.to_svg())?;
    std::fs::write(
        dir.join("index.html"),
        page(
            r,
            &[
                &pareto.to_svg(),
                &tol.to_svg(),
                &growth.to_svg(),
                &exact_growth.to_svg(),
            ],
        ),
    )?;
    staged.commit()?;
    Ok(())
}

fn page(r: &CostReport, figures: &[&str]) -> String {
    let h = &r.headline;
    let mut s = String::new();
    let reached = h.masses.map_or(
        format!(
            "more than N = {} (|de| still {:.2e} there)",
            h.masses_tried, h.chain_error
        ),
        |n| format!("N = {n} (|de| = {:.2e})", h.chain_error),
    );
    let _ = write!(
        s,
        r#"<h1>What accuracy costs in time: {p}</h1>
<p><b>Headline.</b> To reach |de| &lt; {t:e}, the chain needs {reached}: {cs:.3} s per impact; the exact engine takes {es:.2e} s (e = {e:.12}). Ratio: {ratio:.3e}.</p>
<p>Chain time grows as N^{te:.2} and its work (mass-steps) as N^{we:.2}: N masses for a run N steps long.</p>
<div class="figs">
"#,
        p = escape(&r.point),
        t = h.target_error,
        cs = h.chain_seconds,
        es = h.exact_seconds,
        e = r.exact_e,
        ratio = h.ratio,
        te = r.chain_time_exponent,
        we = r.chain_work_exponent
    );
    for f in figures {
        s.push_str(f);
    }
    s.push_str("</div>\n<h2>Exact engine</h2>\n<table><tr><th>point</th><th>drop tolerance</th><th>merge window</th><th>|de|</th><th>|dt_c|</th><th>events</th><th>seconds</th></tr>\n");
    for e in &r.exact {
        let _ = writeln!(
            s,
            "<tr><td>{}</td><td>{:e}</td><td>{:e}</td><td>{:.2e}</td><td>{:.2e}</td><td>{}</td><td>{:.2e}</td></tr>",
            escape(&e.point),
            e.drop_tolerance,
            e.merge_window,
            e.restitution_error,
            e.contact_time_error,
            e.events,
            e.seconds
        );
    }
    s.push_str("</table>\n<h2>Chain</h2>\n<table><tr><th>kind</th><th>N</th><th>dt factor</th><th>e</th><th>|de|</th><th>seconds</th><th>steps</th><th>mass-steps</th><th>ns per mass-step</th></tr>\n");
    for c in &r.chain {
        let _ = writeln!(
            s,
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{:.6}</td><td>{:.2e}</td><td>{:.3}</td><td>{}</td><td>{:.2e}</td><td>{:.2}</td></tr>",
            c.kind,
            c.masses,
            c.dt_factor,
            c.restitution,
            c.restitution_error,
            c.seconds,
            c.steps,
            c.mass_steps,
            1e9 * c.seconds / c.mass_steps
        );
    }
    let overall: Vec<String> = r.pareto.iter().map(|p| escape(&p.2)).collect();
    let _ = write!(
        s,
        "</table>\n<p>Viscous errors are against the chain's own limit, e = {:.6}: Richardson-extrapolated from the three largest N when they converge monotonically, else the largest N's value. The purple squares are what <code>impact run</code> does on a viscous scene: three successive sizes extrapolated, at the cost of the three runs (the largest triple, which defines the limit, is left out).</p>\n<h2>Pareto fronts</h2>\n<p>Over both engines: {} (no chain setting is both faster and more accurate).</p>\n",
        r.viscous_limit,
        overall.join("; ")
    );
    for (name, front) in [
        ("exact engine", &r.pareto_exact),
        ("chain", &r.pareto_chain),
    ] {
        let _ = writeln!(
            s,
            "<h3>{name}</h3>\n<table><tr><th>seconds</th><th>|de|</th><th>setting</th></tr>"
        );
        for p in front {
            let _ = writeln!(
                s,
                "<tr><td>{:.2e}</td><td>{:.2e}</td><td>{}</td></tr>",
                p.0,
                p.1,
                escape(&p.2)
            );
        }
        s.push_str("</table>\n");
    }
    impact_output::page(
        &Head {
            title: &format!("What accuracy costs: {}", r.point),
            style: Stylesheet::shared().rule(".figs svg", "max-width: 620px; height: auto;"),
            layout: Layout::Dense,
        },
        &s,
    )
}

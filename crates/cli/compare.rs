//! `impact compare`: the exact engine against the chain over a grid.

use crate::args::CompareArgs;
use crate::input;
use crate::jobs::{run_journaled, shard, threads};
use impact_chain::ChainRecord;
use impact_report::write::ReportGrid;
use impact_report::{ComparePoint, CompareSettings, compare_point, write_report};
use impact_study::{Axis, Engine, Grid, JournalHeader, JournalPlan, Shard};
use impact_wave::Record;
use std::path::PathBuf;

/// Parses `--n 250,500,1000` into increasing sizes.
fn sizes(text: &str) -> anyhow::Result<Vec<usize>> {
    let bad = || {
        input(format!(
            "--n must be chain sizes >= 2, comma-separated and increasing (got '{text}')"
        ))
    };
    let sizes: Vec<usize> = text
        .split(',')
        .map(|t| t.trim().parse::<usize>().map_err(|_| bad()))
        .collect::<Result<_, _>>()?;
    if sizes.is_empty() || sizes.iter().any(|&n| n < 2) || sizes.windows(2).any(|w| w[1] <= w[0]) {
        return Err(bad());
    }
    Ok(sizes)
}

/// The settings a compare run is defined by: what resume and merge check.
pub fn describe(a: &CompareArgs, settings: &CompareSettings) -> serde_json::Value {
    serde_json::json!({
        "x": a.x,
        "alpha": a.alpha,
        "sizes": settings.sizes,
        "restitution_tolerance": settings.restitution_tolerance,
        "contact_time_tolerance": settings.contact_time_tolerance,
        "wave": settings.wave,
        "chain": impact_chain::ChainConfig { masses: 0, ..settings.chain.clone() },
        "timing": settings.timing,
        "version": env!("CARGO_PKG_VERSION"),
    })
}

/// The grid of a compare run's settings (for merge).
pub fn grid_of(settings: &serde_json::Value) -> anyhow::Result<Grid> {
    let axis = |name: &'static str| -> anyhow::Result<Axis> {
        let text = settings[name]
            .as_str()
            .ok_or_else(|| input(format!("journal settings lack '{name}'")))?;
        Axis::parse(name, text).map_err(crate::flags::grid)
    };
    Ok(Grid {
        x: axis("x")?,
        alpha: axis("alpha")?,
    })
}

/// Writes the report, prints the summary, applies `--fail-above`.
pub fn finish(
    dir: &std::path::Path,
    settings: &serde_json::Value,
    grid: &Grid,
    points: &[ComparePoint],
    fail_above: Option<f64>,
) -> anyhow::Result<()> {
    let report_grid = ReportGrid {
        x: grid.x.values(),
        alpha: grid.alpha.values(),
    };
    let summary = write_report(dir, settings, &report_grid, points)?;
    eprintln!(
        "wrote {}/index.html: {} points, max |de| = {:.3e}, median |de| = {:.3e}, N_b equal on {:.1}%, within tolerance {:.1}%",
        dir.display(),
        summary.points,
        summary.max_abs_de,
        summary.median_abs_de,
        100.0 * summary.bounces_agree,
        100.0 * summary.agree
    );
    if let Some(tol) = fail_above {
        let beyond = points
            .iter()
            .filter(|p| p.de().is_none_or(|d| d.abs() > tol))
            .count();
        if beyond > 0 {
            anyhow::bail!(
                "{beyond} of {} points have |de| > {tol} (or failed): see {}/index.html",
                points.len(),
                dir.display()
            );
        }
    }
    Ok(())
}

pub fn compare(a: CompareArgs) -> anyhow::Result<()> {
    let grid = Grid {
        x: Axis::parse("x", &a.x).map_err(crate::flags::grid)?,
        alpha: Axis::parse("alpha", &a.alpha).map_err(crate::flags::grid)?,
    };
    let sizes = sizes(&a.sizes)?;
    for (name, v) in [
        ("tolerance", a.tolerance),
        ("contact-tolerance", a.contact_tolerance),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(input(format!(
                "--{name} must be a finite number > 0 (got {v})"
            )));
        }
    }
    if let Some(t) = a.fail_above
        && !(t.is_finite() && t >= 0.0)
    {
        return Err(input(format!(
            "--fail-above must be a finite number >= 0 (got {t})"
        )));
    }
    let (Engine::Wave(wave), Engine::Chain(chain)) = (
        a.engine.wave_engine(Record::default())?,
        a.engine.chain_engine(2, ChainRecord::default())?,
    ) else {
        unreachable!("wave_engine and chain_engine return their own kinds")
    };
    let shard = shard(&a.journal)?;
    threads(a.threads)?;
    let settings = CompareSettings {
        wave,
        chain,
        sizes,
        restitution_tolerance: a.tolerance,
        contact_time_tolerance: a.contact_tolerance,
        timing: !a.no_timing,
    };
    let described = describe(&a, &settings);
    let points = grid.points();
    std::fs::create_dir_all(&a.out)?;
    let journal_path: PathBuf = if shard == Shard::ALL {
        a.out.join("points.jsonl")
    } else {
        a.out.join(format!(
            "points-shard-{}-of-{}.jsonl",
            shard.index, shard.count
        ))
    };
    let plan = JournalPlan {
        path: &journal_path,
        header: JournalHeader::new("compare", described.clone(), points.len(), shard),
        resume: a.journal.resume,
    };
    let done = run_journaled(&points, &plan, |_, &p| compare_point(p, &settings))?;
    if shard != Shard::ALL {
        eprintln!(
            "shard {}/{}: {} points ({} resumed) in {}; join the shards with `impact merge {}/points-shard-*-of-{}.jsonl --out DIR`",
            shard.index,
            shard.count,
            done.resumed.len() + done.fresh.len(),
            done.resumed.len(),
            journal_path.display(),
            a.out.display(),
            shard.count
        );
        return Ok(());
    }
    let ordered: Vec<ComparePoint> = done.into_rows().into_values().collect();
    finish(&a.out, &described, &grid, &ordered, a.fail_above)
}

//! `impact sweep`: a grid of canonical bilayers, in parallel.

use crate::args::SweepArgs;
use crate::input;
use crate::jobs::{open_journal, progress, shard, threads};
use crate::output::write_atomically;
use impact_chain::ChainRecord;
use impact_study::{Axis, Grid, JournalHeader, Row, RowFormat, Shard};
use impact_wave::Record;
use std::time::Instant;

pub fn sweep(a: SweepArgs) -> anyhow::Result<()> {
    let grid = Grid {
        x: Axis::parse("x", &a.x).map_err(crate::flags::grid)?,
        alpha: Axis::parse("alpha", &a.alpha).map_err(crate::flags::grid)?,
    };
    let viscosity = a.viscosity.viscosity();
    // validate the viscosity once, on any point, before the long run
    viscosity
        .scene(impact_model::Bilayer { x: 0.5, alpha: 0.5 })
        .validate()
        .map_err(|e| input(e.to_string()))?;
    let engine = a.engine.engine(
        viscosity.is_viscous(),
        a.masses,
        Record::default(),
        ChainRecord::default(),
    )?;
    let shard = shard(&a.journal)?;
    let journaled = a.journal.shard.is_some() || a.journal.resume;
    if journaled && RowFormat::from_path(&a.out) != RowFormat::JsonLines {
        return Err(input(
            "--shard and --resume journal into JSON lines: --out must end in .jsonl (join shards with impact merge)",
        ));
    }
    threads(a.threads)?;
    let timing = !a.no_timing;
    let points: Vec<(usize, impact_model::Bilayer)> =
        grid.points().into_iter().enumerate().collect();
    let start = Instant::now();
    let rows = if journaled {
        let settings = serde_json::json!({
            "x": a.x, "alpha": a.alpha,
            "engine": engine,
            "viscosity": viscosity,
            "timing": timing,
            "version": env!("CARGO_PKG_VERSION"),
        });
        let header = JournalHeader::new("sweep", settings, points.len(), shard);
        let (journal, done) = open_journal::<Row>(&a.out, &header, a.journal.resume)?;
        let todo: Vec<_> = points
            .iter()
            .copied()
            .filter(|(k, _)| shard.contains(*k) && !done.contains_key(k))
            .collect();
        let bar = progress(todo.len(), "points");
        let failures = std::sync::Mutex::new(Vec::new());
        let rows = impact_study::sweep(&todo, &engine, &viscosity, timing, &|k, row| {
            if let Err(e) = journal.append(k, row) {
                failures.lock().unwrap_or_else(|p| p.into_inner()).push(e);
            }
            bar.inc(1);
        });
        bar.finish_and_clear();
        if let Some(e) = failures
            .into_inner()
            .unwrap_or_else(|p| p.into_inner())
            .pop()
        {
            return Err(e.into());
        }
        eprintln!(
            "{}: {} points of shard {}/{} ({} resumed){}",
            a.out.display(),
            done.len() + rows.len(),
            shard.index,
            shard.count,
            done.len(),
            if shard == Shard::ALL {
                "; write the rows a plain sweep would with `impact merge FILE --out rows.csv`"
            } else {
                "; join the shards with `impact merge`"
            }
        );
        rows
    } else {
        let bar = progress(points.len(), "points");
        let rows = impact_study::sweep(&points, &engine, &viscosity, timing, &|_, _| bar.inc(1));
        bar.finish_and_clear();
        let format = RowFormat::from_path(&a.out);
        write_atomically(&a.out, |w| format.write(&rows, timing, w))?;
        rows
    };
    let wall = start.elapsed().as_secs_f64();
    let failed = rows.iter().filter(|r| r.error.is_some()).count();
    let events: u64 = rows.iter().filter_map(|r| r.events).sum();
    let steps: u64 = rows.iter().filter_map(|r| r.steps).sum();
    let work = if steps > 0 {
        format!("{steps} chain steps")
    } else {
        format!(
            "{events} events, {:.1} M events/s",
            events as f64 / wall / 1e6
        )
    };
    eprintln!(
        "computed {} rows in {wall:.2} s ({:.0} points/s, {work}){}",
        rows.len(),
        rows.len() as f64 / wall,
        if failed > 0 {
            format!("; {failed} points failed (see the error column)")
        } else {
            String::new()
        }
    );
    if !journaled {
        eprintln!("wrote {}", a.out.display());
    }
    Ok(())
}

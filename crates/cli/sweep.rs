//! `impact sweep`: a grid of canonical bilayers, in parallel.

use crate::args::SweepArgs;
use crate::input;
use crate::jobs::{Bar, run_journaled, shard, threads};
use crate::output::write_atomically;
use impact_chain::ChainRecord;
use impact_study::{Axis, Grid, JournalHeader, JournalPlan, Row, RowFormat, Shard, par_map};
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
    let to_stdout = a.out.as_os_str() == "-";
    if journaled && (to_stdout || RowFormat::from_path(&a.out) != RowFormat::JsonLines) {
        return Err(input(
            "--shard and --resume journal into JSON lines: --out must end in .jsonl (join shards with impact merge)",
        ));
    }
    threads(a.threads)?;
    let timing = !a.no_timing;
    let points = grid.points();
    let row = |p: &impact_model::Bilayer| impact_study::sweep_row(*p, &engine, &viscosity, timing);
    let start = Instant::now();
    let rows = if journaled {
        let settings = serde_json::json!({
            "x": a.x, "alpha": a.alpha,
            "engine": engine,
            "viscosity": viscosity,
            "timing": timing,
            "version": env!("CARGO_PKG_VERSION"),
        });
        let plan = JournalPlan {
            path: &a.out,
            header: JournalHeader::new("sweep", settings, points.len(), shard),
            resume: a.journal.resume,
        };
        let done = run_journaled(&points, &plan, |_, p| row(p))?;
        eprintln!(
            "{}: {} points of shard {}/{} ({} resumed){}",
            a.out.display(),
            done.resumed.len() + done.fresh.len(),
            shard.index,
            shard.count,
            done.resumed.len(),
            if shard == Shard::ALL {
                "; write the rows a plain sweep would with `impact merge FILE --out rows.csv`"
            } else {
                "; join the shards with `impact merge`"
            }
        );
        // the summary below counts what this run computed
        done.fresh.into_values().collect::<Vec<Row>>()
    } else {
        let rows = par_map(&points, &Bar::new("points"), row);
        if to_stdout {
            let mut w = std::io::BufWriter::new(std::io::stdout().lock());
            RowFormat::Csv.write(&rows, timing, &mut w)?;
            std::io::Write::flush(&mut w)?;
        } else {
            let format = RowFormat::from_path(&a.out);
            write_atomically(&a.out, |w| format.write(&rows, timing, w))?;
        }
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
        "computed {} rows in {wall:.2} s ({} points/s, {work}){}",
        rows.len(),
        crate::output::three_digits(rows.len() as f64 / wall),
        if failed > 0 {
            format!("; {failed} points failed (see the error column)")
        } else {
            String::new()
        }
    );
    if !journaled && !to_stdout {
        eprintln!("wrote {}", a.out.display());
    }
    Ok(())
}

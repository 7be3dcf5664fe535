//! `impact sweep`: a grid of canonical bilayers, in parallel.

use crate::args::SweepArgs;
use crate::input;
use crate::output::write_atomically;
use impact_chain::ChainRecord;
use impact_study::{Axis, Grid, RowFormat};
use impact_wave::Record;
use indicatif::{ProgressBar, ProgressStyle};
use std::io::IsTerminal;
use std::time::Instant;

pub fn sweep(a: SweepArgs) -> anyhow::Result<()> {
    let grid = Grid {
        x: Axis::parse("x", &a.x).map_err(|e| input(e.to_string()))?,
        alpha: Axis::parse("alpha", &a.alpha).map_err(|e| input(e.to_string()))?,
    };
    let viscosity = a.viscosity.viscosity();
    // validate the viscosity once, on any point, before the long run
    viscosity
        .scene(impact_model::Bilayer { x: 0.5, alpha: 0.5 })
        .validate()
        .map_err(|e| input(e.to_string()))?;
    let engine = a.engine.engine(
        viscosity.is_viscous(),
        Record::default(),
        ChainRecord::default(),
    )?;
    if let Some(n) = a.threads {
        if n == 0 {
            return Err(input("--threads must be at least 1 (got 0)"));
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()?;
    }
    let points = grid.points();
    let bar = if std::io::stderr().is_terminal() {
        let bar = ProgressBar::new(points.len() as u64);
        bar.set_style(
            ProgressStyle::with_template(
                "{elapsed_precise} [{bar:40}] {pos}/{len} points ({per_sec}, eta {eta})",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
        );
        bar
    } else {
        ProgressBar::hidden()
    };
    let start = Instant::now();
    let rows = impact_study::sweep(&points, &engine, &viscosity, !a.no_timing, &|| bar.inc(1));
    bar.finish_and_clear();
    let wall = start.elapsed().as_secs_f64();
    let format = RowFormat::from_path(&a.out);
    write_atomically(&a.out, |w| format.write(&rows, !a.no_timing, w))?;
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
        "wrote {} rows to {} in {wall:.2} s ({:.0} points/s, {work}){}",
        rows.len(),
        a.out.display(),
        rows.len() as f64 / wall,
        if failed > 0 {
            format!("; {failed} points failed (see the error column)")
        } else {
            String::new()
        }
    );
    Ok(())
}

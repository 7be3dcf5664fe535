//! Figs. 4, 5, 6: maps over `(x, alpha)` of the reduced contact time, `n1`,
//! `N_b` and `e` from the exact engine on the paper's grid, with isolines;
//! Fig. 6(b): `e(x)` at several `alpha < 0.5` with Eq. 11 where it applies.
//!
//! The steps: sweep the grid (here), draw the maps and the `N_b(x)` cut
//! (`figures.rs`), run the `e(x)` profiles against Eq. 11 (`profiles.rs`),
//! and measure the paper's statements on the grid (`claims.rs`).

mod claims;
mod figures;
mod profiles;

use crate::claim::{Item, csv};
use crate::{PaperError, Settings};
use impact_study::{BilayerViscosity, Engine, Grid, Row, sweep};
use impact_wave::WaveConfig;
use std::path::Path;

pub fn run(dir: &Path, s: &Settings) -> Result<Item, PaperError> {
    let axis = impact_study::Axis {
        start: s.map_step,
        stop: 1.0 - s.map_step,
        step: s.map_step,
    };
    let grid = Grid {
        x: axis.clone(),
        alpha: axis,
    };
    let rows = sweep_grid(&grid)?;
    let (xs, alphas) = (grid.x.values(), grid.alpha.values());
    let data = write_rows(dir, &rows)?;
    let mut figures = figures::maps(dir, &rows, &xs, &alphas)?;
    let profiles = profiles::run(dir, &xs)?;
    figures.push(profiles.figure);
    Ok(Item {
        id: "maps".into(),
        title: "Figs. 4, 5, 6: maps over (x, alpha)".into(),
        figures,
        data: vec![data, profiles.data],
        claims: claims::claims(&rows, profiles.eq11_error),
        notes: vec![format!(
            "Exact engine on the paper's grid: x and alpha from {} to {} in steps of {} ({} points); isolines in black.",
            s.map_step,
            1.0 - s.map_step,
            s.map_step,
            rows.len()
        )],
    })
}

/// The exact engine at every grid point, in grid order; the first failure
/// is an error (a map with holes would not be the paper's).
fn sweep_grid(grid: &Grid) -> Result<Vec<Row>, PaperError> {
    let points = grid.points();
    let rows = sweep(
        &points,
        &Engine::Wave(WaveConfig::default()),
        &BilayerViscosity::default(),
        false,
        &(),
    );
    if let Some(r) = rows.iter().find(|r| r.error.is_some()) {
        return Err(PaperError::Engine(format!(
            "x = {}, alpha = {}: {}",
            r.x,
            r.alpha,
            r.error.clone().unwrap_or_default()
        )));
    }
    Ok(rows)
}

/// `maps.csv`: every grid point's measures.
fn write_rows(dir: &Path, rows: &[Row]) -> Result<String, PaperError> {
    csv(
        dir,
        "maps",
        "x,alpha,reduced_contact_time,n1,bounces,separations,restitution",
        rows.iter().map(|r| {
            vec![
                r.x,
                r.alpha,
                r.reduced_contact_time.unwrap_or(f64::NAN),
                r.n1.unwrap_or(f64::NAN),
                r.bounces.map_or(f64::NAN, f64::from),
                r.separations.map_or(f64::NAN, f64::from),
                r.restitution.unwrap_or(f64::NAN),
            ]
        }),
    )
}

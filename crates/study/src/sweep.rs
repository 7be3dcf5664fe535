//! Parallel sweeps over a grid, one row per point in grid order.

use impact_chain::{ChainConfig, ChainError};
use impact_model::{Bilayer, Outcome, Scene, SceneError, SettingError, Timed, WallContact};
use impact_output::Plain;
use impact_rigid::{RigidConfig, RigidError};
use impact_wave::{WaveConfig, WaveError};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Why one impact of a study could not run or finish: the engine's own
/// error, kept typed until it is written out (a row's `error` cell reads
/// exactly as the engine worded it).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RunError {
    /// The scene was invalid.
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// The exact engine failed.
    #[error(transparent)]
    Wave(#[from] WaveError),
    /// The chain failed.
    #[error(transparent)]
    Chain(#[from] ChainError),
    /// The rigid-bottom model failed.
    #[error(transparent)]
    Rigid(#[from] RigidError),
}

/// The engine a sweep runs, with its validated settings.
#[derive(Debug, Clone, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Engine {
    /// The exact front-tracing engine (elastic layers).
    Wave(WaveConfig),
    /// The discrete mass-spring(-dashpot) chain.
    Chain(ChainConfig),
    /// The rigid-bottom limit (a rigid mass under the elastic stack).
    RigidBottom(RigidConfig),
}

/// Viscosity of the two layers of a canonical bilayer, as a relaxation time
/// `tau_i` or as the paper's layer restitution `e_i` (at most one per layer).
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct BilayerViscosity {
    /// Relaxation time `tau_i` of layer 1 (bottom) and 2 (top).
    pub tau: [Option<f64>; 2],
    /// The paper's layer restitution `e_i` of layer 1 and 2 (the `tau` that gives it is read from the calibration).
    pub restitution: [Option<f64>; 2],
    /// The wall's contact law (absent: the paper's).
    pub wall_contact: Option<WallContact>,
}

impl BilayerViscosity {
    /// The canonical scene of `point` with these viscosities.
    pub fn scene(&self, point: Bilayer) -> Scene {
        let mut scene = point.scene();
        for (i, layer) in scene.layers.iter_mut().enumerate() {
            layer.relaxation_time = self.tau[i];
            layer.restitution = self.restitution[i];
        }
        scene.wall_contact = self.wall_contact;
        scene
    }

    /// Whether either layer has a dashpot (`tau > 0` or `e < 1`).
    pub fn is_viscous(&self) -> bool {
        self.tau.iter().flatten().any(|&t| t > 0.0)
            || self.restitution.iter().flatten().any(|&e| e < 1.0)
    }
}

impl Engine {
    /// Short name, as in the `engine` column.
    pub fn name(&self) -> &'static str {
        match self {
            Engine::Wave(_) => "wave",
            Engine::Chain(_) => "chain",
            Engine::RigidBottom(_) => "rigid-bottom",
        }
    }

    /// The settings' ranges, checked by the engine's own rule: a caller can
    /// refuse bad settings before running anything.
    pub fn check(&self) -> Result<(), SettingError> {
        match self {
            Engine::Wave(config) => config.check(),
            Engine::Chain(config) => config.check(),
            Engine::RigidBottom(config) => config.check(),
        }
    }

    /// Runs one impact.
    pub fn simulate(&self, rod: &impact_model::Rod) -> Result<Outcome, RunError> {
        Ok(match self {
            Engine::Wave(config) => impact_wave::simulate(rod, config)?,
            Engine::Chain(config) => impact_chain::simulate(rod, config)?,
            Engine::RigidBottom(config) => impact_rigid::simulate(rod, config)?,
        })
    }

    /// Runs one canonical bilayer point.
    pub fn run(&self, point: Bilayer, viscosity: &BilayerViscosity) -> Result<Outcome, RunError> {
        let rod = viscosity.scene(point).validate()?;
        self.simulate(&rod)
    }
}

/// One point of a sweep: the scalar observables, or why the point failed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Row {
    /// Composition `x = L2 / L` of the point.
    pub x: f64,
    /// Stiffness ratio `alpha = E2 / (E1 + E2)` of the point.
    pub alpha: f64,
    /// The engine (`wave`, `chain` or `rigid-bottom`).
    pub engine: String,
    /// The wall's contact law of the run (`paper` or `unilateral`).
    pub wall_contact: String,
    /// Coefficient of restitution `e`, from the wall impulse.
    pub restitution: Option<f64>,
    /// `e` from the masses' mean velocity at the end (chain only).
    pub restitution_from_velocity: Option<f64>,
    /// Contact time `t_c`: time of the last separation.
    pub contact_time: Option<f64>,
    /// `t_c / (2 t1 + 2 t2)`.
    pub reduced_contact_time: Option<f64>,
    /// `(t_c - 2 t2) / t1`.
    pub n1: Option<f64>,
    /// The paper's bounce count `N_b` (flights longer than `min(t1, t2)`).
    pub bounces: Option<u32>,
    /// Raw number of separations.
    pub separations: Option<u32>,
    /// Time at which the run stopped.
    pub end_time: Option<f64>,
    /// Why it stopped (`escaped`, `horizon`, `horizon_in_contact`, `rests_on_wall`).
    pub stop_reason: Option<String>,
    /// Boundary events processed (wave engine).
    pub events: Option<u64>,
    /// Time steps taken (chain).
    pub steps: Option<u64>,
    /// Fronts dropped under the drop tolerance (wave engine).
    pub dropped_fronts: Option<u64>,
    /// Fronts merged into neighbours (wave engine).
    pub merged_fronts: Option<u64>,
    /// How far `restitution` may be from the model's exact value.
    #[serde(default)]
    pub error_bound: Option<f64>,
    /// Whether that bound may be low: `true` where a merged run's levels
    /// were not seen converging (`impact run`'s "the merged estimate may
    /// be low, by any factor"), `false` for a merged bound whose levels
    /// converge, empty for a run that merged nothing.
    #[serde(default)]
    pub bound_may_be_low: Option<bool>,
    /// Wall-clock time: the only column that differs between identical runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elapsed_seconds: Option<f64>,
    /// Why the point failed, as the engine or scene worded it; the observables are then empty.
    pub error: Option<String>,
}

impl Row {
    fn new(
        point: Bilayer,
        engine: &'static str,
        wall_contact: WallContact,
        result: Result<Timed<Outcome>, RunError>,
        timing: bool,
    ) -> Self {
        let mut row = Row {
            x: point.x,
            alpha: point.alpha,
            engine: engine.to_string(),
            wall_contact: wall_contact.to_string(),
            restitution: None,
            restitution_from_velocity: None,
            contact_time: None,
            reduced_contact_time: None,
            n1: None,
            bounces: None,
            separations: None,
            end_time: None,
            stop_reason: None,
            events: None,
            steps: None,
            dropped_fronts: None,
            merged_fronts: None,
            error_bound: None,
            bound_may_be_low: None,
            elapsed_seconds: None,
            error: None,
        };
        match result {
            Ok(Timed { value: o, seconds }) => {
                row.restitution = Some(o.restitution);
                row.contact_time = Some(o.contact_time);
                row.reduced_contact_time = Some(o.reduced_contact_time);
                row.n1 = o.n1;
                row.bounces = Some(o.bounces);
                row.separations = Some(o.separations);
                row.end_time = Some(o.end_time);
                row.stop_reason = Some(
                    match o.stop_reason {
                        impact_model::StopReason::Escaped => "escaped",
                        impact_model::StopReason::Horizon => "horizon",
                        impact_model::StopReason::HorizonInContact => "horizon_in_contact",
                        impact_model::StopReason::RestsOnWall => "rests_on_wall",
                    }
                    .to_string(),
                );
                row.events = o.events;
                row.steps = o.steps;
                row.restitution_from_velocity = o.restitution_from_velocity;
                row.dropped_fronts = o.truncation.map(|t| t.dropped_fronts);
                row.merged_fronts = o.truncation.map(|t| t.merged_fronts);
                row.error_bound = o.error_bound;
                row.bound_may_be_low = o
                    .error_estimate
                    .as_ref()
                    .and_then(|e| e.merged_converging)
                    .map(|converging| !converging);
                row.elapsed_seconds = timing.then_some(seconds);
            }
            Err(e) => row.error = Some(e.to_string()),
        }
        row
    }
}

/// A [`Row`] as a CSV line: the same columns in the same order, numbers as
/// `Display` writes them (the shortest text that reads back to the same
/// number, so the text is deterministic), `elapsed_seconds` only in timed
/// sweeps, absent values as empty cells. The JSON lines are the `Row`
/// itself.
#[derive(Serialize)]
struct CsvRow<'a> {
    x: Plain<f64>,
    alpha: Plain<f64>,
    engine: &'a str,
    wall_contact: &'a str,
    restitution: Option<Plain<f64>>,
    restitution_from_velocity: Option<Plain<f64>>,
    contact_time: Option<Plain<f64>>,
    reduced_contact_time: Option<Plain<f64>>,
    n1: Option<Plain<f64>>,
    bounces: Option<u32>,
    separations: Option<u32>,
    end_time: Option<Plain<f64>>,
    stop_reason: Option<&'a str>,
    events: Option<u64>,
    steps: Option<u64>,
    dropped_fronts: Option<u64>,
    merged_fronts: Option<u64>,
    error_bound: Option<Plain<f64>>,
    bound_may_be_low: Option<bool>,
    /// Absent from untimed sweeps; in timed ones, empty for a failed row.
    #[serde(skip_serializing_if = "Option::is_none")]
    elapsed_seconds: Option<Option<Plain<f64>>>,
    error: Option<&'a str>,
}

impl<'a> CsvRow<'a> {
    fn new(r: &'a Row, timing: bool) -> Self {
        Self {
            x: Plain(r.x),
            alpha: Plain(r.alpha),
            engine: &r.engine,
            wall_contact: &r.wall_contact,
            restitution: r.restitution.map(Plain),
            restitution_from_velocity: r.restitution_from_velocity.map(Plain),
            contact_time: r.contact_time.map(Plain),
            reduced_contact_time: r.reduced_contact_time.map(Plain),
            n1: r.n1.map(Plain),
            bounces: r.bounces,
            separations: r.separations,
            end_time: r.end_time.map(Plain),
            stop_reason: r.stop_reason.as_deref(),
            events: r.events,
            steps: r.steps,
            dropped_fronts: r.dropped_fronts,
            merged_fronts: r.merged_fronts,
            error_bound: r.error_bound.map(Plain),
            bound_may_be_low: r.bound_may_be_low,
            elapsed_seconds: timing.then(|| r.elapsed_seconds.map(Plain)),
            error: r.error.as_deref(),
        }
    }
}

/// Output format of a sweep, chosen from the file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RowFormat {
    /// Comma-separated values with a header line.
    Csv,
    /// One JSON object per line.
    JsonLines,
}

impl RowFormat {
    /// `.jsonl` gives JSON lines; anything else CSV.
    pub fn from_path(path: &std::path::Path) -> Self {
        match path.extension().and_then(|e| e.to_str()) {
            Some("jsonl") => RowFormat::JsonLines,
            _ => RowFormat::Csv,
        }
    }

    /// Writes all rows (with a header for CSV).
    pub fn write(
        self,
        rows: &[Row],
        timing: bool,
        out: &mut impl std::io::Write,
    ) -> std::io::Result<()> {
        match self {
            RowFormat::Csv => {
                impact_output::write_csv(out, rows.iter().map(|r| CsvRow::new(r, timing)))?
            }
            RowFormat::JsonLines => {
                for r in rows {
                    let line = serde_json::to_string(r).map_err(std::io::Error::other)?;
                    writeln!(out, "{line}")?;
                }
            }
        }
        Ok(())
    }
}

/// The row of one point.
pub fn sweep_row(p: Bilayer, engine: &Engine, viscosity: &BilayerViscosity, timing: bool) -> Row {
    let law = viscosity.wall_contact.unwrap_or_default();
    let result = Timed::try_measure(|| engine.run(p, viscosity));
    Row::new(p, engine.name(), law, result, timing)
}

/// Runs every point in parallel (through [`crate::par_map`]); rows come back
/// in the order given, whatever the number of threads.
pub fn sweep(
    points: &[Bilayer],
    engine: &Engine,
    viscosity: &BilayerViscosity,
    timing: bool,
    progress: &dyn crate::Progress,
) -> Vec<Row> {
    crate::par_map(points, progress, |&p| {
        sweep_row(p, engine, viscosity, timing)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_come_back_in_grid_order_whatever_the_threads() {
        let grid = crate::Grid {
            x: crate::Axis::parse("x", "0.1:0.9:0.2").unwrap(),
            alpha: crate::Axis::parse("alpha", "0.05:0.95:0.3").unwrap(),
        };
        let points = grid.points();
        let engine = Engine::Wave(WaveConfig::default());
        let v = BilayerViscosity::default();
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let four = rayon::ThreadPoolBuilder::new()
            .num_threads(4)
            .build()
            .unwrap();
        let a = one.install(|| sweep(&points, &engine, &v, false, &()));
        let b = four.install(|| sweep(&points, &engine, &v, false, &()));
        assert_eq!(a, b);
        for (row, p) in a.iter().zip(&points) {
            assert_eq!((row.x, row.alpha), (p.x, p.alpha));
        }
    }

    #[test]
    fn csv_has_one_cell_per_header_column() {
        let point = Bilayer {
            x: 0.4,
            alpha: 0.05,
        };
        // a row of the exact engine at `point` with this result
        let row_of = |result, timing| Row::new(point, "wave", WallContact::Paper, result, timing);
        let row = row_of(
            Timed::try_measure(|| {
                Engine::Wave(WaveConfig::default()).run(point, &BilayerViscosity::default())
            }),
            true,
        );
        // the header line and each row's line, as a CSV file writes them
        let csv = |row: &Row, timing: bool| -> (String, String) {
            let mut out = Vec::new();
            RowFormat::Csv
                .write(std::slice::from_ref(row), timing, &mut out)
                .unwrap();
            let text = String::from_utf8(out).unwrap();
            let (header, line) = text.trim_end_matches('\n').split_once('\n').unwrap();
            (header.to_string(), line.to_string())
        };
        // regression: a failed row had one cell fewer than the header
        let lost = row_of(
            Err(RunError::Wave(WaveError::TimeLimit { time: 1.0 })),
            true,
        );
        for r in [&row, &lost] {
            let (header, line) = csv(r, true);
            assert_eq!(line.split(',').count(), header.split(',').count());
        }
        let failed = row_of(
            Err(RunError::Scene(SceneError::Json("a, \"b\"".into()))),
            false,
        );
        assert!(
            csv(&failed, false)
                .1
                .ends_with("\"scene JSON: a, \"\"b\"\"\"")
        );
    }

    /// A row says whether its bound may be low, as the run's estimate
    /// does: a merged point whose levels do not converge (`x = 0.99`,
    /// `alpha = 0.001`, a stiff base ringing under a long soft top) says
    /// so, and an exact point leaves the cell empty.
    #[test]
    fn a_row_says_when_its_bound_may_be_low() {
        let engine = Engine::Wave(WaveConfig::default());
        let v = BilayerViscosity::default();
        let merged = Bilayer {
            x: 0.99,
            alpha: 0.001,
        };
        let run = engine.run(merged, &v).unwrap();
        let estimate = run.error_estimate.unwrap();
        assert_eq!(estimate.merged_converging, Some(false), "the case");
        let row = sweep_row(merged, &engine, &v, false);
        assert_eq!(row.bound_may_be_low, Some(true));
        assert_eq!(row.error_bound, Some(estimate.bound));
        let exact = sweep_row(
            Bilayer {
                x: 0.4,
                alpha: 0.05,
            },
            &engine,
            &v,
            false,
        );
        assert_eq!(exact.bound_may_be_low, None);
        assert!(exact.error_bound.is_some());
    }
}

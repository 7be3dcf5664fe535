//! Parallel sweeps over a grid, one row per point in grid order.

use impact_chain::{ChainConfig, ChainError};
use impact_model::{Bilayer, Outcome, Scene, SceneError, SettingError, Timed, WallContact};
use impact_rigid::{RigidConfig, RigidError};
use impact_wave::{WaveConfig, WaveError};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Why one impact of a study could not run or finish: the engine's own
/// error, kept typed until it is written out (a row's `error` cell reads
/// exactly as the engine worded it).
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RunError {
    #[error(transparent)]
    Scene(#[from] SceneError),
    #[error(transparent)]
    Wave(#[from] WaveError),
    #[error(transparent)]
    Chain(#[from] ChainError),
    #[error(transparent)]
    Rigid(#[from] RigidError),
}

/// The engine a sweep runs, with its validated settings.
#[derive(Debug, Clone, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Engine {
    Wave(WaveConfig),
    Chain(ChainConfig),
    /// The rigid-bottom limit (a rigid mass under the elastic stack).
    RigidBottom(RigidConfig),
}

/// Viscosity of the two layers of a canonical bilayer, as a relaxation time
/// `tau_i` or as the paper's layer restitution `e_i` (at most one per layer).
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct BilayerViscosity {
    pub tau: [Option<f64>; 2],
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
    pub x: f64,
    pub alpha: f64,
    pub engine: String,
    /// The wall's contact law of the run (`paper` or `unilateral`).
    pub wall_contact: String,
    pub restitution: Option<f64>,
    pub restitution_from_velocity: Option<f64>,
    pub contact_time: Option<f64>,
    pub reduced_contact_time: Option<f64>,
    pub n1: Option<f64>,
    pub bounces: Option<u32>,
    pub separations: Option<u32>,
    pub end_time: Option<f64>,
    pub stop_reason: Option<String>,
    pub events: Option<u64>,
    pub steps: Option<u64>,
    pub dropped_fronts: Option<u64>,
    pub merged_fronts: Option<u64>,
    /// How far `restitution` may be from the model's exact value.
    #[serde(default)]
    pub error_bound: Option<f64>,
    /// Wall-clock time: the only column that differs between identical runs.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub elapsed_seconds: Option<f64>,
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
                row.elapsed_seconds = timing.then_some(seconds);
            }
            Err(e) => row.error = Some(e.to_string()),
        }
        row
    }

    /// CSV header matching [`Row::csv`].
    pub fn csv_header(timing: bool) -> String {
        let mut h = String::from(
            "x,alpha,engine,wall_contact,restitution,restitution_from_velocity,contact_time,reduced_contact_time,n1,bounces,separations,end_time,stop_reason,events,steps,dropped_fronts,merged_fronts,error_bound",
        );
        if timing {
            h.push_str(",elapsed_seconds");
        }
        h.push_str(",error");
        h
    }

    /// One CSV line; absent values are empty cells. Floats use Rust's
    /// shortest round-trip form, so the text is deterministic.
    pub fn csv(&self, timing: bool) -> String {
        fn cell<T: ToString>(v: &Option<T>) -> String {
            v.as_ref().map_or_else(String::new, T::to_string)
        }
        let mut cells = vec![
            self.x.to_string(),
            self.alpha.to_string(),
            self.engine.to_string(),
            self.wall_contact.clone(),
            cell(&self.restitution),
            cell(&self.restitution_from_velocity),
            cell(&self.contact_time),
            cell(&self.reduced_contact_time),
            cell(&self.n1),
            cell(&self.bounces),
            cell(&self.separations),
            cell(&self.end_time),
            cell(&self.stop_reason),
            cell(&self.events),
            cell(&self.steps),
            cell(&self.dropped_fronts),
            cell(&self.merged_fronts),
            cell(&self.error_bound),
        ];
        if timing {
            // failed rows have no time: an empty cell keeps the columns aligned
            cells.push(
                self.elapsed_seconds
                    .map_or_else(String::new, |t| t.to_string()),
            );
        }
        // errors are free text: quote them
        cells.push(
            self.error
                .as_ref()
                .map_or_else(String::new, |e| format!("\"{}\"", e.replace('"', "\"\""))),
        );
        cells.join(",")
    }
}

/// Output format of a sweep, chosen from the file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RowFormat {
    Csv,
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
                writeln!(out, "{}", Row::csv_header(timing))?;
                for r in rows {
                    writeln!(out, "{}", r.csv(timing))?;
                }
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
        let row = Row::new(
            Bilayer {
                x: 0.4,
                alpha: 0.05,
            },
            "wave",
            WallContact::Paper,
            Timed::try_measure(|| {
                Engine::Wave(WaveConfig::default()).run(
                    Bilayer {
                        x: 0.4,
                        alpha: 0.05,
                    },
                    &BilayerViscosity::default(),
                )
            }),
            true,
        );
        assert_eq!(
            row.csv(true).split(',').count(),
            Row::csv_header(true).split(',').count()
        );
        // regression: a failed row had one cell fewer than the header
        let lost = Row::new(
            Bilayer {
                x: 0.4,
                alpha: 0.05,
            },
            "wave",
            WallContact::Paper,
            Err(RunError::Wave(WaveError::TimeLimit { time: 1.0 })),
            true,
        );
        assert_eq!(
            lost.csv(true).split(',').count(),
            Row::csv_header(true).split(',').count()
        );
        let failed = Row::new(
            Bilayer {
                x: 0.4,
                alpha: 0.05,
            },
            "wave",
            WallContact::Paper,
            Err(RunError::Scene(SceneError::Json("a, \"b\"".into()))),
            false,
        );
        assert!(failed.csv(false).ends_with("\"scene JSON: a, \"\"b\"\"\""));
    }
}

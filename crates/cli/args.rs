//! Flags, as `clap` sees them. Validation into engine settings happens in
//! [`WaveArgs::config`] and the subcommands, never in the engines.

use crate::input;
use clap::{Args, Parser, Subcommand, ValueEnum};
use impact_wave::{Record, StopRule, WaveConfig};
use std::path::PathBuf;

#[derive(Parser, Debug)]
#[command(
    name = "impact",
    version,
    about = "Impact of layered elastic projectiles on a rigid wall: exact restitution, contact time and bounces",
    long_about = "Impact of layered (composite) elastic rods on a rigid wall.\n\n\
The exact engine traces every strain front (d'Alembert) through the layers, \
with reflection/transmission at interfaces and unilateral contact at the wall: \
no time step, no mesh. The canonical bilayer of the paper is given by \
x = L2/L and alpha = E2/(E1 + E2); any layered rod can be given as a JSON scene.",
    after_help = "Examples:\n  impact run --x 0.4 --alpha 0.05\n  impact run data/scenes/three-layers.json --json\n  impact sweep --out grid.csv"
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// Simulate one impact (the canonical bilayer or a scene file)
    Run(RunArgs),
    /// Simulate every point of an (x, alpha) grid, in parallel
    Sweep(SweepArgs),
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum EngineChoice {
    /// The exact engine for elastic scenes
    Auto,
    /// The exact front-tracing engine (elastic layers only)
    Wave,
}

/// Settings of the exact engine.
#[derive(Args, Debug, Clone)]
pub struct WaveArgs {
    /// Drop fronts whose velocity jump is below this fraction of v_b (reported in the output)
    #[arg(
        long,
        value_name = "FRACTION",
        default_value_t = 1e-16,
        allow_negative_numbers = true
    )]
    pub drop_tolerance: f64,
    /// Merge fronts born within this many min(t_i) of each other in a layer (0: exact)
    #[arg(
        long,
        value_name = "FRACTION",
        default_value_t = 0.0,
        allow_negative_numbers = true
    )]
    pub merge_window: f64,
    /// Stop at FACTOR * max(t_i), as the paper does with 20, instead of the exact escape rule
    #[arg(long, value_name = "FACTOR", allow_negative_numbers = true)]
    pub horizon: Option<f64>,
    /// Give up after this many events
    #[arg(long, value_name = "N", default_value_t = 10_000_000)]
    pub max_events: u64,
}

impl WaveArgs {
    /// Validated engine settings.
    pub fn config(&self, record: Record) -> anyhow::Result<WaveConfig> {
        let nonneg = |name: &str, v: f64| {
            if v.is_finite() && v >= 0.0 {
                Ok(v)
            } else {
                Err(input(format!(
                    "--{name} must be a finite number >= 0 (got {v})"
                )))
            }
        };
        let stop = match self.horizon {
            None => StopRule::Escape,
            Some(f) if f.is_finite() && f > 0.0 => StopRule::Horizon { factor: f },
            Some(f) => {
                return Err(input(format!(
                    "--horizon must be a finite number > 0 (got {f})"
                )));
            }
        };
        if self.max_events == 0 {
            return Err(input("--max-events must be at least 1 (got 0)"));
        }
        Ok(WaveConfig {
            stop,
            drop_tolerance: nonneg("drop-tolerance", self.drop_tolerance)?,
            merge_window: nonneg("merge-window", self.merge_window)?,
            max_events: self.max_events,
            record,
            ..WaveConfig::default()
        })
    }
}

#[derive(Args, Debug)]
pub struct RunArgs {
    /// Scene file (JSON: impact_speed and layers, bottom first)
    #[arg(value_name = "SCENE", conflicts_with_all = ["x", "alpha"])]
    pub scene: Option<PathBuf>,
    /// Composition x = L2 / L of the canonical bilayer, in (0, 1)
    #[arg(long, allow_negative_numbers = true, requires = "alpha")]
    pub x: Option<f64>,
    /// Stiffness ratio alpha = E2 / (E1 + E2) of the canonical bilayer, in (0, 1)
    #[arg(long, allow_negative_numbers = true, requires = "x")]
    pub alpha: Option<f64>,
    /// Which engine to run
    #[arg(long, value_enum, default_value_t = EngineChoice::Auto)]
    pub engine: EngineChoice,
    /// Print one JSON object on stdout instead of the summary
    #[arg(long)]
    pub json: bool,
    /// Also write the wall history (time, strain, height, velocity) to this CSV file
    #[arg(long, value_name = "FILE")]
    pub wall_trace: Option<PathBuf>,
    #[command(flatten)]
    pub wave: WaveArgs,
}

#[derive(Args, Debug)]
pub struct SweepArgs {
    /// Composition axis START:STOP:STEP (or one value); default: the paper's
    #[arg(
        long,
        value_name = "START:STOP:STEP",
        default_value = "0.005:0.995:0.005",
        allow_hyphen_values = true
    )]
    pub x: String,
    /// Stiffness-ratio axis START:STOP:STEP (or one value); default: the paper's
    #[arg(
        long,
        value_name = "START:STOP:STEP",
        default_value = "0.005:0.995:0.005",
        allow_hyphen_values = true
    )]
    pub alpha: String,
    /// Which engine to run
    #[arg(long, value_enum, default_value_t = EngineChoice::Auto)]
    pub engine: EngineChoice,
    /// Output file: CSV, or JSON lines when it ends in .jsonl
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Leave out the elapsed_seconds column, so identical runs give identical files
    #[arg(long)]
    pub no_timing: bool,
    /// Worker threads (default: all cores)
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    #[command(flatten)]
    pub wave: WaveArgs,
}

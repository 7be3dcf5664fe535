//! Flags, as `clap` sees them: what the user typed, nothing checked beyond
//! clap's own parsing. Validation into library settings happens in
//! `settings.rs` (`WaveArgs::config`, `EngineArgs::engine`, ...) and the
//! subcommands, never in the engines.

use clap::{Args, Parser, Subcommand, ValueEnum};
use impact_model::WallContact;
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
    /// Convert a layer restitution e_i to tau c / L and back (paper Sec. VII)
    Calibrate(CalibrateArgs),
    /// Validate the engines against each other over a grid and write a report
    Compare(CompareArgs),
    /// Join the journals of a sharded sweep or compare into one result
    Merge(MergeArgs),
    /// Draw the space-time (wave-path) diagram of one impact
    Diagram(DiagramArgs),
    /// Regenerate every figure of the paper beside what the paper states
    Reproduce(ReproduceArgs),
    /// What accuracy costs in time: both engines' settings against error and time
    Cost(CostArgs),
    /// The map, any impact's wave paths and a scene editor, live in the browser
    Explore(ExploreArgs),
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum EngineChoice {
    /// The exact engine for elastic scenes, the chain when any layer is viscous
    Auto,
    /// The exact front-tracing engine (elastic layers only)
    Wave,
    /// The paper's discrete Beeman mass-spring(-dashpot) chain
    Chain,
    /// The rigid-bottom limit: the bottom layer a rigid mass under the elastic stack (elastic scenes of 2+ layers)
    RigidBottom,
}

/// Settings of the exact engine.
#[derive(Args, Debug, Clone)]
pub struct WaveArgs {
    /// Drop fronts whose velocity jump is below this fraction of v_b (accounted for in the error bound)
    #[arg(
        long,
        value_name = "FRACTION",
        default_value_t = 1e-16,
        allow_negative_numbers = true
    )]
    pub drop_tolerance: f64,
    /// Exact engine: auto (exact when it fits, else merged fronts with a measured error), exact, or merged
    #[arg(long, value_enum, default_value_t = ResolutionChoice::Auto)]
    pub resolution: ResolutionChoice,
    /// Merge fronts of a layer born within this fraction of its transit time (implies --resolution merged)
    #[arg(long, value_name = "FRACTION", allow_negative_numbers = true)]
    pub merge_window: Option<f64>,
    /// Work a merged ladder may spend under --resolution auto, in event-loop steps (a leap counts the fronts and lattice cells it handles); the lattices are chosen from it. Where the ladder's levels do not converge and the first exact run's growth says an exact run may fit this budget, the exact run is tried again with it (at most 2e7 events) and, if it finishes, reported (the ladder's e and bound beside it)
    #[arg(long, value_name = "N", value_parser = parse_count, allow_negative_numbers = true, default_value_t = 4_000_000)]
    pub event_budget: u64,
    /// Target error on e. Exact engine (--resolution auto): refine merged runs until the error bound is at most DE (default 1e-5, or until the budget is spent). Chain on a viscous scene without --n: double N until the extrapolation's error estimate is at most DE (default: N = 250, 500, 1000 only)
    #[arg(long, value_name = "DE", allow_negative_numbers = true)]
    pub target: Option<f64>,
    /// Arithmetic: checked (double, repeated in double-double when rounding may matter), double, double-double
    #[arg(long, value_enum, default_value_t = PrecisionChoice::Checked)]
    pub precision: PrecisionChoice,
    /// Give a run up after this much work: loop events, and the fronts and lattice cells of leaps (the rigid-bottom model: its events, at most 2e7)
    #[arg(long, value_name = "N", value_parser = parse_count, allow_negative_numbers = true, default_value_t = 200_000_000)]
    pub max_events: u64,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum ResolutionChoice {
    /// Exact when the exact run takes at most 2e5 events, else merged under the event budget
    Auto,
    /// Never merge fronts (fails where fronts multiply without bound)
    Exact,
    /// Merge fronts within --merge-window (default 1e-2), error measured at twice the window
    Merged,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum PrecisionChoice {
    /// Double precision, repeated in double-double when decisions came near grazing or the rod chattered
    Checked,
    /// Double precision only (rounding estimated a priori)
    Double,
    /// Double-double (about 32 digits) throughout
    DoubleDouble,
}

/// Settings of the chain.
#[derive(Args, Debug, Clone)]
pub struct ChainArgs {
    /// Chain time step as a fraction of the paper's min(2 pi sqrt(m/k))/100
    #[arg(
        long,
        value_name = "FACTOR",
        default_value_t = 1.0,
        allow_negative_numbers = true
    )]
    pub dt_factor: f64,
    /// Give the chain up after this many steps
    #[arg(long, value_name = "N", value_parser = parse_count, allow_negative_numbers = true, default_value_t = 2_000_000_000)]
    pub max_steps: u64,
    /// Which kernel steps a viscous chain (both have the same dt -> 0 limit)
    #[arg(long, value_enum, value_name = "KERNEL", default_value_t = ViscousKernelChoice::Implicit)]
    pub viscous_kernel: ViscousKernelChoice,
}

/// The viscous chain's kernels.
#[derive(clap::ValueEnum, Debug, Clone, Copy, PartialEq, Eq)]
pub enum ViscousKernelChoice {
    /// SDIRK2 on springs and dashpots together: second order and stiffly accurate, within 2e-5 of the dt -> 0 limit at the paper's step wherever measured
    Implicit,
    /// A Beeman step of the springs, then an SDIRK2 step of the dashpots: 3-4x faster than implicit on short chains (under a few hundred masses), about as fast on longer ones, but up to 6e-4 from the limit where a dashpot is stiff against the step
    Split,
}

impl From<ViscousKernelChoice> for impact_chain::ViscousKernel {
    fn from(choice: ViscousKernelChoice) -> Self {
        match choice {
            ViscousKernelChoice::Split => Self::Split,
            ViscousKernelChoice::Implicit => Self::Implicit,
        }
    }
}

/// Which engine, and the settings of both.
#[derive(Args, Debug, Clone)]
pub struct EngineArgs {
    /// Which engine to run
    #[arg(long, value_enum, default_value_t = EngineChoice::Auto)]
    pub engine: EngineChoice,
    /// Stop at FACTOR * max(t_i), as the paper does with 20, instead of the exact escape rule
    #[arg(long, value_name = "FACTOR", allow_negative_numbers = true)]
    pub horizon: Option<f64>,
    #[command(flatten)]
    pub wave: WaveArgs,
    #[command(flatten)]
    pub chain: ChainArgs,
}

/// Viscosity of the canonical bilayer's layers.
#[derive(Args, Debug, Clone)]
pub struct ViscosityArgs {
    /// Relaxation time tau = eta/E of the bottom layer P1 (chain only)
    #[arg(
        long,
        value_name = "TAU",
        allow_negative_numbers = true,
        conflicts_with = "e1"
    )]
    pub tau1: Option<f64>,
    /// Relaxation time tau = eta/E of the top layer P2 (chain only)
    #[arg(
        long,
        value_name = "TAU",
        allow_negative_numbers = true,
        conflicts_with = "e2"
    )]
    pub tau2: Option<f64>,
    /// Restitution e_1 of a whole-length rod made of P1 (the paper's way, Sec. VII)
    #[arg(long, value_name = "E", allow_negative_numbers = true)]
    pub e1: Option<f64>,
    /// Restitution e_2 of a whole-length rod made of P2
    #[arg(long, value_name = "E", allow_negative_numbers = true)]
    pub e2: Option<f64>,
    /// The wall's contact law for viscous bottoms: paper (Sec. III: the bottom element's spring
    /// and dashpot act while it is compressed, so the wall may pull) or unilateral (the wall only
    /// pushes). The same physics for elastic rods. Default: the scene's, else paper
    #[arg(long, value_name = "LAW", value_parser = parse_wall_contact)]
    pub wall_contact: Option<WallContact>,
}

fn parse_wall_contact(s: &str) -> Result<WallContact, String> {
    s.parse()
}

/// A count given as an integer (`4000000`, `4_000_000`) or in the
/// scientific notation physicists write budgets in (`4e6`, `1e8`), if that
/// names a whole number a `u64` holds.
fn parse_count(s: &str) -> Result<u64, String> {
    let digits = s.replace('_', "");
    if let Ok(n) = digits.parse::<u64>() {
        return Ok(n);
    }
    match digits.parse::<f64>() {
        // 2^64 is exact in binary: below it, every whole double fits
        Ok(x) if x >= 0.0 && x.fract() == 0.0 && x < 2f64.powi(64) => Ok(x as u64),
        _ => Err(format!(
            "'{s}' is not a whole number from 0 to 1.8e19 (an integer, or like 4e6)"
        )),
    }
}

/// [`parse_count`] for sizes (numbers of masses).
fn parse_size(s: &str) -> Result<usize, String> {
    let n = parse_count(s)?;
    usize::try_from(n).map_err(|_| format!("'{s}' is too large for this machine"))
}

#[derive(Args, Debug)]
pub struct RunArgs {
    #[command(flatten)]
    pub subject: SceneArgs,
    #[command(flatten)]
    pub viscosity: ViscosityArgs,
    /// Print one JSON object on stdout instead of the summary
    #[arg(long)]
    pub json: bool,
    /// Also write the wall history (time, strain, height, velocity) to this CSV file
    #[arg(long, value_name = "FILE")]
    pub wall_trace: Option<PathBuf>,
    /// Run one chain of N masses. Without it a viscous scene runs chains of
    /// 250, 500 and 1000 masses and extrapolates e to N -> infinity with an
    /// error estimate; an elastic scene on the chain runs the paper's 10^4
    #[arg(long = "n", value_name = "N", value_parser = parse_size)]
    pub masses: Option<usize>,
    /// The largest chain --target may run
    #[arg(
        long,
        value_name = "N",
        value_parser = parse_size,
        default_value_t = 64_000,
        conflicts_with = "masses"
    )]
    pub max_n: usize,
    #[command(flatten)]
    pub engine: EngineArgs,
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
    #[command(flatten)]
    pub viscosity: ViscosityArgs,
    /// Output file: CSV, or JSON lines when it ends in .jsonl; `-` writes CSV to standard output
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Leave out the elapsed_seconds column, so identical runs give identical files
    #[arg(long)]
    pub no_timing: bool,
    /// Number of masses of the chain (the paper's 10^4); at least one per layer
    #[arg(long = "n", value_name = "N", value_parser = parse_size, default_value_t = 10_000)]
    pub masses: usize,
    /// Worker threads (default: all cores)
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    #[command(flatten)]
    pub journal: JournalArgs,
    #[command(flatten)]
    pub engine: EngineArgs,
}

/// Splitting a long run over machines, and surviving interruptions.
#[derive(Args, Debug, Clone)]
pub struct JournalArgs {
    /// Run only shard I of N (1-based; point k belongs to shard k mod N + 1), journaling as it goes
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,
    /// Complete an interrupted run from its journal instead of starting over
    #[arg(long)]
    pub resume: bool,
}

#[derive(Args, Debug)]
pub struct CompareArgs {
    /// Composition axis START:STOP:STEP (or one value); the default grid and sizes take ~2 minutes on 2 cores
    #[arg(
        long,
        value_name = "START:STOP:STEP",
        default_value = "0.05:0.95:0.05",
        allow_hyphen_values = true
    )]
    pub x: String,
    /// Stiffness-ratio axis START:STOP:STEP (or one value)
    #[arg(
        long,
        value_name = "START:STOP:STEP",
        default_value = "0.05:0.95:0.05",
        allow_hyphen_values = true
    )]
    pub alpha: String,
    /// Chain sizes, comma-separated and increasing; several give convergence orders and Richardson extrapolation
    #[arg(long = "n", value_name = "N[,N...]", default_value = "500,1000,2000")]
    pub sizes: String,
    /// Report directory
    #[arg(long, value_name = "DIR", default_value = "compare-report")]
    pub out: PathBuf,
    /// |e_chain - e_exact| above this counts as a disagreement
    #[arg(
        long,
        value_name = "DE",
        default_value_t = 0.01,
        allow_negative_numbers = true
    )]
    pub tolerance: f64,
    /// |difference of t_c / (2 sum t_i)| above this is a contact-class change
    #[arg(
        long,
        value_name = "D",
        default_value_t = 0.02,
        allow_negative_numbers = true
    )]
    pub contact_tolerance: f64,
    /// Exit with status 1 if any |de| exceeds TOL (for CI)
    #[arg(long, value_name = "TOL", allow_negative_numbers = true)]
    pub fail_above: Option<f64>,
    /// Leave wall-clock times out, so identical runs give identical reports
    #[arg(long)]
    pub no_timing: bool,
    /// Worker threads (default: all cores)
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    #[command(flatten)]
    pub journal: JournalArgs,
    #[command(flatten)]
    pub engine: EngineArgs,
}

#[derive(Args, Debug)]
pub struct MergeArgs {
    /// Journals written by `--shard` runs of one sweep or compare
    #[arg(value_name = "JOURNAL", required = true)]
    pub journals: Vec<PathBuf>,
    /// Output: the file a sweep would write (.csv or .jsonl), or the report directory of a compare
    #[arg(long, value_name = "PATH")]
    pub out: PathBuf,
}

#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("what").required(true).args(["restitution", "tau_c_over_l", "regenerate"])))]
pub struct CalibrateArgs {
    /// Print the tau c / L that gives this layer restitution
    #[arg(long, value_name = "E", allow_negative_numbers = true)]
    pub restitution: Option<f64>,
    /// Print the restitution of a homogeneous rod with this tau c / L
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub tau_c_over_l: Option<f64>,
    /// Recompute the calibration table with the chain (minutes) and write it to --out
    #[arg(long)]
    pub regenerate: bool,
    /// The wall's contact law whose table to use or regenerate: paper or unilateral
    #[arg(long, value_name = "LAW", value_parser = parse_wall_contact, default_value = "paper")]
    pub wall_contact: WallContact,
    /// Chain size for --regenerate (each entry uses N and 2N, Richardson-extrapolated)
    #[arg(long = "n", value_name = "N", value_parser = parse_size, default_value_t = 2000)]
    pub masses: usize,
    /// Where --regenerate writes the table [default: data/calibration/kelvin-voigt-<LAW>.csv]
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Print JSON instead of text
    #[arg(long)]
    pub json: bool,
}

#[derive(Args, Debug)]
pub struct DiagramArgs {
    #[command(flatten)]
    pub subject: SceneArgs,
    /// Output figure: .svg (vector, real text), .png, or .html (self-contained page with the event table)
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
    /// Also write the self-contained HTML page (diagram with tooltips and event table) beside --out
    #[arg(long)]
    pub html: bool,
    /// Which picture: the exact fronts (wave) or the chain's strain field
    #[arg(long, value_enum, default_value_t = DiagramEngine::Wave)]
    pub engine: DiagramEngine,
    /// Both pictures side by side, sharing axes and colour scale
    #[arg(long)]
    pub side_by_side: bool,
    /// Number of masses of the chain picture
    #[arg(long = "n", value_name = "N", value_parser = parse_size, default_value_t = 2000)]
    pub masses: usize,
    /// Time window start
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub t_start: Option<f64>,
    /// Time window end (default: a little after the final takeoff)
    #[arg(long, value_name = "T", allow_negative_numbers = true)]
    pub t_end: Option<f64>,
    /// Colour scale: strains of this magnitude are fully red or blue (default: the largest shown)
    #[arg(long, value_name = "STRAIN", allow_negative_numbers = true)]
    pub strain_scale: Option<f64>,
    /// Do not draw the front lines
    #[arg(long)]
    pub no_fronts: bool,
}

#[derive(ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub enum DiagramEngine {
    Wave,
    Chain,
}

#[derive(Args, Debug)]
#[command(group(clap::ArgGroup::new("mode").args(["quick", "full"])))]
pub struct ReproduceArgs {
    /// Report directory
    #[arg(long, value_name = "DIR", default_value = "paper-report")]
    pub out: PathBuf,
    /// A few minutes on 2 cores: chains of 400 masses, coarser scans (the default)
    #[arg(long)]
    pub quick: bool,
    /// The paper's resolution (chains of 10^4 masses): hours on 2 cores
    #[arg(long)]
    pub full: bool,
    /// Worker threads (default: all cores)
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
}

#[derive(Args, Debug)]
pub struct CostArgs {
    /// Scene file (JSON, elastic); default: the canonical bilayer --x/--alpha
    #[arg(value_name = "SCENE", conflicts_with_all = ["x", "alpha"])]
    pub scene: Option<PathBuf>,
    /// Composition x of the canonical bilayer
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.3)]
    pub x: f64,
    /// Stiffness ratio alpha of the canonical bilayer
    #[arg(long, allow_negative_numbers = true, default_value_t = 0.3)]
    pub alpha: f64,
    /// Report directory
    #[arg(long, value_name = "DIR", default_value = "cost-report")]
    pub out: PathBuf,
    /// Error in e the headline asks the chain to reach
    #[arg(
        long,
        value_name = "DE",
        default_value_t = 1e-3,
        allow_negative_numbers = true
    )]
    pub target: f64,
    /// A small study (seconds): fewer sizes and tolerances
    #[arg(long)]
    pub quick: bool,
    /// The wall's contact law of the viscous part of the study: paper (default) or unilateral
    #[arg(long, value_name = "LAW", value_parser = parse_wall_contact)]
    pub wall_contact: Option<WallContact>,
}

#[derive(Args, Debug)]
#[command(
    after_help = "The page lives at the printed URL; its API (GET /api/run?x=X&alpha=A, POST /api/run with a scene, /api/diagram, /api/map?step=S) answers with what `impact run --json` prints.\n\nExamples:\n  impact explore --open\n  impact explore data/scenes/steel-under-rubber.json --port 0"
)]
pub struct ExploreArgs {
    /// Scene file to show first (JSON); default: the canonical bilayer
    #[arg(value_name = "SCENE")]
    pub scene: Option<PathBuf>,
    /// Port to listen on (0: any free port, printed)
    #[arg(long, value_name = "P", default_value_t = 8321)]
    pub port: u16,
    /// Address to listen on; anything but loopback serves other machines too (a warning says so)
    #[arg(long, value_name = "ADDR", default_value = "127.0.0.1")]
    pub bind: std::net::IpAddr,
    /// Open the page in the default browser
    #[arg(long)]
    pub open: bool,
}

/// What to simulate: a scene file, or the canonical bilayer.
#[derive(Args, Debug, Clone)]
pub struct SceneArgs {
    /// Scene file (JSON: impact_speed and layers, bottom first)
    #[arg(value_name = "SCENE", conflicts_with_all = ["x", "alpha"])]
    pub scene: Option<PathBuf>,
    /// Composition x = L2 / L of the canonical bilayer, in (0, 1)
    #[arg(long, allow_negative_numbers = true, requires = "alpha")]
    pub x: Option<f64>,
    /// Stiffness ratio alpha = E2 / (E1 + E2) of the canonical bilayer, in (0, 1)
    #[arg(long, allow_negative_numbers = true, requires = "x")]
    pub alpha: Option<f64>,
}

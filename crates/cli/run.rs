//! `impact run`: one impact.

use crate::args::RunArgs;
use crate::input;
use crate::output::{summary, write_atomically};
use impact_chain::{ChainEngine, ChainLayout, ChainRecord};
use impact_model::{Scene, Timed, WallSample};
use impact_output::Plain;
use impact_rigid::RigidError;
use impact_study::{Engine, LimitSettings, chain_limit};
use impact_wave::{Record, WaveError};
use std::io::Write;

/// One line of the wall trace: a [`WallSample`], numbers as `Display`
/// writes them. Every engine records the impact, so the file always has
/// its header.
#[derive(serde::Serialize)]
struct WallTraceLine {
    time: Plain<f64>,
    strain: Plain<f64>,
    height: Plain<f64>,
    velocity: Plain<f64>,
}

/// Reads and validates a scene file; every failure is an input error.
pub fn read_scene(path: &std::path::Path) -> anyhow::Result<Scene> {
    read_scene_text(path).map(|(_, scene)| scene)
}

/// A scene file's text and the scene it holds; every failure is an input
/// error.
pub fn read_scene_text(path: &std::path::Path) -> anyhow::Result<(String, Scene)> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| input(format!("cannot read scene {}: {e}", path.display())))?;
    let scene = Scene::from_json(&text).map_err(|e| input(format!("{}: {e}", path.display())))?;
    Ok((text, scene))
}

/// What one `impact run` computed: the title of its summary, the outcome
/// with its wall time, and the wall history (recorded only when asked).
pub struct Computed {
    pub title: String,
    pub outcome: Timed<impact_model::Outcome>,
    pub wall: Vec<WallSample>,
}

pub fn run(a: RunArgs) -> anyhow::Result<()> {
    let Computed {
        title,
        outcome,
        wall,
    } = compute(&a, None)?;
    if let Some(path) = &a.wall_trace {
        let lines = wall.iter().map(|s| WallTraceLine {
            time: Plain(s.time),
            strain: Plain(s.strain),
            height: Plain(s.height),
            velocity: Plain(s.velocity),
        });
        write_atomically(path, |w| impact_output::write_csv(w, lines))?;
    }
    let mut stdout = std::io::stdout().lock();
    if a.json {
        writeln!(stdout, "{}", serde_json::to_string(&outcome)?)?;
    } else {
        write!(stdout, "{}", summary(&title, &outcome))?;
    }
    Ok(())
}

/// Runs what `a` asks for, on `given` instead of the scene `a` names when
/// the caller already holds one (the explorer: a scene sent over HTTP,
/// never a file). Writes nothing.
pub fn compute(a: &RunArgs, given: Option<Scene>) -> anyhow::Result<Computed> {
    if (a.subject.scene.is_some() || given.is_some()) && a.viscosity.given() {
        return Err(input(
            "--tau1/--tau2/--e1/--e2 apply to --x/--alpha only: give viscosity in the scene file",
        ));
    }
    let (scene, bilayer, name) = a.subject.load(given)?;
    let (scene, title) = match bilayer {
        Some(b) => (
            a.viscosity.viscosity().scene(b),
            format!(
                "Canonical bilayer {name} (L = 1, rho = 1, E1 = 1 - alpha, E2 = alpha, v_b = 1)"
            ),
        ),
        None => (scene, format!("Scene {name}")),
    };
    let mut scene = scene;
    if let Some(law) = a.viscosity.wall_contact {
        scene.wall_contact = Some(law);
    }
    let rod = scene.validate().map_err(|e| input(e.to_string()))?;
    let trace = a.wall_trace.is_some();
    let wave_record = Record {
        wall: trace,
        fronts: false,
    };
    let chain_record = ChainRecord {
        wall_every: trace.then_some(16),
        raster: None,
        record_until: None,
    };
    let masses = a.masses.unwrap_or(10_000);
    let engine = a
        .engine
        .engine(rod.is_viscous(), masses, wave_record, chain_record)?;
    let target = a.engine.wave.target;
    if a.max_n < 1000 {
        return Err(input(format!(
            "--max-n must be at least 1000 (got {})",
            a.max_n
        )));
    }
    if rod.is_viscous() && a.masses.is_some() && target.is_some() {
        return Err(input(
            "--target drives the chain's extrapolation over N; it cannot go with --n (one chain)",
        ));
    }
    let ladder = LimitSettings {
        target,
        max_masses: a.max_n,
        ..LimitSettings::default()
    };
    // --target is checked whichever engine runs
    ladder.check().map_err(crate::flags::setting)?;
    let limit = (rod.is_viscous() && a.masses.is_none()).then_some(ladder);
    let (outcome, wall): (_, Vec<WallSample>) = match engine {
        Engine::Wave(config) => {
            let spinner = crate::jobs::LadderSpinner::new();
            let solution = Timed::try_measure(|| {
                impact_wave::solve_observed(&rod, &config, &|p| spinner.show(p))
            })
            .map_err(wave_failure)?;
            drop(spinner);
            let o = Timed {
                value: solution.value.outcome,
                seconds: solution.seconds,
            };
            (o, solution.value.engine.recording().wall.clone())
        }
        Engine::Chain(config) if limit.is_some() => {
            let settings = limit.unwrap_or_default();
            let done = Timed::try_measure(|| chain_limit(&rod, &config, &settings))
                .map_err(crate::flags::chain)?;
            if done.target_met == Some(false) {
                eprintln!(
                    "warning: --target {} not met with chains up to --max-n {}: the estimate is the one below",
                    settings.target.unwrap_or(0.0),
                    settings.max_masses
                );
            }
            let o = Timed {
                value: done.value.outcome,
                seconds: done.seconds,
            };
            (o, done.value.recording.wall)
        }
        Engine::Chain(config) => {
            let layout = ChainLayout::new(&rod, config.masses).map_err(crate::flags::chain)?;
            for (layer, count) in layout.thin_layers() {
                eprintln!(
                    "warning: layer {layer} has {count} masses (< 50, the paper's minimum for ~1% accuracy); raise --n"
                );
            }
            let mut e = ChainEngine::new(&rod, config).map_err(crate::flags::chain)?;
            let o = Timed::try_measure(|| e.run()).map_err(crate::flags::chain)?;
            (o, e.recording().wall.clone())
        }
        Engine::RigidBottom(config) => {
            let o = Timed::try_measure(|| impact_rigid::simulate(&rod, &config)).map_err(|e| match e {
                RigidError::Setting(e) => crate::flags::setting(e),
                RigidError::ViscousLayer { .. } => input(e.to_string()),
                RigidError::Unfinished { .. } => anyhow::Error::new(e).context(
                    "the rigid-bottom model could not finish (raise --horizon, or drop it for the exact escape rule)",
                ),
                RigidError::EventLimit { .. } => anyhow::Error::new(e).context(
                    "the rigid-bottom model could not finish (raise --max-events, up to its 2e7; it follows every piece of the stack's waves exactly and merges none, so on stacks of several layers they can multiply past any budget: --engine wave bounds them on its merged lattice)",
                ),
            })?;
            if a.wall_trace.is_some() {
                return Err(input(
                    "--wall-trace: the rigid-bottom model records no wall trace (use --engine wave or chain)",
                ));
            }
            (o, Vec::new())
        }
    };
    Ok(Computed {
        title,
        outcome,
        wall,
    })
}

/// An exact-engine failure as the command line reports it: settings are
/// input errors (exit 2); a run that could not finish (exit 1) names the
/// flags that change the outcome.
pub fn wave_failure(e: WaveError) -> anyhow::Error {
    let hint = match &e {
        WaveError::Setting(e) => return crate::flags::setting(e.clone()),
        WaveError::ViscousLayer { .. } => return input(e.to_string()),
        WaveError::EventLimit { .. } => {
            "raise --max-events, or let fronts merge with --resolution auto (the default) or merged"
        }
        WaveError::LatticeLimit { .. } => {
            "raise --max-events: a merged run's work grows with how long the contact lasts"
        }
        WaveError::TimeLimit { .. } => "stop at a horizon with --horizon FACTOR",
        WaveError::Unfinished { .. } => {
            "raise --horizon, or drop it for the exact escape rule; no restitution is reported"
        }
        WaveError::EventInPast { .. } => "this is a bug: please report the scene",
    };
    anyhow::Error::new(e).context(format!("the exact engine could not finish ({hint})"))
}

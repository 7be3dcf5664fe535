//! Runs made for drawing: the engines asked to record what a picture needs
//! (fronts and parents, wall history, strain raster), and nothing more.

use crate::field::ExactField;
use crate::figure::{ChainPicture, Picture};
use crate::takeoff::takeoff_path;
use impact_chain::{ChainConfig, ChainEngine, ChainError, ChainRecord};
use impact_model::{Outcome, Rod};
use impact_wave::{Record, WaveConfig, WaveEngine, WaveError};

/// A picture with the run it came from.
#[derive(Debug, Clone)]
pub struct Run {
    /// What to draw.
    pub picture: Picture,
    /// The run's outcome.
    pub outcome: Outcome,
    /// `(time, wall strain)` after each wall event or sample.
    pub wall: Vec<(f64, f64)>,
}

/// Events an exact run for a picture may take. A diagram draws every front
/// with its parents, so it cannot merge fronts as `impact run` does where
/// they multiply without bound (a stiff layer ringing under a soft one);
/// there the run stops here, with the engine's `EventLimit`, instead of
/// recording fronts until memory runs out. The hard corner of the paper's
/// grid takes 33,149 events.
pub const MAX_DRAWN_EVENTS: u64 = 1_000_000;

/// The exact engine with fronts and parents recorded, at most
/// [`MAX_DRAWN_EVENTS`] events.
pub fn exact_run(rod: &Rod) -> Result<Run, WaveError> {
    let config = WaveConfig {
        record: Record {
            wall: true,
            fronts: true,
        },
        max_events: MAX_DRAWN_EVENTS,
        ..WaveConfig::default()
    };
    let mut e = WaveEngine::new(rod, config)?;
    let outcome = e.run()?;
    let rec = e.recording();
    let wall = rec.wall.iter().map(|s| (s.time, s.strain)).collect();
    let picture = match ExactField::new(rod, rec) {
        Ok(field) => Picture::Exact {
            path: takeoff_path(rod, &rec.fronts, outcome.contact_time),
            field,
            fronts: rec.fronts.clone(),
        },
        // a run with no front at all cannot happen (the impact launches one)
        Err(_) => Picture::Chain(ChainPicture { frames: Vec::new() }),
    };
    Ok(Run {
        picture,
        outcome,
        wall,
    })
}

/// The chain of `masses`, with ~1500 raster frames of up to 200 rows over
/// `[0, until]`, and on at that rate to the end of the run.
pub fn chain_run(rod: &Rod, masses: usize, until: f64) -> Result<Run, ChainError> {
    chain_frames(rod, masses, until, None)
}

/// [`chain_run`] with no frames or wall samples after `until`: a window
/// far shorter than the run, sampled as finely, without samples for the
/// rest of it.
pub fn chain_run_within(rod: &Rod, masses: usize, until: f64) -> Result<Run, ChainError> {
    chain_frames(rod, masses, until, Some(until))
}

fn chain_frames(
    rod: &Rod,
    masses: usize,
    until: f64,
    record_until: Option<f64>,
) -> Result<Run, ChainError> {
    let probe = ChainEngine::new(
        rod,
        ChainConfig {
            masses,
            ..ChainConfig::default()
        },
    )?;
    let every = ((until / probe.time_step()) / 1500.0).ceil().max(1.0) as u64;
    let config = ChainConfig {
        masses,
        record: ChainRecord {
            wall_every: Some(every),
            raster: Some((every, 200.min(masses))),
            record_until,
        },
        ..ChainConfig::default()
    };
    let mut e = ChainEngine::new(rod, config)?;
    let outcome = e.run()?;
    let wall = e
        .recording()
        .wall
        .iter()
        .map(|s| (s.time, s.strain))
        .collect();
    Ok(Run {
        picture: Picture::Chain(ChainPicture {
            frames: e.recording().raster.clone(),
        }),
        outcome,
        wall,
    })
}

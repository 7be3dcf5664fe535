//! The chain's answer in the continuum limit: the same impact at `N`, `2N`,
//! `4N` masses (more when a target asks), Richardson-extrapolated to
//! `N -> infinity` with an error estimate (`impact_model::numerics::richardson`).
//!
//! Why: the viscous chain converges in `N` at about order one, so one `N`
//! carries a finite-size error as large as `1e-3` at `N = 10^3`, while three
//! small chains and an extrapolation reach `1e-4` for a fraction of the cost
//! of one large chain (the cost grows as `N^2`: `N` masses for a number of
//! steps proportional to `N`).

use impact_chain::{ChainConfig, ChainEngine, ChainError, ChainRecord, ChainRecording};
use impact_model::numerics::{Extrapolation, extrapolate};
use impact_model::{Allowed, Outcome, Rod, SettingError};

/// How far to refine.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LimitSettings {
    /// The coarsest chain.
    pub base_masses: usize,
    /// Keep doubling until the error estimate is at most this.
    pub target: Option<f64>,
    /// Never run a chain larger than this.
    pub max_masses: usize,
}

impl LimitSettings {
    /// The settings' ranges: a chain of at least one mass, and a target
    /// error above zero.
    pub fn check(&self) -> Result<(), SettingError> {
        Allowed::AtLeast(1).check_count("base_masses", self.base_masses as u64)?;
        Allowed::AtLeast(1).check_count("max_masses", self.max_masses as u64)?;
        if let Some(target) = self.target {
            Allowed::Positive.check("target", target)?;
        }
        Ok(())
    }
}

impl Default for LimitSettings {
    fn default() -> Self {
        Self {
            base_masses: 250,
            target: None,
            max_masses: 64_000,
        }
    }
}

/// The ladder's result: the finest run's outcome, carrying the
/// extrapolation, and its recording.
#[derive(Debug, Clone)]
pub struct ChainLimit {
    /// The finest run's outcome; its `extrapolation` holds the `N -> infinity` limit.
    pub outcome: Outcome,
    /// What the finest run recorded.
    pub recording: ChainRecording,
    /// Whether the target was met (`None` without a target).
    pub target_met: Option<bool>,
}

/// How far the finest chain's `e` may be from the continuum's: its distance
/// from the extrapolated limit plus the limit's own estimate. Why: the
/// outcome's `restitution` (like its `t_c` and `N_b`) is the finest chain's,
/// and its `error_bound` must say how far that figure is from the model the
/// ladder answers for, `N -> infinity`, not how far the extrapolation is.
fn finest_chain_error(finest: f64, limit: &Extrapolation) -> f64 {
    (finest - limit.value).abs() + limit.error
}

/// Runs the chain of `config` (its `masses` ignored) at growing sizes and
/// extrapolates `e`. The three first sizes run in parallel; the recording
/// asked for in `config` is kept for the finest run only.
pub fn chain_limit(
    rod: &Rod,
    config: &ChainConfig,
    settings: &LimitSettings,
) -> Result<ChainLimit, ChainError> {
    let run = |masses: usize, record: bool| -> Result<(Outcome, ChainRecording), ChainError> {
        let config = ChainConfig {
            masses,
            record: if record {
                config.record
            } else {
                ChainRecord::default()
            },
            ..config.clone()
        };
        let mut engine = ChainEngine::new(rod, config)?;
        let outcome = engine.run()?;
        Ok((outcome, engine.recording().clone()))
    };
    settings.check()?;
    let n = settings.base_masses;
    let (coarse, finest) = rayon::join(
        || run(n, false).and_then(|a| Ok((a, run(2 * n, false)?))),
        || run(4 * n, true),
    );
    let ((first, _), (second, _)) = coarse?;
    let (mut outcome, mut recording) = finest?;
    let mut sizes = vec![n, 2 * n, 4 * n];
    let mut values = vec![first.restitution, second.restitution, outcome.restitution];
    // elastic layers keep sharp fronts: no clean order in N
    let sharp_fronts = (0..rod.layers().len()).any(|i| rod.relaxation_time(i) == 0.0);
    // e <= 1: the rod leaves with no more energy than it brought (springs
    // store it, dashpots take it); past 1 the chains are not yet asymptotic
    let extrapolation = |sizes: &[usize], values: &[f64]| -> Extrapolation {
        extrapolate(sizes, values, sharp_fronts)
            .expect("three ascending sizes")
            .at_most(1.0, "energy")
    };
    let mut x = extrapolation(&sizes, &values);
    if let Some(target) = settings.target {
        while x.error > target && 2 * sizes[sizes.len() - 1] <= settings.max_masses {
            let next = 2 * sizes[sizes.len() - 1];
            (outcome, recording) = run(next, true)?;
            sizes.push(next);
            values.push(outcome.restitution);
            x = extrapolation(&sizes, &values);
        }
    }
    let target_met = settings.target.map(|t| x.error <= t);
    outcome.error_bound = Some(finest_chain_error(outcome.restitution, &x));
    outcome.extrapolation = Some(x);
    Ok(ChainLimit {
        outcome,
        recording,
        target_met,
    })
}

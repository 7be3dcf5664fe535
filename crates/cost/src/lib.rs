//! What accuracy costs in time. For each engine, each setting that trades
//! accuracy for time is varied and the error (against the exact value, or
//! the chain's own extrapolated limit for viscous rods), the wall time and
//! the hardware-independent work (events, mass-steps) are measured.
//!
//! Timings are measurements, reported, never asserted.

#![warn(missing_docs)]

mod chain;
mod exact;
mod growth;
mod report;

pub use chain::{ChainCost, ChainKind, ChainStudy, Headline, chain_study, headline};
pub use exact::{ExactCost, exact_study};
pub use growth::{Growth, GrowthSweep, growth_study};
pub use report::{CostReport, write_report};

use impact_model::Rod;
use std::time::Instant;
use thiserror::Error;

/// Why a cost study could not run.
#[derive(Debug, Error)]
pub enum CostError {
    /// A viscous layer: the study needs an elastic scene, whose exact solution is the reference.
    #[error(
        "layers[{layer}] is viscous: the cost study needs an elastic scene, whose exact solution is the reference (the viscous study is made from it)"
    )]
    ViscousScene {
        /// Index of the first viscous layer, bottom first.
        layer: usize,
    },
    /// The scene was invalid.
    #[error(transparent)]
    Scene(#[from] impact_model::SceneError),
    /// The exact engine failed.
    #[error(transparent)]
    Wave(#[from] impact_wave::WaveError),
    /// The chain failed.
    #[error(transparent)]
    Chain(#[from] impact_chain::ChainError),
    /// A figure could not be written.
    #[error(transparent)]
    Plot(#[from] impact_plot::PlotError),
    /// A report file could not be written.
    #[error(transparent)]
    Io(#[from] std::io::Error),
}

/// The settings of a cost study.
#[derive(Debug, Clone, PartialEq)]
pub struct CostSettings {
    /// Chain sizes for the N study.
    pub sizes: Vec<usize>,
    /// Time-step factors (of the paper's step) for the dt study.
    pub dt_factors: Vec<f64>,
    /// Chain size of the dt study.
    pub dt_masses: usize,
    /// Exact-engine drop tolerances (0, the reference, is always added).
    pub drop_tolerances: Vec<f64>,
    /// Exact-engine merge windows (0 is always added).
    pub merge_windows: Vec<f64>,
    /// Headline: the error in `e` to reach.
    pub target_error: f64,
    /// The largest `N` the headline tries.
    pub max_masses: usize,
    /// Layer restitution of the top for the viscous chain study.
    pub viscous_e2: f64,
}

impl CostSettings {
    /// A few minutes on 2 cores.
    pub fn standard() -> Self {
        Self {
            sizes: vec![50, 100, 200, 400, 800, 1600, 3200],
            dt_factors: vec![2.0, 1.0, 0.5, 0.25],
            dt_masses: 400,
            drop_tolerances: vec![1e-16, 1e-14, 1e-12, 1e-10, 1e-8, 1e-6, 1e-4],
            merge_windows: vec![1e-6, 1e-4, 1e-3, 1e-2],
            target_error: 1e-3,
            max_masses: 12_800,
            viscous_e2: 0.72,
        }
    }

    /// Seconds, for tests.
    pub fn tiny() -> Self {
        Self {
            sizes: vec![50, 100, 200, 400],
            dt_factors: vec![2.0, 1.0, 0.5],
            dt_masses: 100,
            drop_tolerances: vec![1e-14, 1e-8, 1e-4],
            merge_windows: vec![1e-3, 1e-2],
            target_error: 5e-3,
            max_masses: 800,
            viscous_e2: 0.72,
        }
    }
}

/// The whole study at `rod` (labelled `label`): the exact engine there and
/// at two reference points (Fig. 3(c) and the hard corner), the chain
/// elastic and viscous (the top layer given restitution `viscous_e2`), cost
/// growth, and the headline ratio.
pub fn cost_study(
    label: &str,
    rod: &Rod,
    s: &CostSettings,
    progress: &dyn Fn(&str),
) -> Result<CostReport, CostError> {
    if let Some(layer) = rod.scene().layers.iter().position(|l| l.is_viscous()) {
        return Err(CostError::ViscousScene { layer });
    }
    progress("exact engine: tolerances and merge windows");
    let mut exact = exact_study(label, rod, s)?;
    for (name, x, alpha) in [
        ("Fig. 3(c) x = 0.4, alpha = 0.05", 0.4, 0.05),
        ("hard corner x = 0.995, alpha = 0.005", 0.995, 0.005),
    ] {
        let r = impact_model::Bilayer::new(x, alpha)?.scene().validate()?;
        exact.extend(exact_study(name, &r, s)?);
    }
    let (_, reference) = exact_reference(rod)?;
    progress("chain, elastic: N and time step");
    let (mut chain, _) = chain_study(ChainKind::Elastic, rod, Some(reference.restitution), s)?;
    progress("chain, viscous: N and time step");
    let mut viscous_scene = rod.scene().clone();
    if let Some(top) = viscous_scene.layers.last_mut() {
        top.restitution = Some(s.viscous_e2);
    }
    let viscous_rod = viscous_scene.validate()?;
    let (viscous, limit) = chain_study(ChainKind::Viscous, &viscous_rod, None, s)?;
    chain.extend(viscous);
    progress("exact engine: growth with t2/t1 and alpha");
    let growth = growth_study()?;
    progress("headline: the chain to the target error");
    let headline = headline(rod, s)?;
    Ok(CostReport::new(
        label,
        reference.restitution,
        exact,
        chain,
        limit,
        growth,
        headline,
    ))
}

/// Runs `f` repeatedly until at least 20 ms have passed (timings of microsecond
/// runs need it) and returns the mean time per run with the last result.
pub(crate) fn timed<T>(mut f: impl FnMut() -> Result<T, CostError>) -> Result<(f64, T), CostError> {
    let start = Instant::now();
    let mut runs = 0u32;
    loop {
        let out = f()?;
        runs += 1;
        let elapsed = start.elapsed().as_secs_f64();
        if elapsed >= 0.02 || runs >= 10_000 {
            return Ok((elapsed / f64::from(runs), out));
        }
    }
}

/// A rod's exact restitution and its time (default settings).
pub(crate) fn exact_reference(rod: &Rod) -> Result<(f64, impact_model::Outcome), CostError> {
    timed(|| {
        Ok(impact_wave::simulate(
            rod,
            &impact_wave::WaveConfig::default(),
        )?)
    })
}

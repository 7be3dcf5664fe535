//! The chain: number of masses and time step against error and cost.

use crate::{CostError, CostSettings, exact_reference};
use impact_chain::{ChainConfig, simulate};
use impact_model::Rod;
use serde::Serialize;
use std::time::Instant;

/// One setting of the chain at one point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChainCost {
    /// `"elastic"` or `"viscous"`.
    pub kind: String,
    /// `"masses"` (N varied at the paper's step) or `"time_step"` (the step
    /// varied at fixed N).
    pub study: String,
    pub masses: usize,
    pub dt_factor: f64,
    pub restitution: f64,
    /// Against the exact engine (elastic) or the chain's Richardson limit
    /// (viscous).
    pub restitution_error: f64,
    pub seconds: f64,
    pub steps: u64,
    /// `steps * N`: the hardware-independent work.
    pub mass_steps: f64,
}

fn run(
    rod: &Rod,
    masses: usize,
    dt_factor: f64,
) -> Result<(f64, impact_model::Outcome), CostError> {
    let start = Instant::now();
    let o = simulate(
        rod,
        &ChainConfig {
            masses,
            dt_factor,
            ..ChainConfig::default()
        },
    )
    .map_err(|e| CostError::Engine(e.to_string()))?;
    Ok((start.elapsed().as_secs_f64(), o))
}

/// The N study then the dt study, against `reference` (or, if `None`, the
/// Richardson limit of the N study's three largest sizes).
pub fn chain_study(
    kind: &str,
    rod: &Rod,
    reference: Option<f64>,
    s: &CostSettings,
) -> Result<(Vec<ChainCost>, f64), CostError> {
    let mut out = Vec::new();
    for &n in &s.sizes {
        let (seconds, o) = run(rod, n, 1.0)?;
        out.push((n, 1.0, o.restitution, seconds, o.steps.unwrap_or(0)));
    }
    let n_study = out.len();
    for &f in &s.dt_factors {
        let (seconds, o) = run(rod, s.dt_masses, f)?;
        out.push((s.dt_masses, f, o.restitution, seconds, o.steps.unwrap_or(0)));
    }
    let limit = reference.unwrap_or_else(|| richardson(&out[..s.sizes.len()]));
    let rows = out
        .into_iter()
        .enumerate()
        .map(|(i, (masses, dt_factor, e, seconds, steps))| ChainCost {
            kind: kind.to_string(),
            study: if i < n_study { "masses" } else { "time_step" }.to_string(),
            masses,
            dt_factor,
            restitution: e,
            restitution_error: (e - limit).abs(),
            seconds,
            steps,
            mass_steps: steps as f64 * masses as f64,
        })
        .collect();
    Ok((rows, limit))
}

/// Richardson limit from the last three sizes (self-consistent order). When
/// the differences change sign the convergence is not yet monotone and
/// extrapolation would be noise: the finest value is the limit then.
fn richardson(runs: &[(usize, f64, f64, f64, u64)]) -> f64 {
    let k = runs.len();
    if k < 3 {
        return runs.last().map_or(f64::NAN, |r| r.2);
    }
    let (e1, e2, e3) = (runs[k - 3].2, runs[k - 2].2, runs[k - 1].2);
    if (e2 - e1) * (e3 - e2) <= 0.0 {
        return e3;
    }
    let r = runs[k - 1].0 as f64 / runs[k - 2].0 as f64;
    let p = ((e2 - e1).abs() / (e3 - e2).abs()).ln() / r.ln();
    let p = if p.is_finite() {
        p.clamp(0.25, 4.0)
    } else {
        1.0
    };
    e3 + (e3 - e2) / (r.powf(p) - 1.0)
}

/// The headline: the smallest doubling of N from 100 at which the chain is
/// within `target` of the exact `e`, its time, and the exact engine's time.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Headline {
    pub target_error: f64,
    /// `None` when `max_masses` was not enough.
    pub masses: Option<usize>,
    /// The largest N tried.
    pub masses_tried: usize,
    pub chain_seconds: f64,
    pub chain_error: f64,
    pub exact_seconds: f64,
    /// Chain time over exact time.
    pub ratio: f64,
}

pub fn headline(rod: &Rod, s: &CostSettings) -> Result<Headline, CostError> {
    let (exact_seconds, exact) = exact_reference(rod)?;
    let mut n = 100;
    loop {
        let (seconds, o) = run(rod, n, 1.0)?;
        let error = (o.restitution - exact.restitution).abs();
        if error < s.target_error || 2 * n > s.max_masses {
            let reached = error < s.target_error;
            return Ok(Headline {
                target_error: s.target_error,
                masses: reached.then_some(n),
                masses_tried: n,
                chain_seconds: seconds,
                chain_error: error,
                exact_seconds,
                ratio: seconds / exact_seconds,
            });
        }
        n *= 2;
    }
}

//! The chain: number of masses and time step against error and cost.

use crate::{CostError, CostSettings, exact_reference};
use impact_chain::{ChainConfig, simulate};
use impact_model::Rod;
use impact_model::numerics::extrapolate;
use serde::Serialize;
use std::time::Instant;

/// Which rod the chain ran: the elastic point, or its viscous variant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ChainKind {
    /// The elastic point itself: errors against the exact engine.
    Elastic,
    /// The same rod with a viscous top: errors against the chain's own limit.
    Viscous,
}

impl std::fmt::Display for ChainKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Self::Elastic => "elastic",
            Self::Viscous => "viscous",
        })
    }
}

/// What a chain row varied.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ChainStudy {
    /// `N` varied at the paper's step.
    Masses,
    /// The step varied at fixed `N`.
    TimeStep,
    /// Three successive sizes of the `N` study, Richardson-extrapolated:
    /// `masses` is the largest, the time and work are the three runs'.
    Extrapolated,
}

/// One setting of the chain at one point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ChainCost {
    /// Elastic point or viscous variant.
    pub kind: ChainKind,
    /// Which setting the row varied.
    pub study: ChainStudy,
    /// Number of masses `N`.
    pub masses: usize,
    /// Time step as a fraction of the paper's.
    pub dt_factor: f64,
    /// The chain's `e` at this setting.
    pub restitution: f64,
    /// Against the exact engine (elastic) or the chain's Richardson limit
    /// (viscous).
    pub restitution_error: f64,
    /// Wall time of the run(s), in seconds.
    pub seconds: f64,
    /// Time steps taken.
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
    )?;
    Ok((start.elapsed().as_secs_f64(), o))
}

/// The N study then the dt study, against `reference` (or, if `None`, the
/// Richardson limit of the N study's three largest sizes).
pub fn chain_study(
    kind: ChainKind,
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
    let n_runs = &out[..n_study];
    let limit = reference.unwrap_or_else(|| limit_of(n_runs));
    let mut rows: Vec<ChainCost> = out
        .iter()
        .enumerate()
        .map(|(i, &(masses, dt_factor, e, seconds, steps))| ChainCost {
            kind,
            study: if i < n_study {
                ChainStudy::Masses
            } else {
                ChainStudy::TimeStep
            },
            masses,
            dt_factor,
            restitution: e,
            restitution_error: (e - limit).abs(),
            seconds,
            steps,
            mass_steps: steps as f64 * masses as f64,
        })
        .collect();
    if reference.is_none() {
        rows.extend(extrapolated(kind, n_runs, limit));
    }
    Ok((rows, limit))
}

/// The chain's own limit: Richardson over the three largest sizes
/// (`impact_model::numerics::richardson`), or the largest size's value when there
/// are fewer than three.
fn limit_of(runs: &[(usize, f64, f64, f64, u64)]) -> f64 {
    let sizes: Vec<usize> = runs.iter().map(|r| r.0).collect();
    let values: Vec<f64> = runs.iter().map(|r| r.2).collect();
    let k = runs.len();
    if k < 3 {
        return values.last().copied().unwrap_or(f64::NAN);
    }
    extrapolate(&sizes[k - 3..], &values[k - 3..], false).map_or(values[k - 1], |x| x.value)
}

/// What `impact run` does on a viscous scene, at every rung of the N study:
/// three successive sizes extrapolated, costing the three runs together.
/// The last triple defines the limit, so it is left out.
fn extrapolated(
    kind: ChainKind,
    runs: &[(usize, f64, f64, f64, u64)],
    limit: f64,
) -> Vec<ChainCost> {
    let k = runs.len();
    (2..k.saturating_sub(1))
        .filter_map(|j| {
            let triple = &runs[j - 2..=j];
            let sizes: Vec<usize> = triple.iter().map(|r| r.0).collect();
            let values: Vec<f64> = triple.iter().map(|r| r.2).collect();
            let x = extrapolate(&sizes, &values, false)?;
            Some(ChainCost {
                kind,
                study: ChainStudy::Extrapolated,
                masses: sizes[2],
                dt_factor: 1.0,
                restitution: x.value,
                restitution_error: (x.value - limit).abs(),
                seconds: triple.iter().map(|r| r.3).sum(),
                steps: triple.iter().map(|r| r.4).sum(),
                mass_steps: triple.iter().map(|r| r.4 as f64 * r.0 as f64).sum(),
            })
        })
        .collect()
}

/// The headline: the smallest doubling of N from 100 at which the chain is
/// within `target` of the exact `e`, its time, and the exact engine's time.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Headline {
    /// The error in `e` to reach.
    pub target_error: f64,
    /// `None` when `max_masses` was not enough.
    pub masses: Option<usize>,
    /// The largest N tried.
    pub masses_tried: usize,
    /// Wall time of the chain's last run, in seconds.
    pub chain_seconds: f64,
    /// `|e - e_exact|` of the chain's last run.
    pub chain_error: f64,
    /// Wall time of the exact engine on the same rod, in seconds.
    pub exact_seconds: f64,
    /// Chain time over exact time.
    pub ratio: f64,
}

/// Doubles `N` from 100 until the chain's `e` is within `s.target_error` of
/// the exact engine's or `N` would pass `s.max_masses`.
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

//! How cost grows with the problem: chain time against N, exact-engine
//! events against `t2 / t1` and against `alpha`.

use crate::{CostError, timed};
use impact_model::Bilayer;
use serde::Serialize;

/// Which parameter a growth point varies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum GrowthSweep {
    /// `x` varied at `alpha = 0.005` (`t2 / t1` grows).
    X,
    /// `alpha` varied at `x = 0.5`.
    Alpha,
}

/// Exact-engine work at one bilayer.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Growth {
    /// Which parameter this point varies.
    pub sweep: GrowthSweep,
    /// Composition `x = L2 / L`.
    pub x: f64,
    /// Stiffness ratio `alpha = E2 / (E1 + E2)`.
    pub alpha: f64,
    /// Transit-time ratio `t2 / t1`: how many round trips the bottom rings per top transit.
    pub transit_ratio: f64,
    /// Boundary events of the exact run.
    pub events: u64,
    /// Wall time of the run, in seconds.
    pub seconds: f64,
}

/// Events and time along `x` at small `alpha` (large `t2 / t1`) and along
/// `alpha` at `x = 0.5`.
pub fn growth_study() -> Result<Vec<Growth>, CostError> {
    let mut points: Vec<(GrowthSweep, f64, f64)> = [0.5, 0.7, 0.8, 0.9, 0.95, 0.98, 0.99, 0.995]
        .iter()
        .map(|&x| (GrowthSweep::X, x, 0.005))
        .collect();
    points.extend(
        [
            0.002, 0.005, 0.01, 0.02, 0.05, 0.1, 0.2, 0.5, 0.8, 0.95, 0.99,
        ]
        .iter()
        .map(|&a| (GrowthSweep::Alpha, 0.5, a)),
    );
    points
        .into_iter()
        .map(|(sweep, x, alpha)| {
            let b = Bilayer { x, alpha };
            let rod = b.scene().validate()?;
            let (seconds, o) = timed(|| {
                Ok(impact_wave::simulate(
                    &rod,
                    &impact_wave::WaveConfig::default(),
                )?)
            })?;
            Ok(Growth {
                sweep,
                x,
                alpha,
                transit_ratio: b.transit_ratio(),
                events: o.events.unwrap_or(0),
                seconds,
            })
        })
        .collect()
}

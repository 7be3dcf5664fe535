//! The exact engine: drop tolerance and merge window against error and cost.

use crate::{CostError, CostSettings, timed};
use impact_model::Rod;
use impact_wave::{Resolution, WaveConfig, WaveEngine};
use serde::Serialize;

/// One setting of the exact engine at one point.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExactCost {
    /// Label of the rod (the point of the study).
    pub point: String,
    /// Drop tolerance (fronts under `drop_tolerance * v_b` in velocity are dropped).
    pub drop_tolerance: f64,
    /// Merge window, as a fraction of the lane's transit time and of the longest one; 0: exact.
    pub merge_window: f64,
    /// `|e - e_ref|`, `|t_c - t_c,ref|` against drop 0, merge 0.
    pub restitution_error: f64,
    /// `|t_c - t_c,ref|`.
    pub contact_time_error: f64,
    /// Boundary events processed.
    pub events: u64,
    /// Wall time of the run, in seconds.
    pub seconds: f64,
}

/// Drop tolerances then merge windows, each against the untruncated run.
pub fn exact_study(label: &str, rod: &Rod, s: &CostSettings) -> Result<Vec<ExactCost>, CostError> {
    // one run per setting (no automatic choice, no error estimate): what
    // each setting alone costs and gives
    let run = |drop: f64, merge: f64| {
        let config = WaveConfig {
            drop_tolerance: drop,
            resolution: if merge > 0.0 {
                Resolution::Merged {
                    per_transit: merge,
                    per_longest: merge,
                }
            } else {
                Resolution::Exact
            },
            ..WaveConfig::default()
        };
        timed(|| {
            WaveEngine::new(rod, config.clone())
                .and_then(|mut e| e.run())
                .map_err(CostError::from)
        })
    };
    let (_, reference) = run(0.0, 0.0)?;
    let mut settings: Vec<(f64, f64)> = std::iter::once((0.0, 0.0))
        .chain(s.drop_tolerances.iter().map(|&d| (d, 0.0)))
        .collect();
    settings.extend(
        s.merge_windows
            .iter()
            .map(|&m| (WaveConfig::default().drop_tolerance, m)),
    );
    settings
        .into_iter()
        .map(|(drop, merge)| {
            let (seconds, o) = run(drop, merge)?;
            Ok(ExactCost {
                point: label.to_string(),
                drop_tolerance: drop,
                merge_window: merge,
                restitution_error: (o.restitution - reference.restitution).abs(),
                contact_time_error: (o.contact_time - reference.contact_time).abs(),
                events: o.events.unwrap_or(0),
                seconds,
            })
        })
        .collect()
}

//! The canonical bilayer's `(x, alpha)` map, computed by the exact engine at
//! a few grid steps (coarse first, so the page can refine progressively)
//! and kept once computed.

use super::api::ApiError;
use impact_model::theory;
use impact_study::{Axis, BilayerViscosity, Engine, Grid, sweep};
use impact_wave::WaveConfig;
use serde::Serialize;
use std::sync::{Arc, Mutex};

/// The grid steps the page asks for, coarse to the paper's.
pub const STEPS: [&str; 4] = ["0.05", "0.02", "0.01", "0.005"];

/// Maps computed so far, as the JSON sent, by step, and the threads that
/// compute them: a pool of their own, so a map never queues behind the
/// chains a viscous run spreads over rayon's global pool (the operating
/// system shares the cores between the two instead).
pub struct Maps {
    done: Mutex<Vec<(String, Arc<String>)>>,
    pool: Option<rayon::ThreadPool>,
}

impl Default for Maps {
    fn default() -> Self {
        Self {
            done: Mutex::default(),
            // without a pool of its own (no thread could be started) the
            // map runs on the global one
            pool: rayon::ThreadPoolBuilder::new()
                .thread_name(|i| format!("explore-map-{i}"))
                .build()
                .ok(),
        }
    }
}

/// Sec. VI's lines: `alpha = 1/10` (where `1 + 2 R12 = 0`), the upper
/// boundary `alpha = 0.82278...` (the root of `1 + 2 R12 - 2 T21 T12`) and
/// the commensurate compositions `x_n` (`t2 = n t1`) along the alpha axis.
#[derive(Serialize)]
struct Overlays {
    alpha_tenth: f64,
    upper_boundary: f64,
    /// `x_n` for n = 1, 2, ... at each alpha of the map.
    x_n: Vec<Vec<f64>>,
}

/// One map: the axes and, point by point (alpha outer, x inner, as `impact
/// sweep` writes them), the observables; `null` where a point failed.
#[derive(Serialize)]
struct Map {
    step: f64,
    x: Vec<f64>,
    alpha: Vec<f64>,
    restitution: Vec<Option<f64>>,
    reduced_contact_time: Vec<Option<f64>>,
    n1: Vec<Option<f64>>,
    bounces: Vec<Option<u32>>,
    events: u64,
    /// The paper's lines drawn over the map.
    overlays: Overlays,
    /// Wall time of the computation (the server's, not the page's).
    seconds: f64,
}

impl Maps {
    /// The map at `step` (one of [`STEPS`]), computed on first use.
    pub fn get(&self, step: &str) -> Result<Arc<String>, ApiError> {
        if !STEPS.contains(&step) {
            return Err(ApiError::bad(format!(
                "step must be one of {} (got '{step}')",
                STEPS.join(", ")
            )));
        }
        if let Some((_, json)) = self
            .done
            .lock()
            .map_err(|_| ApiError::internal("the map cache was poisoned by a failed computation"))?
            .iter()
            .find(|(s, _)| s == step)
        {
            return Ok(Arc::clone(json));
        }
        let json = Arc::new(match &self.pool {
            Some(pool) => pool.install(|| compute(step))?,
            None => compute(step)?,
        });
        if let Ok(mut done) = self.done.lock() {
            done.push((step.to_string(), Arc::clone(&json)));
        }
        Ok(json)
    }
}

/// The map's JSON at `step`: `step:1-step:step` on both axes.
pub fn compute(step: &str) -> Result<String, ApiError> {
    let h: f64 = step
        .parse()
        .map_err(|_| ApiError::bad(format!("step: not a number ({step})")))?;
    let axis = |name| {
        Axis::parse(name, &format!("{step}:{}:{step}", round(1.0 - h)))
            .map_err(|e| ApiError::bad(e.to_string()))
    };
    let grid = Grid {
        x: axis("x")?,
        alpha: axis("alpha")?,
    };
    let start = std::time::Instant::now();
    let rows = sweep(
        &grid.points(),
        &Engine::Wave(WaveConfig::default()),
        &BilayerViscosity::default(),
        false,
        &(),
    );
    let seconds = start.elapsed().as_secs_f64();
    let map = Map {
        step: h,
        x: grid.x.values(),
        alpha: grid.alpha.values(),
        restitution: rows.iter().map(|r| r.restitution).collect(),
        reduced_contact_time: rows.iter().map(|r| r.reduced_contact_time).collect(),
        n1: rows.iter().map(|r| r.n1).collect(),
        bounces: rows.iter().map(|r| r.bounces).collect(),
        events: rows.iter().filter_map(|r| r.events).sum(),
        overlays: Overlays {
            alpha_tenth: 0.1,
            upper_boundary: theory::upper_boundary_alpha(),
            x_n: (1..=6)
                .map(|n| {
                    grid.alpha
                        .values()
                        .iter()
                        .map(|&a| theory::x_n(n, a))
                        .collect()
                })
                .collect(),
        },
        seconds,
    };
    serde_json::to_string(&map).map_err(|e| ApiError::bad(e.to_string()))
}

/// `1 - step` as written (0.95, not 0.9500000000000001).
fn round(v: f64) -> f64 {
    (v * 1e9).round() / 1e9
}

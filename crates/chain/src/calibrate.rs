//! Calibration of the paper's layer restitution (Sec. VII): the restitution
//! of a homogeneous Kelvin-Voigt rod as a function of `tau c / L` alone.

use crate::{ChainConfig, ChainError, simulate};
use impact_model::{Layer, Scene};

/// How the table in `data/calibration/kelvin-voigt.csv` is made: each entry
/// is the chain at `n` and `2n` masses, Richardson-extrapolated assuming the
/// first-order convergence in `N` measured for viscous rods.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CalibrationPoint {
    pub tau_c_over_l: f64,
    /// Extrapolated restitution.
    pub restitution: f64,
    /// Size of the Richardson correction: an estimate of the error left.
    pub correction: f64,
}

/// Restitution of a homogeneous rod (`L = c = 1`) with `tau c / L = t`.
pub fn homogeneous_restitution(t: f64, masses: usize) -> Result<f64, ChainError> {
    let mut layer = Layer::elastic(1.0, 1.0, 1.0);
    layer.relaxation_time = Some(t);
    let rod = Scene {
        impact_speed: 1.0,
        layers: vec![layer],
    }
    .validate()
    .map_err(|_| ChainError::Setting {
        field: "tau_c_over_l",
        allowed: "a finite number >= 0",
        value: t,
    })?;
    Ok(simulate(
        &rod,
        &ChainConfig {
            masses,
            ..ChainConfig::default()
        },
    )?
    .restitution)
}

/// One table entry from chains of `n` and `2 n` masses.
pub fn calibration_point(t: f64, n: usize) -> Result<CalibrationPoint, ChainError> {
    let coarse = homogeneous_restitution(t, n)?;
    let fine = homogeneous_restitution(t, 2 * n)?;
    let correction = fine - coarse;
    Ok(CalibrationPoint {
        tau_c_over_l: t,
        restitution: fine + correction,
        correction,
    })
}

/// The `tau c / L` values of the table: 0, then 6 per decade from `1e-4` to 3.
pub fn calibration_grid() -> Vec<f64> {
    let mut grid = vec![0.0];
    let mut k = 0;
    loop {
        let t = 1e-4 * 10f64.powf(f64::from(k) / 6.0);
        if t > 3.0 + 1e-9 {
            break;
        }
        grid.push(t);
        k += 1;
    }
    grid
}

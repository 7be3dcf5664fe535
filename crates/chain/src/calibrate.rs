//! Calibration of the paper's layer restitution (Sec. VII): the restitution
//! of a homogeneous Kelvin-Voigt rod as a function of `tau c / L` alone.

use crate::{ChainConfig, ChainError, simulate};
use impact_model::{Allowed, Layer, Rod, Scene, SettingError, WallContact};

/// How the tables in `data/calibration/kelvin-voigt-<law>.csv` are made: each entry
/// is the chain at `n` and `2n` masses, Richardson-extrapolated assuming the
/// first-order convergence in `N` measured for viscous rods.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CalibrationPoint {
    /// Reduced relaxation time `tau c / L` of the homogeneous rod.
    pub tau_c_over_l: f64,
    /// Extrapolated restitution (exactly 1 for the elastic rod, `t = 0`).
    pub restitution: f64,
    /// Size of the Richardson correction: an estimate of the error left.
    pub correction: f64,
}

/// The homogeneous Kelvin-Voigt rod (`L = c = v_b = 1`) with
/// `tau c / L = t` under the wall contact law `law`: the rod the table
/// (and the paper's Fig. 2) is about.
pub fn homogeneous_rod(t: f64, law: WallContact) -> Result<Rod, ChainError> {
    let mut layer = Layer::elastic(1.0, 1.0, 1.0);
    layer.relaxation_time = Some(t);
    Scene {
        impact_speed: 1.0,
        layers: vec![layer],
        wall_contact: Some(law),
    }
    .validate()
    .map_err(|_| SettingError::new("tau_c_over_l", Allowed::NonNegative, t).into())
}

/// Restitution of a homogeneous rod (`L = c = 1`) with `tau c / L = t`
/// under the wall contact law `law`.
pub fn homogeneous_restitution(t: f64, masses: usize, law: WallContact) -> Result<f64, ChainError> {
    let rod = homogeneous_rod(t, law)?;
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
pub fn calibration_point(
    t: f64,
    n: usize,
    law: WallContact,
) -> Result<CalibrationPoint, ChainError> {
    let coarse = homogeneous_restitution(t, n, law)?;
    let fine = homogeneous_restitution(t, 2 * n, law)?;
    let correction = fine - coarse;
    // an elastic rod gives back all its energy: e = 1 exactly, where the
    // chains' dispersion leaves the extrapolation a little off (the
    // correction still says by how much the chains miss it); otherwise first
    // order in N, sizes in ratio 2: the step adds `fine - coarse`
    let restitution = if t == 0.0 {
        1.0
    } else {
        impact_model::numerics::richardson_step(coarse, fine, 2.0, 1.0)
    };
    Ok(CalibrationPoint {
        tau_c_over_l: t,
        restitution,
        correction,
    })
}

/// The `tau c / L` values of the table: 0, then 6 per decade from `1e-4` to
/// 3 (unilateral wall) or to 1 (the paper's wall: beyond, the wall holds the
/// rod, `e` falls below `1e-6` and no longer orders the table).
pub fn calibration_grid(law: WallContact) -> Vec<f64> {
    let last = match law {
        WallContact::Paper => 1.0,
        WallContact::Unilateral => 3.0,
    };
    let mut grid = vec![0.0];
    let mut k = 0;
    loop {
        let t = 1e-4 * 10f64.powf(f64::from(k) / 6.0);
        if t > last + 1e-9 {
            break;
        }
        grid.push(t);
        k += 1;
    }
    grid
}

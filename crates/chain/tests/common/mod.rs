#![allow(dead_code)]
use impact_chain::{ChainConfig, simulate};
use impact_model::{Bilayer, Layer, Outcome, Rod, Scene, WallContact};

pub fn bilayer(x: f64, alpha: f64) -> Rod {
    Bilayer::new(x, alpha).unwrap().scene().validate().unwrap()
}

pub fn homogeneous(tau_c_over_l: f64) -> Rod {
    let mut layer = Layer::elastic(1.0, 1.0, 1.0);
    layer.relaxation_time = Some(tau_c_over_l);
    Scene {
        impact_speed: 1.0,
        layers: vec![layer],
        wall_contact: None,
    }
    .validate()
    .unwrap()
}

/// `scene` under the wall law `law`.
pub fn with_law(mut scene: Scene, law: WallContact) -> Rod {
    scene.wall_contact = Some(law);
    scene.validate().unwrap()
}

/// The homogeneous viscous rod of `tau c / L = tau` under `law`.
pub fn homogeneous_under(tau: f64, law: WallContact) -> Rod {
    let mut scene = homogeneous(tau).scene().clone();
    scene.wall_contact = Some(law);
    scene.validate().unwrap()
}

/// The canonical bilayer with relaxation times `tau` (0: elastic) under
/// `law`.
pub fn viscous_bilayer(x: f64, alpha: f64, tau: [f64; 2], law: WallContact) -> Rod {
    let mut scene = Bilayer::new(x, alpha).unwrap().scene();
    for (layer, tau) in scene.layers.iter_mut().zip(tau) {
        layer.relaxation_time = (tau > 0.0).then_some(tau);
    }
    with_law(scene, law)
}

pub fn chain(rod: &Rod, masses: usize) -> Outcome {
    simulate(
        rod,
        &ChainConfig {
            masses,
            ..ChainConfig::default()
        },
    )
    .unwrap()
}

/// Least-squares slope of ln(y) against ln(x) (`impact_model::numerics`),
/// every point having a logarithm: none may be left out of the fit.
pub fn log_slope(points: &[(f64, f64)]) -> f64 {
    assert!(points.iter().all(|p| p.0 > 0.0 && p.1 > 0.0), "{points:?}");
    impact_model::numerics::power_fit(points).exponent
}

/// A stack of elastic layers `(length, modulus, density)`, bottom first,
/// hitting the wall at `speed`.
pub fn elastic_stack(speed: f64, layers: &[(f64, f64, f64)]) -> Rod {
    Scene {
        impact_speed: speed,
        layers: layers
            .iter()
            .map(|&(l, e, rho)| Layer::elastic(l, e, rho))
            .collect(),
        wall_contact: None,
    }
    .validate()
    .unwrap()
}

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
    Scene::elastic_stack(speed, layers).validate().unwrap()
}

/// Beeman's chain written out plainly (six arrays, the one-sided wall
/// spring, contacts timed by linear interpolation of `u_0`): the oracle of
/// the kernels (`tests/kernel.rs`, `tests/viscous_kernel.rs`). Dashpots,
/// if any, are the caller's, between `springs` and `end_step`.
pub struct PlainBeeman {
    pub k: Vec<f64>,
    pub m: Vec<f64>,
    pub u: Vec<f64>,
    pub v: Vec<f64>,
    a: Vec<f64>,
    a_prev: Vec<f64>,
    pub dt: f64,
    pub t: f64,
    pub contacts: Vec<(f64, f64)>,
    start: Option<f64>,
}

impl PlainBeeman {
    pub fn new(layout: &impact_chain::ChainLayout, impact_speed: f64) -> Self {
        let n = layout.len();
        Self {
            k: layout.stiffness.clone(),
            m: layout.mass.clone(),
            u: vec![0.0; n],
            v: vec![-impact_speed; n],
            a: vec![0.0; n],
            a_prev: vec![0.0; n],
            dt: layout.paper_time_step(),
            t: 0.0,
            contacts: Vec::new(),
            start: Some(0.0),
        }
    }

    /// The wall spring's force on mass 0 (upward while compressed).
    pub fn wall_force(&self) -> f64 {
        -self.k[0] * self.u[0].min(0.0)
    }

    /// One Beeman step of the springs; returns `u_0` before it.
    pub fn springs(&mut self) -> f64 {
        let (k, m, n, dt) = (&self.k, &self.m, self.u.len(), self.dt);
        let acc = |u: &[f64], j: usize| {
            let below = if j == 0 {
                k[0] * u[0].min(0.0)
            } else {
                k[j] * (u[j] - u[j - 1])
            };
            let above = if j + 1 < n {
                k[j + 1] * (u[j + 1] - u[j])
            } else {
                0.0
            };
            (above - below) / m[j]
        };
        let u0_old = self.u[0];
        for j in 0..n {
            self.u[j] += dt * self.v[j] + dt * dt * (4.0 * self.a[j] - self.a_prev[j]) / 6.0;
        }
        let new: Vec<f64> = (0..n).map(|j| acc(&self.u, j)).collect();
        for (((v, &a_new), &a), &a_prev) in
            self.v.iter_mut().zip(&new).zip(&self.a).zip(&self.a_prev)
        {
            *v += dt * (2.0 * a_new + 5.0 * a - a_prev) / 6.0;
        }
        self.a_prev.copy_from_slice(&self.a);
        self.a.copy_from_slice(&new);
        u0_old
    }

    /// Ends the step begun at `u_0 = u0_old`: the clock, and the contacts
    /// (the wall element compressed while `u_0 < 0`).
    pub fn end_step(&mut self, u0_old: f64) {
        let dt = self.dt;
        self.t += dt;
        let crossing = self.t - dt + dt * (u0_old / (u0_old - self.u[0])).clamp(0.0, 1.0);
        match (self.start, self.u[0] < 0.0) {
            (Some(s), false) => {
                self.contacts.push((s, crossing));
                self.start = None;
            }
            (None, true) => self.start = Some(crossing),
            _ => {}
        }
    }
}

/// Largest `|x - y|` against the largest `|y|`.
pub fn gap(x: &[f64], y: &[f64]) -> f64 {
    let scale = y.iter().fold(0.0f64, |s, y| s.max(y.abs()));
    x.iter()
        .zip(y)
        .fold(0.0f64, |s, (x, y)| s.max((x - y).abs()))
        / scale
}

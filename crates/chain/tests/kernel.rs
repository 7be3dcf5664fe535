//! The elastic chain runs Beeman's positions in Verlet's summed form on two
//! arrays (`crates/chain/src/verlet.rs`). Against the straightforward Beeman
//! loop written out here (six arrays, the wall impulse as the trapezoid on
//! the wall spring, contacts timed by linear interpolation), it must give
//! the same `e` to `1e-12` and the same contacts.

mod common;
use common::*;
use impact_chain::{ChainConfig, ChainEngine};

/// `e` and the contact intervals of the written-out Beeman chain after
/// `steps` steps.
fn beeman(rod: &impact_model::Rod, masses: usize, steps: u64) -> (f64, Vec<(f64, f64)>) {
    let layout = impact_chain::ChainLayout::new(rod, masses).unwrap();
    let (k, m) = (&layout.stiffness, &layout.mass);
    let n = layout.len();
    let dt = layout.paper_time_step();
    let v0 = rod.impact_speed();
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
    let (mut u, mut v) = (vec![0.0; n], vec![-v0; n]);
    let (mut a, mut a_prev) = (vec![0.0; n], vec![0.0; n]);
    let (mut impulse, mut force, mut t) = (0.0, 0.0, 0.0);
    let mut contacts: Vec<(f64, f64)> = Vec::new();
    let mut start = Some(0.0);
    for _ in 0..steps {
        let u0_old = u[0];
        for j in 0..n {
            u[j] += dt * v[j] + dt * dt * (4.0 * a[j] - a_prev[j]) / 6.0;
        }
        let new: Vec<f64> = (0..n).map(|j| acc(&u, j)).collect();
        for j in 0..n {
            v[j] += dt * (2.0 * new[j] + 5.0 * a[j] - a_prev[j]) / 6.0;
        }
        a_prev.copy_from_slice(&a);
        a.copy_from_slice(&new);
        let f = -k[0] * u[0].min(0.0);
        impulse += 0.5 * dt * (force + f);
        force = f;
        t += dt;
        let crossing = t - dt + dt * (u0_old / (u0_old - u[0])).clamp(0.0, 1.0);
        match (start, u[0] < 0.0) {
            (Some(s), false) => {
                contacts.push((s, crossing));
                start = None;
            }
            (None, true) => start = Some(crossing),
            _ => {}
        }
    }
    let total: f64 = m.iter().sum();
    ((-v0 + impulse / total) / v0, contacts)
}

#[test]
fn the_elastic_kernel_gives_beemans_e_and_contacts() {
    // two bounces (Fig. 3(d)'s region) and a stiff three-layer rod
    let three = impact_model::Scene {
        impact_speed: 1.0,
        layers: vec![
            impact_model::Layer::elastic(0.5, 2.0, 1.5),
            impact_model::Layer::elastic(0.2, 30.0, 0.4),
            impact_model::Layer::elastic(0.3, 1.0, 1.0),
        ],
        wall_contact: None,
    }
    .validate()
    .unwrap();
    for rod in [bilayer(0.4, 0.05), three] {
        let mut engine = ChainEngine::new(
            &rod,
            ChainConfig {
                masses: 200,
                ..ChainConfig::default()
            },
        )
        .unwrap();
        let o = engine.run().unwrap();
        let (e, contacts) = beeman(&rod, 200, o.steps.unwrap());
        assert!(
            (o.restitution - e).abs() <= 1e-12,
            "{} vs {e}",
            o.restitution
        );
        assert_eq!(o.contacts.len(), contacts.len());
        for (c, r) in o.contacts.iter().zip(&contacts) {
            assert!(
                (c[0] - r.0).abs() <= 1e-12 && (c[1] - r.1).abs() <= 1e-12,
                "{c:?} vs {r:?}"
            );
        }
    }
}

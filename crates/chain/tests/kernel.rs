//! The elastic chain runs Beeman's positions in Verlet's summed form on two
//! arrays (`crates/chain/src/verlet.rs`). Against the straightforward Beeman
//! loop written out here (six arrays, the wall impulse as the trapezoid on
//! the wall spring, contacts timed by linear interpolation) it must give the
//! same positions to `1e-12` of themselves over `10^4` steps, and the same
//! `e` and contacts to `1e-12`.

mod common;
use common::*;
use impact_chain::{ChainConfig, ChainEngine, ChainLayout, VerletChain};

/// The written-out Beeman chain after some steps.
struct Beeman {
    u: Vec<f64>,
    v: Vec<f64>,
    restitution: f64,
    contacts: Vec<(f64, f64)>,
}

fn beeman(rod: &impact_model::Rod, masses: usize, steps: u64) -> Beeman {
    let layout = ChainLayout::new(rod, masses).unwrap();
    let v0 = rod.impact_speed();
    let mut chain = PlainBeeman::new(&layout, v0);
    let (mut impulse, mut force) = (0.0, 0.0);
    for _ in 0..steps {
        let u0_old = chain.springs();
        let f = chain.wall_force();
        impulse += 0.5 * chain.dt * (force + f);
        force = f;
        chain.end_step(u0_old);
    }
    let total: f64 = chain.m.iter().sum();
    Beeman {
        u: chain.u,
        v: chain.v,
        restitution: (-v0 + impulse / total) / v0,
        contacts: chain.contacts,
    }
}

/// Three layers, one of them stiff and light: runs, interface masses, the
/// wall.
fn three_layers(speed: f64) -> impact_model::Rod {
    elastic_stack(speed, &[(0.5, 2.0, 1.5), (0.2, 30.0, 0.4), (0.3, 1.0, 1.0)])
}

#[test]
fn positions_and_velocities_are_beemans_over_ten_thousand_steps() {
    let rod = three_layers(1.3);
    let layout = ChainLayout::new(&rod, 100).unwrap();
    let reference = beeman(&rod, 100, 10_000);
    let mut chain = VerletChain::new(&layout, layout.paper_time_step(), 1.3);
    for _ in 0..10_000 {
        chain.step();
    }
    // each position to 1e-12 of itself (seen: 5e-14; Verlet's three-term
    // form, u(n+1) = 2 u(n) - u(n-1) + ..., was 2e-10 off)
    for (j, (u, r)) in chain.displacement().iter().zip(&reference.u).enumerate() {
        assert!((u - r).abs() <= 1e-12 * r.abs(), "u[{j}]: {u} vs {r}");
    }
    // rebuilt velocities: a difference of positions over dt, so some ulps
    // of the positions worse (seen: 4e-12)
    let scale = reference.v.iter().fold(0.0f64, |s, v| s.max(v.abs()));
    for (j, (v, r)) in chain.velocities().iter().zip(&reference.v).enumerate() {
        assert!((v - r).abs() <= 2e-11 * scale, "v[{j}]: {v} vs {r}");
    }
}

#[test]
fn the_elastic_kernel_gives_beemans_e_and_contacts() {
    // two bounces (Fig. 3(d)'s region) and the stiff three-layer rod
    for rod in [bilayer(0.4, 0.05), three_layers(1.0)] {
        let config = ChainConfig {
            masses: 200,
            ..ChainConfig::default()
        };
        let o = ChainEngine::new(&rod, config).unwrap().run().unwrap();
        let reference = beeman(&rod, 200, o.steps.unwrap());
        let e = reference.restitution;
        assert!(
            (o.restitution - e).abs() <= 1e-12,
            "{} vs {e}",
            o.restitution
        );
        assert_eq!(o.contacts.len(), reference.contacts.len());
        for (c, r) in o.contacts.iter().zip(&reference.contacts) {
            let close = (c[0] - r.0).abs() <= 1e-12 && (c[1] - r.1).abs() <= 1e-12;
            assert!(close, "{c:?} vs {r:?}");
        }
    }
}

//! Viscous chains: the paper's scaling, stability, energy, and the accuracy of
//! the implicit-dashpot remedy.

mod common;
use common::*;
use impact_chain::{ChainConfig, ChainEngine};
use impact_model::{Bilayer, Rod};

#[test]
fn an_elastic_scene_does_no_dashpot_work() {
    let elastic = ChainEngine::new(
        &bilayer(0.4, 0.05),
        ChainConfig {
            masses: 100,
            ..ChainConfig::default()
        },
    )
    .unwrap();
    assert!(!elastic.uses_dashpots());
    let viscous = ChainEngine::new(
        &homogeneous(0.1),
        ChainConfig {
            masses: 100,
            ..ChainConfig::default()
        },
    )
    .unwrap();
    assert!(viscous.uses_dashpots());
}

/// Fig. 2(a): 1 - e ~ (tau c / L)^(1/2) at small tau c / L.
#[test]
fn homogeneous_viscous_rod_follows_the_square_root_law() {
    let points: Vec<(f64, f64)> = [0.005, 0.01, 0.02, 0.04]
        .iter()
        .map(|&t| (t, 1.0 - chain(&homogeneous(t), 1000).restitution))
        .collect();
    let exponent = log_slope(&points);
    println!("1 - e vs tau c / L: {points:?}; exponent {exponent:.3}");
    assert!((0.4..0.6).contains(&exponent), "{exponent}");
}

fn strong_dashpot_cases() -> Vec<(&'static str, Rod)> {
    let bilayer_with = |e1: f64, e2: f64| {
        let mut s = Bilayer::new(0.5, 0.005).unwrap().scene();
        s.layers[0].restitution = Some(e1);
        s.layers[1].restitution = Some(e2);
        s.validate().unwrap()
    };
    vec![
        ("homogeneous, tau c / L = 1", homogeneous(1.0)),
        ("alpha = 0.005, e1 = 0.4", bilayer_with(0.4, 1.0)),
        ("alpha = 0.005, e2 = 0.4", bilayer_with(1.0, 0.4)),
    ]
}

/// The paper's time step with the paper's strongest dashpots: finite e in
/// [0, 1] and mechanical energy that never rises above its start (beyond the
/// O(dt^2) wobble of Beeman's energy in elastic parts), at N = 200 and 2000.
#[test]
fn strong_dashpots_stay_stable_and_never_gain_energy() {
    for (label, rod) in strong_dashpot_cases() {
        for n in [200, 2000] {
            let mut e = ChainEngine::new(
                &rod,
                ChainConfig {
                    masses: n,
                    ..ChainConfig::default()
                },
            )
            .unwrap();
            let e0 = e.mechanical_energy();
            let mut peak: f64 = e0;
            let mut last = e0;
            let mut rises = 0.0f64;
            while e.stopped().is_none() && e.time() < 40.0 {
                for _ in 0..64 {
                    e.step().unwrap();
                }
                let now = e.mechanical_energy();
                peak = peak.max(now);
                rises = rises.max(now - last);
                last = now;
                // stop as the engine would (run() applies the same rule)
                if !e.in_contact() && e.time() > 3.0 * rod.transit_times().iter().sum::<f64>() {
                    break;
                }
            }
            let o = e.outcome();
            assert!(
                o.restitution.is_finite() && (0.0..=1.0).contains(&o.restitution),
                "{label}, N = {n}: {o:?}"
            );
            assert!(
                peak <= e0 * (1.0 + 1e-4),
                "{label}, N = {n}: energy rose to {}",
                peak / e0
            );
            assert!(last < e0, "{label}, N = {n}: dashpots dissipated nothing");
            println!(
                "{label}, N = {n}: e = {:.4}, E_end/E0 = {:.4}, largest rise {:.1e} E0",
                o.restitution,
                last / e0,
                rises / e0
            );
        }
    }
}

#[test]
fn fully_viscous_chain_loses_energy_at_every_step() {
    let mut e = ChainEngine::new(
        &homogeneous(0.3),
        ChainConfig {
            masses: 300,
            ..ChainConfig::default()
        },
    )
    .unwrap();
    let mut last = e.mechanical_energy();
    for _ in 0..20_000 {
        e.step().unwrap();
        let now = e.mechanical_energy();
        assert!(
            now <= last * (1.0 + 1e-13),
            "t = {}: {now} > {last}",
            e.time()
        );
        last = now;
    }
}

/// `step()` reports the stop where `run()` stops: same step, same outcome.
#[test]
fn stepping_by_hand_stops_where_run_stops() {
    let rod = strong_dashpot_cases().remove(1).1;
    let config = ChainConfig {
        masses: 200,
        ..ChainConfig::default()
    };
    let run = ChainEngine::new(&rod, config.clone())
        .unwrap()
        .run()
        .unwrap();
    let mut e = ChainEngine::new(&rod, config).unwrap();
    let reason = loop {
        if let Some(reason) = e.step().unwrap() {
            break reason;
        }
    };
    let by_hand = e.outcome();
    assert_eq!(reason, run.stop_reason);
    assert_eq!(by_hand.steps, run.steps);
    assert_eq!(by_hand.restitution, run.restitution);
}

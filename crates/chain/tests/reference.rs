//! The chain against the exact engine and the paper's Appendix A.

mod common;
use common::*;
use impact_chain::{ChainConfig, ChainStop, simulate};
use impact_wave::WaveConfig;

/// Appendix A: a homogeneous elastic chain should rebound with e = 1; its
/// error falls with N as a power law, about 1% at N = 50 (paper).
#[test]
fn appendix_a_finite_size_error_is_a_power_law() {
    let rod = homogeneous(0.0);
    let errors: Vec<(f64, f64)> = [50, 100, 200, 400, 800]
        .iter()
        .map(|&n| (n as f64, 1.0 - chain(&rod, n).restitution))
        .collect();
    for w in errors.windows(2) {
        assert!(w[1].1 < w[0].1, "{errors:?}");
    }
    let exponent = -log_slope(&errors);
    println!(
        "1 - e at N = 50: {:.4}; exponent {exponent:.3}; {errors:?}",
        errors[0].1
    );
    assert!((0.45..0.75).contains(&exponent), "{exponent}");
    assert!(
        (0.005..0.02).contains(&errors[0].1),
        "paper: about 1% at N = 50"
    );
}

/// At a point of each region, |e_chain - e_exact| shrinks as N grows, with a
/// positive observed order, and the bounce count matches the exact engine.
#[test]
fn chain_converges_to_the_exact_engine_in_every_region() {
    // lower, central, upper (alpha > 0.82), multiple bounces
    for &(x, alpha) in &[(0.2, 0.05), (0.3, 0.3), (0.7, 0.9), (0.4, 0.05)] {
        let rod = bilayer(x, alpha);
        let exact = impact_wave::simulate(&rod, &WaveConfig::default()).unwrap();
        let runs: Vec<(f64, impact_model::Outcome)> = [250, 500, 1000, 2000]
            .iter()
            .map(|&n| (n as f64, chain(&rod, n)))
            .collect();
        let de: Vec<(f64, f64)> = runs
            .iter()
            .map(|(n, o)| (*n, (o.restitution - exact.restitution).abs()))
            .collect();
        for w in de.windows(2) {
            assert!(w[1].1 < w[0].1, "({x}, {alpha}): {de:?}");
        }
        let order = -log_slope(&de);
        println!("({x}, {alpha}): |de| {de:?}, order {order:.2}");
        assert!(order > 0.3, "({x}, {alpha}): order {order}");
        let (_, finest) = runs.last().unwrap();
        assert_eq!(finest.bounces, exact.bounces, "({x}, {alpha})");
        assert!((finest.reduced_contact_time - exact.reduced_contact_time).abs() < 5e-3);
    }
}

/// Fig. 3(d): the chain, like the exact engine, sees the second contact the
/// caption misses (n1 = 3.5, N_b = 2).
#[test]
fn chain_agrees_with_the_exact_engine_on_figure_3d() {
    let o = chain(&bilayer(0.6, 0.8), 2000);
    assert_eq!(o.bounces, 2);
    assert!((o.n1.unwrap() - 3.5).abs() < 0.05, "{:?}", o.n1);
}

#[test]
fn restitution_estimates_agree() {
    // impulse (trapezoid on the wall force, Eq. 6) vs final mean velocity
    for rod in [bilayer(0.4, 0.05), bilayer(0.6, 0.8), homogeneous(0.1)] {
        let o = chain(&rod, 400);
        let v = o.restitution_from_velocity.unwrap();
        assert!((o.restitution - v).abs() < 1e-9, "{} vs {v}", o.restitution);
    }
}

#[test]
fn results_do_not_depend_on_impact_speed() {
    let base = chain(&bilayer(0.4, 0.05), 300);
    let mut scene = impact_model::Bilayer::new(0.4, 0.05).unwrap().scene();
    scene.impact_speed = 0.003;
    let slow = chain(&scene.validate().unwrap(), 300);
    assert!((slow.restitution - base.restitution).abs() < 1e-10);
    assert_eq!(slow.contacts.len(), base.contacts.len());
    assert!((slow.contact_time - base.contact_time).abs() < 1e-9);
}

#[test]
fn paper_horizon_and_exact_stop_agree() {
    let rod = bilayer(0.4, 0.05);
    let exact_stop = chain(&rod, 300);
    let paper = simulate(
        &rod,
        &ChainConfig {
            masses: 300,
            stop: ChainStop::PAPER,
            ..ChainConfig::default()
        },
    )
    .unwrap();
    assert_eq!(exact_stop.stop_reason, impact_model::StopReason::Escaped);
    assert_eq!(paper.stop_reason, impact_model::StopReason::Horizon);
    assert!(paper.end_time > exact_stop.end_time);
    assert!((paper.restitution - exact_stop.restitution).abs() < 1e-12);
    assert_eq!(paper.contacts, exact_stop.contacts);
}

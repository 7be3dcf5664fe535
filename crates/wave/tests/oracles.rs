//! The exact engine against the paper's closed-form results (Sec. IV, VI).

mod common;
use common::*;
use impact_model::{Bilayer, Layer, Scene, theory};
use impact_wave::{WaveConfig, simulate};

#[test]
fn homogeneous_rod_rebounds_elastically_after_two_transits() {
    for &(length, modulus, density, speed) in &[
        (1.0, 1.0, 1.0, 1.0),
        (2.5, 4.0, 1.0, 0.3),
        (0.01, 200.0, 7.8, 12.0),
    ] {
        let scene = Scene {
            impact_speed: speed,
            layers: vec![Layer::elastic(length, modulus, density)],
            wall_contact: None,
        };
        let o = simulate(&scene.validate().unwrap(), &WaveConfig::default()).unwrap();
        let c = (modulus / density).sqrt();
        assert!((o.restitution - 1.0).abs() < 1e-14, "{o:?}");
        assert!((o.contact_time - 2.0 * length / c).abs() < 1e-14 * length / c);
        assert_eq!((o.bounces, o.separations), (1, 1));
    }
}

#[test]
fn a_homogeneous_rod_cut_into_layers_is_still_homogeneous() {
    let layers = vec![
        Layer::elastic(0.2, 3.0, 2.0),
        Layer::elastic(0.5, 3.0, 2.0),
        Layer::elastic(0.3, 3.0, 2.0),
    ];
    let scene = Scene {
        impact_speed: 1.0,
        layers,
        wall_contact: None,
    };
    let o = simulate(&scene.validate().unwrap(), &WaveConfig::default()).unwrap();
    assert!((o.restitution - 1.0).abs() < 1e-14);
    assert!((o.reduced_contact_time - 1.0).abs() < 1e-14);
}

#[test]
fn interface_coefficients_are_the_papers_for_equal_densities() {
    for alpha in [0.005, 0.1, 0.3, 0.5, 0.82, 0.995] {
        let rod = rod(0.4, alpha);
        let k = impact_model::InterfaceCoefficients::between(&rod.layers()[0], &rod.layers()[1]);
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-13 * b.abs().max(1.0);
        assert!(close(k.up_reflected, theory::r12(alpha)), "R12 at {alpha}");
        assert!(
            close(k.up_transmitted, theory::t12(alpha)),
            "T12 at {alpha}"
        );
        assert!(
            close(k.down_reflected, theory::r21(alpha)),
            "R21 at {alpha}"
        );
        assert!(
            close(k.down_transmitted, theory::t21(alpha)),
            "T21 at {alpha}"
        );
    }
}

#[test]
fn lower_region_single_takeoff_at_two_t1() {
    // alpha < 0.1 (1 + 2 R12 < 0) and small x: e = 1 - 2x (Eq. 15), t_c = 2 t1.
    for &(x, alpha) in &[(0.2, 0.05), (0.1, 0.02), (0.25, 0.08), (0.05, 0.005)] {
        let o = run(x, alpha);
        let (t1, _) = transits(x, alpha);
        assert!(
            (o.restitution - theory::lower_restitution(x)).abs() < 1e-12,
            "{x} {alpha}: {o:?}"
        );
        assert!(
            (o.contact_time - 2.0 * t1).abs() < 1e-12,
            "{x} {alpha}: {o:?}"
        );
        assert_eq!(o.bounces, 1);
    }
}

#[test]
fn minimum_restitution_tends_to_one_fifth_at_x_0_4() {
    // The paper's e ~ 0.2 at x = 0.4, alpha -> 0: single takeoff, e = 1 - 2x.
    for alpha in [1e-3, 1e-4] {
        let o = run(0.4, alpha);
        assert!((o.restitution - 0.2).abs() < 1e-12, "{alpha}: {o:?}");
    }
    // ...but not yet at alpha = 0.05, where a second bounce lifts it (Fig. 3c).
    assert!(run(0.4, 0.05).restitution > 0.7);
}

#[test]
fn central_region_equals_eq_11() {
    let mut checked = 0;
    for ai in 0..=13 {
        let alpha = 0.1 + 0.05 * f64::from(ai); // 0.10 ..= 0.75
        for xi in 1..=39 {
            let x = 0.025 * f64::from(xi);
            let b = Bilayer::new(x, alpha).unwrap();
            let o = run(x, alpha);
            let (t1, t2) = transits(x, alpha);
            assert!(
                (o.restitution - theory::central_restitution(b)).abs() < 1e-12,
                "x = {x}, alpha = {alpha}: engine {} vs Eq. 11 {}",
                o.restitution,
                theory::central_restitution(b)
            );
            assert!((o.contact_time - 2.0 * (t1 + t2)).abs() < 1e-12 * (t1 + t2));
            assert_eq!(o.separations, 1);
            checked += 1;
        }
    }
    assert_eq!(checked, 14 * 39);
}

/// Bisects `alpha` in `(lo, hi)` for the point where the engine stops matching
/// Eq. 11 at composition `x`; `holds_below` says on which side it holds.
fn eq11_boundary(x: f64, mut lo: f64, mut hi: f64, holds_below: bool) -> f64 {
    let holds = |alpha: f64| {
        let b = Bilayer::new(x, alpha).unwrap();
        (run(x, alpha).restitution - theory::central_restitution(b)).abs() < 1e-9
    };
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        if holds(mid) == holds_below {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[test]
fn eq_11_stops_holding_where_the_wall_strain_changes_sign() {
    // Lower edge: 1 + 2 R12 = 0 at alpha = 1/10 exactly (takeoff at 2 t1 below).
    let lower = eq11_boundary(0.3, 0.05, 0.15, false);
    assert!((lower - 0.1).abs() < 1e-9, "{lower}");
    // Upper edge for x < x_1: 1 + 2 R12 - 2 T21 T12 = 0 (the paper's 0.82).
    let upper = eq11_boundary(0.3, 0.7, 0.9, true);
    assert!(
        (upper - theory::upper_boundary_alpha()).abs() < 1e-9,
        "{upper}"
    );
}

#[test]
fn slope_of_e_breaks_at_x_n() {
    // e(x) is linear between consecutive x_n: zero second difference inside a
    // segment, a kink at x_n itself.
    let alpha = 0.3;
    let second_difference = |x: f64, h: f64| {
        run(x + h, alpha).restitution - 2.0 * run(x, alpha).restitution
            + run(x - h, alpha).restitution
    };
    for n in 1..=3 {
        let xn = theory::x_n(n, alpha);
        let h = 1e-3;
        let kink = second_difference(xn, h);
        let inside = second_difference(xn - 3.0 * h, h);
        assert!(inside.abs() < 1e-12, "n = {n}: {inside}");
        assert!(kink.abs() > 1e-5, "n = {n}: no kink ({kink})");
        // the kink equals the change of slope a_n - a_{n-1} times h
        let (a_prev, _) = theory::central_segment(n - 1, alpha);
        let (a_next, _) = theory::central_segment(n, alpha);
        assert!((kink - (a_next - a_prev) * h).abs() < 1e-12, "n = {n}");
    }
}

#[test]
fn x_min_and_e_min_follow_eqs_12_and_14() {
    // alpha = 0.5 is excluded: R12 = 0 there, the rod is effectively
    // homogeneous and e = 1 for every x (no unique minimum).
    for alpha in [0.15, 0.3, 0.45, 0.6, 0.7] {
        // scan x finely, then compare the minimum with Eqs. 12 and 14
        let (x_best, e_best) = (1..1000)
            .map(|i| f64::from(i) / 1000.0)
            .map(|x| (x, run(x, alpha).restitution))
            .fold((0.0, f64::INFINITY), |a, b| if b.1 < a.1 { b } else { a });
        assert!(
            (x_best - theory::x_min(alpha)).abs() <= 1e-3,
            "{alpha}: {x_best}"
        );
        let at_x1 = run(theory::x_min(alpha), alpha).restitution;
        assert!((at_x1 - theory::e_min(alpha)).abs() < 1e-12, "{alpha}");
        assert!(e_best >= at_x1 - 1e-12, "{alpha}: {e_best} < e_min {at_x1}");
    }
}

#[test]
fn figure_3_contact_time_classes() {
    // (a) x = 0.2, alpha = 0.05: t_c = 2 t1, single bounce.
    let o = run(0.2, 0.05);
    let (t1, t2) = transits(0.2, 0.05);
    assert!((o.contact_time - 2.0 * t1).abs() < 1e-12);
    assert_eq!(o.bounces, 1);
    // (b) x = 0.3, alpha = 0.3: t_c = 2 t1 + 2 t2, single bounce.
    let o = run(0.3, 0.3);
    let (t1b, t2b) = transits(0.3, 0.3);
    assert!((o.contact_time - 2.0 * (t1b + t2b)).abs() < 1e-12);
    assert_eq!(o.bounces, 1);
    // (c) x = 0.4, alpha = 0.05: t_c = 2 t1 + 2 t2 after more than one bounce.
    let o = run(0.4, 0.05);
    let (t1c, t2c) = transits(0.4, 0.05);
    assert!((o.contact_time - 2.0 * (t1c + t2c)).abs() < 1e-12);
    assert!(o.bounces > 1, "{o:?}");
    assert!(t1 < t2);
}

/// Fig. 3(d), x = 0.6, alpha = 0.8 (t2 = 0.75 t1): the caption says
/// t_c = 4 t1 + 2 t2. The exact engine finds: first takeoff at 2 t1 + 2 t2
/// (the wave through P2 returns), a flight of exactly t1 (longer than
/// min(t1, t2), so N_b = 2), a second, lightly compressed contact from
/// 3 t1 + 2 t2 (the caption's "very light red") and the final takeoff at
/// 3.5 t1 + 2 t2: n1 = 3.5. The text's own analysis of that corner (n1 not an
/// integer, between 2 and 4) agrees with the engine; the caption does not.
#[test]
fn figure_3d_caption_is_wrong_about_the_contact_time() {
    let o = run(0.6, 0.8);
    let (t1, t2) = transits(0.6, 0.8);
    let at = |k: f64| k * t1 + 2.0 * t2;
    let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
    assert_eq!(o.contacts.len(), 2, "{o:?}");
    assert!(close(o.contacts[0][1], at(2.0)));
    assert!(close(o.contacts[1][0], at(3.0)));
    assert!(close(o.contacts[1][1], at(3.5)));
    assert!((o.n1.unwrap() - 3.5).abs() < 1e-12);
    assert_eq!((o.separations, o.bounces), (2, 2));
    assert!(
        (o.contact_time - at(4.0)).abs() > 0.4 * t1,
        "not the caption's 4 t1 + 2 t2"
    );
}

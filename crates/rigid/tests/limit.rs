//! The rigid-bottom model against independent oracles: the paper's
//! Appendix C (a one-layer stack followed until `2 t2`, recomputed by its
//! own recursion in `impact_model::rigid_bottom`), the lower region's
//! closed form `e = 1 - 2x`, and momentum bookkeeping.

use impact_model::{Bilayer, rigid_bottom::rigid_bottom};
use impact_rigid::{RigidBottom, RigidConfig, RigidStop, simulate};

/// Followed to the paper's `t_c = 2 t2` on a soft top (`alpha -> 0`), the
/// model's `e` at that instant is Appendix C's: the recursion of landings
/// there (Eqs. C1-C3) and the event loop here are separate codes.
#[test]
fn followed_to_two_top_transits_it_is_appendix_c() {
    for x in [0.3, 0.5, 0.6, 0.7, 0.8, 0.9] {
        let rod = Bilayer::new(x, 1e-4).unwrap().scene().validate().unwrap();
        let config = RigidConfig {
            rest_ratio: 1e-12,
            stop: RigidStop::Horizon { factor: 2.0 },
            ..RigidConfig::default()
        };
        let mut model = RigidBottom::new(&rod, &config).unwrap();
        while model.step().unwrap() {}
        let o = model.outcome();
        let c = rigid_bottom(x);
        eprintln!(
            "x = {x}: e(2 t2) = {:.12}, Appendix C {:.12}, {} separations, {} landings in C",
            o.restitution,
            c.restitution,
            o.separations,
            c.bounces.len()
        );
        assert!(
            (o.restitution - c.restitution).abs() < 1e-9,
            "x = {x}: {} vs Appendix C {}",
            o.restitution,
            c.restitution
        );
    }
}

fn scene(file: &str) -> impact_model::Rod {
    let path = format!("{}/../../data/scenes/{file}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    impact_model::Scene::from_json(&text)
        .unwrap()
        .validate()
        .unwrap()
}

/// Taking rest early (the chatter's bounces below `rest_ratio` of the
/// push's speed scale) moves `e` by no more than the bound it reports:
/// checked against runs that chatter a thousand times longer.
#[test]
fn resting_early_stays_within_its_bound() {
    for file in [
        "pmma-under-silicone.json",
        "steel-under-rubber.json",
        "aluminium-under-silicone.json",
    ] {
        let rod = scene(file);
        let at = |rest_ratio| RigidConfig {
            rest_ratio,
            ..RigidConfig::default()
        };
        let coarse = simulate(&rod, &at(1e-3)).unwrap();
        let fine = simulate(&rod, &at(1e-6)).unwrap();
        let d = (coarse.restitution - fine.restitution).abs();
        let bound = coarse.error_bound.unwrap();
        eprintln!(
            "{file}: e = {:.12} ± {bound:.1e} ({} separations), rest ratio 1e-6: {:.12} ({} separations), |d| = {d:.1e}",
            coarse.restitution, coarse.separations, fine.restitution, fine.separations
        );
        assert!(d <= bound + fine.error_bound.unwrap(), "{file}");
        assert!(coarse.restitution > 0.0 && coarse.restitution <= 1.0);
    }
}

/// A steel base under rubber, silicone and a steel top: the top's mass
/// presses the soft layers for about a dozen of their transits, and the
/// base lands and lifts off 1,072 times. At a lift-off from rest the base's
/// height rises like `s^3`, under the rounding of its terms for a while;
/// taken as a landing at zero speed, pulled up, it lifted off again at the
/// same instant until the event budget was spent (sixteen million events
/// at one instant). Here it finishes, and agrees with
/// the exact engine (an independent code) within both bounds and the
/// model's own difference, of first order in `t1 / t2` (at most 3 `t1 /
/// t2` on the real pairs as their base stiffens, `crates/study/tests/
/// rigid_limit.rs`; `2e-5` here).
#[test]
fn a_stack_of_three_above_a_steel_base_finishes() {
    let text = r#"{"impact_speed": 1.0, "layers": [
        {"material": "steel", "length": 0.001},
        {"material": "natural-rubber", "length": 0.02},
        {"material": "silicone", "length": 0.013},
        {"material": "steel", "length": 0.02}]}"#;
    let rod = impact_model::Scene::from_json(text)
        .unwrap()
        .validate()
        .unwrap();
    let config = RigidConfig {
        max_events: 10_000_000,
        ..RigidConfig::default()
    };
    let rigid = simulate(&rod, &config).unwrap();
    let exact = impact_wave::simulate(&rod, &impact_wave::WaveConfig::default()).unwrap();
    let ratio = exact.transit_times[0] / exact.transit_times[1];
    let d = (rigid.restitution - exact.restitution).abs();
    let allowed = rigid.error_bound.unwrap() + exact.error_bound.unwrap() + 3.0 * ratio;
    eprintln!(
        "rigid {:.9} ± {:.1e} ({} separations, {} events), exact {:.9} ± {:.1e}, t1/t2 = {ratio:.1e}, |d| = {d:.1e}",
        rigid.restitution,
        rigid.error_bound.unwrap(),
        rigid.separations,
        rigid.events.unwrap_or(0),
        exact.restitution,
        exact.error_bound.unwrap()
    );
    assert!(d <= allowed, "|d| = {d:.2e} over {allowed:.2e}");
    assert_eq!(rigid.stop_reason, impact_model::StopReason::Escaped);
}

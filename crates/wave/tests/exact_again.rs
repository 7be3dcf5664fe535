//! The exact run again where a ladder's levels do not converge
//! (`crates/wave/src/exact_again.rs`): the ladder's estimate may then be
//! low by any factor, and an exact run that fits the ladder's budget
//! leaves nothing to estimate.

use impact_model::{Outcome, Rod, Scene};
use impact_wave::{LadderProgress, Resolution, WaveConfig, simulate, solve_observed};
use std::cell::RefCell;

mod common;
use common::exact_run;

/// A stack of real materials (`scripts/survey-layers.py --materials
/// --seed 13`, its rod 27): 0.13 mm of brass and 0.84 mm of aluminium
/// under 2.6 mm of natural rubber and 0.28 mm of polyurethane, at 0.2 m/s,
/// named as a user names them. Its ladder's levels do not converge (order
/// `-0.3`), and its exact run takes 1.19 M events.
fn brass_and_aluminium_under_rubber() -> Rod {
    Scene::from_json(
        r#"{"impact_speed": 0.19906387860847444, "layers": [
            {"material": "brass", "length": 0.0001325440758307445},
            {"material": "aluminium", "length": 0.0008421317142154826},
            {"material": "natural rubber", "length": 0.0025922956632931484},
            {"material": "polyurethane", "length": 0.00028349778905198853}]}"#,
    )
    .unwrap()
    .validate()
    .unwrap()
}

/// A unit-speed impact of `layers` (length, modulus, density), bottom first.
fn unit_impact(layers: &[(f64, f64, f64)]) -> Rod {
    Scene::elastic_stack(1.0, layers).validate().unwrap()
}

/// The default resolution with the ladder's budget `budget_events` and the
/// exact run again on or off.
fn auto(budget_events: u64, exact_again: bool) -> WaveConfig {
    WaveConfig {
        resolution: Resolution::Auto {
            exact_events: 200_000,
            budget_events,
            target: 1e-5,
            exact_again,
        },
        ..WaveConfig::default()
    }
}

/// The outcome and whether the exact run was announced as tried again.
fn observed(rod: &Rod, config: &WaveConfig) -> (Outcome, Vec<LadderProgress>) {
    let seen = RefCell::new(Vec::new());
    let outcome = solve_observed(rod, config, &|p| seen.borrow_mut().push(p))
        .unwrap()
        .outcome;
    (outcome, seen.into_inner())
}

fn tried_again(seen: &[LadderProgress]) -> bool {
    seen.iter()
        .any(|p| matches!(p, LadderProgress::ExactAgain { .. }))
}

/// Where the levels do not converge and the exact run fits the ladder's
/// budget, the outcome is the exact run's, to the bit (the exact engine is
/// held to an independent tracker elsewhere), and the ladder's `e`, bound
/// and order are kept beside it as it reported them alone.
#[test]
fn a_ladder_whose_levels_do_not_converge_gives_way_to_the_exact_run() {
    let rod = brass_and_aluminium_under_rubber();
    let (o, seen) = observed(&rod, &WaveConfig::default());
    let alone = simulate(&rod, &auto(4_000_000, false)).unwrap();
    let ladder = alone.error_estimate.clone().unwrap();
    assert_eq!(
        ladder.merged_converging,
        Some(false),
        "the case: a ladder whose levels do not converge ({:?})",
        ladder.merged_observed_order
    );
    assert!(tried_again(&seen), "{seen:?}");
    assert!(seen.contains(&LadderProgress::ExactAgain { events: 4_000_000 }));
    let x = exact_run(&rod, 4_000_000, true).expect("the exact run fits the ladder's budget");
    assert_eq!(o.restitution, x.restitution);
    assert_eq!(o.error_bound, x.error_bound);
    assert_eq!(o.events, x.events);
    assert_eq!(o.truncation.unwrap().merged_fronts, 0);
    let estimate = o.error_estimate.unwrap();
    assert_eq!(estimate.merged, 0.0);
    assert_eq!(estimate.merged_converging, None);
    let kept = estimate.ladder_set_aside.expect("the ladder kept beside");
    assert_eq!(kept.restitution, alone.restitution);
    assert_eq!(kept.merged_bound, ladder.merged);
    assert_eq!(kept.observed_order, ladder.merged_observed_order);
    assert_eq!(kept.exact_events, 4_000_000);
    assert!(
        estimate.method.contains("did not converge") && estimate.method.contains("finished in"),
        "{}",
        estimate.method
    );
    // counted in events, so the same on one thread
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let alone_on_one = pool.install(|| simulate(&rod, &WaveConfig::default()).unwrap());
    assert_eq!(alone_on_one.error_estimate.as_ref(), Some(&estimate));
    assert_eq!(alone_on_one.restitution, o.restitution);
    eprintln!(
        "exact {:.10} ± {:.1e}; the ladder {:.10} ± {:.1e} (order {:?}), {:.2} of its bound away",
        o.restitution,
        o.error_bound.unwrap(),
        kept.restitution,
        kept.merged_bound,
        kept.observed_order,
        (kept.restitution - o.restitution).abs() / kept.merged_bound
    );
}

/// Where the exact run does not fit the ladder's budget, the ladder's
/// outcome stands as it is without the second try: the same rod with a
/// budget of 1 M events (its exact run takes 1.19 M).
#[test]
fn a_budget_the_exact_run_does_not_fit_leaves_the_ladders_outcome() {
    let rod = brass_and_aluminium_under_rubber();
    let (o, _) = observed(&rod, &auto(1_000_000, true));
    let alone = simulate(&rod, &auto(1_000_000, false)).unwrap();
    assert_eq!(o, alone);
    let estimate = o.error_estimate.unwrap();
    assert!(estimate.merged > 0.0 && estimate.ladder_set_aside.is_none());
    assert_eq!(estimate.exact_again_unfinished, None);
}

/// A ladder whose levels converge is left alone, though its exact run
/// would fit: layer survey seed 53's rod 22 (three layers, transit ratio
/// 180), whose exact run takes 203 k events, just past the first run's
/// 200 k.
#[test]
fn a_ladder_whose_levels_converge_is_not_run_again() {
    let rod = unit_impact(&[
        (0.5368391303020945, 36.81750461491677, 1.2433156895204054),
        (1.107001899169865, 772991.0539634638, 6.921418951221943),
        (0.3051333006579689, 26366604.473739702, 0.5228796026115057),
    ]);
    let (o, seen) = observed(&rod, &WaveConfig::default());
    let estimate = o.error_estimate.clone().unwrap();
    assert_eq!(estimate.merged_converging, Some(true), "the case");
    assert!(estimate.merged > 0.0 && !tried_again(&seen), "{seen:?}");
    let x = exact_run(&rod, 4_000_000, true).expect("the case: its exact run would fit");
    // and the ladder is within its bound of it
    let d = (o.restitution - x.restitution).abs();
    assert!(
        d <= o.error_bound.unwrap() + x.error_bound.unwrap(),
        "{d:e}"
    );
}

/// A rod whose exact run is tried again in vain says so, and its outcome
/// is otherwise the ladder's, to the bit: layer survey seed 53's rod 1
/// (three layers, transit ratio `1.1e5`), whose first run's growth
/// predicts `1.8e6` events and whose exact run takes `4.4e6`, past the
/// budget.
#[test]
fn an_exact_run_tried_in_vain_says_so_and_leaves_the_ladders_outcome() {
    let rod = unit_impact(&[
        (0.3381984826266848, 60176583.40736058, 1.0353335428417532),
        (0.5182595782843709, 1271158332609.2417, 2.091903402278884),
        (0.25508544543600103, 4.39305135251702, 0.3602903314681281),
    ]);
    let (o, seen) = observed(&rod, &WaveConfig::default());
    assert!(tried_again(&seen), "the case: tried again");
    let alone = simulate(&rod, &auto(4_000_000, false)).unwrap();
    assert_eq!(
        (o.restitution, o.error_bound, o.events),
        (alone.restitution, alone.error_bound, alone.events)
    );
    let estimate = o.error_estimate.unwrap();
    assert!(estimate.ladder_set_aside.is_none() && estimate.merged > 0.0);
    assert_eq!(estimate.exact_again_unfinished, Some(4_000_000));
    assert!(
        estimate.method.contains("did not finish"),
        "{}",
        estimate.method
    );
    assert!(
        exact_run(&rod, 4_000_000, true).is_none(),
        "the case: past the budget"
    );
}

/// However large the ladder's budget, the exact run again is allowed at
/// most `2e7` events (an exact run holds every front it keeps, so a
/// budget of `1e9` could otherwise let it fill the machine): layer survey
/// seed 3's rod 37 (four layers, transit ratio 290), whose levels do not
/// converge and whose exact run takes 510 k events, with a budget of
/// `1e8`.
#[test]
fn the_exact_run_again_is_allowed_at_most_2e7_events() {
    let rod = unit_impact(&[
        (0.6477453867296215, 35056.512156111814, 0.5285157325814629),
        (1.1697267711363772, 5157.833769300799, 4.058702231125916),
        (0.5696300696095613, 13081781.100634966, 5.13817556683631),
        (0.35909290469651983, 1144980.7178680243, 0.1107781479997433),
    ]);
    let (o, seen) = observed(&rod, &auto(100_000_000, true));
    assert!(
        seen.contains(&LadderProgress::ExactAgain { events: 20_000_000 }),
        "{seen:?}"
    );
    let kept = o.error_estimate.unwrap().ladder_set_aside.expect("exact");
    assert_eq!(kept.exact_events, 20_000_000);
    let x = exact_run(&rod, 20_000_000, true).unwrap();
    assert_eq!(o.restitution, x.restitution);
}

//! The chain's extrapolation to `N -> infinity` (`impact run` on a viscous
//! scene): its estimate contains the value of much larger chains, it meets
//! the target on the Fig. 10 materials, and it says so where the
//! order in `N` is not clean.

use impact_chain::{ChainConfig, simulate};
use impact_model::numerics::{Extrapolation, extrapolate};
use impact_model::{Bilayer, Layer, Rod, Scene};
use impact_study::{LimitSettings, chain_limit};

fn e_at(rod: &Rod, masses: usize) -> f64 {
    let config = ChainConfig {
        masses,
        ..ChainConfig::default()
    };
    simulate(rod, &config).unwrap().restitution
}

/// The reference: the same chain at three large sizes, extrapolated.
fn large_n_limit(rod: &Rod, sizes: [usize; 3]) -> (f64, f64) {
    let values: Vec<f64> = sizes.iter().map(|&n| e_at(rod, n)).collect();
    let x = extrapolate(&sizes, &values, false).unwrap();
    eprintln!(
        "reference {sizes:?}: {values:?} -> {:.7} +- {:.1e}",
        x.value, x.error
    );
    (x.value, x.error)
}

/// A homogeneous Kelvin-Voigt rod of `tau c / L = tau` (paper's wall law).
fn homogeneous(tau: f64) -> Rod {
    let mut layer = Layer::elastic(1.0, 1.0, 1.0);
    layer.relaxation_time = Some(tau);
    let scene = Scene {
        impact_speed: 1.0,
        layers: vec![layer],
        wall_contact: None,
    };
    scene.validate().unwrap()
}

/// The default ladder on `rod` against the limit of chains of the
/// `reference` sizes: the ladder's interval must cover the gap between the
/// two, and the outcome's `error_bound` the gap between its finest chain
/// (the outcome's `restitution`) and that limit (both tests of the estimate
/// ask this). Returns the estimate and the gap.
fn ladder_covers_the_large_n_limit(rod: &Rod, reference: [usize; 3]) -> (Extrapolation, f64) {
    let ladder = chain_limit(rod, &ChainConfig::default(), &LimitSettings::default()).unwrap();
    let x = ladder.outcome.extrapolation.clone().unwrap();
    let (limit, limit_error) = large_n_limit(rod, reference);
    let gap = (x.value - limit).abs();
    eprintln!(
        "ladder {:.7} +- {:.1e} (order {:?}); gap {gap:.1e}",
        x.value, x.error, x.order
    );
    assert!(
        gap <= x.error + limit_error,
        "the estimate {:.1e} misses the gap {gap:.1e}",
        x.error
    );
    let finest = ladder.outcome.restitution;
    let bound = ladder.outcome.error_bound.unwrap();
    let finest_gap = (finest - limit).abs();
    eprintln!("finest chain {finest:.7} +- {bound:.1e}; gap {finest_gap:.1e}");
    assert!(
        finest_gap <= bound + limit_error,
        "the finest chain's bound {bound:.1e} misses its gap {finest_gap:.1e}"
    );
    (x, gap)
}

fn fig10_materials() -> Rod {
    let mut scene = Bilayer::new(0.5, 0.005).unwrap().scene();
    scene.layers[0].restitution = Some(0.94);
    scene.layers[1].restitution = Some(0.72);
    scene.validate().unwrap()
}

/// Fig. 10's materials (e1 = 0.94, e2 = 0.72, alpha = 0.005) at x = 0.5:
/// the default ladder (N = 250, 500, 1000; 0.9 s on the development
/// machine, `cargo bench -p impact-study --bench sweep`) is within 1e-4 of
/// the limit of chains of 1000, 2000 and 4000 masses (which itself agrees
/// with 8000 and 16000 to 2e-6), and its estimate covers the gap.
#[test]
fn fig10_materials_within_1e_4_of_the_large_n_limit() {
    let (x, gap) = ladder_covers_the_large_n_limit(&fig10_materials(), [1000, 2000, 4000]);
    assert_eq!(x.sizes, [250, 500, 1000]);
    assert!(gap <= 1e-4, "gap {gap}");
    // the chain converges at about order one here
    assert!((0.8..1.6).contains(&x.order.unwrap()), "{x:?}");
}

/// A fully viscous homogeneous rod: the order in N is one, clean, and the
/// ladder's interval contains the limit of chains 8 to 16 times larger.
#[test]
fn the_estimate_contains_the_limit_of_larger_chains() {
    let (x, _) = ladder_covers_the_large_n_limit(&homogeneous(0.3), [2000, 4000, 8000]);
    assert!(x.clean, "{x:?}");
    assert!((0.9..1.1).contains(&x.order.unwrap()), "{x:?}");
}

/// An elastic bottom under a viscous top keeps sharp fronts: the ladder
/// says the order is not clean and widens its estimate, which still
/// contains the limit of larger chains.
#[test]
fn an_elastic_layer_is_flagged_and_the_wider_estimate_holds() {
    let mut scene = Bilayer::new(0.3, 0.005).unwrap().scene();
    scene.layers[1].relaxation_time = Some(2.0);
    let rod = scene.validate().unwrap();
    let ladder = chain_limit(&rod, &ChainConfig::default(), &LimitSettings::default()).unwrap();
    let x = ladder.outcome.extrapolation.clone().unwrap();
    let finest = e_at(&rod, 4000);
    eprintln!(
        "ladder {:.7} +- {:.1e} ({:?}); N = 4000: {finest:.7}",
        x.value, x.error, x.note
    );
    assert!(!x.clean && x.note.is_some(), "{x:?}");
    assert!((x.value - finest).abs() <= x.error, "{x:?} vs {finest}");
    // the N = 1000 chain's own bound covers the chain four times as fine
    let bound = ladder.outcome.error_bound.unwrap();
    assert!(
        (ladder.outcome.restitution - finest).abs() <= bound,
        "{} +- {bound:.1e} vs {finest}",
        ladder.outcome.restitution
    );
}

/// `--target` doubles N until the estimate is below it.
#[test]
fn a_target_drives_the_ladder() {
    let rod = fig10_materials();
    let settings = LimitSettings {
        target: Some(1e-4),
        max_masses: 4000,
        ..LimitSettings::default()
    };
    let ladder = chain_limit(&rod, &ChainConfig::default(), &settings).unwrap();
    let x = ladder.outcome.extrapolation.unwrap();
    eprintln!("{x:?}");
    assert_eq!(ladder.target_met, Some(x.error <= 1e-4));
    assert!(x.sizes.len() > 3 || x.error <= 1e-4);
    assert!(x.error <= 1e-4 || *x.sizes.last().unwrap() == 4000);
}

/// The over-damped wall (homogeneous, tau c / L = 1, paper's law), whose
/// single chains of N = 200 carry a time-step error of 1e-4
/// (`impact-chain`'s `tests/dt_order.rs`): that error falls as 1/N (5.6e-5,
/// 2.8e-5, 1.6e-5 at N = 250, 500, 1000), so the continuum answer moves by
/// less than 2e-5 between the paper's step and a step 16 times smaller.
#[test]
fn the_over_damped_wall_s_step_error_vanishes_from_the_continuum_answer() {
    let rod = homogeneous(1.0);
    let at = |dt_factor: f64| {
        let config = ChainConfig {
            dt_factor,
            ..ChainConfig::default()
        };
        let ladder = chain_limit(&rod, &config, &LimitSettings::default()).unwrap();
        ladder.outcome.extrapolation.unwrap()
    };
    let (paper, fine) = (at(1.0), at(1.0 / 16.0));
    eprintln!("paper's step: {paper:?}\ndt/16: {fine:?}");
    assert!(
        (paper.value - fine.value).abs() <= 2e-5,
        "{} vs {}",
        paper.value,
        fine.value
    );
    // and each chain's own step error shrinks as N grows
    let gaps: Vec<f64> = paper
        .values
        .iter()
        .zip(&fine.values)
        .map(|(a, b)| (a - b).abs())
        .collect();
    assert!(gaps.windows(2).all(|w| w[1] < w[0]), "{gaps:?}");
}

//! A block's fastest layer answered by its own response inside the
//! block's trace (`block/response/nested.rs`, `WaveConfig::nest_blocks`)
//! against the exact engine and against the trace that follows every one
//! of its fronts.

use impact_model::Rod;
use impact_model::{Outcome, Scene};
use impact_wave::{Resolution, WaveConfig, simulate};

mod common;
use common::{SURVEY_SEED_7_ROD_20, XorShift, exact_run, layer_of, scene_of};

fn bound(o: &Outcome) -> f64 {
    o.error_bound.expect("a bound")
}

/// A ladder of the three levels it needs at least (a target it meets
/// there), with `nest_blocks` as asked: nesting is priced at each level,
/// and its sums grow as the square of the lattices' density, the fronts
/// it saves only with it, so a ladder refined further stops nesting at
/// its finer levels.
fn ladder(rod: &Rod, nest_blocks: bool) -> Outcome {
    let config = WaveConfig {
        resolution: Resolution::Auto {
            exact_events: 1_000,
            budget_events: 4_000_000,
            target: 1e-3,
            exact_again: false,
        },
        nest_blocks,
        ..WaveConfig::default()
    };
    simulate(rod, &config).expect("a merged outcome")
}

/// The layers the outcome says its traces nested.
fn nested(o: &Outcome) -> Vec<usize> {
    o.error_estimate
        .as_ref()
        .map_or_else(Vec::new, |e| e.nested_layers.clone())
}

/// A slow bottom and top around a block of three layers a hundred to a
/// thousand times faster, whose middle layer is twenty to forty times
/// faster still (not the 64 at which it would leap on its own instead),
/// with impedances within a factor three: the block's
/// fronts die out within a few dozen round trips, so the exact engine can
/// follow them, and the middle layer holds most of the trace's lattice
/// points.
fn fast_middle(rng: &mut XorShift) -> Scene {
    let outer = rng.log_uniform(1e2, 1e3);
    let middle = outer * rng.log_uniform(20.0, 40.0);
    let mut layers = vec![layer_of(rng.uniform(0.5, 1.0), 1.0, 1.0)];
    for speed in [outer, middle, outer] {
        let speed = speed * rng.log_uniform(0.8, 1.25);
        layers.push(layer_of(
            rng.uniform(0.3, 1.0),
            speed,
            rng.log_uniform(0.3, 3.0),
        ));
    }
    let top_speed = rng.log_uniform(0.5, 2.0);
    layers.push(layer_of(
        rng.uniform(0.5, 1.0),
        top_speed,
        rng.log_uniform(0.3, 3.0),
    ));
    scene_of(layers)
}

/// Merged runs whose block nests its middle layer land within their bound
/// of the exact value, and within the sum of the two bounds of the same
/// ladder without nesting: the nested response is added at every lattice
/// point arriving at it, so an error in its arrivals, deliveries or the
/// trace's steps around it moves every front through the block.
#[test]
fn a_nested_layer_lands_within_its_bound_of_the_exact_value() {
    let mut rng = XorShift(0x2545_f491_4f6c_dd1d);
    let mut nesting = 0;
    for k in 0..6 {
        let scene = fast_middle(&mut rng);
        let rod = scene.validate().expect("a valid scene");
        let (on, off) = (ladder(&rod, true), ladder(&rod, false));
        assert!(nested(&off).is_empty(), "scene {k}\n{off:?}");
        // (where the middle layer is not fast enough for its response to
        // pay at the finest level, the two are the same run)
        if nested(&on) == [2] {
            nesting += 1;
        } else {
            assert!(nested(&on).is_empty(), "scene {k}\n{on:?}");
        }
        let x = exact_run(&rod, 4_000_000, true)
            .unwrap_or_else(|| panic!("scene {k}: the exact run did not fit\n{scene:?}"));
        let d = (on.restitution - x.restitution).abs();
        let apart = (on.restitution - off.restitution).abs();
        eprintln!(
            "scene {k}: nested e = {:.10} ± {:.1e}, not {:.10} ± {:.1e}, exact {:.10}",
            on.restitution,
            bound(&on),
            off.restitution,
            bound(&off),
            x.restitution
        );
        assert!(
            d <= bound(&on) + bound(&x),
            "scene {k}: |e - e_exact| = {d:.3e} exceeds the bound {:.3e}\n{scene:?}",
            bound(&on)
        );
        assert!(
            apart <= bound(&on) + bound(&off),
            "scene {k}: nested and not {apart:.3e} apart\n{scene:?}"
        );
    }
    assert!(nesting >= 4, "{nesting} of 6 nest");
}

/// Where nesting does not pay it is not taken: layer survey rod 20 (seed
/// 7), whose block's fastest layer is only 4.4 and 5.9 times faster than
/// its neighbours, so that its response spans as many of their lattice
/// points as the fronts it would save (`nested.rs`, the price).
#[test]
fn a_layer_whose_response_costs_more_than_its_fronts_is_not_nested() {
    let rod = Scene::elastic_stack(1.0, &SURVEY_SEED_7_ROD_20)
        .validate()
        .expect("a valid scene");
    let o = ladder(&rod, true);
    assert!(nested(&o).is_empty(), "{o:?}");
}

//! Blocks of fast layers answered by their traced response (`block.rs`,
//! `WaveConfig::fast_blocks`) against the exact engine and against the
//! event loop that follows every front of the block.

use impact_model::{Layer, Outcome, Rod, Scene};
use impact_wave::{Resolution, WaveConfig, simulate};

mod common;
use common::{SURVEY_SEED_7_ROD_20, XorShift, exact_run, ladder};

fn bound(o: &Outcome) -> f64 {
    o.error_bound.expect("a bound")
}

/// Whether the outcome says a block was answered by its response.
fn answered(o: &Outcome) -> bool {
    o.error_estimate
        .as_ref()
        .is_some_and(|e| !e.answered_blocks.is_empty() && e.method.contains("as one block"))
}

/// The rod of these elastic layers (length, modulus, density; bottom
/// first) at unit impact speed.
fn rod_of(layers: &[(f64, f64, f64)]) -> Rod {
    Scene::elastic_stack(1.0, layers)
        .validate()
        .expect("a valid rod")
}

/// The default run of `rod` answers a block and lands within its bound
/// of the exact engine (run to at most `exact_events`).
fn answered_within_bound_of_exact(rod: &Rod, exact_events: u64) {
    let o = simulate(rod, &WaveConfig::default()).expect("an outcome");
    assert!(answered(&o), "{o:?}");
    let x = exact_run(rod, exact_events, true).expect("the exact run fits");
    let d = (o.restitution - x.restitution).abs();
    eprintln!(
        "block e = {:.12} ± {:.1e}, exact {:.12} ± {:.1e}, |d| = {d:.1e}",
        o.restitution,
        bound(&o),
        x.restitution,
        bound(&x)
    );
    assert!(d <= bound(&o) + bound(&x));
}

/// Slow layers around a block of two or three layers a thousand to ten
/// thousand times faster, whose impedances stay within a factor three of
/// the bottom's: the block's fronts die out within a few dozen round
/// trips, so the exact engine can follow them.
fn matched_block(rng: &mut XorShift) -> Scene {
    let layer = |length: f64, speed: f64, impedance: f64| {
        let density = impedance / speed;
        Layer::elastic(length, density * speed * speed, density)
    };
    let mut layers = vec![layer(rng.uniform(0.5, 1.0), 1.0, 1.0)];
    for _ in 0..2 + usize::from(rng.next() < 0.5) {
        let speed = rng.log_uniform(1e4, 1e5);
        layers.push(layer(
            rng.uniform(0.2, 1.0),
            speed,
            rng.log_uniform(0.3, 3.0),
        ));
    }
    if rng.next() < 0.7 {
        let speed = rng.log_uniform(0.5, 2.0);
        layers.push(layer(
            rng.uniform(0.5, 1.0),
            speed,
            rng.log_uniform(0.3, 3.0),
        ));
    }
    Scene {
        impact_speed: 1.0,
        layers,
        wall_contact: None,
    }
}

/// Merged runs that answer a block by its response land within their
/// bound of the exact value, on rods where the exact engine can follow
/// every front: the response is traced once and added at every arrival,
/// so an error in the trace, its deposits or its deliveries moves every
/// arrival's share (the first build's stepping put a birth on the wrong
/// point and missed a four-layer rod by 1.5 times its bound).
#[test]
fn blocks_land_within_their_bound_of_the_exact_value() {
    let mut rng = XorShift(0x5bd1_e995_7f4a_7c15);
    let mut checked = 0;
    for k in 0..6 {
        let scene = matched_block(&mut rng);
        let rod = scene.validate().unwrap();
        let o = ladder(
            &rod,
            WaveConfig {
                fast_blocks: true,
                ..WaveConfig::default()
            },
        );
        assert!(answered(&o), "scene {k}: no block answered\n{o:?}");
        let x = exact_run(&rod, 4_000_000, true)
            .unwrap_or_else(|| panic!("scene {k}: the exact run did not fit\n{scene:?}"));
        let d = (o.restitution - x.restitution).abs();
        eprintln!(
            "scene {k}: {} layers, e = {:.10} ± {:.1e}, exact {:.10}, |d| = {d:.1e}",
            scene.layers.len(),
            o.restitution,
            bound(&o),
            x.restitution
        );
        assert!(
            d <= bound(&o) + bound(&x),
            "scene {k}: |e - e_exact| = {d:.3e} exceeds the bound {:.3e}\n{scene:?}",
            bound(&o)
        );
        checked += 1;
    }
    assert_eq!(checked, 6);
}

/// Where the block rings long (a fast block between slow, soft layers,
/// survey rod 20's kind) the exact engine cannot follow it, but the loop
/// can, front by front on the same lattices: the ladders must agree
/// within their bounds, the block traced on one lattice (the default,
/// `one_lattice_blocks`) or on each layer's own.
#[test]
fn blocks_agree_with_the_loop_where_the_block_rings_long() {
    // survey rod 20 (seed 7): a slow bottom under four fast layers and a
    // top a hundred times slower than them
    let rod = rod_of(&SURVEY_SEED_7_ROD_20);
    let on = ladder(
        &rod,
        WaveConfig {
            fast_blocks: true,
            ..WaveConfig::default()
        },
    );
    let off = ladder(
        &rod,
        WaveConfig {
            fast_blocks: false,
            ..WaveConfig::default()
        },
    );
    let own = ladder(
        &rod,
        WaveConfig {
            fast_blocks: true,
            one_lattice_blocks: false,
            ..WaveConfig::default()
        },
    );
    assert!(answered(&on) && answered(&own), "{on:?}\n{own:?}");
    assert!(!answered(&off), "{off:?}");
    let method = |o: &Outcome| o.error_estimate.as_ref().unwrap().method.clone();
    assert!(
        method(&on).contains("(one_lattice_blocks)"),
        "{}",
        method(&on)
    );
    assert!(!method(&own).contains("one_lattice"), "{}", method(&own));
    for blocks in [&on, &own] {
        let d = (blocks.restitution - off.restitution).abs();
        eprintln!(
            "blocks e = {:.10} ± {:.1e}, loop {:.10} ± {:.1e}, |d| = {d:.1e}",
            blocks.restitution,
            bound(blocks),
            off.restitution,
            bound(&off)
        );
        assert!(d <= bound(blocks) + bound(&off));
    }
}

/// A block that the choice takes only since its sums are priced as the
/// dense dot products cost (`block/choice.rs`, `NS_PER_ADD`): layer survey
/// rod 11 (seed 7), a top of two fast layers (transits `2.1e-5` and
/// `7.2e-6`) over one of `4.6e-2`: the default run answers them as a
/// block (1,176 loop events where the loop took 108,060) and lands within
/// its bound of the exact engine (7.8 M events: `e` the same to 12
/// digits).
#[test]
fn a_block_taken_at_the_dense_price_lands_within_its_bound() {
    let rod = rod_of(&[
        (1.1785012427189727, 1205067826.1583042, 5.329053258284448),
        (0.46111519722936195, 54.68950567790808, 0.5412520864675717),
        (0.9719379084020312, 2593244652.673352, 1.1619429225609141),
        (0.5296649950477623, 1528334115.2924802, 0.27930798145917035),
    ]);
    answered_within_bound_of_exact(&rod, 10_000_000);
}

/// The fast-bottom survey's rod 17 (seed 11): a light pair (transits
/// `1.1e-6` and `1.5e-5`) between a heavy bottom of `2.4e-4` and a slow
/// top.
fn fast_bottom_rod_17() -> Rod {
    rod_of(&[
        (1.1242304467980708, 178026015.17940763, 8.42955819531295),
        (
            0.44229188933956426,
            297258.59940420586,
            1.801533894307802e-06,
        ),
        (
            0.28784235997020097,
            1006836.9796508452,
            0.0028850732552570886,
        ),
        (1.1767485841422314, 205.24445995520156, 1.0610479358752047),
    ])
}

/// A block beside a fast bottom that the worst-case price refuses (its
/// port on the bottom's lattice delivers so often that sums over the
/// whole run would cost more than the loop) but whose response rings out
/// within the sums' allowance, as a probe of it shows (`block/flow.rs`):
/// the fast-bottom survey's rod 17 (seed 11), a light pair (transits
/// `1.1e-6` and `1.5e-5`) between a heavy bottom of `2.4e-4` and a slow
/// top. The default run answers it and lands within its bound of the
/// exact engine (18.7 M events).
#[test]
fn a_block_that_rings_out_beside_a_fast_bottom_lands_within_its_bound() {
    answered_within_bound_of_exact(&fast_bottom_rod_17(), 30_000_000);
}

/// A block's response fronts that their arrival scales under what the
/// neighbour's lane keeps apart are put on the port's lattice as the
/// arrival comes (`block/folded.rs`, `WaveConfig::fold_small_exact`),
/// split as the lane would have split them: each lattice point receives
/// the same total, summed in another order. What can differ is how the
/// fronts born together on a point are grouped among the lane's fronts
/// there (kept ones, which may not be merged into, sit between them), and
/// so which of their reflections the next lane keeps apart. Runs on one
/// lattice with and without folding agree far within the merged error:
/// the fast-bottom survey's rod 17 (seed 11, above) to the last digit,
/// and rod 36, whose block's response holds 16 large fronts an arrival
/// (all but a few folded), within `1.2e-11` at a fifth of each transit,
/// under a ladder's bound of `1.2e-5`; the loop takes 10.7 times fewer
/// events there (a front whose earlier point the port delivered last is
/// folded too: its share there is deposited with the arrival's others,
/// `Folded::take_behind`). (On a rod that chatters such a difference can change a
/// grazing contact: the ladder measures it as any merge error.)
#[test]
fn folded_response_fronts_change_only_the_order_of_the_sums() {
    let rod_17 = fast_bottom_rod_17();
    let rod_36 = rod_of(&[
        (0.3506851119469851, 760637.2208789994, 0.003806984903070696),
        (
            1.0363439439921123,
            3377868.594378576,
            4.1676290105211325e-07,
        ),
        (
            0.49088567606071726,
            711170438.0910461,
            0.0031711267516118724,
        ),
        (1.0261569583477455, 47865.820780144764, 8826.044285296111),
        (0.6620162462828918, 3779.0529122686276, 355.52597146771296),
    ]);
    for (name, rod) in [("rod 17", &rod_17), ("rod 36", &rod_36)] {
        for per_transit in [0.2, 0.1] {
            let run = |fold_small_exact: bool| {
                let config = WaveConfig {
                    resolution: Resolution::Merged {
                        per_transit,
                        per_longest: per_transit / 50.0,
                    },
                    fold_small_exact,
                    ..WaveConfig::default()
                };
                simulate(rod, &config).expect("an outcome")
            };
            let (folded, apart) = (run(true), run(false));
            assert!(answered(&folded) && answered(&apart), "{name}");
            let d = (folded.restitution - apart.restitution).abs();
            eprintln!(
                "{name} at {per_transit}: e = {:.15} folded, {:.15} apart, |d| = {d:.1e}; events {} and {}",
                folded.restitution,
                apart.restitution,
                folded.events.unwrap_or(0),
                apart.events.unwrap_or(0)
            );
            assert!(d <= 1e-9, "{name} at {per_transit}: |d| = {d:.3e}");
            assert_eq!(folded.bounces, apart.bounces, "{name}");
            assert!(
                folded.events.unwrap_or(0) < apart.events.unwrap_or(0),
                "{name}: nothing folded"
            );
            if name == "rod 36" && per_transit == 0.2 {
                // a response front whose earlier point was delivered last
                // is folded too, its share there deposited with the
                // arrival's others: 10.7 times fewer events (7.1 times
                // while such fronts went through the queue)
                assert!(
                    10 * folded.events.unwrap_or(0) < apart.events.unwrap_or(0),
                    "{name}: the fronts behind the port's next point went through the queue"
                );
            }
        }
    }
}

/// A block's traced response, as `Tracer::block_responses` reports it
/// (`crates/wave/examples/block_taps.rs` writes it out), is over all time
/// what the interface between the block's neighbours does (the block is
/// transparent at zero frequency): with the block's faces' own
/// reflections, its taps and exact fronts at each port sum to the direct
/// interface's reflection and transmission. On the matched blocks, whose
/// responses ring out within a few dozen round trips, to `1e-9`; the
/// dropped fronts and the rest carry at most `1e-13` each.
#[test]
fn a_blocks_reported_response_is_the_interface_between_its_neighbours() {
    use impact_model::{InterfaceCoefficients, WaveConstants};
    use impact_wave::WaveEngine;
    let mut rng = XorShift(0x5bd1_e995_7f4a_7c15);
    let mut scenes: Vec<Scene> = (0..4).map(|_| matched_block(&mut rng)).collect();
    // and one that rings long, its response mostly taps: the layer
    // survey's rod 20 (seed 7), as above
    scenes.push(Scene::elastic_stack(1.0, &SURVEY_SEED_7_ROD_20));
    for (k, scene) in scenes.iter().enumerate() {
        let rod = scene.validate().unwrap();
        let config = WaveConfig {
            resolution: Resolution::Merged {
                per_transit: 0.1,
                per_longest: 2e-3,
            },
            ..WaveConfig::default()
        };
        let mut engine = WaveEngine::new(&rod, config).unwrap();
        let blocks = engine.answered_blocks();
        assert!(!blocks.is_empty(), "scene {k}: no block answered");
        let responses = engine.block_responses(100.0);
        let side = |m: usize| {
            let l = &scene.layers[m];
            let (modulus, density) = (l.modulus, l.density);
            let w = WaveConstants::of(l.length, modulus, density);
            (w.impedance, modulus)
        };
        for (&(lower, upper), inputs) in blocks.iter().zip(&responses) {
            let top = upper + 1 == scene.layers.len();
            let face_below = InterfaceCoefficients::of_sides(side(lower - 1), side(lower));
            let total = |r: &impact_wave::BlockResponse| {
                r.taps.iter().sum::<f64>() + r.exact.iter().map(|e| e.1).sum::<f64>()
            };
            let close = |a: f64, b: f64| (a - b).abs() < 1e-9;
            eprintln!(
                "scene {k}: block {lower}..={upper}{}, taps {:?}, exact fronts {:?}",
                if top { " under the free top" } else { "" },
                inputs[0].iter().map(|r| r.taps.len()).collect::<Vec<_>>(),
                inputs[0].iter().map(|r| r.exact.len()).collect::<Vec<_>>(),
            );
            if top {
                // under the free top: everything comes back down
                let back = total(&inputs[0][0]) + face_below.up_reflected;
                assert!(close(back, -1.0), "scene {k}: {back}");
                continue;
            }
            let direct = InterfaceCoefficients::of_sides(side(lower - 1), side(upper + 1));
            let face_above = InterfaceCoefficients::of_sides(side(upper), side(upper + 1));
            let from_below = (total(&inputs[0][0]), total(&inputs[0][1]));
            let from_above = (total(&inputs[1][0]), total(&inputs[1][1]));
            assert!(
                close(from_below.0 + face_below.up_reflected, direct.up_reflected),
                "scene {k}: {from_below:?} {direct:?}"
            );
            assert!(close(from_below.1, direct.up_transmitted), "scene {k}");
            assert!(
                close(
                    from_above.1 + face_above.down_reflected,
                    direct.down_reflected
                ),
                "scene {k}: {from_above:?} {direct:?}"
            );
            assert!(close(from_above.0, direct.down_transmitted), "scene {k}");
        }
    }
}

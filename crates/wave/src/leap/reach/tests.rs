use crate::engine::{StepKind, Tracer};
use crate::{Resolution, WaveConfig};
use impact_model::Scene;

/// Layer survey seed 71's rod 27: eight layers (transits `1.8e-4`,
/// `2.0e-6`, `6.7e-4`, `2.0e-6`, `6.3e-5`, `0.17`, `0.36`, `1.6e-4`), a
/// block of layers 3 and 4 whose upper port, on the lattice of the layer
/// of `0.17` above it, gives the blocks a margin longer than the way from
/// the block's lower port to layer 1: layer 1 tried to leap at nearly
/// every loop event and never did.
fn survey_seed_71_rod_27() -> impact_model::Rod {
    let layers = [
        (0.22436858523117792, 8209199.532319025, 5.011049876585219),
        (1.1569826794448301, 217603816164.44586, 0.6519566190966186),
        (0.8001716821543876, 1521618.2981178665, 1.0712382022461013),
        (0.7318857623704467, 819717631950.9319, 5.910597170758888),
        (0.26809553495341515, 99006941.99250051, 5.381439174581063),
        (0.9469700269778369, 24.04725430523074, 0.7501291812451525),
        (0.42677945176838733, 1.1306941717319374, 0.8246422170851864),
        (1.0294212424933677, 26674438.968159564, 0.6343429203331157),
    ];
    Scene::elastic_stack(1.0, &layers)
        .validate()
        .expect("valid")
}

/// Layer survey seed 7's rod 11: a fast bottom (`7.8e-5`) under a slow
/// layer (`4.6e-2`) and a block of two fast layers on top; the bottom
/// leaps, the block beside it notwithstanding.
fn survey_seed_7_rod_11() -> impact_model::Rod {
    let layers = [
        (1.1785012427189727, 1205067826.1583042, 5.329053258284448),
        (0.46111519722936195, 54.68950567790808, 0.5412520864675717),
        (0.9719379084020312, 2593244652.673352, 1.1619429225609141),
        (0.5296649950477623, 1528334115.2924802, 0.27930798145917035),
    ];
    Scene::elastic_stack(1.0, &layers)
        .validate()
        .expect("valid")
}

fn merged(p: f64) -> WaveConfig {
    WaveConfig {
        resolution: Resolution::Merged {
            per_transit: p,
            per_longest: p / 50.0,
        },
        ..WaveConfig::default()
    }
}

/// The layers that leapt, and the outcome's numbers: `e`'s bits, events,
/// work, contacts.
type Ran = (Vec<usize>, u64, u64, u64, Vec<[f64; 2]>);

fn run(mut tracer: Tracer<f64>) -> Ran {
    let mut leapt = Vec::new();
    while tracer.stopped().is_none() {
        if let StepKind::Leap { layer, .. } = tracer.step().expect("a step").kind {
            leapt.push(layer);
        }
    }
    let e = tracer.restitution().to_bits();
    (
        leapt,
        e,
        tracer.events(),
        tracer.steps(),
        tracer.outcome().contacts,
    )
}

/// The layers whose leaps a block's port rules out do not try, and their
/// tries would have changed nothing: the same rod with those layers'
/// tries put back runs to the same outcome, to the bit, and leaps none
/// of them. Seed 71's rod 27 has such a layer; seed 7's rod 11 has a
/// block and a layer that leaps, which must not be ruled out.
#[test]
fn a_layer_a_ports_bound_keeps_from_leaping_does_not_try_and_nothing_changes() {
    for (rod, must_rule_out, must_leap) in [
        (survey_seed_71_rod_27(), Some(1), false),
        (survey_seed_7_rod_11(), None, true),
    ] {
        let config = merged(0.2);
        let ruled = Tracer::<f64>::new(&rod, config.clone()).expect("a run");
        assert!(!ruled.blocks.list.is_empty(), "a rod with a block");
        let may_leap = crate::leap::first_leaps(&ruled.layers, false);
        let ruled_out: Vec<usize> = (0..ruled.layers.len())
            .filter(|&i| may_leap[i] == f64::NEG_INFINITY && ruled.leap_after[i] == f64::INFINITY)
            .collect();
        assert!(
            must_rule_out.is_none_or(|i| ruled_out.contains(&i)),
            "ruled out: {ruled_out:?}"
        );
        let mut tried = Tracer::<f64>::new(&rod, config).expect("a run");
        for &i in &ruled_out {
            tried.leap_after[i] = f64::NEG_INFINITY;
        }
        let (ruled, tried) = (run(ruled), run(tried));
        assert!(
            ruled_out.iter().all(|i| !tried.0.contains(i)),
            "a layer ruled out leapt: {:?}",
            tried.0
        );
        assert!(!must_leap || !ruled.0.is_empty(), "no leap");
        assert_eq!(ruled, tried);
    }
}

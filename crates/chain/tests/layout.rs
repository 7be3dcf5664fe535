mod common;
use common::*;
use impact_chain::{ChainError, ChainLayout};

#[test]
fn masses_follow_lengths_with_at_least_one_per_layer() {
    let l = ChainLayout::new(&bilayer(0.3, 0.5), 1000).unwrap();
    assert_eq!(l.per_layer, vec![700, 300]);
    assert_eq!(l.len(), 1000);
    let thin = ChainLayout::new(&bilayer(0.001, 0.5), 100).unwrap();
    assert_eq!(thin.per_layer, vec![99, 1]);
    assert_eq!(thin.thin_layers(), vec![(1, 1)]);
    assert!(matches!(
        ChainLayout::new(&bilayer(0.3, 0.5), 1),
        Err(ChainError::TooFewMasses { .. })
    ));
}

#[test]
fn the_chain_has_the_rods_mass_and_length() {
    let rod = elastic_stack(1.0, &[(0.3, 5.0, 2.0), (0.5, 0.2, 0.5), (0.2, 1.5, 7.0)]);
    let l = ChainLayout::new(&rod, 997).unwrap();
    assert!((l.mass.iter().sum::<f64>() - rod.mass()).abs() < 1e-12);
    assert!((l.height.last().unwrap() - rod.total_length()).abs() < 1e-12);
    // each element's wave speed is its layer's: sqrt(k l0^2 / m) = c
    for j in 0..l.len() {
        let c = (l.stiffness[j] * l.rest_length[j].powi(2) / l.mass[j]).sqrt();
        assert!((c - rod.layers()[l.layer_of[j]].wave_speed).abs() < 1e-12);
    }
}

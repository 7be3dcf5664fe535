//! The two-pass kernel against the stage-by-stage kernel it replaces on long
//! chains (itself checked against the method written out the long way in
//! `tests/implicit_kernel.rs`), and its vector instructions against the
//! baseline's.

use super::*;
use impact_model::{Bilayer, Rod};

/// The canonical bilayer with relaxation times `tau` (0: elastic).
fn viscous_bilayer(x: f64, alpha: f64, tau: [f64; 2], law: WallContact) -> Rod {
    let mut scene = Bilayer::new(x, alpha).unwrap().scene();
    for (layer, tau) in scene.layers.iter_mut().zip(tau) {
        layer.relaxation_time = (tau > 0.0).then_some(tau);
    }
    scene.wall_contact = Some(law);
    scene.validate().unwrap()
}

fn cases(law: WallContact) -> Vec<(&'static str, Rod)> {
    vec![
        (
            "viscous bottom (x 0.5, alpha 0.3, tau1 0.08)",
            viscous_bilayer(0.5, 0.3, [0.08, 0.0], law),
        ),
        (
            "viscous top (x 0.3, alpha 0.005, tau2 2)",
            viscous_bilayer(0.3, 0.005, [0.0, 2.0], law),
        ),
        (
            "both viscous (x 0.4, alpha 0.05, tau 0.02, 0.5)",
            viscous_bilayer(0.4, 0.05, [0.02, 0.5], law),
        ),
        ("five layers, moduli over five decades", five_layers(law)),
    ]
}

/// Steel-, gel-, aluminium-, foam- and rubber-like layers (moduli from
/// `2e-3` to `200`, densities from 0.9 to 7.8), the two soft ones viscous.
fn five_layers(law: WallContact) -> Rod {
    use impact_model::{Layer, Scene};
    let mut layers = vec![
        Layer::elastic(0.3, 200.0, 7.8),
        Layer::elastic(0.5, 0.01, 1.1),
        Layer::elastic(0.2, 70.0, 2.7),
        Layer::elastic(0.6, 0.002, 0.9),
        Layer::elastic(0.4, 3.0, 1.2),
    ];
    layers[1].relaxation_time = Some(0.05);
    layers[3].relaxation_time = Some(0.5);
    Scene {
        impact_speed: 1.0,
        layers,
        wall_contact: Some(law),
    }
    .validate()
    .unwrap()
}

/// A homogeneous rod of `tau c / L = tau` (short blocks suffice: its
/// dashpots are mild).
fn homogeneous(tau: f64, law: WallContact) -> Rod {
    let mut layer = impact_model::Layer::elastic(1.0, 1.0, 1.0);
    layer.relaxation_time = Some(tau);
    impact_model::Scene {
        impact_speed: 1.0,
        layers: vec![layer],
        wall_contact: Some(law),
    }
    .validate()
    .unwrap()
}

fn chain(rod: &Rod, masses: usize, isa: Option<Isa>) -> ImplicitChain {
    let layout = ChainLayout::new(rod, masses).unwrap();
    let dt = layout.paper_time_step();
    ImplicitChain::with_isa(&layout, dt, rod.impact_speed(), rod.wall_contact(), isa)
}

/// Largest `|x - y|` against the largest `|y|`.
fn gap(x: &[f64], y: &[f64]) -> f64 {
    let scale = y.iter().fold(0.0f64, |s, y| s.max(y.abs()));
    x.iter()
        .zip(y)
        .fold(0.0f64, |s, (x, y)| s.max((x - y).abs()))
        / scale
}

/// Steps `fused` and `plain` side by side; the gaps in positions,
/// velocities and the summed wall impulse, and how often the wall
/// switched (the stage-by-stage kernel takes those steps).
fn side_by_side(
    fused: &mut ImplicitChain,
    plain: &mut ImplicitChain,
    steps: usize,
    label: &str,
) -> usize {
    assert!(
        fused.fused.is_some(),
        "{label}: the two-pass kernel is not used"
    );
    let (mut impulses, mut switches) = ((0.0, 0.0), 0);
    for _ in 0..steps {
        let was = fused.wall_on;
        impulses.0 += fused.step();
        impulses.1 += plain.step();
        assert_eq!(fused.wall_on, plain.wall_on, "{label}");
        switches += usize::from(fused.wall_on != was);
    }
    let du = gap(&fused.displacement(), &plain.displacement());
    let dv = gap(&fused.velocities(), &plain.velocities());
    let di = (impulses.0 - impulses.1).abs() / impulses.1.abs();
    println!(
        "{label}: {switches} switches; positions {du:.1e}, velocities {dv:.1e}, impulse {di:.1e}"
    );
    assert!(du <= 1e-12, "{label}: positions {du:.1e} apart");
    assert!(dv <= 1e-11, "{label}: velocities {dv:.1e} apart");
    assert!(di <= 1e-12, "{label}: impulses {di:.1e} apart");
    switches
}

/// 4800 masses, blocks of 600, over 4000 steps into the contact:
/// positions, velocities and the wall's impulse.
#[test]
fn the_two_pass_kernel_steps_as_the_stage_by_stage_kernel() {
    for law in WallContact::ALL {
        for (label, rod) in cases(law) {
            let isa = Some(Isa::Detected(pulp::Arch::new()));
            let label = format!("{label}, {law}");
            side_by_side(
                &mut chain(&rod, 4800, isa),
                &mut chain(&rod, 4800, None),
                4_000,
                &label,
            );
        }
    }
}

/// Whole contacts of homogeneous rods at 1200 masses (blocks of 150):
/// the steps where the wall switches or would pull go to the stage-by-stage
/// kernel, and the two-pass kernel takes over again after them.
#[test]
fn the_two_pass_kernel_hands_the_wall_s_switches_over_and_back() {
    for law in WallContact::ALL {
        for tau in [0.005, 0.01] {
            let rod = homogeneous(tau, law);
            let isa = Some(Isa::Detected(pulp::Arch::new()));
            let label = format!("homogeneous, tau c / L = {tau}, {law}");
            let switches = side_by_side(
                &mut chain(&rod, 1200, isa),
                &mut chain(&rod, 1200, None),
                60_000,
                &label,
            );
            assert!(switches >= 1, "{label}: the wall never switched");
        }
    }
}

/// The passes compiled for this processor's widest vectors (and for AVX2,
/// where it has it) give the baseline's bits: no operation is fused or
/// reordered.
#[test]
fn every_instruction_set_gives_the_same_bits() {
    let rod = viscous_bilayer(0.4, 0.05, [0.02, 0.5], WallContact::Paper);
    let run = |isa: Isa| {
        let mut chain = chain(&rod, 2000, Some(isa));
        assert!(chain.fused.is_some());
        let impulses: Vec<u64> = (0..2_000).map(|_| chain.step().to_bits()).collect();
        let bits = |x: &[f64]| x.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        (
            impulses,
            bits(&chain.displacement()),
            bits(&chain.velocities()),
        )
    };
    let baseline = run(Isa::Baseline);
    assert!(baseline == run(Isa::Detected(pulp::Arch::new())));
    #[cfg(target_arch = "x86_64")]
    if let Some(v3) = pulp::x86::V3::try_new() {
        assert!(baseline == run(Isa::Avx2(v3)));
    }
}

//! The viscous chain (its default, implicit kernel: SDIRK2 on springs and
//! dashpots together) is second order in the time step, and at the paper's
//! step it is within 2e-5 of its `dt -> 0` limit on viscous bottoms,
//! viscous tops and fully viscous rods at `N = 200`. The limit
//! is Richardson's from `dt / 8` and `dt / 16`, whose own error is below
//! 1e-7 here.

mod common;

use common::{homogeneous_under as homogeneous, viscous_bilayer as bilayer};
use impact_chain::{ChainConfig, ChainStop, ViscousKernel, simulate};
use impact_model::{Rod, WallContact};

const N: usize = 200;

/// `e` at `dt_factor` times the paper's step, to the paper's horizon.
fn e_at(rod: &Rod, dt_factor: f64) -> f64 {
    let config = ChainConfig {
        masses: N,
        dt_factor,
        stop: ChainStop::PAPER,
        ..ChainConfig::default()
    };
    simulate(rod, &config).unwrap().restitution
}

/// `e` at `dt`, `dt/2`, `dt/4`, `dt/8`, `dt/16`.
fn ladder(rod: &Rod) -> Vec<f64> {
    (0..5).map(|k| e_at(rod, 0.5f64.powi(k))).collect()
}

#[test]
fn second_order_and_within_2e_5_of_the_limit_at_the_paper_step() {
    use WallContact::{Paper, Unilateral};
    let scenes = [
        (
            "viscous bottom (x 0.5, alpha 0.3, tau1 0.08)",
            bilayer(0.5, 0.3, [0.08, 0.0], Paper),
            true,
        ),
        (
            "same, unilateral wall",
            bilayer(0.5, 0.3, [0.08, 0.0], Unilateral),
            true,
        ),
        (
            "viscous top (x 0.3, alpha 0.005, tau2 2)",
            bilayer(0.3, 0.005, [0.0, 2.0], Paper),
            true,
        ),
        (
            "fully viscous (x 0.5, alpha 0.05, tau 0.05, 0.5)",
            bilayer(0.5, 0.05, [0.05, 0.5], Paper),
            true,
        ),
        ("homogeneous tau c/L 0.1", homogeneous(0.1, Paper), false),
        ("homogeneous tau c/L 0.3", homogeneous(0.3, Paper), false),
    ];
    for (name, rod, clean) in &scenes {
        let e = ladder(rod);
        let limit = e[4] + (e[4] - e[3]) / 3.0;
        let error = (e[0] - limit).abs();
        let order = ((e[1] - e[2]) / (e[2] - e[3])).abs().log2();
        eprintln!(
            "{name}: e(dt) = {:.7}, limit {limit:.7}, error {error:.1e}, order {order:.2}",
            e[0]
        );
        assert!(error <= 2e-5, "{name}: |e(dt) - e(0)| = {error:.2e}");
        // where the dt error is above rounding and the contact's end
        // jitter (the homogeneous rods: both below 1e-6), it falls as dt^2
        // (from dt/2 to dt/8: at the paper's step the unilateral wall's
        // release still shows, order 1.78)
        if *clean {
            assert!(order >= 1.8, "{name}: observed order {order:.2} in {e:?}");
        }
    }
}

/// The hard case: a homogeneous rod at tau c / L = 1 under the paper's law.
/// The wall dashpot over-damps mass 0 (`c0 dt / m0 = 12.6` at `N = 200`),
/// the rod peels off the wall slowly (`t_c = 3.4 L/c`) and `e = 0.009` is
/// set by when `u0` creeps back to zero. The split kernel's creep is first
/// order there (`9.3e-5` from the limit at the paper's step, `2.8e-5` at
/// `dt / 32`); the implicit kernel's `e` at the paper's step is within
/// `2e-5` of its own limit (measured: `1e-9`) and,
/// independently, within `3e-5` of the explicit chain of
/// `tests/wall_law.rs` at `dt / 200` (`0.009135`; measured `5e-6`).
#[test]
fn an_overdamped_wall_is_within_2e_5_at_the_paper_step() {
    let rod = homogeneous(1.0, WallContact::Paper);
    let e = ladder(&rod);
    let limit = e[4] + (e[4] - e[3]) / 3.0;
    eprintln!("e(dt) = {:.10}, limit {limit:.10}", e[0]);
    assert!((e[0] - limit).abs() <= 2e-5, "{e:?}");
    assert!((e[0] - 0.009135).abs() <= 3e-5, "{}", e[0]);
}

/// The implicit kernel is second order on a scene where its step error
/// stands above rounding: the viscous top at `N = 200` (`5e-6` at the
/// paper's step, against the split kernel's `1.5e-5`).
///
/// And why it is the default: on a viscous top whose dashpots are stiff
/// against the step (`x = 0.5`, `alpha = 0.05`, `tau2 = 1`, seven
/// separations) the split kernel lands `3.3e-4` from its limit at the
/// paper's step, the implicit one `1.6e-5`. The limit is each kernel's own
/// at `dt / 16` (the two agree there to `2e-6`).
#[test]
fn the_implicit_kernel_is_second_order() {
    let rod = bilayer(0.3, 0.005, [0.0, 2.0], WallContact::Paper);
    let e: Vec<f64> = (0..4)
        .map(|k| {
            let config = ChainConfig {
                masses: N,
                dt_factor: 0.5f64.powi(k),
                stop: ChainStop::PAPER,
                viscous_kernel: ViscousKernel::Implicit,
                ..ChainConfig::default()
            };
            simulate(&rod, &config).unwrap().restitution
        })
        .collect();
    let order = ((e[0] - e[1]) / (e[1] - e[2])).log2();
    let order_fine = ((e[1] - e[2]) / (e[2] - e[3])).log2();
    let limit = e[3] + (e[3] - e[2]) / 3.0;
    eprintln!("e = {e:?}, orders {order:.2}, {order_fine:.2}, limit {limit:.8}");
    assert!(order >= 1.8 && order_fine >= 1.8, "{e:?}");
    assert!((e[0] - limit).abs() <= 2e-5, "{e:?}");

    let stiff_top = bilayer(0.5, 0.05, [0.0, 1.0], WallContact::Paper);
    let e = |kernel, dt_factor| {
        let config = ChainConfig {
            masses: N,
            dt_factor,
            stop: ChainStop::PAPER,
            viscous_kernel: kernel,
            ..ChainConfig::default()
        };
        simulate(&stiff_top, &config).unwrap().restitution
    };
    let [split, implicit] = [ViscousKernel::Split, ViscousKernel::Implicit]
        .map(|kernel| (e(kernel, 1.0) - e(kernel, 1.0 / 16.0)).abs());
    eprintln!("stiff top: split {split:.1e}, implicit {implicit:.1e} from dt / 16");
    assert!(implicit <= 2e-5, "{implicit}");
    assert!(split > 1e-4, "the split kernel was 3.3e-4 away: {split}");
}

//! The wall's contact law against an independent oracle: a plain Beeman
//! chain written here, with *explicit* dashpots (their velocities from the
//! Beeman predictor) and the wall force evaluated directly from the law, run
//! at a step 200 times below the paper's, where explicit dashpots are
//! stable. It shares only the discretisation (`ChainLayout`: masses, springs,
//! dashpot constants) with the engine, not its splitting, implicit solve or
//! wall bookkeeping.

mod common;

use common::{homogeneous_under as homogeneous, viscous_bilayer as bilayer, with_law};
use impact_chain::{ChainConfig, ChainLayout, ChainStop, simulate};
use impact_model::{Bilayer, Rod, WallContact};

/// Both chains stop at `HORIZON` times the sum of the transit times: the
/// contact of every scene here ends before twice that sum, and a landing
/// after it would show as a disagreement, never hide one.
const HORIZON: f64 = 4.0;

/// `e` of the explicit chain of `n` masses at `dt / refine`, stopped at
/// [`HORIZON`].
fn explicit_chain(rod: &Rod, n: usize, law: WallContact, refine: f64) -> f64 {
    let layout = ChainLayout::new(rod, n).unwrap();
    let (m, k, c) = (&layout.mass, &layout.stiffness, &layout.viscosity);
    let dt = layout.paper_time_step() / refine;
    let vb = rod.impact_speed();
    let total: f64 = m.iter().sum();
    let end = HORIZON * rod.transit_times().iter().sum::<f64>();
    let mut u = vec![0.0; n];
    let mut v = vec![-vb; n];
    // forces on each mass from displacements and velocities; returns the
    // wall's force on mass 0 too
    let forces = |u: &[f64], v: &[f64], f: &mut [f64]| -> f64 {
        let wall = if u[0] < 0.0 {
            let push = -(k[0] * u[0] + c[0] * v[0]);
            match law {
                WallContact::Paper => push,
                WallContact::Unilateral => push.max(0.0),
            }
        } else {
            0.0
        };
        f.iter_mut().for_each(|x| *x = 0.0);
        f[0] = wall;
        for j in 1..n {
            let t = k[j] * (u[j] - u[j - 1]) + c[j] * (v[j] - v[j - 1]);
            f[j - 1] += t;
            f[j] -= t;
        }
        wall
    };
    let mut f = vec![0.0; n];
    let mut wall = forces(&u, &v, &mut f);
    let mut a: Vec<f64> = f.iter().zip(m).map(|(f, m)| f / m).collect();
    let mut a_prev = a.clone();
    let mut predicted = vec![0.0; n];
    let mut impulse = 0.0;
    let mut t = 0.0;
    while t < end {
        for j in 0..n {
            u[j] += dt * v[j] + dt * dt * (4.0 * a[j] - a_prev[j]) / 6.0;
            predicted[j] = v[j] + dt * (3.0 * a[j] - a_prev[j]) / 2.0;
        }
        let wall_new = forces(&u, &predicted, &mut f);
        for j in 0..n {
            let a_new = f[j] / m[j];
            v[j] += dt * (2.0 * a_new + 5.0 * a[j] - a_prev[j]) / 6.0;
            a_prev[j] = a[j];
            a[j] = a_new;
        }
        impulse += 0.5 * dt * (wall + wall_new);
        wall = wall_new;
        t += dt;
    }
    (-vb + impulse / total) / vb
}

/// The engine's `e` with `n` masses at `dt_factor` times the paper's step,
/// to [`HORIZON`].
fn engine(rod: &Rod, n: usize, dt_factor: f64) -> f64 {
    let factor = HORIZON * rod.transit_times().iter().sum::<f64>() / rod.max_transit_time();
    let config = ChainConfig {
        masses: n,
        dt_factor,
        stop: ChainStop::Horizon { factor },
        ..ChainConfig::default()
    };
    simulate(rod, &config).unwrap().restitution
}

/// A scene under a given wall law.
type RodOf = fn(WallContact) -> Rod;

/// Both laws, on the five scenes, at `N = 200`: the engine at the
/// paper's step agrees with the explicit oracle at `dt / 200` to 3e-5; the
/// laws differ where the bottom is viscous, by the amounts the issue
/// measured (`tau c / L = 1`: `e = 0.009` under the paper's law, `0.151`
/// unilateral), and coincide where it is not. The engine runs its default,
/// implicit kernel (`src/implicit/mod.rs`); the split kernel was `1e-4` away
/// at the over-damped wall (`tau c / L = 1`, paper's law).
#[test]
fn both_laws_agree_with_an_explicit_chain() {
    const N: usize = 200;
    let scenes: [(&str, RodOf); 5] = [
        ("homogeneous tau c/L = 0.1", |l| homogeneous(0.1, l)),
        ("homogeneous tau c/L = 0.3", |l| homogeneous(0.3, l)),
        ("homogeneous tau c/L = 1", |l| homogeneous(1.0, l)),
        ("viscous bottom x = 0.5, alpha = 0.3, tau1 = 0.08", |l| {
            bilayer(0.5, 0.3, [0.08, 0.0], l)
        }),
        ("viscous top x = 0.3, alpha = 0.005, tau2 = 2", |l| {
            bilayer(0.3, 0.005, [0.0, 2.0], l)
        }),
    ];
    // the ten oracle runs are independent: two threads
    type Job = (&'static str, RodOf, WallContact);
    fn run(part: &[Job]) -> Vec<(&'static str, WallContact, f64, f64)> {
        part.iter()
            .map(|&(name, rod, law)| {
                let rod = rod(law);
                let oracle = explicit_chain(&rod, N, law, 200.0);
                (name, law, engine(&rod, N, 1.0), oracle)
            })
            .collect()
    }
    let jobs: Vec<Job> = scenes
        .iter()
        .flat_map(|&(name, rod)| WallContact::ALL.map(|law| (name, rod, law)))
        .collect();
    let (first, second) = jobs.split_at(jobs.len() / 2);
    let results = std::thread::scope(|scope| {
        let other = scope.spawn(|| run(second));
        let mut all = run(first);
        all.extend(other.join().unwrap());
        all
    });
    for pair in results.chunks(2) {
        let name = pair[0].0;
        for &(_, law, e, oracle) in pair {
            eprintln!("{name}, {law}: engine {e:.6}, explicit oracle {oracle:.6}");
            assert!(
                (e - oracle).abs() < 3e-5,
                "{name}, {law}: engine {e} vs explicit {oracle}"
            );
        }
        let gap = (pair[0].2 - pair[1].2).abs();
        if name.starts_with("viscous top") {
            assert!(
                gap < 1e-12,
                "{name}: an elastic bottom, yet the laws differ by {gap}"
            );
        } else {
            assert!(
                gap > 5e-3,
                "{name}: a viscous bottom, yet the laws agree ({gap})"
            );
        }
    }
}

/// An elastic rod has no dashpot: the two laws are one model, bit for bit.
#[test]
fn elastic_rods_do_not_depend_on_the_law() {
    for (x, alpha) in [(0.4, 0.05), (0.7, 0.3), (0.995, 0.005)] {
        let scene = Bilayer::new(x, alpha).unwrap().scene();
        let e: Vec<f64> = WallContact::ALL
            .iter()
            .map(|&law| engine(&with_law(scene.clone(), law), 400, 1.0))
            .collect();
        assert_eq!(e[0], e[1], "x = {x}, alpha = {alpha}");
    }
}

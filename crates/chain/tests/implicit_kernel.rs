//! The implicit kernel (`crates/chain/src/implicit/mod.rs`) against the method
//! written out here the long way: the two SDIRK2 stages with their stage
//! positions and all four force evaluations (`K u`, `K U1`, `D V1` and
//! `K (u + (1 - g) h V1)`, where the kernel folds three into one stencil),
//! each stage's tridiagonal system built afresh and solved by the Thomas
//! algorithm (the kernel: kept factors, blocked sweeps for long chains), the
//! step redone in two parts where `u_0` crosses zero and, under the
//! unilateral law, redone without the wall when its impulse would pull.
//! Only the layout (`ChainLayout`) is shared.
//!
//! And which kernel the engine runs: the implicit one unless told.

mod common;

use common::{gap, homogeneous_under, viscous_bilayer};
use impact_chain::{ChainConfig, ChainEngine, ChainLayout, ChainStop, ViscousKernel};
use impact_model::{Rod, WallContact};

/// SDIRK2's `g = 1 - 1/sqrt(2)`.
const G: f64 = 1.0 - std::f64::consts::FRAC_1_SQRT_2;

/// The written-out chain.
struct Plain {
    u: Vec<f64>,
    v: Vec<f64>,
    m: Vec<f64>,
    k: Vec<f64>,
    c: Vec<f64>,
    unilateral: bool,
    wall_on: bool,
    impulse: f64,
}

impl Plain {
    fn new(rod: &Rod, n: usize, law: WallContact) -> Self {
        let layout = ChainLayout::new(rod, n).unwrap();
        Self {
            u: vec![0.0; n],
            v: vec![-rod.impact_speed(); n],
            m: layout.mass.clone(),
            k: layout.stiffness.clone(),
            c: layout.viscosity.clone(),
            unilateral: law == WallContact::Unilateral,
            wall_on: true,
            impulse: 0.0,
        }
    }

    /// Forces of elements of constants `s` (the wall's only if `wall`) on
    /// each mass, from `x`.
    fn forces(&self, s: &[f64], wall: bool, x: &[f64]) -> Vec<f64> {
        let n = x.len();
        let mut f = vec![0.0; n];
        if wall {
            f[0] -= s[0] * x[0];
        }
        for j in 1..n {
            let t = s[j] * (x[j] - x[j - 1]);
            f[j - 1] += t;
            f[j] -= t;
        }
        f
    }

    /// Solves `(M - g h D - g^2 h^2 K) x = r`.
    fn solve(&self, h: f64, wall: bool, r: &[f64]) -> Vec<f64> {
        let n = r.len();
        let q: Vec<f64> = (0..=n)
            .map(|j| {
                if j == n || (j == 0 && !wall) {
                    0.0
                } else {
                    G * h * self.c[j] + G * G * h * h * self.k[j]
                }
            })
            .collect();
        let diag: Vec<f64> = (0..n).map(|i| self.m[i] + q[i] + q[i + 1]).collect();
        // Thomas, off-diagonal -q[i + 1] joining i and i + 1
        let (mut cp, mut x) = (vec![0.0; n], vec![0.0; n]);
        let mut pivot = diag[0];
        x[0] = r[0] / pivot;
        for i in 1..n {
            cp[i - 1] = -q[i] / pivot;
            pivot = diag[i] + q[i] * cp[i - 1];
            x[i] = (r[i] + q[i] * x[i - 1]) / pivot;
        }
        for i in (0..n - 1).rev() {
            x[i] -= cp[i] * x[i + 1];
        }
        x
    }

    /// One SDIRK2 step of `h`; returns the wall's impulse.
    fn sdirk(&mut self, h: f64, wall: bool) -> f64 {
        let n = self.u.len();
        let ku = self.forces(&self.k, wall, &self.u);
        let r1: Vec<f64> = (0..n)
            .map(|j| self.m[j] * self.v[j] + G * h * ku[j])
            .collect();
        let v1 = self.solve(h, wall, &r1);
        let u1: Vec<f64> = (0..n).map(|j| self.u[j] + G * h * v1[j]).collect();
        let ku1 = self.forces(&self.k, wall, &u1);
        let dv1 = self.forces(&self.c, wall, &v1);
        let partial: Vec<f64> = (0..n).map(|j| self.u[j] + (1.0 - G) * h * v1[j]).collect();
        let k_partial = self.forces(&self.k, wall, &partial);
        let r2: Vec<f64> = (0..n)
            .map(|j| {
                self.m[j] * self.v[j] + (1.0 - G) * h * (ku1[j] + dv1[j]) + G * h * k_partial[j]
            })
            .collect();
        let v2 = self.solve(h, wall, &r2);
        let u2: Vec<f64> = (0..n).map(|j| partial[j] + G * h * v2[j]).collect();
        let wall_force = |u: &[f64], v: &[f64]| {
            if wall {
                -(self.k[0] * u[0] + self.c[0] * v[0])
            } else {
                0.0
            }
        };
        let impulse = h * ((1.0 - G) * wall_force(&u1, &v1) + G * wall_force(&u2, &v2));
        self.u = u2;
        self.v = v2;
        impulse
    }

    /// A step of `h` under the wall law.
    fn wall_step(&mut self, h: f64) -> f64 {
        let (u, v) = (self.u.clone(), self.v.clone());
        let impulse = self.sdirk(h, self.wall_on);
        if self.unilateral && self.wall_on && impulse < 0.0 {
            (self.u, self.v) = (u, v);
            self.sdirk(h, false);
            return 0.0;
        }
        impulse
    }

    /// A step of `dt`, split where `u_0` crosses zero.
    fn step(&mut self, dt: f64) {
        let (u, v) = (self.u.clone(), self.v.clone());
        let impulse = self.wall_step(dt);
        if (self.u[0] < 0.0) == self.wall_on {
            self.impulse += impulse;
            return;
        }
        let theta = (u[0] / (u[0] - self.u[0])).clamp(0.0, 1.0);
        (self.u, self.v) = (u, v);
        if theta > 0.0 {
            self.impulse += self.wall_step(theta * dt);
        }
        self.wall_on = !self.wall_on;
        if theta < 1.0 {
            self.impulse += self.wall_step((1.0 - theta) * dt);
        }
    }
}

fn cases(law: WallContact) -> Vec<(&'static str, Rod)> {
    vec![
        ("homogeneous, tau c / L = 1", homogeneous_under(1.0, law)),
        (
            "viscous bottom (x 0.5, alpha 0.3, tau1 0.08)",
            viscous_bilayer(0.5, 0.3, [0.08, 0.0], law),
        ),
        (
            "viscous top (x 0.3, alpha 0.005, tau2 2)",
            viscous_bilayer(0.3, 0.005, [0.0, 2.0], law),
        ),
    ]
}

fn implicit(masses: usize, stop: ChainStop) -> ChainConfig {
    ChainConfig {
        masses,
        stop,
        viscous_kernel: ViscousKernel::Implicit,
        ..ChainConfig::default()
    }
}

/// The engine's and the written-out chain's positions and velocities after
/// `steps` steps of `masses` masses: their largest gaps, relative.
fn state_gaps(rod: &Rod, law: WallContact, masses: usize, steps: usize) -> (f64, f64) {
    let mut engine = ChainEngine::new(rod, implicit(masses, ChainStop::Escape)).unwrap();
    let mut plain = Plain::new(rod, masses, law);
    let dt = engine.time_step();
    for _ in 0..steps {
        engine.step().unwrap();
        plain.step(dt);
    }
    let (u, v) = engine.state();
    (gap(&u, &plain.u), gap(&v, &plain.v))
}

/// A whole run of `masses` masses to `stop`: the engine's `e` and the
/// written-out chain's over as many steps, and their numbers of contacts.
fn whole_run(rod: &Rod, law: WallContact, masses: usize, stop: ChainStop) -> [(f64, usize); 2] {
    let o = ChainEngine::new(rod, implicit(masses, stop))
        .unwrap()
        .run()
        .unwrap();
    let mut plain = Plain::new(rod, masses, law);
    let dt = ChainLayout::new(rod, masses).unwrap().paper_time_step();
    let mut contacts = 1;
    let mut was = true;
    for _ in 0..o.steps.unwrap() {
        plain.step(dt);
        if plain.wall_on && !was {
            contacts += 1;
        }
        was = plain.wall_on;
    }
    let total: f64 = plain.m.iter().sum();
    let vb = rod.impact_speed();
    let e = (-vb + plain.impulse / total) / vb;
    [(o.restitution, o.contacts.len()), (e, contacts)]
}

/// 300 masses: the kernel's solves run in the blocked sweeps (the plain
/// ones in one piece). Both laws, through the contact's start, the
/// unilateral wall's release and the rods' leaving.
#[test]
fn positions_and_velocities_are_the_written_out_methods() {
    for law in WallContact::ALL {
        for (label, rod) in cases(law) {
            let (du, dv) = state_gaps(&rod, law, 300, 4_000);
            println!("{label}, {law}: positions {du:.1e}, velocities {dv:.1e}");
            assert!(du <= 1e-12, "{label}, {law}: positions {du:.1e} apart");
            assert!(dv <= 1e-11, "{label}, {law}: velocities {dv:.1e} apart");
        }
    }
}

/// Whole runs at 120 masses to the paper's horizon: the same `e` (from the
/// wall's impulse) and the same contacts.
#[test]
fn e_and_contacts_are_the_written_out_methods() {
    for law in WallContact::ALL {
        for (label, rod) in cases(law) {
            let [(e, contacts), (plain_e, plain_contacts)] =
                whole_run(&rod, law, 120, ChainStop::PAPER);
            println!("{label}, {law}: e = {e} vs {plain_e}");
            assert!(
                (e - plain_e).abs() <= 1e-12,
                "{label}, {law}: e {e} vs {plain_e}"
            );
            assert_eq!(contacts, plain_contacts, "{label}, {law}");
        }
    }
}

/// Chains long enough for the two-pass kernel (`src/implicit/fused.rs`:
/// blocks of 600 masses swept side by side, the first stage solved up then
/// down and the second down then up), 3000 steps into the contact.
#[test]
fn long_chains_step_as_the_written_out_method() {
    for law in WallContact::ALL {
        for (label, rod) in cases(law).into_iter().skip(1) {
            let (du, dv) = state_gaps(&rod, law, 4800, 3_000);
            println!("{label}, {law}, 4800 masses: positions {du:.1e}, velocities {dv:.1e}");
            assert!(du <= 1e-12, "{label}, {law}: positions {du:.1e} apart");
            assert!(dv <= 1e-11, "{label}, {law}: velocities {dv:.1e} apart");
        }
    }
}

/// A whole contact and the rod's leaving at 1200 masses, where the
/// two-pass kernel takes the steps and the stage-by-stage kernel the wall's
/// switches: the same `e` and contacts as the written-out method.
#[test]
fn whole_runs_of_long_chains_give_the_written_out_e() {
    for law in WallContact::ALL {
        let rod = homogeneous_under(0.01, law);
        let [(e, contacts), (plain_e, plain_contacts)] =
            whole_run(&rod, law, 1200, ChainStop::Escape);
        println!("tau c / L = 0.01, {law}: e = {e} vs {plain_e}");
        assert!((e - plain_e).abs() <= 1e-12, "{law}: e {e} vs {plain_e}");
        assert_eq!(contacts, plain_contacts, "{law}");
    }
}

/// The engine's choice: the implicit kernel for any viscous chain unless
/// the split one is asked for by name; an elastic chain runs neither.
#[test]
fn viscous_chains_run_the_implicit_kernel_unless_told() {
    let chosen = |rod: &Rod, kernel: Option<ViscousKernel>| {
        let mut config = ChainConfig {
            masses: 200,
            ..ChainConfig::default()
        };
        if let Some(kernel) = kernel {
            config.viscous_kernel = kernel;
        }
        ChainEngine::new(rod, config).unwrap().viscous_kernel()
    };
    let (split, implicit) = (Some(ViscousKernel::Split), Some(ViscousKernel::Implicit));
    for law in WallContact::ALL {
        for (label, rod) in cases(law) {
            assert_eq!(chosen(&rod, None), implicit, "{label}");
            assert_eq!(chosen(&rod, split), split, "{label}");
        }
    }
    let elastic = common::bilayer(0.4, 0.05);
    assert_eq!(chosen(&elastic, None), None);
    assert_eq!(chosen(&elastic, split), None);
}

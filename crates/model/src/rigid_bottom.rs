//! Appendix C: the limit `alpha -> 0`, where the stiff bottom `P1` is a rigid
//! body and the soft top `P2` acts on it like a dashpot until the first wave
//! through `P2` returns (`t < t1 + 2 t2 ~ 2 t2`).
//!
//! Between wall contacts (Eq. C1) `dv1/dt + v1/tau = -v_b/tau` with
//! `tau = L1 / c2`, so after leaving the wall at `t_i` with speed `v_i`
//! (Eq. C2) `y1(t) - L1/2 = tau (v_b + v_i)(1 - e^{-s/tau}) - v_b s`,
//! `s = t - t_i`. Each landing reverses `v1` instantly. `P2` (Eq. C3) gets
//! `v2(t) = -v_b + (y1(t) - y1(0))/t2 + v_b t / t2`, and
//! `e = (1 - x) v1(t_c)/v_b + x v2(t_c)/v_b` at `t_c = 2 t2`.
//!
//! With the canonical scene `t2 / tau = x / (1 - x)` whatever `alpha`: the
//! model's `e` depends on `x` alone.

/// One contact of the rigid part with the wall: leaves at `time` with
/// upward speed `speed`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bounce {
    /// Time the rigid part leaves the wall, in units of `tau`.
    pub time: f64,
    /// Its upward speed then, in units of `v_b`.
    pub speed: f64,
}

/// The recursion's result, in units of `tau` (time) and `v_b` (speed).
#[derive(Debug, Clone, PartialEq)]
pub struct RigidBottom {
    /// Composition `x = L2 / L` the recursion ran for.
    pub x: f64,
    /// `t2 / tau = x / (1 - x)`: the model stops at `t_c = 2 t2`.
    pub takeoff_time: f64,
    /// Every bounce before `t_c`, from the impact (`t = 0`, speed 1).
    pub bounces: Vec<Bounce>,
    /// Time from which the rigid part rests on the wall (bounces too small
    /// to follow, under `1e-12 v_b`), if before `t_c`.
    pub rests_from: Option<f64>,
    /// `v1(t_c)`: the rigid part's velocity at takeoff, in units of `v_b`.
    pub v1: f64,
    /// `v2(t_c)`: the elastic top's mean velocity at takeoff (Eq. C3), in units of `v_b`.
    pub v2: f64,
    /// `e = (1 - x) v1(t_c) + x v2(t_c)`: the centre of mass's final speed over `v_b`.
    pub restitution: f64,
}

/// Height of the rigid part's centre above its contact position, `s` after
/// leaving with speed `v` (units of `tau` and `v_b`).
pub fn height(v: f64, s: f64) -> f64 {
    (1.0 + v) * (1.0 - (-s).exp()) - s
}

/// Its velocity then.
pub fn velocity(v: f64, s: f64) -> f64 {
    (1.0 + v) * (-s).exp() - 1.0
}

/// The landing time `s > 0` of a flight that starts with speed `v > 0`
/// (Newton from above, bracketed: `height > 0` just after leaving, and
/// `height(s) < 0` for `s >= 1 + v`).
fn landing(v: f64) -> f64 {
    // bisection to a good bracket, then Newton
    let mut s = crate::numerics::bisect_to(0.0, 1.0 + v, 60, 1e-6, |s| height(v, s) > 0.0);
    for _ in 0..30 {
        let step = height(v, s) / velocity(v, s);
        s -= step;
        if step.abs() < 1e-15 * s {
            break;
        }
    }
    s
}

/// Runs the recursion for composition `x` in `(0, 1)`.
pub fn rigid_bottom(x: f64) -> RigidBottom {
    let end = 2.0 * x / (1.0 - x);
    let mut bounces = vec![Bounce {
        time: 0.0,
        speed: 1.0,
    }];
    let mut rests_from = None;
    let (mut t, mut v) = (0.0, 1.0);
    // position and velocity at t_c
    let (y_end, v1_end) = loop {
        if v < 1e-12 {
            rests_from = Some(t);
            break (0.0, 0.0);
        }
        let s = landing(v);
        if t + s >= end {
            break (height(v, end - t), velocity(v, end - t));
        }
        t += s;
        v = -velocity(v, s);
        bounces.push(Bounce { time: t, speed: v });
    };
    // Eq. C3 with y1 measured from its start: v2 = -1 + (y1 - y1(0))/t2 + t/t2
    let t2 = x / (1.0 - x);
    let v2 = -1.0 + y_end / t2 + end / t2;
    RigidBottom {
        x,
        takeoff_time: end,
        bounces,
        rests_from,
        v1: v1_end,
        v2,
        restitution: (1.0 - x) * v1_end + x * v2,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_lone_bounce_gives_one_minus_two_x() {
        // small x: t_c = 2 t2 comes before the first landing; the rigid part
        // still moves up at ~v_b... e -> 1 - 2x as x -> 0 (Eq. 15)
        for x in [0.01, 0.02] {
            let r = rigid_bottom(x);
            assert_eq!(r.bounces.len(), 1);
            assert!(
                (r.restitution - (1.0 - 2.0 * x)).abs() < 0.02,
                "{x}: {}",
                r.restitution
            );
        }
    }

    #[test]
    fn large_x_tends_to_e_equals_x() {
        // the rigid part is damped to rest: e -> x (Sec. VI C)
        for x in [0.8, 0.9, 0.95] {
            let r = rigid_bottom(x);
            assert!((r.restitution - x).abs() < 0.01, "{x}: {}", r.restitution);
            assert!(r.bounces.len() > 3);
        }
    }

    #[test]
    fn landings_reverse_the_velocity_and_return_to_the_wall() {
        let r = rigid_bottom(0.6);
        for w in r.bounces.windows(2) {
            let s = w[1].time - w[0].time;
            assert!(height(w[0].speed, s).abs() < 1e-12);
            assert!((velocity(w[0].speed, s) + w[1].speed).abs() < 1e-12);
            assert!(w[1].speed < w[0].speed, "bounces decay");
        }
    }
}

//! The elastic stack above the rigid mass: lanes of waveform segments.
//!
//! Velocity components, `alpha` going up and `beta` going down, make the
//! velocity `alpha + beta` and the force `Z (beta - alpha)`. A lane carries
//! one component of one layer as the function of the time it was emitted at
//! the lane's start, in [`ExpPoly`] pieces; it arrives unchanged at the far
//! end one transit later. Boundaries combine what arrives into what they
//! emit: interfaces by continuity of velocity and force, the free top by
//! `beta = alpha` (its lane is folded: a wave going up comes back down two
//! transits later), the mass by `alpha = V - beta`.

use crate::exppoly::ExpPoly;
use std::collections::VecDeque;

/// One piece of a lane's waveform: emitted from `start` on, `f(t - start)`.
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    pub start: f64,
    pub f: ExpPoly,
}

/// One component of one layer, oldest piece first: the front piece is the
/// one arriving at the far end now.
#[derive(Debug, Clone)]
pub struct Lane {
    /// Time from emission to arrival (two transits for the folded top).
    pub delay: f64,
    pub segments: VecDeque<Segment>,
}

impl Lane {
    /// A lane that has carried the constant `value` forever.
    pub fn steady(delay: f64, value: f64) -> Self {
        let mut segments = VecDeque::new();
        segments.push_back(Segment {
            start: -2.0 * delay - 1.0,
            f: ExpPoly::constant(value),
        });
        Self { delay, segments }
    }

    /// Starts emitting `f` (a function of the time since `t`) at `t`.
    pub fn emit(&mut self, t: f64, f: ExpPoly) {
        match self.segments.back_mut() {
            Some(last) if last.start >= t => last.f = f,
            _ => self.segments.push_back(Segment { start: t, f }),
        }
    }

    /// When the next piece starts arriving, if one is queued.
    pub fn next_arrival(&self) -> Option<f64> {
        self.segments.get(1).map(|s| s.start + self.delay)
    }

    /// Moves to the next piece if it has arrived by `t`; true if it did.
    pub fn advance(&mut self, t: f64) -> bool {
        if self.next_arrival().is_some_and(|a| a <= t) {
            self.segments.pop_front();
            true
        } else {
            false
        }
    }

    /// What arrives from `t` on, as a function of the time since `t`.
    pub fn arriving(&self, t: f64, lambda: f64) -> ExpPoly {
        match self.segments.front() {
            Some(seg) => seg.f.rebased(t - self.delay - seg.start, lambda),
            None => ExpPoly::default(),
        }
    }
}

/// Interface scattering for velocity components between a lower layer of
/// impedance `zl` and an upper one of `zu`: `(beta below, alpha above)`
/// from `(alpha arriving from below, beta arriving from above)`.
pub fn scatter(zl: f64, zu: f64, alpha: &ExpPoly, beta: &ExpPoly) -> (ExpPoly, ExpPoly) {
    let sum = zl + zu;
    let down = alpha.combine((zl - zu) / sum, beta, 2.0 * zu / sum);
    let up = alpha.combine(2.0 * zl / sum, beta, (zu - zl) / sum);
    (down, up)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scattering_keeps_velocity_and_force_continuous() {
        let (zl, zu) = (3.0, 0.5);
        let a = ExpPoly::constant(0.7);
        let b = ExpPoly::constant(-0.2);
        let (down, up) = scatter(zl, zu, &a, &b);
        let (d, u) = (down.eval(0.0, 1.0), up.eval(0.0, 1.0));
        // velocity below a + d equals above u + b
        assert!((0.7 + d - (u - 0.2)).abs() < 1e-15);
        // force Z (beta - alpha) on both sides
        assert!((zl * (d - 0.7) - zu * (-0.2 - u)).abs() < 1e-15);
        // uniform motion passes unchanged
        let c = ExpPoly::constant(-0.5);
        let (down, up) = scatter(zl, zu, &c, &c);
        assert!(
            (down.eval(0.0, 1.0) + 0.5).abs() < 1e-15 && (up.eval(0.0, 1.0) + 0.5).abs() < 1e-15
        );
    }

    #[test]
    fn lanes_deliver_what_they_were_given_one_delay_later() {
        let mut lane = Lane::steady(2.0, -0.5);
        lane.emit(
            1.0,
            ExpPoly {
                p: vec![1.0, 1.0],
                q: vec![],
            },
        );
        assert_eq!(lane.next_arrival(), Some(3.0));
        assert!(!lane.advance(2.9));
        assert!((lane.arriving(2.5, 1.0).eval(0.0, 1.0) + 0.5).abs() < 1e-15);
        assert!(lane.advance(3.0));
        // emitted at 1.5: 1 + 0.5
        assert!((lane.arriving(3.5, 1.0).eval(0.0, 1.0) - 1.5).abs() < 1e-15);
    }
}

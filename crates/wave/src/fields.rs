//! The fields of the rod, rebuilt exactly from the fronts.
//!
//! In layer `i` the strain is `a + b` and the velocity `c (b - a)`, with `a`
//! the up-going and `b` the down-going component (`u = F(y - ct) + G(y + ct)`,
//! `a = F'`, `b = G'`). Each component is piecewise constant: `a` equals
//! `up_base[i]` at the layer's bottom and drops by `d` across every up front
//! (value behind minus ahead); likewise `b` from the top. Energy density is
//! `E (a^2 + b^2)` (the cross terms cancel because `rho c^2 = E`), momentum
//! density `rho c (b - a)`.
//!
//! A folded top lane holds up-going fronts and, once they have passed the
//! top, their reflections (`-d`, going down); both are rebuilt from it.

use crate::engine::Tracer;
use crate::lane::{Direction, Lane};
use crate::real::Real;

/// Strain and velocity at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FieldSample {
    /// Strain `du/dy` (negative in compression).
    pub strain: f64,
    /// Velocity (positive upward).
    pub velocity: f64,
}

/// Integrals of the fields over the whole rod.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FieldTotals {
    /// Kinetic plus elastic energy.
    pub energy: f64,
    /// Momentum (unit cross-section, positive upward).
    pub momentum: f64,
}

/// Field integrals in internal units, for the escape check.
pub(crate) struct FieldState<R> {
    pub energy: R,
    pub momentum: R,
    /// `(1/M) integral(m(s) eps(s) ds)`: how far the centre of mass sits
    /// above the bottom's displacement.
    pub bottom_below_centre: R,
}

/// One component of one layer: its value at the lane's start and the
/// fronts met going away from it, as `(distance from the start, jump)`,
/// nearest first.
struct Profile<R> {
    start: R,
    steps: Vec<(R, R)>,
}

impl<R: Real> Profile<R> {
    /// `(from, to, value)` segments over `[0, length]`.
    fn segments(&self, length: R) -> Vec<(R, R, R)> {
        let mut out = Vec::with_capacity(self.steps.len() + 1);
        let mut from = R::zero();
        let mut value = self.start;
        for &(at, jump) in &self.steps {
            let at = at.min(length);
            out.push((from, at, value));
            from = at;
            value -= jump;
        }
        out.push((from, length, value));
        out
    }

    /// The value at distance `s` from the start (a front exactly at `s` is
    /// not yet crossed).
    fn at(&self, s: R) -> R {
        let mut value = self.start;
        for &(at, jump) in &self.steps {
            if at < s {
                value -= jump;
            } else {
                break;
            }
        }
        value
    }
}

impl<R: Real> Tracer<R> {
    /// The up (`a`, from the layer's bottom) and down (`b`, from its top)
    /// profiles of layer `i` now.
    fn profiles(&self, i: usize) -> (Profile<R>, Profile<R>) {
        let c = self.layers[i].wave_speed;
        let now = self.now;
        let up = &self.lanes[Lane::<R>::index(i, Direction::Up)];
        let mut a = Profile {
            start: self.up_base[i],
            steps: Vec::new(),
        };
        let mut b = Profile {
            start: self.down_base[i],
            steps: Vec::new(),
        };
        if up.folded {
            // fronts past the top are reflections going down
            let mut reflected: Vec<(R, R)> = Vec::new();
            for f in up.fronts() {
                let age = now - f.born;
                if age >= up.transit {
                    reflected.push((c * (age - up.transit), -f.jump));
                    // the engine moves the top's base only when they return
                    b.start -= f.jump;
                } else {
                    a.steps.push((c * age, f.jump));
                }
            }
            // the newest fronts are nearest the lane's start
            a.steps.reverse();
            reflected.reverse();
            // the value at the top is that behind all reflections: undo them
            // from the nearest to the top outward
            b.steps = reflected;
        } else {
            // the newest fronts are nearest the lane's start
            for f in up.fronts() {
                a.steps.push((c * (now - f.born), f.jump));
            }
            a.steps.reverse();
            let down = &self.lanes[Lane::<R>::index(i, Direction::Down)];
            for f in down.fronts() {
                b.steps.push((c * (now - f.born), f.jump));
            }
            b.steps.reverse();
        }
        (a, b)
    }

    /// Energy, momentum and the centre of mass's offset above the bottom, in
    /// internal units.
    pub(crate) fn field_state(&self) -> FieldState<R> {
        let mut energy = R::zero();
        let mut momentum = R::zero();
        let mut moment = R::zero();
        let mut above = R::zero();
        let half = R::of(0.5);
        for i in (0..self.layers.len()).rev() {
            let l = self.layers[i];
            let rho = l.impedance / l.wave_speed;
            let (a, b) = self.profiles(i);
            // a is measured from the bottom, b from the top
            for (from, to, v) in a.segments(l.length) {
                energy += l.modulus * v * v * (to - from);
                momentum -= l.impedance * v * (to - from);
                // integral of m(s) over [bottom + from, bottom + to]
                let m = |s: R| above * s + rho * (l.length * s - half * s * s);
                moment += v * (m(to) - m(from));
            }
            for (from, to, v) in b.segments(l.length) {
                energy += l.modulus * v * v * (to - from);
                momentum += l.impedance * v * (to - from);
                // distances from the top: s from the bottom is length - d
                let m = |d: R| above * d + half * rho * d * d;
                moment += v * (m(to) - m(from));
            }
            above += rho * l.length;
        }
        FieldState {
            energy,
            momentum,
            bottom_below_centre: moment / self.mass,
        }
    }

    /// Energy and momentum of the rod now, from the fronts, in the scene's
    /// units. A merged run's blocks of fast layers (`WaveConfig::fast_blocks`)
    /// hold their fronts inside their response, which these totals leave
    /// out ([`Tracer::answered_blocks`] says which).
    pub fn field_totals(&self) -> FieldTotals {
        let s = self.field_state();
        let u = &self.units;
        FieldTotals {
            energy: s.energy.to_f64() * u.mass * u.amplitude * u.amplitude,
            momentum: s.momentum.to_f64() * u.mass * u.amplitude,
        }
    }

    /// Strain and velocity at height `y` (scene units) of the undeformed rod,
    /// now. A front sitting exactly at `y` is not counted: the sample is taken
    /// on the side the front came from, so at a layer's end it is the state
    /// after the event that just happened there. After a leap
    /// ([`crate::StepKind::Leap`]) the leapt layer's fronts already stand
    /// where the leap ends, later than now: sample a run event by event
    /// (`leap_quiet_layers` off, or fronts recorded) for the field at every
    /// event.
    pub fn field_at(&self, y: f64) -> FieldSample {
        let y = R::of(y / self.units.length);
        let last = self.layers.len() - 1;
        let i = self.layers.iter().position(|l| y < l.top).unwrap_or(last);
        let l = self.layers[i];
        let (up, down) = self.profiles(i);
        let a = up.at(y - l.bottom);
        let b = down.at(l.top - y);
        let u = &self.units;
        FieldSample {
            strain: (a + b).to_f64() * u.strain(),
            velocity: (l.wave_speed * (b - a)).to_f64() * u.amplitude,
        }
    }
}

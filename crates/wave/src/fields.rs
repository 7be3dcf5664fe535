//! The fields of the rod, rebuilt exactly from the fronts.
//!
//! In layer `i` the strain is `a + b` and the velocity `c (b - a)`, with `a`
//! the up-going and `b` the down-going component (`u = F(y - ct) + G(y + ct)`,
//! `a = F'`, `b = G'`). Each component is piecewise constant: `a` equals
//! `up_base[i]` at the layer's bottom and drops by `d` across every up front
//! (value behind minus ahead); likewise `b` from the top. Energy density is
//! `E (a^2 + b^2)` (the cross terms cancel because `rho c^2 = E`), momentum
//! density `rho c (b - a)`.

use crate::engine::WaveEngine;
use crate::lane::{Direction, Lane};

/// Strain and velocity at one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FieldSample {
    pub strain: f64,
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

impl WaveEngine {
    /// Piecewise-constant profile of one component of layer `layer` at the
    /// current time: `(distance from the lane's start, value)` breakpoints,
    /// starting at 0 with the base value; each front moves the value on.
    fn component(&self, layer: usize, dir: Direction) -> (f64, Vec<(f64, f64)>) {
        let lane = &self.lanes[Lane::index(layer, dir)];
        let c = self.layers[layer].wave_speed;
        let mut value = match dir {
            Direction::Up => self.up_base[layer],
            Direction::Down => self.down_base[layer],
        };
        let mut steps = Vec::with_capacity(lane.fronts.len() + 1);
        steps.push((0.0, value));
        // newest fronts are nearest the lane's start
        for f in lane.fronts.iter().rev() {
            value -= f.jump;
            steps.push((c * (self.time() - f.born), value));
        }
        (self.layers[layer].length, steps)
    }

    /// Integral of `g(value)` over a component profile.
    fn integrate(length: f64, steps: &[(f64, f64)], g: impl Fn(f64) -> f64) -> f64 {
        let mut sum = 0.0;
        for (k, &(from, value)) in steps.iter().enumerate() {
            let to = steps.get(k + 1).map_or(length, |s| s.0).min(length);
            sum += g(value) * (to - from.min(length)).max(0.0);
        }
        sum
    }

    /// Energy and momentum of the rod now, from the fronts.
    pub fn field_totals(&self) -> FieldTotals {
        let mut energy = 0.0;
        let mut momentum = 0.0;
        for (i, l) in self.layers.iter().enumerate() {
            let (len, up) = self.component(i, Direction::Up);
            let (_, down) = self.component(i, Direction::Down);
            energy += l.modulus
                * (Self::integrate(len, &up, |a| a * a) + Self::integrate(len, &down, |b| b * b));
            momentum += l.impedance
                * (Self::integrate(len, &down, |b| b) - Self::integrate(len, &up, |a| a));
        }
        FieldTotals { energy, momentum }
    }

    /// Strain and velocity at height `y` of the undeformed rod, now. A front
    /// sitting exactly at `y` is not counted: the sample is taken on the side
    /// the front came from, so at a layer's end it is the state after the
    /// event that just happened there.
    pub fn field_at(&self, y: f64) -> FieldSample {
        let last = self.layers.len() - 1;
        let i = self.layers.iter().position(|l| y < l.top).unwrap_or(last);
        let l = &self.layers[i];
        // value of a component at distance `s` from its lane's start
        let value_at = |dir: Direction, s: f64| {
            let (_, steps) = self.component(i, dir);
            let mut value = steps[0].1;
            for &(from, v) in &steps[1..] {
                if from < s {
                    value = v;
                } else {
                    break;
                }
            }
            value
        };
        let a = value_at(Direction::Up, y - l.bottom);
        let b = value_at(Direction::Down, l.top - y);
        FieldSample {
            strain: a + b,
            velocity: l.wave_speed * (b - a),
        }
    }
}

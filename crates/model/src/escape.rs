//! The escape bound (DESIGN.md §2): when a free rod can provably never touch
//! the wall again. Every engine stops on it, each with its own margin for
//! what its state cannot see; the physics is here, once.
//!
//! After the last separation no force acts on the rod, so its centre of mass
//! moves away from the wall at the constant velocity `v`, while the parts
//! vibrate about it with the internal energy `E_int = E - M v^2 / 2`. How far
//! the bottom can lie below the centre of mass is bounded by Cauchy-Schwarz:
//! with `m(s)` the mass above height `s`, the bottom's offset is
//! `|integral m(s) strain(s) ds| / M <= sqrt(integral m^2/E ds)
//! sqrt(integral E strain^2 ds) / M <= D = sqrt(integral m^2/E ds)
//! sqrt(2 E_int) / M`. Once the centre of mass stands `D` above the height
//! at which the bottom would touch the wall, no part can return.

use std::ops::{Add, Div, Mul, Sub};

/// The arithmetic the bound is computed in: `f64`, or an engine's own
/// higher precision, so that a rerun in another precision differs from the
/// original only in the rounding of each operation.
pub trait Arithmetic:
    Copy
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
{
    /// From a double (exact).
    fn of(x: f64) -> Self;
    /// Square root, to this arithmetic's precision.
    fn sqrt(self) -> Self;
}

impl Arithmetic for f64 {
    #[inline(always)]
    fn of(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn sqrt(self) -> Self {
        f64::sqrt(self)
    }
}

/// `x`, or zero when `x` is negative or NaN.
fn at_least_zero<T: Arithmetic>(x: T) -> T {
    let zero = T::of(0.0);
    if x > zero { x } else { zero }
}

/// What an engine adds to `D` for what its state cannot see (dropped
/// fronts, rounding, an integrator's energy drift): the reach used is
/// `D (1 + relative) + absolute`. Each engine states its margins once, with
/// the reason.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Margin<T> {
    /// Fraction of `D` added (for an energy balance the engine knows only approximately).
    pub relative: f64,
    /// Length added to `D`, in the units of the bound (rounding that grows with the run).
    pub absolute: T,
}

impl<T: Arithmetic> Margin<T> {
    /// A relative margin alone.
    pub fn relative(relative: f64) -> Self {
        Self {
            relative,
            absolute: T::of(0.0),
        }
    }
}

/// The bound for one rod: `sqrt(integral m^2/E ds) / M`, the reach per unit
/// of `sqrt(2 E_int)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EscapeBound<T> {
    reach_per_energy: T,
}

impl<T: Arithmetic> EscapeBound<T> {
    /// From the rod's compliance moment `integral m(s)^2 / E ds` (a
    /// chain's discrete sum `sum M_j^2 / k_j` is the same moment) and its
    /// mass.
    pub fn new(compliance_moment: T, mass: T) -> Self {
        Self {
            reach_per_energy: compliance_moment.sqrt() / mass,
        }
    }

    /// `D`, widened by `margin`: how far below the centre of mass the bottom
    /// can be with this internal energy.
    pub fn reach(&self, internal_energy: T, margin: Margin<T>) -> T {
        self.reach_per_energy * (T::of(2.0) * internal_energy).sqrt() * T::of(1.0 + margin.relative)
            + margin.absolute
    }

    /// When no part can return: the centre of mass, which at `now` stands
    /// `rise` above the height at which the bottom would touch the wall and
    /// moves away at `velocity`, reaches `reach`. `now` itself when it is
    /// already there; `None` while the centre of mass does not move away
    /// (then nothing is proved).
    pub fn escape_time(now: T, reach: T, rise: T, velocity: T) -> Option<T> {
        (velocity > T::of(0.0)).then(|| now + at_least_zero(reach - rise) / velocity)
    }
}

/// The energy not in the centre of mass's motion, `E - M v^2 / 2`, never
/// negative (rounding can take the difference below zero).
pub fn internal_energy<T: Arithmetic>(energy: T, mass: T, velocity: T) -> T {
    at_least_zero(energy - T::of(0.5) * mass * velocity * velocity)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A homogeneous rod (`L = rho = E = 1`, so `M = 1` and the moment is
    /// `integral (1 - s)^2 ds = 1/3`) strained as `strain(s) = -k (1 - s)`,
    /// the case where Cauchy-Schwarz is an equality: the strain energy is
    /// `k^2 / 6` and the bottom sits `integral (1 - s) k ds = k / 2 -
    /// k / 6 = k / 3` from the centre of mass. With `k = 3/2`:
    /// `E_int = 3/8` and `D = 1/2`.
    #[test]
    fn the_bound_is_reached_by_the_extremal_strain() {
        let bound = EscapeBound::new(1.0 / 3.0, 1.0);
        let d = bound.reach(0.375, Margin::relative(0.0));
        assert!((d - 0.5).abs() < 1e-15, "{d}");
        // the margins widen it as stated
        let wide = bound.reach(
            0.375,
            Margin {
                relative: 0.05,
                absolute: 0.01,
            },
        );
        assert!((wide - (0.525 + 0.01)).abs() < 1e-15, "{wide}");
    }

    #[test]
    fn escape_time_is_when_the_centre_of_mass_has_risen_by_the_reach() {
        // at t = 2 the centre of mass is 0.1 up, rising at 0.2: it needs 0.4
        // more to reach 0.5, two time units
        let t = EscapeBound::escape_time(2.0, 0.5, 0.1, 0.2).unwrap();
        assert!((t - 4.0).abs() < 1e-15, "{t}");
        assert_eq!(EscapeBound::escape_time(2.0, 0.5, 0.7, 0.2), Some(2.0));
        assert_eq!(EscapeBound::escape_time(2.0, 0.5, 0.1, 0.0), None);
        assert_eq!(EscapeBound::escape_time(2.0, 0.5, 0.1, -0.3), None);
    }

    #[test]
    fn internal_energy_is_what_the_centre_of_mass_does_not_carry() {
        // M = 2, E = 5, v = 1: 5 - 1 = 4
        assert_eq!(internal_energy(5.0, 2.0, 1.0), 4.0);
        // rounding below zero is zero
        assert_eq!(internal_energy(1.0, 2.0, 1.0 + 1e-15), 0.0);
    }
}

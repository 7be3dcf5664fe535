//! Scattering of strain fronts at an interface between two layers.
//!
//! A front carries a strain jump `d` (value behind minus value ahead). An
//! up-going front's velocity jump is `-c d`, a down-going front's `+c d`.
//! Continuity of velocity and force across the interface gives, for layer `i`
//! below and `j` above (DESIGN.md §2):
//!
//! - up-going `d` from `i`: reflected `(Z_j - Z_i)/(Z_i + Z_j) d` down in `i`,
//!   transmitted `2 Z_j/(Z_i + Z_j) (E_i/E_j) d` up in `j`;
//! - down-going `d` from `j`: reflected `(Z_i - Z_j)/(Z_i + Z_j) d` up in `j`,
//!   transmitted `2 Z_i/(Z_i + Z_j) (E_j/E_i) d` down in `i`.
//!
//! With equal densities these are the paper's `R12, T12, R21, T21` (Appendix B,
//! Eqs. B1-B2), see [`crate::theory`].

use crate::escape::Arithmetic;
use crate::scene::LayerProps;

/// Strain reflection and transmission coefficients of one interface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InterfaceCoefficients<T = f64> {
    /// Up-going front from below, reflected down into the lower layer.
    pub up_reflected: T,
    /// Up-going front from below, transmitted up into the upper layer.
    pub up_transmitted: T,
    /// Down-going front from above, reflected up into the upper layer.
    pub down_reflected: T,
    /// Down-going front from above, transmitted down into the lower layer.
    pub down_transmitted: T,
}

impl<T> InterfaceCoefficients<T> {
    /// The same coefficients in another number type.
    pub fn map<U>(self, f: impl Fn(T) -> U) -> InterfaceCoefficients<U> {
        InterfaceCoefficients {
            up_reflected: f(self.up_reflected),
            up_transmitted: f(self.up_transmitted),
            down_reflected: f(self.down_reflected),
            down_transmitted: f(self.down_transmitted),
        }
    }
}

impl InterfaceCoefficients {
    /// Coefficients of the interface with `lower` below and `upper` above.
    pub fn between(lower: &LayerProps, upper: &LayerProps) -> Self {
        Self::of_sides(
            (lower.impedance, lower.modulus),
            (upper.impedance, upper.modulus),
        )
    }
}

impl<T: Arithmetic> InterfaceCoefficients<T> {
    /// Coefficients of the interface between layers of `(impedance,
    /// modulus)` `lower` and `upper`, in any arithmetic (an engine running
    /// in double-double derives them in its own, from the same formulas).
    pub fn of_sides((zi, ei): (T, T), (zj, ej): (T, T)) -> Self {
        let sum = zi + zj;
        let two = T::of(2.0);
        Self {
            up_reflected: (zj - zi) / sum,
            up_transmitted: two * zj / sum * (ei / ej),
            down_reflected: (zi - zj) / sum,
            down_transmitted: two * zi / sum * (ej / ei),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Layer, Scene};
    use proptest::prelude::*;

    fn pair(e1: f64, r1: f64, e2: f64, r2: f64) -> (LayerProps, LayerProps) {
        let rod = Scene {
            impact_speed: 1.0,
            layers: vec![Layer::elastic(1.0, e1, r1), Layer::elastic(1.0, e2, r2)],
            wall_contact: None,
        }
        .validate()
        .unwrap();
        (rod.layers()[0], rod.layers()[1])
    }

    #[test]
    fn equal_impedances_do_not_reflect() {
        let (a, b) = pair(4.0, 1.0, 1.0, 4.0); // Z = 2 on both sides
        let k = InterfaceCoefficients::between(&a, &b);
        assert_eq!(k.up_reflected, 0.0);
        assert_eq!(k.down_reflected, 0.0);
        // the velocity jump passes unchanged: c_i d = c_j (T d)
        assert!((k.up_transmitted * b.wave_speed - a.wave_speed).abs() < 1e-15);
    }

    proptest! {
        /// Energy flux of a front (per unit time) is `Z (c d)^2`: reflected plus
        /// transmitted flux equals incident flux, for any two layers.
        #[test]
        fn scattering_conserves_energy(e1 in 1e-3..1e3f64, r1 in 1e-3..1e3f64,
                                       e2 in 1e-3..1e3f64, r2 in 1e-3..1e3f64) {
            let (a, b) = pair(e1, r1, e2, r2);
            let k = InterfaceCoefficients::between(&a, &b);
            let flux = |z: f64, c: f64, d: f64| z * (c * d).powi(2);
            let incident = flux(a.impedance, a.wave_speed, 1.0);
            let out = flux(a.impedance, a.wave_speed, k.up_reflected)
                + flux(b.impedance, b.wave_speed, k.up_transmitted);
            prop_assert!((out - incident).abs() <= 1e-12 * incident);
            let incident = flux(b.impedance, b.wave_speed, 1.0);
            let out = flux(b.impedance, b.wave_speed, k.down_reflected)
                + flux(a.impedance, a.wave_speed, k.down_transmitted);
            prop_assert!((out - incident).abs() <= 1e-12 * incident);
        }

        /// Force (E * strain) and velocity are continuous across the interface.
        #[test]
        fn scattering_keeps_force_and_velocity_continuous(e1 in 1e-3..1e3f64, r1 in 1e-3..1e3f64,
                                                          e2 in 1e-3..1e3f64, r2 in 1e-3..1e3f64) {
            let (a, b) = pair(e1, r1, e2, r2);
            let k = InterfaceCoefficients::between(&a, &b);
            let force_below = a.modulus * (1.0 + k.up_reflected);
            let force_above = b.modulus * k.up_transmitted;
            prop_assert!((force_below - force_above).abs() <= 1e-12 * force_below.abs().max(force_above.abs()));
            let vel_below = -a.wave_speed + a.wave_speed * k.up_reflected;
            let vel_above = -b.wave_speed * k.up_transmitted;
            prop_assert!((vel_below - vel_above).abs() <= 1e-12 * vel_below.abs().max(1e-300));
        }
    }
}

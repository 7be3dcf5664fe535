//! Internal units: every engine computes in units where the rod's length,
//! mean density, stiffness and impact speed are all of order one, so that a
//! scene written in any consistent units (lengths of `1e-120`, speeds of
//! `1e-170`, moduli of `1e300`) gives the same numbers as the unit bilayer.
//!
//! Every scale is a power of two. Dividing by a power of two is exact in
//! binary floating point (unless it under- or overflows), so a scene already
//! in units of order one (the canonical bilayer) is computed bit for bit as if
//! it were not scaled at all, and any other scene differs from its unscaled
//! computation only where that computation would have over- or underflowed.
//!
//! The problem is linear and homogeneous in the impact speed, so amplitudes
//! (velocities, strains, displacements) get their own scale, the impact
//! speed's, independent of the kinematic speed scale `length / time`.

use serde::{Deserialize, Serialize};

/// The power of two nearest to a positive finite `x` (in `log2`), as its
/// exponent.
pub fn nearest_power_of_two_exponent(x: f64) -> i32 {
    debug_assert!(x > 0.0 && x.is_finite());
    x.log2().round() as i32
}

/// `2^k` for `-1074 <= k <= 1023`, exactly.
pub fn power_of_two(k: i32) -> f64 {
    if k >= -1022 {
        f64::from_bits(((k + 1023) as u64) << 52)
    } else {
        // subnormal: 2^k = 2^-1022 * 2^(k + 1022)
        f64::from_bits(1u64 << (k + 1074))
    }
}

/// The scales (powers of two) that take a scene into internal units:
/// internal value = scene value / scale.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Units {
    /// Near the rod's total length.
    pub length: f64,
    /// Near the rod's mean density.
    pub density: f64,
    /// Near the sum of the moduli, adjusted so that `modulus / density` is an
    /// even power of two (its square root, the speed scale, is then exact).
    pub modulus: f64,
    /// Kinematic speed, `sqrt(modulus / density)`.
    pub speed: f64,
    /// Time, `length / speed`.
    pub time: f64,
    /// Mass per unit cross-section, `density * length`.
    pub mass: f64,
    /// Amplitudes: the impact speed's scale. Velocities are divided by it,
    /// strains by `amplitude / speed`, displacements by `amplitude * time`.
    pub amplitude: f64,
}

/// Exponents of the scales, before they become numbers.
struct Exponents {
    length: i32,
    density: i32,
    modulus: i32,
    amplitude: i32,
}

impl Units {
    /// Scales for layers of the given lengths, densities and moduli (all
    /// positive and finite) and impact speed. Sums and means are formed in
    /// pre-scaled arithmetic, so they never overflow.
    pub fn new(lengths: &[f64], densities: &[f64], moduli: &[f64], impact_speed: f64) -> Self {
        let max = |v: &[f64]| v.iter().copied().fold(0.0, f64::max);
        // total length: sum of lengths pre-scaled by the largest
        let l0 = nearest_power_of_two_exponent(max(lengths));
        let total: f64 = lengths.iter().map(|l| l / power_of_two(l0)).sum();
        let length = l0 + nearest_power_of_two_exponent(total);
        // mean density: sum(rho L) / sum(L), pre-scaled
        let r0 = nearest_power_of_two_exponent(max(densities));
        let (mass, len): (f64, f64) = densities
            .iter()
            .zip(lengths)
            .map(|(r, l)| {
                (
                    r / power_of_two(r0) * (l / power_of_two(length)),
                    l / power_of_two(length),
                )
            })
            .fold((0.0, 0.0), |(m, s), (a, b)| (m + a, s + b));
        let density = r0 + nearest_power_of_two_exponent(mass / len);
        // sum of moduli, pre-scaled
        let e0 = nearest_power_of_two_exponent(max(moduli));
        let sum: f64 = moduli.iter().map(|e| e / power_of_two(e0)).sum();
        let mut modulus = e0 + nearest_power_of_two_exponent(sum);
        if (modulus - density).rem_euclid(2) == 1 {
            // toward zero: a modulus near the largest double keeps a scale
            modulus += if modulus > 0 { -1 } else { 1 };
        }
        Self::from_exponents(Exponents {
            length,
            density,
            modulus,
            amplitude: nearest_power_of_two_exponent(impact_speed),
        })
    }

    fn from_exponents(k: Exponents) -> Self {
        let speed = (k.modulus - k.density) / 2;
        // a scale beyond double precision becomes infinite or zero, so that
        // every quantity in scene units that needs it fails validation
        // instead of being silently saturated
        let clamp = |e: i32| match e {
            ..-1074 => 0.0,
            1024.. => f64::INFINITY,
            _ => power_of_two(e),
        };
        Self {
            length: clamp(k.length),
            density: clamp(k.density),
            modulus: clamp(k.modulus),
            speed: clamp(speed),
            time: clamp(k.length - speed),
            mass: clamp(k.density + k.length),
            amplitude: clamp(k.amplitude),
        }
    }

    /// The scales of a scene already in units of order one.
    pub const ONE: Units = Units {
        length: 1.0,
        density: 1.0,
        modulus: 1.0,
        speed: 1.0,
        time: 1.0,
        mass: 1.0,
        amplitude: 1.0,
    };

    /// Strain scale, `amplitude / speed`.
    pub fn strain(&self) -> f64 {
        self.amplitude / self.speed
    }

    /// Displacement scale, `amplitude * time`.
    pub fn displacement(&self) -> f64 {
        self.amplitude * self.time
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn powers_of_two_are_exact() {
        for k in [-1074, -1060, -1022, -1, 0, 1, 52, 1023] {
            assert_eq!(power_of_two(k), 2f64.powi(k), "{k}");
        }
        assert_eq!(nearest_power_of_two_exponent(0.99), 0);
        assert_eq!(nearest_power_of_two_exponent(1.5), 1);
        assert_eq!(nearest_power_of_two_exponent(1e-300), -997);
    }

    #[test]
    fn the_canonical_bilayer_is_already_in_internal_units() {
        for (x, alpha) in [(0.4, 0.05), (0.995, 0.005), (0.005, 0.995), (0.7, 0.3)] {
            let u = Units::new(&[1.0 - x, x], &[1.0, 1.0], &[1.0 - alpha, alpha], 1.0);
            assert_eq!(u, Units::ONE, "{x} {alpha}");
        }
    }

    #[test]
    fn scales_follow_the_scene() {
        // SI steel/rubber: lengths ~0.1 m, densities ~1e3, moduli ~2e11
        let u = Units::new(&[0.001, 0.1], &[7850.0, 1100.0], &[200e9, 2e6], 0.5);
        let ratio = |a: f64, b: f64| (a / b).log2().abs();
        assert!(ratio(u.length, 0.101) <= 0.5);
        assert!(ratio(u.density, (7.85 + 110.0) / 0.101) <= 0.5);
        assert!(ratio(u.modulus, 200e9) <= 1.5);
        assert_eq!(u.speed * u.speed, u.modulus / u.density);
        assert_eq!(u.time, u.length / u.speed);
        assert_eq!(u.amplitude, 0.5);
        // extreme but consistent units stay representable
        let u = Units::new(&[1e-120], &[1e120], &[1e-130], 1e-170);
        assert!(u.time.is_normal() && u.speed.is_normal() && u.amplitude.is_normal());
    }
}

//! Four numbers side by side: one per block of a blocked sweep.

use std::ops::{Add, Mul, Sub};

/// Blocks whose sweeps run side by side. A sweep is a linear recurrence,
/// one multiply and one subtraction on its critical path per mass (6
/// cycles on a current core), while the core can issue the whole step of
/// a mass in about one: independent recurrences, one per block, fill that
/// gap (see `Factor`).
pub(crate) const LANES: usize = 4;

/// One number per block, element-wise arithmetic. Aligned to 32 bytes, so
/// the compiler knows a `Quad` in memory is two aligned SSE2 registers'
/// worth and folds its loads into the arithmetic (`mulpd xmm, [mem]`)
/// instead of loading it apart (`movupd`), which it must for an `[f64; 4]`
/// of unknown alignment: a load fewer per operand in the sweeps' loops.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C, align(32))]
pub(crate) struct Quad(pub(crate) [f64; LANES]);

impl Quad {
    /// Zero in every lane.
    pub(crate) const ZERO: Quad = Quad([0.0; LANES]);

    /// `x` in every lane.
    #[inline(always)]
    pub(crate) fn splat(x: f64) -> Quad {
        Quad([x; LANES])
    }

    /// The lanes moved one block down (lane `k` takes lane `k + 1`'s
    /// value), `top` entering the last: the values just above each block's
    /// first mass are the next block's first values.
    #[inline(always)]
    pub(crate) fn down(self, top: f64) -> Quad {
        let [_, a, b, c] = self.0;
        Quad([a, b, c, top])
    }

    /// The lanes moved one block up (lane `k` takes lane `k - 1`'s value),
    /// `bottom` entering the first: the values just below each block's
    /// last mass are the previous block's last values.
    #[inline(always)]
    pub(crate) fn up(self, bottom: f64) -> Quad {
        let [a, b, c, _] = self.0;
        Quad([bottom, a, b, c])
    }
}

impl Add for Quad {
    type Output = Quad;
    #[inline(always)]
    fn add(self, o: Quad) -> Quad {
        Quad(std::array::from_fn(|k| self.0[k] + o.0[k]))
    }
}

impl Sub for Quad {
    type Output = Quad;
    #[inline(always)]
    fn sub(self, o: Quad) -> Quad {
        Quad(std::array::from_fn(|k| self.0[k] - o.0[k]))
    }
}

impl Mul for Quad {
    type Output = Quad;
    #[inline(always)]
    fn mul(self, o: Quad) -> Quad {
        Quad(std::array::from_fn(|k| self.0[k] * o.0[k]))
    }
}

//! The arithmetic the tracer runs in: `f64`, or double-double (`TwoFloat`,
//! about 32 significant digits) to measure how much a long run loses to
//! rounding. One algorithm, two precisions: the rerun differs from the
//! original only in the rounding of each operation.

use impact_model::escape::Arithmetic;
use ordered_float::OrderedFloat;
use std::fmt::Debug;
use std::ops::{Add, AddAssign, Div, Mul, Neg, Sub, SubAssign};
use twofloat::TwoFloat;

/// A real number type the tracer can run in: the field operations and the
/// few functions the tracer calls, nothing more. Conversion from a double
/// (`of`) and `sqrt` come from the model's [`Arithmetic`], so the model's
/// shared formulas (the escape bound) run in the tracer's precision.
pub trait Real:
    Arithmetic
    + Copy
    + Debug
    + Default
    + PartialEq
    + PartialOrd
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + SubAssign
    + Send
    + Sync
    + 'static
{
    /// A totally ordered image of the number, for the event queue
    /// (`ordered-float` over its double parts).
    type Key: Ord + Copy + Debug;
    /// Whether a run in this arithmetic may leap quiet layers (`leap.rs`):
    /// the leaps' geometric sums go through `ln` and `exp_m1`, which
    /// `twofloat` computes to about `1e-18` only, so a double-double run
    /// that leapt would lose the digits it is run for (the hard corner's
    /// `e` moved by `2.3e-15` against the loop in double-double).
    const LEAPS: bool;
    /// Whether a block's long sums may be taken by FFT in double precision
    /// (`block/partitioned.rs`) without losing the digits the type keeps.
    const FFT_SUMS: bool;
    /// To the nearest double.
    fn to_f64(self) -> f64;
    /// The number's key: keys order as the numbers do.
    fn key(self) -> Self::Key;
    /// The number back from its key, exactly.
    fn from_key(key: Self::Key) -> Self;
    /// Name for messages.
    const NAME: &'static str;

    /// Zero.
    fn zero() -> Self {
        Self::of(0.0)
    }
    /// One.
    fn one() -> Self {
        Self::of(1.0)
    }
    /// Minus infinity: a time before every event.
    fn neg_infinity() -> Self {
        Self::of(f64::NEG_INFINITY)
    }
    /// Absolute value.
    fn abs(self) -> Self;
    /// Largest integer not above the number.
    fn floor(self) -> Self;
    /// Smallest integer not below the number.
    fn ceil(self) -> Self;
    /// Nearest integer.
    fn round(self) -> Self;
    /// Natural logarithm.
    fn ln(self) -> Self;
    /// Integer power.
    fn powi(self, n: i32) -> Self;
    /// Real power.
    fn powf(self, n: Self) -> Self;
    /// `exp(x) - 1`, accurate for small `x`.
    fn exp_m1(self) -> Self;
    /// Neither infinite nor NaN.
    fn is_finite(self) -> bool;
    /// Not a number.
    fn is_nan(self) -> bool;
    /// The larger of the two; a NaN loses to a number.
    fn max(self, other: Self) -> Self {
        if other > self || self.is_nan() {
            other
        } else {
            self
        }
    }
    /// The smaller of the two; a NaN loses to a number.
    fn min(self, other: Self) -> Self {
        if other < self || self.is_nan() {
            other
        } else {
            self
        }
    }
}

/// Above this every double is an integer (`2^52`).
const EXACT_INTEGERS: f64 = 4_503_599_627_370_496.0;

impl Real for f64 {
    const LEAPS: bool = true;
    const FFT_SUMS: bool = true;
    type Key = OrderedFloat<f64>;
    #[inline(always)]
    fn key(self) -> Self::Key {
        OrderedFloat(self)
    }
    #[inline(always)]
    fn from_key(key: Self::Key) -> Self {
        key.0
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
    const NAME: &'static str = "double";
    #[inline(always)]
    fn zero() -> Self {
        0.0
    }
    #[inline(always)]
    fn one() -> Self {
        1.0
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64::abs(self)
    }
    /// `f64::floor` compiles to a call into libm on the baseline x86-64
    /// target (no SSE4.1 `roundsd`), and a merged run's lattice cells are
    /// floors (3 to 6 % of its profile samples; inlined, 1.6 % fewer
    /// instructions on a four-layer rod, callgrind). Below `2^52` in
    /// magnitude a truncating conversion gives the same value (a zero's
    /// sign aside).
    #[inline(always)]
    fn floor(self) -> Self {
        if self.abs() < EXACT_INTEGERS {
            let t = self as i64 as f64;
            if t > self { t - 1.0 } else { t }
        } else {
            f64::floor(self)
        }
    }
    /// As [`Real::floor`].
    #[inline(always)]
    fn ceil(self) -> Self {
        if self.abs() < EXACT_INTEGERS {
            let t = self as i64 as f64;
            if t < self { t + 1.0 } else { t }
        } else {
            f64::ceil(self)
        }
    }
    #[inline(always)]
    fn round(self) -> Self {
        f64::round(self)
    }
    #[inline(always)]
    fn ln(self) -> Self {
        f64::ln(self)
    }
    #[inline(always)]
    fn powi(self, n: i32) -> Self {
        f64::powi(self, n)
    }
    #[inline(always)]
    fn powf(self, n: Self) -> Self {
        f64::powf(self, n)
    }
    #[inline(always)]
    fn exp_m1(self) -> Self {
        f64::exp_m1(self)
    }
    #[inline(always)]
    fn is_finite(self) -> bool {
        f64::is_finite(self)
    }
    #[inline(always)]
    fn is_nan(self) -> bool {
        f64::is_nan(self)
    }
    #[inline(always)]
    fn max(self, other: Self) -> Self {
        f64::max(self, other)
    }
    #[inline(always)]
    fn min(self, other: Self) -> Self {
        f64::min(self, other)
    }
}

/// Double-double numbers (about 32 significant digits): `twofloat`'s,
/// with a correct quotient. `twofloat` 0.8.4 divides by a double-double
/// with Joldes et al. (2017) Algorithm 18 but forms `1 - b_hi / b_hi`-type
/// residuals without a fused multiply-add, so its quotients (and
/// reciprocals) are only as good as a double's: `(1/3) * 3 - 1` came out
/// `-5.6e-17`. A rerun in that arithmetic would share double's error in
/// every transit time and landing time, and say nothing about it.
/// Ordered by its own [`PartialOrd`], not `twofloat`'s (see there).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct DoubleDouble(TwoFloat);

/// The order of the numbers: by the leading double, then the trailing one
/// (a normalised pair's trailing part is under half an ulp of its leading
/// one, so this is the order of their sums). `twofloat` 0.8.4 ranks any
/// pair it deems invalid, an infinite one among them, above every valid
/// one and equal to every other: `0.5 < -inf` held, and `-inf == inf`. (A
/// double-double run then never passed the `t >= -inf` that lets a layer
/// leap; it still does not, now by [`Real::LEAPS`].)
impl PartialOrd for DoubleDouble {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        match self.hi().partial_cmp(&other.hi())? {
            std::cmp::Ordering::Equal => self.lo().partial_cmp(&other.lo()),
            unequal => Some(unequal),
        }
    }
}

impl DoubleDouble {
    /// The leading double: the number rounded to double precision.
    pub fn hi(self) -> f64 {
        self.0.hi()
    }
    /// The trailing double: what the leading one misses.
    pub fn lo(self) -> f64 {
        self.0.lo()
    }
}

macro_rules! forward {
    ($($op:ident $method:ident),*) => {$(
        impl $op for DoubleDouble {
            type Output = Self;
            #[inline]
            fn $method(self, rhs: Self) -> Self {
                DoubleDouble($op::$method(self.0, rhs.0))
            }
        }
    )*};
}
forward!(Add add, Sub sub, Mul mul);

impl Div for DoubleDouble {
    type Output = Self;
    /// Long division: three double quotients, each of the remainder left
    /// by the ones before (exact products and differences in
    /// double-double), summed.
    fn div(self, rhs: Self) -> Self {
        let b = rhs.0;
        let q1 = self.0.hi() / b.hi();
        if !q1.is_finite() || q1 == 0.0 {
            return DoubleDouble(TwoFloat::from(q1));
        }
        let r = self.0 - b * q1;
        let q2 = r.hi() / b.hi();
        let r = r - b * q2;
        let q3 = r.hi() / b.hi();
        DoubleDouble(TwoFloat::new_add(q1, q2) + q3)
    }
}

impl Neg for DoubleDouble {
    type Output = Self;
    fn neg(self) -> Self {
        DoubleDouble(-self.0)
    }
}

impl AddAssign for DoubleDouble {
    fn add_assign(&mut self, rhs: Self) {
        self.0 += rhs.0;
    }
}

impl SubAssign for DoubleDouble {
    fn sub_assign(&mut self, rhs: Self) {
        self.0 -= rhs.0;
    }
}

impl Arithmetic for DoubleDouble {
    #[inline]
    fn of(x: f64) -> Self {
        DoubleDouble(TwoFloat::from(x))
    }
    fn sqrt(self) -> Self {
        DoubleDouble(self.0.sqrt())
    }
}

impl Real for DoubleDouble {
    const LEAPS: bool = false;
    const FFT_SUMS: bool = false;
    /// A normalised double-double orders as its (high, low) parts do.
    type Key = (OrderedFloat<f64>, OrderedFloat<f64>);
    fn key(self) -> Self::Key {
        (OrderedFloat(self.hi()), OrderedFloat(self.lo()))
    }
    fn from_key(key: Self::Key) -> Self {
        DoubleDouble(TwoFloat::try_from((key.0.0, key.1.0)).unwrap_or(TwoFloat::from(key.0.0)))
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self.hi() + self.lo()
    }
    const NAME: &'static str = "double-double";
    fn abs(self) -> Self {
        DoubleDouble(self.0.abs())
    }
    fn floor(self) -> Self {
        DoubleDouble(self.0.floor())
    }
    fn ceil(self) -> Self {
        DoubleDouble(self.0.ceil())
    }
    fn round(self) -> Self {
        DoubleDouble(self.0.round())
    }
    /// `twofloat`'s logarithm (about `1e-18` relative): used only to count
    /// terms of geometric series, which are then checked with products.
    fn ln(self) -> Self {
        DoubleDouble(self.0.ln())
    }
    fn powi(self, n: i32) -> Self {
        // by squaring, in the corrected arithmetic
        let (mut base, mut e, mut acc) = (self, n.unsigned_abs(), Self::one());
        while e > 0 {
            if e & 1 == 1 {
                acc = acc * base;
            }
            base = base * base;
            e >>= 1;
        }
        if n < 0 { Self::one() / acc } else { acc }
    }
    fn powf(self, n: Self) -> Self {
        DoubleDouble(self.0.powf(n.0))
    }
    /// `twofloat`'s (preliminary, about `1e-18` relative): used in the
    /// closed forms of geometric series, never in a time.
    fn exp_m1(self) -> Self {
        DoubleDouble(self.0.exp_m1())
    }
    fn is_finite(self) -> bool {
        self.0.hi().is_finite()
    }
    fn is_nan(self) -> bool {
        self.0.hi().is_nan()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_fast_floor_and_ceil_are_libms() {
        let mut values = vec![
            0.0,
            0.5,
            1.0,
            1.5,
            2.0 - 1e-16,
            1e15 + 0.5,
            4.5e15 - 0.5,
            4.6e15,
            1e300,
            f64::MIN_POSITIVE,
            1e-300,
            0.1,
            2.5,
            3.0,
            123456.789,
        ];
        // a seeded sweep over magnitudes, through the lattice's range
        let mut x = 0.123_456_789_f64;
        for _ in 0..100_000 {
            x = (x * 9_301.0 + 0.497).fract();
            values.push(x * 10f64.powi((x * 40.0) as i32 - 20));
        }
        for v in values.iter().flat_map(|&v| [v, -v]) {
            assert_eq!(<f64 as Real>::floor(v), v.floor(), "{v:e}");
            assert_eq!(<f64 as Real>::ceil(v), v.ceil(), "{v:e}");
        }
        assert!(<f64 as Real>::floor(f64::NAN).is_nan());
        assert_eq!(<f64 as Real>::floor(f64::INFINITY), f64::INFINITY);
        assert_eq!(<f64 as Real>::ceil(f64::NEG_INFINITY), f64::NEG_INFINITY);
    }

    #[test]
    fn double_double_keeps_what_double_loses() {
        type D = DoubleDouble;
        let third = D::of(1.0) / D::of(3.0);
        let back = third * D::of(3.0) - D::of(1.0);
        assert!(back.to_f64().abs() < 1e-31, "{back:?}");
        let tiny = D::of(1.0) + D::of(1e-20) - D::of(1.0);
        assert!((tiny.to_f64() - 1e-20).abs() < 1e-34);
        assert_eq!(f64::of(0.1).to_f64(), 0.1);
        // keys order as the numbers, and give them back exactly
        let a = D::of(1.0) + D::of(1e-20);
        let b = D::of(1.0) + D::of(2e-20);
        assert!(a.key() < b.key());
        assert_eq!(D::from_key(b.key()), b);
    }

    /// Double-doubles order as the numbers they stand for, infinities
    /// included (`twofloat`'s own order put `0.5` below `-inf`, and a
    /// double-double run never leapt).
    #[test]
    fn double_doubles_order_as_numbers_infinities_included() {
        type D = DoubleDouble;
        let ladder = [
            D::neg_infinity(),
            D::of(-1e300),
            D::of(-1.0),
            D::of(0.0),
            D::of(1.0),
            D::of(1.0) + D::of(1e-25),
            D::of(1.0) + D::of(2e-25),
            D::of(1.0 + f64::EPSILON),
            D::of(1e300),
            -D::neg_infinity(),
        ];
        for (i, a) in ladder.iter().enumerate() {
            for (j, b) in ladder.iter().enumerate() {
                assert_eq!(a.partial_cmp(b), i.partial_cmp(&j), "{a:?} against {b:?}");
            }
        }
        let nan = D::of(f64::NAN);
        assert_eq!(nan.partial_cmp(&D::of(1.0)), None);
    }

    /// Quotients of double-doubles against exact rational arithmetic:
    /// `p / q` for small integers is checked by multiplying back, and a
    /// quotient of two double-doubles (not doubles) by the identity
    /// `(a / b) * b = a` to 32 digits.
    #[test]
    fn quotients_have_double_double_accuracy() {
        type D = DoubleDouble;
        for p in 1..40 {
            for q in 1..40 {
                let (p, q) = (D::of(p as f64), D::of(q as f64));
                let back = (p / q) * q - p;
                assert!(
                    back.to_f64().abs() <= 4e-32 * p.to_f64(),
                    "{p:?}/{q:?}: {back:?}"
                );
            }
        }
        let a = D::of(1.0) / D::of(7.0) + D::of(1e-20);
        let b = D::of(3.0).sqrt() + D::of(1e-19);
        let back = (a / b) * b - a;
        assert!(back.to_f64().abs() <= 1e-32, "{back:?}");
        // sqrt and powers
        let s = D::of(2.0).sqrt();
        assert!((s * s - D::of(2.0)).to_f64().abs() <= 1e-31);
        let p = D::of(1.0) / D::of(3.0);
        assert!((p.powi(-3) - D::of(27.0)).to_f64().abs() <= 1e-29);
    }
}

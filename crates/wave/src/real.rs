//! The arithmetic the tracer runs in: `f64`, or double-double (`TwoFloat`,
//! about 32 significant digits) to measure how much a long run loses to
//! rounding. One algorithm, two precisions: the rerun differs from the
//! original only in the rounding of each operation.

use ordered_float::OrderedFloat;
use std::fmt::Debug;
use std::ops::{AddAssign, SubAssign};
use twofloat::TwoFloat;

/// A real number type the tracer can run in.
pub trait Real: num_traits::Float + Debug + Default + AddAssign + SubAssign + 'static {
    /// A totally ordered image of the number, for the event queue
    /// (`ordered-float` over its double parts).
    type Key: Ord + Copy + Debug;
    /// From a double (exact).
    fn of(x: f64) -> Self;
    /// To the nearest double.
    fn to_f64(self) -> f64;
    /// The number's key: keys order as the numbers do.
    fn key(self) -> Self::Key;
    /// The number back from its key, exactly.
    fn from_key(key: Self::Key) -> Self;
    /// Name for messages.
    const NAME: &'static str;
}

impl Real for f64 {
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
    fn of(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn to_f64(self) -> f64 {
        self
    }
    const NAME: &'static str = "double";
}

impl Real for TwoFloat {
    /// A normalised double-double orders as its (high, low) parts do.
    type Key = (OrderedFloat<f64>, OrderedFloat<f64>);
    fn key(self) -> Self::Key {
        (OrderedFloat(self.hi()), OrderedFloat(self.lo()))
    }
    fn from_key(key: Self::Key) -> Self {
        TwoFloat::try_from((key.0.0, key.1.0)).unwrap_or(TwoFloat::from(key.0.0))
    }
    #[inline]
    fn of(x: f64) -> Self {
        TwoFloat::from(x)
    }
    #[inline]
    fn to_f64(self) -> f64 {
        self.hi() + self.lo()
    }
    const NAME: &'static str = "double-double";
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn double_double_keeps_what_double_loses() {
        let third = TwoFloat::of(1.0) / TwoFloat::of(3.0);
        let back = third * TwoFloat::of(3.0) - TwoFloat::of(1.0);
        assert!(back.to_f64().abs() < 1e-30);
        let tiny = TwoFloat::of(1.0) + TwoFloat::of(1e-20) - TwoFloat::of(1.0);
        assert!((tiny.to_f64() - 1e-20).abs() < 1e-34);
        assert_eq!(f64::of(0.1).to_f64(), 0.1);
        // keys order as the numbers, and give them back exactly
        let a = TwoFloat::of(1.0) + TwoFloat::of(1e-20);
        let b = TwoFloat::of(1.0) + TwoFloat::of(2e-20);
        assert!(a.key() < b.key());
        assert_eq!(TwoFloat::from_key(b.key()), b);
    }
}

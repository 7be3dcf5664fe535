//! A numerical setting out of its range, in one shape for every engine and
//! study. The error names the setting by its field and says the range in
//! words; which command-line flag sets the field is the binary's business
//! (it keeps the table), so the same error reads right in a library test, a
//! journal and a terminal.

use std::fmt;
use thiserror::Error;

/// The range a numerical setting must lie in. Each variant both decides
/// ([`Allowed::admits`]) and words ([`fmt::Display`]) its range, so a check
/// and its message cannot drift apart. NaN and infinities are never admitted.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Allowed {
    /// Finite and `>= 0`.
    NonNegative,
    /// Finite and `> 0`.
    Positive,
    /// A count of at least this many.
    AtLeast(u64),
    /// In `(0, high]`.
    PositiveUpTo(f64),
    /// In `[0, high]`.
    NonNegativeUpTo(f64),
    /// In `[0, 1)`.
    UnitFraction,
}

impl Allowed {
    /// Whether `value` lies in the range.
    pub fn admits(self, value: f64) -> bool {
        value.is_finite()
            && match self {
                Allowed::NonNegative => value >= 0.0,
                Allowed::Positive => value > 0.0,
                Allowed::AtLeast(n) => value >= n as f64,
                Allowed::PositiveUpTo(high) => value > 0.0 && value <= high,
                Allowed::NonNegativeUpTo(high) => (0.0..=high).contains(&value),
                Allowed::UnitFraction => (0.0..1.0).contains(&value),
            }
    }

    /// `value` if it lies in the range, else the error naming `field`.
    pub fn check(self, field: &'static str, value: f64) -> Result<f64, SettingError> {
        if self.admits(value) {
            Ok(value)
        } else {
            Err(SettingError::new(field, self, value))
        }
    }

    /// A count checked against [`Allowed::AtLeast`] (or any range), keeping
    /// the count's own spelling in the message.
    pub fn check_count(self, field: &'static str, count: u64) -> Result<u64, SettingError> {
        if self.admits(count as f64) {
            Ok(count)
        } else {
            Err(SettingError::new(field, self, count))
        }
    }
}

impl fmt::Display for Allowed {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Allowed::NonNegative => f.write_str("a finite number >= 0"),
            Allowed::Positive => f.write_str("a finite number > 0"),
            Allowed::AtLeast(n) => write!(f, "at least {n}"),
            Allowed::PositiveUpTo(high) => write!(f, "a number in (0, {high}]"),
            Allowed::NonNegativeUpTo(high) => write!(f, "a number in [0, {high}]"),
            Allowed::UnitFraction => f.write_str("a number in [0, 1)"),
        }
    }
}

/// A numerical setting outside its range: `field` is the settings struct's
/// field (or the name the settings' documentation gives the number), never
/// a flag.
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{field} must be {allowed} (got {value})")]
pub struct SettingError {
    /// The settings struct's field (or documented name) that is out of range.
    pub field: &'static str,
    /// The range it must lie in.
    pub allowed: Allowed,
    /// The value as given, spelled as Rust displays it (`-1`, `NaN`, `0`).
    pub value: String,
}

impl SettingError {
    /// The error for `field`, whose value `value` is outside `allowed`.
    pub fn new(field: &'static str, allowed: Allowed, value: impl fmt::Display) -> Self {
        Self {
            field,
            allowed,
            value: value.to_string(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_the_field_the_range_and_the_value() {
        let cases = [
            (
                Allowed::NonNegative.check("drop_tolerance", -1.0),
                "drop_tolerance must be a finite number >= 0 (got -1)",
            ),
            (
                Allowed::Positive.check("horizon", 0.0),
                "horizon must be a finite number > 0 (got 0)",
            ),
            (
                Allowed::Positive.check("target", f64::NAN),
                "target must be a finite number > 0 (got NaN)",
            ),
            (
                Allowed::PositiveUpTo(10.0).check("dt_factor", 11.0),
                "dt_factor must be a number in (0, 10] (got 11)",
            ),
            (
                Allowed::PositiveUpTo(0.25).check("per_transit", 0.0),
                "per_transit must be a number in (0, 0.25] (got 0)",
            ),
            (
                Allowed::NonNegativeUpTo(0.5).check("per_transit", 0.75),
                "per_transit must be a number in [0, 0.5] (got 0.75)",
            ),
            (
                Allowed::UnitFraction.check("rest_ratio", 1.0),
                "rest_ratio must be a number in [0, 1) (got 1)",
            ),
        ];
        for (result, message) in cases {
            assert_eq!(result.unwrap_err().to_string(), message);
        }
        assert_eq!(
            Allowed::AtLeast(1)
                .check_count("max_events", 0)
                .unwrap_err()
                .to_string(),
            "max_events must be at least 1 (got 0)"
        );
    }

    #[test]
    fn ranges_admit_their_ends_as_written() {
        assert!(Allowed::NonNegative.admits(0.0));
        assert!(!Allowed::Positive.admits(0.0));
        assert!(!Allowed::Positive.admits(f64::INFINITY));
        assert!(Allowed::PositiveUpTo(0.25).admits(0.25));
        assert!(!Allowed::PositiveUpTo(0.25).admits(0.2500001));
        assert!(Allowed::NonNegativeUpTo(0.5).admits(0.0));
        assert!(Allowed::UnitFraction.admits(0.0));
        assert!(!Allowed::UnitFraction.admits(1.0));
        assert!(Allowed::AtLeast(1).admits(1.0));
        assert!(!Allowed::AtLeast(1).admits(0.0));
    }
}

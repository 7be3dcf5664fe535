//! Axes written `START:STOP:STEP` (or a single value) and the grids they span.

use impact_model::Bilayer;
use thiserror::Error;

/// A malformed axis or a grid point outside the allowed range.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum GridError {
    /// The text is not `START:STOP:STEP` or a single number.
    #[error("{name} must be START:STOP:STEP or a single value, with numbers (got '{text}')")]
    Syntax {
        /// The axis (`x` or `alpha`).
        name: &'static str,
        /// What was given.
        text: String,
    },
    /// A step that is not positive, or a start past the stop.
    #[error("{name} must have STEP > 0 and START <= STOP (got '{text}')")]
    Order {
        /// The axis (`x` or `alpha`).
        name: &'static str,
        /// What was given.
        text: String,
    },
    /// More than `10^7` values on one axis.
    #[error("{name} spans {count} values; at most 10^7 are allowed")]
    TooMany {
        /// The axis (`x` or `alpha`).
        name: &'static str,
        /// How many values it would span.
        count: f64,
    },
    /// A value outside `(0, 1)`, where `x` and `alpha` of a bilayer live.
    #[error("{name} values must be numbers in (0, 1) (got {value})")]
    Range {
        /// The axis (`x` or `alpha`).
        name: &'static str,
        /// The offending value.
        value: f64,
    },
}

/// Evenly spaced values `start, start + step, ..., stop` (inclusive, with the
/// count rounded so that rounding of `stop` never drops the last value).
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// First value.
    pub start: f64,
    /// Last value (reached within rounding).
    pub stop: f64,
    /// Spacing between values (positive).
    pub step: f64,
}

impl Axis {
    /// The paper's axis: 0.005 to 0.995 in steps of 0.005 (199 values).
    pub const PAPER: Axis = Axis {
        start: 0.005,
        stop: 0.995,
        step: 0.005,
    };

    /// Parses `START:STOP:STEP` or a single value for the axis `name`.
    pub fn parse(name: &'static str, text: &str) -> Result<Self, GridError> {
        let syntax = || GridError::Syntax {
            name,
            text: text.to_string(),
        };
        let nums: Vec<f64> = text
            .split(':')
            .map(|p| p.trim().parse::<f64>().map_err(|_| syntax()))
            .collect::<Result<_, _>>()?;
        let axis = match nums[..] {
            [v] => Axis {
                start: v,
                stop: v,
                step: 1.0,
            },
            [start, stop, step] => Axis { start, stop, step },
            _ => return Err(syntax()),
        };
        if !(axis.start.is_finite() && axis.stop.is_finite() && axis.step.is_finite()) {
            return Err(syntax());
        }
        if axis.step <= 0.0 || axis.start > axis.stop {
            return Err(GridError::Order {
                name,
                text: text.to_string(),
            });
        }
        let count = axis.count_f64();
        if count > 1e7 {
            return Err(GridError::TooMany { name, count });
        }
        for v in axis.values() {
            if !(v > 0.0 && v < 1.0) {
                return Err(GridError::Range { name, value: v });
            }
        }
        Ok(axis)
    }

    fn count_f64(&self) -> f64 {
        ((self.stop - self.start) / self.step + 1e-9).floor() + 1.0
    }

    /// The values `start + i step`, as the axis writes them: when `start`
    /// and `step` are decimals of at most 12 places, in integer multiples of
    /// `10^-d` (so `0.005:0.995:0.005` gives `0.95`, not
    /// `0.9500000000000001`); otherwise computed directly. Never
    /// accumulated.
    pub fn values(&self) -> Vec<f64> {
        let n = self.count_f64() as usize;
        let decimal = (0..=12).map(|d| 10f64.powi(d)).find(|scale| {
            let whole = |v: f64| {
                ((v * scale).round() - v * scale).abs() <= 1e-9 * (v * scale).abs().max(1.0)
            };
            whole(self.start) && whole(self.step)
        });
        match decimal {
            Some(scale) => {
                let (start, step) = ((self.start * scale).round(), (self.step * scale).round());
                (0..n).map(|i| (start + i as f64 * step) / scale).collect()
            }
            None => (0..n).map(|i| self.start + i as f64 * self.step).collect(),
        }
    }
}

/// A rectangular grid over composition `x` and stiffness ratio `alpha`.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Composition `x = L2 / L` values.
    pub x: Axis,
    /// Stiffness ratio `alpha = E2 / (E1 + E2)` values.
    pub alpha: Axis,
}

impl Grid {
    /// The paper's 199 x 199 grid (39,601 points).
    pub fn paper() -> Self {
        Self {
            x: Axis::PAPER,
            alpha: Axis::PAPER,
        }
    }

    /// Points in output order: `alpha` outer, `x` inner.
    pub fn points(&self) -> Vec<Bilayer> {
        let xs = self.x.values();
        self.alpha
            .values()
            .into_iter()
            .flat_map(|alpha| xs.iter().map(move |&x| Bilayer { x, alpha }))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_axis_has_199_values_ending_at_0_995() {
        let v = Axis::PAPER.values();
        assert_eq!(v.len(), 199);
        assert_eq!(v[198], 0.995);
        // every value is the decimal the axis writes
        for (i, x) in v.iter().enumerate() {
            assert_eq!(
                x.to_string(),
                format!("{}", (i as f64 + 1.0) * 5.0 / 1000.0)
            );
            assert!(x.to_string().len() <= 5, "{x}");
        }
        assert_eq!(Grid::paper().points().len(), 39_601);
    }

    #[test]
    fn parsing() {
        assert_eq!(Axis::parse("x", "0.4").unwrap().values(), vec![0.4]);
        assert_eq!(Axis::parse("x", "0.1:0.3:0.1").unwrap().values().len(), 3);
        let e = Axis::parse("alpha", "0:0.5:0.1").unwrap_err();
        assert_eq!(
            e.to_string(),
            "alpha values must be numbers in (0, 1) (got 0)"
        );
        // not numbers: a syntax error; numbers out of order or a step that
        // walks away from STOP: an order error
        for (text, syntax) in [
            ("a:b", true),
            ("0.5:0.1:0.1", false),
            ("0.1:0.5:-1", false),
            ("NaN", true),
        ] {
            let e = Axis::parse("x", text).unwrap_err();
            if syntax {
                assert!(matches!(e, GridError::Syntax { .. }), "{text}: {e:?}");
            } else {
                assert!(matches!(e, GridError::Order { .. }), "{text}: {e:?}");
            }
        }
    }
}

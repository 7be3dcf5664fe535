//! Least-squares straight lines, and the power laws and exponentials that
//! become straight lines on logarithmic axes.
//!
//! Degenerate input (fewer than two points, or all at one `x`) gives NaN
//! coefficients rather than an error: the callers print fitted exponents
//! beside a verdict, and a NaN there says "no fit" in the output itself.

/// The line `y = slope x + intercept`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    /// Change of `y` per unit of `x`.
    pub slope: f64,
    /// `y` at `x = 0`.
    pub intercept: f64,
}

/// The power law `y = prefactor x^exponent`, fitted on log-log axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerLaw {
    /// Exponent: the slope of the fitted line on log-log axes.
    pub exponent: f64,
    /// `ln prefactor`: the fitted line's intercept on log-log axes.
    pub ln_prefactor: f64,
}

impl PowerLaw {
    /// The prefactor `exp(ln_prefactor)`: `y` at `x = 1`.
    pub fn prefactor(&self) -> f64 {
        self.ln_prefactor.exp()
    }
}

/// The least-squares line through `points`: `slope = cov(x, y) / var(x)`.
pub fn least_squares(points: &[(f64, f64)]) -> Line {
    let n = points.len() as f64;
    let (mx, my) = (
        points.iter().map(|p| p.0).sum::<f64>() / n,
        points.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let cov: f64 = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let var: f64 = points.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let slope = cov / var;
    Line {
        slope,
        intercept: my - slope * mx,
    }
}

/// The least-squares line of `ln y` against `ln x` (points with `x` or `y`
/// not positive are left out: errors of exactly 0 have no logarithm).
pub fn power_fit(points: &[(f64, f64)]) -> PowerLaw {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let line = least_squares(&logs);
    PowerLaw {
        exponent: line.slope,
        ln_prefactor: line.intercept,
    }
}

/// The least-squares line of `ln y` against `x`: `y = exp(intercept + slope
/// x)` (points with `y` not positive are left out).
pub fn exponential_fit(points: &[(f64, f64)]) -> Line {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(_, y)| *y > 0.0)
        .map(|(x, y)| (*x, y.ln()))
        .collect();
    least_squares(&logs)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Through (0, 1), (1, 3), (2, 2): means (1, 2), cov = (-1)(-1) + 0 +
    /// (1)(0) = 1, var = 2, so slope 1/2 and intercept 2 - 1/2 = 3/2.
    #[test]
    fn a_line_through_three_points_by_hand() {
        let l = least_squares(&[(0.0, 1.0), (1.0, 3.0), (2.0, 2.0)]);
        assert!((l.slope - 0.5).abs() < 1e-15, "{l:?}");
        assert!((l.intercept - 1.5).abs() < 1e-15, "{l:?}");
    }

    #[test]
    fn an_exact_power_law_is_recovered() {
        let pts: Vec<(f64, f64)> = [0.5, 1.0, 2.0, 7.0, 40.0]
            .iter()
            .map(|&x: &f64| (x, 3.0 * x.powf(1.5)))
            .collect();
        let f = power_fit(&pts);
        assert!((f.exponent - 1.5).abs() < 1e-12, "{f:?}");
        assert!((f.ln_prefactor - 3f64.ln()).abs() < 1e-12, "{f:?}");
    }

    #[test]
    fn points_without_a_logarithm_are_left_out() {
        let f = power_fit(&[(0.0, 5.0), (1.0, 2.0), (4.0, 1.0), (2.0, 0.0)]);
        // through (1, 2) and (4, 1) alone: y = 2 x^(-1/2)
        assert!((f.exponent + 0.5).abs() < 1e-12, "{f:?}");
        assert!((f.prefactor() - 2.0).abs() < 1e-12, "{f:?}");
    }

    #[test]
    fn an_exact_exponential_is_recovered() {
        let pts: Vec<(f64, f64)> = [0.0, 1.0, 2.5, 4.0]
            .iter()
            .map(|&t: &f64| (t, 2.0 * (-0.5 * t).exp()))
            .collect();
        let l = exponential_fit(&pts);
        assert!((l.slope + 0.5).abs() < 1e-12, "{l:?}");
        assert!((l.intercept - 2f64.ln()).abs() < 1e-12, "{l:?}");
    }

    #[test]
    fn one_point_has_no_fit() {
        assert!(least_squares(&[(1.0, 1.0)]).slope.is_nan());
    }
}

//! The Lagrange polynomial through a few points, evaluated outside them:
//! a value at a limit (`x -> 0`) that cannot be run directly, from runs
//! near it.

/// The weights `w_i` with `p(at) = sum w_i y_i` for the polynomial `p`
/// through the points at `xs` (distinct): `w_i = prod_{j != i} (at - x_j)
/// / (x_i - x_j)`. An error bound on the `y_i` carries over as
/// `sum |w_i| error_i`.
pub fn lagrange_weights(xs: &[f64], at: f64) -> Vec<f64> {
    xs.iter()
        .enumerate()
        .map(|(i, &xi)| {
            xs.iter()
                .enumerate()
                .filter(|&(j, _)| j != i)
                .fold(1.0, |w, (_, &xj)| w * ((at - xj) / (xi - xj)))
        })
        .collect()
}

/// The polynomial through `points` evaluated at `at`.
pub fn lagrange_extrapolate(points: &[(f64, f64)], at: f64) -> f64 {
    let xs: Vec<f64> = points.iter().map(|p| p.0).collect();
    lagrange_weights(&xs, at)
        .iter()
        .zip(points)
        .fold(0.0, |sum, (w, p)| sum + w * p.1)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Through 1, 2, 3 to 0: w = (0-2)(0-3)/((1-2)(1-3)) = 3,
    /// (0-1)(0-3)/((2-1)(2-3)) = -3, (0-1)(0-2)/((3-1)(3-2)) = 1.
    #[test]
    fn weights_by_hand() {
        assert_eq!(
            lagrange_weights(&[1.0, 2.0, 3.0], 0.0),
            vec![3.0, -3.0, 1.0]
        );
        // two points h, 2h to 0: the linear extrapolation 2 y(h) - y(2h)
        assert_eq!(lagrange_weights(&[0.25, 0.5], 0.0), vec![2.0, -1.0]);
    }

    /// A quadratic through three points is the quadratic: 1 + 2x + 3x^2
    /// gives 6, 17, 34 at 1, 2, 3, and 3*6 - 3*17 + 34 = 1 at 0.
    #[test]
    fn a_quadratic_through_three_points_is_exact() {
        let p = |x: f64| 1.0 + 2.0 * x + 3.0 * x * x;
        let pts: Vec<(f64, f64)> = [1.0, 2.0, 3.0].iter().map(|&x| (x, p(x))).collect();
        assert_eq!(lagrange_extrapolate(&pts, 0.0), 1.0);
        assert!((lagrange_extrapolate(&pts, -1.5) - p(-1.5)).abs() < 1e-12);
    }
}

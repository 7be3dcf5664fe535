//! Bisection for a root bracketed by a sign test.

/// The root of a monotone test in `[lo, hi]` after `iterations` halvings:
/// `below(x)` is true left of the root. Returns the last bracket's middle.
pub fn bisect(mut lo: f64, mut hi: f64, iterations: usize, below: impl Fn(f64) -> bool) -> f64 {
    for _ in 0..iterations {
        let mid = 0.5 * (lo + hi);
        if below(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    #[test]
    fn finds_the_square_root_of_two() {
        let r = super::bisect(1.0, 2.0, 60, |x| x * x < 2.0);
        assert!((r - std::f64::consts::SQRT_2).abs() < 1e-15);
    }
}

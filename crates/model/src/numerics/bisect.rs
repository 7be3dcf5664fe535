//! Bisection for a root bracketed by a sign test.

/// The root of a monotone test in `[lo, hi]` after `iterations` halvings:
/// `below(x)` is true left of the root. Returns the last bracket's middle.
pub fn bisect(lo: f64, hi: f64, iterations: usize, below: impl Fn(f64) -> bool) -> f64 {
    bisect_to(lo, hi, iterations, 0.0, below)
}

/// [`bisect`] that stops early once the bracket is narrower than
/// `relative_width * hi`: a start for a faster method (Newton) needs no
/// more. A `relative_width` of 0 never stops early.
pub fn bisect_to(
    mut lo: f64,
    mut hi: f64,
    iterations: usize,
    relative_width: f64,
    below: impl Fn(f64) -> bool,
) -> f64 {
    for _ in 0..iterations {
        let mid = 0.5 * (lo + hi);
        if below(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < relative_width * hi {
            break;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_the_square_root_of_two() {
        let r = bisect(1.0, 2.0, 60, |x| x * x < 2.0);
        assert!((r - std::f64::consts::SQRT_2).abs() < 1e-15);
    }

    #[test]
    fn stops_once_the_bracket_is_narrow() {
        // Root 0.3 in [0, 1]; brackets and their widths against 0.1 hi:
        // [0, .5] .5 vs .05; [.25, .5] .25 vs .05; [.25, .375] .125 vs
        // .0375; [.25, .3125] .0625 vs .03125; [.28125, .3125] .03125 vs
        // .03125 (not below); [.296875, .3125] .015625 < .03125: stop.
        let r = bisect_to(0.0, 1.0, 60, 0.1, |x| x < 0.3);
        assert_eq!(r, 0.3046875);
    }
}

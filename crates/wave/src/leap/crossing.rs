//! The closed-form searches of a leap: the first return at which a
//! geometric sequence crosses a threshold, and counts of a lattice of times.

use crate::real::Real;

/// The smallest `k < kmax` with `c0 + cp q^k >= threshold`, `0 <= q < 1`.
pub(super) fn first_crossing_positive<R: Real>(
    c0: R,
    cp: R,
    q: R,
    kmax: u64,
    threshold: R,
) -> Option<u64> {
    if kmax == 0 {
        return None;
    }
    let at = |k: u64| c0 + cp * q.powi(k.min(i32::MAX as u64) as i32);
    if at(0) >= threshold {
        return Some(0);
    }
    if q == R::zero() {
        return (kmax > 1 && c0 >= threshold).then_some(1);
    }
    // cp >= 0: decreasing from at(0) < threshold: never
    if cp >= R::zero() || c0 < threshold {
        return None;
    }
    // increasing towards c0 >= threshold: q^k <= (c0 - threshold) / (-cp)
    let x = (c0 - threshold) / (-cp);
    let mut k = if x >= R::one() {
        0
    } else {
        let v = (x.ln() / q.ln()).ceil().to_f64();
        if !(v.is_finite()) || v > kmax as f64 {
            return None;
        }
        v.max(0.0) as u64
    };
    while k > 0 && at(k - 1) >= threshold {
        k -= 1;
    }
    while k < kmax && at(k) < threshold {
        k += 1;
    }
    (k < kmax).then_some(k)
}

/// The smallest `k < kmax` with `c0 + cp q^k >= threshold`, `|q| < 1`.
pub(super) fn first_crossing<R: Real>(c0: R, cp: R, q: R, kmax: u64, threshold: R) -> Option<u64> {
    if q >= R::zero() {
        return first_crossing_positive(c0, cp, q, kmax, threshold);
    }
    // even k = 2j: c0 + cp Q^j; odd k = 2j + 1: c0 + cp q Q^j, Q = q^2
    let big_q = q * q;
    let even = first_crossing_positive(c0, cp, big_q, kmax.div_ceil(2), threshold).map(|j| 2 * j);
    let odd = first_crossing_positive(c0, cp * q, big_q, kmax / 2, threshold).map(|j| 2 * j + 1);
    match (even, odd) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// The first `k < kmax` with `f0 + b k + c (q^k - 1) <= 0`, `|q| < 1`.
pub(super) fn first_nonpositive<R: Real>(f0: R, b: R, c: R, q: R, kmax: u64) -> Option<u64> {
    if kmax == 0 {
        return None;
    }
    if f0 <= R::zero() {
        return Some(0);
    }
    if q >= R::zero() {
        return first_nonpositive_positive(f0, b, c, q, kmax);
    }
    // parity: k = 2j + r, q^k - 1 = q^r (Q^j - 1) + (q^r - 1), Q = q^2
    let big_q = q * q;
    let even = first_nonpositive_positive(f0, b + b, c, big_q, kmax.div_ceil(2)).map(|j| 2 * j);
    let odd_f0 = f0 + b + c * (q - R::one());
    let odd = if kmax >= 2 {
        first_nonpositive_positive(odd_f0, b + b, c * q, big_q, kmax / 2).map(|j| 2 * j + 1)
    } else {
        None
    };
    match (even, odd) {
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// [`first_nonpositive`] for `0 <= q < 1`: the differences
/// `b + c q^k (q - 1)` change sign at most once, so the function has at most
/// two monotone pieces; each is searched by bisection.
pub(super) fn first_nonpositive_positive<R: Real>(
    f0: R,
    b: R,
    c: R,
    q: R,
    kmax: u64,
) -> Option<u64> {
    let ln_q = q.ln();
    let f = |k: u64| f0 + b * R::of(k as f64) + c * (ln_q * R::of(k as f64)).exp_m1();
    if kmax == 0 {
        return None;
    }
    if f(0) <= R::zero() {
        return Some(0);
    }
    // where the differences change sign: q^k = -b / (c (q - 1))
    let x = -b / (c * (q - R::one()));
    let turn = if q > R::zero() && x > R::zero() && x < R::one() {
        let k = (x.ln() / ln_q).to_f64();
        if k.is_finite() && k > 0.0 {
            (k.floor() as u64).min(kmax - 1)
        } else {
            0
        }
    } else {
        0
    };
    for (lo, hi) in [(0, turn), (turn, kmax - 1)] {
        if hi < lo || f(hi) > R::zero() {
            continue;
        }
        // monotone on [lo, hi], positive at lo (else found before), not at hi
        if f(lo) <= R::zero() {
            return Some(lo);
        }
        let (mut a, mut z) = (lo, hi);
        while z - a > 1 {
            let mid = a + (z - a) / 2;
            if f(mid) <= R::zero() {
                z = mid;
            } else {
                a = mid;
            }
        }
        return Some(z);
    }
    None
}

/// `q^k`, for any `k`.
pub(super) fn pow<R: Real>(q: R, k: u64) -> R {
    if k <= i32::MAX as u64 {
        q.powi(k as i32)
    } else {
        q.powf(R::of(k as f64))
    }
}

/// [`pow`] for the first few powers without the call (the same products:
/// `q^1 = q`, `q^2 = q q`).
#[inline(always)]
pub(super) fn pow_small<R: Real>(q: R, k: u64) -> R {
    match k {
        0 => R::one(),
        1 => q,
        2 => q * q,
        _ => pow(q, k),
    }
}

/// How many `k >= 0` have `start + k period < end`.
pub(super) fn count_before<R: Real>(start: R, period: R, end: R) -> u64 {
    if start >= end {
        return 0;
    }
    // (the loops below end here too: a short leap's common cases, a
    // front returning once or twice, without the division)
    if start + period >= end {
        return 1;
    }
    if start + R::of(2.0) * period >= end {
        return 2;
    }
    let mut n = ((end - start) / period).ceil().to_f64().max(1.0) as u64;
    while n > 0 && start + R::of((n - 1) as f64) * period >= end {
        n -= 1;
    }
    while start + R::of(n as f64) * period < end {
        n += 1;
    }
    n
}

/// [`count_before`] searched from `guess` (its count for a neighbouring
/// start: the previous cell's, the previous phase's), without the
/// division: the count is the first `n` with `start + n period >= end`,
/// and the sum grows with `n`, so both searches end at it wherever they
/// start. A guess of 0 (none) counts as [`count_before`] does.
#[inline(always)]
pub(super) fn count_before_near<R: Real>(start: R, period: R, end: R, guess: u64) -> u64 {
    if guess == 0 || start >= end {
        return count_before(start, period, end);
    }
    let mut n = guess;
    while n > 0 && start + R::of((n - 1) as f64) * period >= end {
        n -= 1;
    }
    while start + R::of(n as f64) * period < end {
        n += 1;
    }
    n
}

#[cfg(test)]
mod tests {
    use super::{count_before, count_before_near};

    /// The count by brute force: the first `n` whose `start + n period`, as
    /// computed, is at or past `end` (the sum grows with `n`).
    fn counted(start: f64, period: f64, end: f64) -> u64 {
        let mut n = 0u64;
        while start + (n as f64) * period < end {
            n += 1;
        }
        n
    }

    /// `count_before` against the count by brute force, ends near 0 to 40
    /// periods after the start, just before, at and after a multiple (the
    /// fast paths for one and two returns, and the division, meet there),
    /// starts from zero to far from it (where rounding of the sum decides).
    #[test]
    fn count_before_counts_the_lattice_times_before_the_end() {
        let mut checked = 0;
        for start in [0.0, 0.37, 1.0, 1e3, 123_456.789, 1e9] {
            for period in [1e-3, 0.01, 0.1, 1.0 / 3.0, 2.0] {
                for k in 0..40u32 {
                    let at = start + f64::from(k) * period;
                    for end in [
                        at,
                        at.next_down(),
                        at.next_up(),
                        at + 0.5 * period,
                        start - period,
                    ] {
                        let want = counted(start, period, end);
                        assert_eq!(
                            count_before(start, period, end),
                            want,
                            "start {start}, period {period}, end {end}"
                        );
                        // from any guess, near or far
                        for guess in [
                            0,
                            1,
                            2,
                            want.saturating_sub(1),
                            want,
                            want + 1,
                            3 * want + 7,
                        ] {
                            assert_eq!(
                                count_before_near(start, period, end, guess),
                                want,
                                "start {start}, period {period}, end {end}, guess {guess}"
                            );
                        }
                        checked += 1;
                    }
                }
            }
        }
        assert_eq!(checked, 6 * 5 * 40 * 5);
    }
}

//! Sums of geometric sequences with polynomial weights, for advancing a
//! ringing layer over many round trips at once.
//!
//! A front ringing in a layer returns to the same boundary every round trip
//! multiplied by `q` (the product of the two reflections): its arrivals
//! carry `a q^k` at times `tau + k P`. Impulses and heights then need
//! `sum q^k`, `sum k q^k` and `sum k^2 q^k` over `k < n`. Near `q = 1` (a
//! free stiff base under a soft layer: `q = 1 - 2 Z2/Z1`) the textbook
//! closed forms cancel catastrophically; these are evaluated through
//! `expm1` and a Taylor series where that matters, and summed directly where
//! the terms die fast.

use crate::real::Real;

/// `(sum q^k, sum k q^k, sum k^2 q^k)` over `0 <= k < n`.
pub fn sums<R: Real>(q: R, n: u64) -> (R, R, R) {
    let zero = R::zero();
    if n == 0 || q == zero {
        return if n == 0 {
            (zero, zero, zero)
        } else {
            (R::one(), zero, zero)
        };
    }
    // few terms, or terms that die fast: add them
    if added(q, n) {
        let mut terms = Terms::new(q);
        terms.add_to(n);
        return terms.sums;
    }
    if q < zero {
        // alternating: even terms minus odd terms, each geometric in q^2
        let q2 = q * q;
        let half_even = n.div_ceil(2);
        let half_odd = n / 2;
        let (e0, e1, e2) = positive_sums(q2, half_even);
        let (o0, o1, o2) = positive_sums(q2, half_odd);
        let two = R::of(2.0);
        let four = R::of(4.0);
        // even k = 2j: k = 2j, k^2 = 4 j^2; odd k = 2j + 1, weight q
        let s0 = e0 + q * o0;
        let s1 = two * e1 + q * (two * o1 + o0);
        let s2 = four * e2 + q * (four * o2 + four * o1 + o0);
        return (s0, s1, s2);
    }
    positive_sums(q, n)
}

/// Whether [`sums`] adds the terms one by one (few, or dying fast).
#[inline(always)]
fn added<R: Real>(q: R, n: u64) -> bool {
    n <= 64 || q.abs() < R::of(0.5)
}

/// The sums [`sums`] adds term by term, over the first `n` terms.
#[derive(Debug, Clone, Copy)]
struct Terms<R> {
    q: R,
    n: u64,
    /// `q^n` as the products give it, and whether the terms stopped
    /// (negligible from there on).
    p: R,
    stopped: bool,
    sums: (R, R, R),
}

impl<R: Real> Terms<R> {
    fn new(q: R) -> Self {
        let zero = R::zero();
        Self {
            q,
            n: 0,
            p: R::one(),
            stopped: false,
            sums: (zero, zero, zero),
        }
    }

    /// Adds the terms up to `n` (from the last `n`, which is not larger).
    #[inline(always)]
    fn add_to(&mut self, n: u64) {
        while self.n < n && !self.stopped {
            let (s0, s1, s2) = &mut self.sums;
            let (k, p) = (R::of(self.n as f64), self.p);
            *s0 += p;
            *s1 += k * p;
            *s2 += k * k * p;
            self.p = p * self.q;
            self.n += 1;
            self.stopped = self.p.abs() < R::of(1e-40) * (R::one() + s0.abs());
        }
        self.n = self.n.max(n);
    }
}

/// [`sums`] for counts asked in increasing order, the same values: where
/// it adds the terms, from where the last count left them. A leap's
/// trains deposited together ask for the sums at each one's start and
/// end, in order of both, counts of up to 64 terms, each a loop over all
/// of them (560,000 loops of 47 terms on average on seed 3's rod 5 of
/// the layer survey at 0.1 of a transit, 6 % of its instructions).
#[derive(Debug, Clone, Copy)]
pub(crate) struct AscendingSums<R> {
    terms: Terms<R>,
}

impl<R: Real> AscendingSums<R> {
    pub(crate) fn new(q: R) -> Self {
        Self {
            terms: Terms::new(q),
        }
    }

    /// `sums(q, n)`; from the start again if `n` is below the last.
    #[inline(always)]
    pub(crate) fn at(&mut self, n: u64) -> (R, R, R) {
        let q = self.terms.q;
        if n == 0 || q == R::zero() || !added(q, n) {
            return sums(q, n);
        }
        if n < self.terms.n {
            self.terms = Terms::new(q);
        }
        self.terms.add_to(n);
        self.terms.sums
    }
}

/// The sums for `0 < q` (`q != 1` allowed near 1), large `n`.
fn positive_sums<R: Real>(q: R, n: u64) -> (R, R, R) {
    let zero = R::zero();
    if n == 0 {
        return (zero, zero, zero);
    }
    let one = R::one();
    let lambda = q.ln();
    let nf = R::of(n as f64);
    let x = nf * lambda;
    if x.abs() < R::of(0.1) {
        // q^k = exp(lambda k) = sum_m (lambda k)^m / m!: moments of k;
        // |n lambda| < 0.1 needs m < 14 for 1e-17
        const TERMS: usize = 14;
        let powers = power_sums::<R>(n);
        let mut s = [zero; 3];
        let mut term = one;
        for m in 0..TERMS {
            if m > 0 {
                term = term * lambda / R::of(m as f64);
            }
            for (w, slot) in s.iter_mut().enumerate() {
                *slot += term * powers[m + w];
            }
        }
        return (s[0], s[1], s[2]);
    }
    // closed forms through expm1: E = q^n - 1, u = q - 1 (|n ln q| >= 0.1,
    // so the cancellations below cost at most ~100 ulps)
    let u = lambda.exp_m1();
    let big = x.exp_m1();
    let qn = big + one;
    let s0 = big / u;
    // sum k q^k = q d/dq s0 = (n q^n u - q E) / u^2
    let s1 = (nf * qn * u - q * big) / (u * u);
    (s0, s1, second_moment(q, u, big, nf))
}

/// `sum_{k<n} k^2 q^k` from `u = q - 1`, `E = q^n - 1`.
fn second_moment<R: Real>(q: R, u: R, big: R, nf: R) -> R {
    let one = R::one();
    let two = R::of(2.0);
    let qn = big + one;
    // S2 = [q (1 + q) (q^n - 1) - n^2 q^n u^2 ... ] / u^3, written as
    // (n^2 q^n u^2 - (2n - 1) ... ) is error-prone: use
    // S2 = q d/dq S1 with S1 = (n q^n u - q E) / u^2:
    // d/dq (n q^n u) = n^2 q^(n-1) u + n q^n
    // d/dq (q E)     = E + q n q^(n-1) = E + n q^n
    // d/dq (1/u^2)   = -2 / u^3
    let num = nf * qn * u - q * big;
    let dnum = (nf * nf * qn * u) / q + nf * qn - big - nf * qn;
    q * (dnum / (u * u) - two * num / (u * u * u))
}

/// Bernoulli numbers `B_0 .. B_20` (with `B_1 = -1/2`).
const BERNOULLI: [f64; 21] = [
    1.0,
    -0.5,
    1.0 / 6.0,
    0.0,
    -1.0 / 30.0,
    0.0,
    1.0 / 42.0,
    0.0,
    -1.0 / 30.0,
    0.0,
    5.0 / 66.0,
    0.0,
    -691.0 / 2730.0,
    0.0,
    7.0 / 6.0,
    0.0,
    -3617.0 / 510.0,
    0.0,
    43867.0 / 798.0,
    0.0,
    -174611.0 / 330.0,
];

/// How many power sums the Taylor branch uses.
const POWERS: usize = 16;

/// `[sum_{k<n} k^m for m in 0..16]`: added up for small `n`, else by
/// Faulhaber's formula `1/(m+1) sum_j C(m+1, j) B_j n^(m+1-j)`, whose
/// leading terms dominate for large `n`.
fn power_sums<R: Real>(n: u64) -> [R; POWERS] {
    let count = POWERS;
    let mut out = [R::zero(); POWERS];
    if n <= 64 {
        for k in 0..n {
            let kf = R::of(k as f64);
            let mut p = R::one();
            for slot in out.iter_mut() {
                *slot += p;
                p = p * kf;
            }
        }
        return out;
    }
    let nf = R::of(n as f64);
    // n^j for j = 0 ..= count
    let mut npow = [R::one(); POWERS + 1];
    for j in 1..=count {
        npow[j] = npow[j - 1] * nf;
    }
    for (m, slot) in out.iter_mut().enumerate() {
        let mut sum = R::zero();
        let mut binomial = 1.0; // C(m + 1, j)
        for (j, b) in BERNOULLI.iter().enumerate().take(m + 1) {
            if *b != 0.0 {
                sum += R::of(binomial * b) * npow[m + 1 - j];
            }
            binomial *= (m + 1 - j) as f64 / (j + 1) as f64;
        }
        *slot = sum / R::of((m + 1) as f64);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sums, and the sums of absolute terms (the scale of rounding).
    fn direct(q: f64, n: u64) -> ([f64; 3], [f64; 3]) {
        let (mut s, mut m) = ([0.0; 3], [0.0; 3]);
        let mut p = 1.0;
        for k in 0..n {
            let k = k as f64;
            for (w, t) in [p, k * p, k * k * p].into_iter().enumerate() {
                s[w] += t;
                m[w] += t.abs();
            }
            p *= q;
        }
        (s, m)
    }

    #[test]
    fn closed_forms_equal_direct_sums() {
        for q in [
            0.3,
            -0.4,
            0.9,
            -0.9,
            0.999,
            -0.999,
            0.999_999,
            -0.999_999,
            1.0 - 1e-9,
        ] {
            for n in [1, 5, 63, 64, 65, 200, 10_000, 300_000] {
                let (a, b, c) = sums(q, n);
                let (x, m) = direct(q, n);
                for (w, got) in [a, b, c].into_iter().enumerate() {
                    assert!(
                        (got - x[w]).abs() <= 1e-9 * m[w].max(1.0),
                        "q = {q}, n = {n}, weight k^{w}: {got} vs {}",
                        x[w]
                    );
                }
            }
        }
    }

    /// [`AscendingSums`] gives `sums` to the bit, asked in increasing
    /// order with repeats and the odd step back: ratios that die fast and
    /// that do not, counts across the 64 terms where `sums` stops adding,
    /// and a ratio whose terms stop (`1e-40` of the sum) within the count.
    #[test]
    fn ascending_sums_are_the_sums_to_the_bit() {
        let mut next = crate::test_random::xorshift(0x9e37_79b9_7f4a_7c15u64);
        let mut asked = 0;
        for q in [0.0, 0.3, -0.4, 0.49, -0.5, 0.9, -0.97, 0.999, 1e-30, -1e-21] {
            let mut ascending = AscendingSums::new(q);
            let (mut n, mut most) = (0, 0);
            for _ in 0..300 {
                n = match next() % 40 {
                    0 => n / 2,
                    1..=3 => n,
                    _ => n + next() % 5,
                };
                let (a, b, c) = ascending.at(n);
                let (x, y, z) = sums(q, n);
                assert_eq!(
                    (a.to_bits(), b.to_bits(), c.to_bits()),
                    (x.to_bits(), y.to_bits(), z.to_bits()),
                    "q = {q}, n = {n}"
                );
                asked += 1;
                most = most.max(n);
            }
            assert!(most > 64, "q = {q}: counts up to {most} only");
        }
        assert_eq!(asked, 3000);
    }
}

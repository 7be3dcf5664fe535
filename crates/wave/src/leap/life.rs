//! How long a ringing front lives: the round trips before its jump, `a
//! q^k`, falls under the drop threshold, counted as the event loop would
//! drop it.

use super::crossing::{pow, pow_small};
use crate::engine::Tracer;
use crate::real::Real;

impl<R: Real> Tracer<R> {
    /// `q^k`, as [`pow_small`] gives it, remembered: a leap's phases ask
    /// for one or two powers over and over (their round trips within the
    /// leap differ by one at most), the ratio's and its magnitude's, and
    /// the call for each was 8 % of seed 3's rod 5 of the layer survey.
    #[inline(always)]
    pub(crate) fn pow_remembered(&mut self, q: R, k: u64) -> R {
        // (a zero ratio is not remembered: `-0` and `0` compare equal,
        // their odd powers do not)
        if k <= 2 || q == R::zero() {
            return pow_small(q, k);
        }
        let slot = &mut self.pow_memo[usize::from(q < R::zero())];
        if slot.0 != q || slot.1 != k {
            *slot = (q, k, pow_small(q, k));
        }
        slot.2
    }

    /// [`Tracer::life`], but no more than `cap`: where the front is still
    /// above the threshold after `cap - 1` round trips, one power says so
    /// without the logarithms. Most fronts outlive the leap that counts
    /// them: the logarithms were a fifth of a short leap's work (the
    /// chatter of a stiff base, contacts of two round trips) and a sixth
    /// of survey rod 26's leaps. The same count: `life` itself counts with
    /// these powers wherever its logarithms come near an integer, and a
    /// power's rounding moves the count only where they do.
    #[inline(always)]
    pub(crate) fn life_within(&mut self, a: R, q: R, thr: R, from: u64, cap: u64) -> u64 {
        // (`life` never counts fewer than `from`)
        if cap <= from {
            return cap;
        }
        let aq = q.abs();
        if aq > R::zero() && aq < R::one() && a.abs() * self.pow_remembered(aq, cap - 1) >= thr {
            return cap;
        }
        self.life(a, q, thr, from).min(cap)
    }

    /// How many round trips a front of jump `a` lives (counted from `from`)
    /// before it falls under the drop threshold `thr`.
    pub(super) fn life(&mut self, a: R, q: R, thr: R, from: u64) -> u64 {
        if a.abs() < thr && from == 0 {
            return 0;
        }
        let aq = q.abs();
        if aq == R::zero() {
            return from.max(1);
        }
        if aq >= R::one() {
            return u64::MAX;
        }
        // a leap's trains share one ratio: its logarithm is kept
        let ln_q = match self.ln_memo {
            Some((q, ln)) if q == aq => ln,
            _ => {
                let ln = aq.ln();
                self.ln_memo = Some((aq, ln));
                ln
            }
        };
        let k = ((thr / a.abs()).ln() / ln_q).to_f64();
        if !k.is_finite() || k < 0.0 {
            return from.max(if a.abs() >= thr { 1 } else { 0 });
        }
        // the first integer above k, unless k is so near an integer that
        // the logarithms' rounding could decide: then count with powers
        // (the common case needs none; they were half of a leap's time).
        // (`f64::floor` and `round` are calls into libm on the baseline
        // target; the distance to the nearest integer is `min(f, 1 - f)`
        // of the fraction `f`, exactly `|k - round(k)|`.)
        let whole = <f64 as Real>::floor(k);
        let fraction = k - whole;
        if fraction.min(1.0 - fraction) > 1e-9 * k.max(1.0) {
            return (whole as u64 + 1).max(from);
        }
        let mut k = whole.max(0.0) as u64;
        // the first k with |a| |q|^k < thr
        while k > 0 && a.abs() * pow(aq, k - 1) < thr {
            k -= 1;
        }
        while a.abs() * pow(aq, k) >= thr {
            k += 1;
        }
        k.max(from)
    }
}

#[cfg(test)]
mod tests {
    use crate::config::WaveConfig;
    use crate::engine::WaveEngine;
    use impact_model::Bilayer;

    /// `life_within` is `life` capped, whatever the jump, ratio, threshold,
    /// start and cap: jumps at the threshold times powers of the ratio (the
    /// near-integer logarithms `life` counts with powers), ratios of both
    /// signs and near one, caps on both sides of the life, up to `2^40`.
    #[test]
    fn a_capped_life_is_the_life_capped() {
        let rod = Bilayer::new(0.5, 0.5).unwrap().scene().validate().unwrap();
        let mut engine = WaveEngine::new(&rod, WaveConfig::default()).unwrap();
        let thr = 1e-16;
        let mut checked = 0;
        for q in [
            -0.999, -0.93, -0.5, -1e-3, 0.0, 1e-3, 0.5, 0.93, 0.999, 0.999_999, 1.0,
        ] {
            for a in [0.0, 3e-17, 1e-16, 1e-15, 0.3, -0.7, 1.0] {
                // and jumps that reach the threshold after exactly k trips
                let exact: Vec<f64> = [1, 2, 3, 5, 11, 40, 300, 5_000]
                    .iter()
                    .map(|&k| thr / f64::abs(q).powi(k))
                    .filter(|a| a.is_finite())
                    .collect();
                for &a in [a].iter().chain(exact.iter()) {
                    for from in [0, 1] {
                        for cap in [0, 1, 2, 3, 5, 16, 17, 100, 4_321, 1_000_000, 1 << 40] {
                            let whole = engine.life(a, q, thr, from);
                            let capped = engine.life_within(a, q, thr, from, cap);
                            assert_eq!(
                                capped,
                                whole.min(cap),
                                "a {a}, q {q}, from {from}, cap {cap}: life {whole}"
                            );
                            checked += 1;
                        }
                    }
                }
            }
        }
        assert!(checked > 5000, "{checked}");
    }

    /// A remembered power is the power itself, to the bit, whatever
    /// ratios and counts were asked before: ratios of both signs and
    /// their magnitudes in turn (the two slots), the same count again,
    /// counts apart and near, and an exponent past `i32`.
    #[test]
    fn a_remembered_power_is_the_power() {
        use crate::leap::crossing::pow_small;
        let rod = Bilayer::new(0.5, 0.5).unwrap().scene().validate().unwrap();
        let mut engine = WaveEngine::new(&rod, WaveConfig::default()).unwrap();
        let ratios = [
            0.93, -0.93, 0.5, -0.999_999, 0.999_999, 0.0, -0.0, 1.0, -1.0,
        ];
        let counts = [0, 1, 2, 3, 3, 4, 3, 17, 16, 17, 1_000, 999, 1 << 33, 3];
        let mut asked = 0;
        for &q in &ratios {
            for &k in &counts {
                for base in [q, -q, f64::abs(q)] {
                    let remembered = engine.pow_remembered(base, k);
                    let power = pow_small(base, k);
                    assert_eq!(
                        remembered.to_bits(),
                        power.to_bits(),
                        "{base}^{k}: remembered {remembered}, the power {power}"
                    );
                    asked += 1;
                }
            }
        }
        assert_eq!(asked, ratios.len() * counts.len() * 3);
    }
}

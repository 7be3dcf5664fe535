//! Richardson extrapolation of a quantity computed at growing sizes (the
//! chain's `e` at `N`, `2N`, `4N`, ...), with an error estimate that says
//! when the convergence is not clean enough to trust.
//!
//! With `e(N) = e_inf + C N^-p`, three sizes give `p` (whatever their
//! spacing) and `e_inf`. The estimate is Roache's grid convergence index,
//! `1.25 |e_3 - e_2| / (r^p - 1)`, when the last three values converge
//! monotonically at an order in `[0.5, 3]` (and, given four or more sizes,
//! the last two orders agree within 0.35). Otherwise the sizes are not yet
//! asymptotic, or sharp fronts survive (an elastic layer in a chain), and
//! the estimate widens to three times the larger of the last two changes.

use serde::{Deserialize, Serialize};

/// Orders outside this range are not taken as asymptotic.
const CLEAN_ORDERS: (f64, f64) = (0.5, 3.0);
/// Two successive observed orders differing by more than this are drifting.
const ORDER_DRIFT: f64 = 0.35;
/// Roache's safety factor for a three-size study with a clean order.
const SAFETY_CLEAN: f64 = 1.25;
/// The widened estimate: this times the larger of the last two changes.
const SAFETY_UNCLEAR: f64 = 3.0;

/// The extrapolated value of a sequence and how far it may be off.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Extrapolation {
    /// The sizes (ascending).
    pub sizes: Vec<usize>,
    /// The value at each size, in the order of `sizes`.
    pub values: Vec<f64>,
    /// Observed order `p` of `|e(N) - e_inf| ~ N^-p` from the last three
    /// sizes, when their changes are monotone.
    pub order: Option<f64>,
    /// The extrapolated value (the last value where no order is observed).
    pub value: f64,
    /// Estimated `|value - e_inf|`.
    pub error: f64,
    /// Whether the convergence looks asymptotic (see the module notes).
    pub clean: bool,
    /// Why it is not clean, in words.
    pub note: Option<String>,
}

/// Extrapolates `values` at ascending `sizes` (at least three of each);
/// `sharp_fronts` marks a sequence known not to converge at a clean order,
/// which widens the estimate whatever the numbers look like.
pub fn extrapolate(sizes: &[usize], values: &[f64], sharp_fronts: bool) -> Option<Extrapolation> {
    let k = values.len();
    if k < 3 || sizes.len() != k || sizes.windows(2).any(|w| w[0] >= w[1]) {
        return None;
    }
    let last = |j: usize| -> ([f64; 3], [f64; 3]) {
        let n = [sizes[j - 2], sizes[j - 1], sizes[j]].map(|n| n as f64);
        (n, [values[j - 2], values[j - 1], values[j]])
    };
    let (n, v) = last(k - 1);
    let (d1, d2) = (v[1] - v[0], v[2] - v[1]);
    let r = n[2] / n[1];
    let mut out = Extrapolation {
        sizes: sizes.to_vec(),
        values: values.to_vec(),
        order: None,
        value: v[2],
        error: 0.0,
        clean: true,
        note: None,
    };
    if d1 == 0.0 && d2 == 0.0 {
        out.note = Some("the values do not change with size".into());
        return Some(out);
    }
    let order = observed_order(n, v);
    out.order = order;
    let mut why: Option<String> = match order {
        None if d1 * d2 <= 0.0 => Some("the changes alternate in sign".into()),
        None => Some("the changes do not shrink".into()),
        Some(p) if !(CLEAN_ORDERS.0..=CLEAN_ORDERS.1).contains(&p) => Some(format!(
            "observed order {p:.2} is outside [{}, {}]",
            CLEAN_ORDERS.0, CLEAN_ORDERS.1
        )),
        Some(p) => (k >= 4)
            .then(|| observed_order(last(k - 2).0, last(k - 2).1))
            .flatten()
            .filter(|q| (p - q).abs() > ORDER_DRIFT)
            .map(|q| format!("the observed order drifts from {q:.2} to {p:.2}")),
    };
    if sharp_fronts && why.is_none() {
        why = Some("an elastic layer keeps sharp fronts, so the order in N is not clean".into());
    }
    if let Some(p) = order {
        let p = p.clamp(CLEAN_ORDERS.0, CLEAN_ORDERS.1);
        out.value = richardson_step(v[1], v[2], r, p);
        out.error = SAFETY_CLEAN * d2.abs() / (r.powf(p) - 1.0);
    }
    if why.is_some() {
        out.clean = false;
        out.error = out.error.max(SAFETY_UNCLEAR * d1.abs().max(d2.abs()));
        out.note = why;
    }
    Some(out)
}

impl Extrapolation {
    /// The extrapolation of a quantity known to be at most `ceiling`
    /// (`what` names the law that says so): a value past it says the sizes
    /// are not yet asymptotic, so the estimate is marked not clean and
    /// widened as any unclear one is, and at least to the ceiling.
    pub fn at_most(mut self, ceiling: f64, what: &str) -> Self {
        if self.value <= ceiling {
            return self;
        }
        let v = &self.values;
        let change = v.windows(2).rev().take(2).map(|w| (w[1] - w[0]).abs());
        let change = change.fold(0.0, f64::max);
        self.error = self
            .error
            .max(SAFETY_UNCLEAR * change)
            .max(self.value - ceiling);
        let why = format!(
            "the extrapolated value {:.6} is above {ceiling}, which {what} forbids",
            self.value
        );
        self.note = Some(match self.note.take() {
            Some(note) => format!("{why}; {note}"),
            None => why,
        });
        self.clean = false;
        self
    }
}

/// One Richardson step: the limit of `e(N) = e_inf + C N^-p` from its
/// values `coarse` at `N` and `fine` at `ratio N`,
/// `fine + (fine - coarse) / (ratio^p - 1)`.
pub fn richardson_step(coarse: f64, fine: f64, ratio: f64, order: f64) -> f64 {
    fine + (fine - coarse) / (ratio.powf(order) - 1.0)
}

/// The order `p` of `e(N) = e_inf + C N^-p` through three sizes, when the
/// changes are monotone and shrinking.
fn observed_order(n: [f64; 3], v: [f64; 3]) -> Option<f64> {
    let (d1, d2) = (v[1] - v[0], v[2] - v[1]);
    (d1 * d2 > 0.0 && d2.abs() < d1.abs()).then(|| self_consistent_order(n, d1 / d2))
}

/// The order `p` of `e(N) = e_inf + C N^-p` through three sizes `n` whose
/// successive differences have ratio `q = (e2 - e1) / (e3 - e2)`: the root
/// of `(n1^-p - n2^-p) / (n2^-p - n3^-p) = q`, by bisection on `[0.25, 4]`,
/// for any spacing of the sizes.
pub fn self_consistent_order(n: [f64; 3], q: f64) -> f64 {
    let ratio = |p: f64| (n[0].powf(-p) - n[1].powf(-p)) / (n[1].powf(-p) - n[2].powf(-p));
    let (lo, hi) = (0.25, 4.0);
    if q <= ratio(lo) {
        return lo;
    }
    if q >= ratio(hi) {
        return hi;
    }
    super::bisect(lo, hi, 100, |p| ratio(p) < q)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values rising towards a ceiling too fast for their order: the
    /// extrapolation passes it, is marked and widened to reach back under
    /// it; one under the ceiling is left as it was.
    #[test]
    fn a_limit_past_its_ceiling_is_not_clean() {
        let sizes = [250, 500, 1000];
        let x = extrapolate(&sizes, &[0.98, 0.995, 0.9995], false).unwrap();
        assert!(x.value > 1.0, "{x:?}");
        let capped = x.clone().at_most(1.0, "energy");
        assert!(!capped.clean);
        assert!(
            capped
                .note
                .as_deref()
                .unwrap()
                .contains("which energy forbids")
        );
        assert!(capped.value - capped.error <= 1.0);
        assert!(capped.error >= 3.0 * 0.015 - 1e-12, "{capped:?}");
        let under = extrapolate(&sizes, &[0.9, 0.95, 0.97], false).unwrap();
        assert!(under.value < 1.0);
        assert_eq!(under.clone().at_most(1.0, "energy"), under);
    }

    /// `e(N) = 0.3 + 0.7 N^-p`: the order and the limit come back, and the
    /// estimate covers the true error.
    #[test]
    fn recovers_a_clean_power_law_at_any_spacing() {
        for p in [0.7, 1.0, 2.0] {
            for sizes in [[100, 200, 400], [100, 300, 1000]] {
                let v: Vec<f64> = sizes
                    .iter()
                    .map(|&n| 0.3 + 0.7 * (n as f64).powf(-p))
                    .collect();
                let x = extrapolate(&sizes, &v, false).unwrap();
                assert!(x.clean, "{x:?}");
                assert!((x.order.unwrap() - p).abs() < 1e-9, "{x:?}");
                assert!((x.value - 0.3).abs() < 1e-12, "{x:?}");
            }
        }
    }

    /// A fast term dying out over a slow one: the estimate covers the limit.
    #[test]
    fn a_slow_term_under_a_fast_one_is_covered() {
        let e = |n: f64| 0.5 + 2.0 / n + 0.05 / n.sqrt();
        let sizes = [100, 200, 400, 800];
        let v: Vec<f64> = sizes.iter().map(|&n| e(n as f64)).collect();
        let x = extrapolate(&sizes, &v, false).unwrap();
        assert!((x.value - 0.5).abs() <= x.error, "{x:?}");
    }

    /// Changes of 0.4, 0.1, 0.05: order 2, then 1. Flagged, widened.
    #[test]
    fn a_drifting_order_is_flagged() {
        let x = extrapolate(&[100, 200, 400, 800], &[1.0, 0.6, 0.5, 0.45], false).unwrap();
        assert!(!x.clean, "{x:?}");
        assert!(
            x.note
                .as_deref()
                .unwrap()
                .contains("drifts from 2.00 to 1.00"),
            "{x:?}"
        );
        assert!((x.error - 0.3).abs() < 1e-12, "{x:?}");
    }

    #[test]
    fn alternating_changes_are_not_extrapolated() {
        let x = extrapolate(&[100, 200, 400], &[0.5, 0.52, 0.51], false).unwrap();
        assert!(!x.clean && x.order.is_none());
        assert_eq!(x.value, 0.51);
        assert!((x.error - 0.06).abs() < 1e-12);
    }

    #[test]
    fn sharp_fronts_widen_the_estimate() {
        let sizes = [100, 200, 400];
        let v: Vec<f64> = sizes.iter().map(|&n| 0.3 + 1.0 / n as f64).collect();
        let plain = extrapolate(&sizes, &v, false).unwrap();
        let sharp = extrapolate(&sizes, &v, true).unwrap();
        assert!(plain.clean && !sharp.clean);
        assert!(sharp.error > plain.error);
        assert!(sharp.note.unwrap().contains("elastic"));
    }

    /// `e(N) = 2 + 1/N` at N = 10 and 20: 2.1 and 2.05, so one step at
    /// order 1 and ratio 2 gives 2.05 + (-0.05) / 1 = 2 exactly in reals.
    #[test]
    fn one_step_removes_a_first_order_term() {
        assert!((richardson_step(2.1, 2.05, 2.0, 1.0) - 2.0).abs() < 1e-15);
        // order 2, ratio 3: 1 + 1/N^2 at 1 and 3 is 2 and 10/9;
        // 10/9 + (10/9 - 2) / 8 = 10/9 - 1/9 = 1
        assert!((richardson_step(2.0, 10.0 / 9.0, 3.0, 2.0) - 1.0).abs() < 1e-15);
    }

    /// The report's regression: uneven sizes were given the order
    /// `ln(d1/d2) / ln(N2/N1)`, which assumes even spacing.
    #[test]
    fn uneven_sizes_recover_the_order() {
        let sizes = [200, 400, 1000];
        let v: Vec<f64> = sizes.iter().map(|&n| 1.0 + 3.0 / n as f64).collect();
        let x = extrapolate(&sizes, &v, false).unwrap();
        assert!((x.order.unwrap() - 1.0).abs() < 1e-9);
        // and the order alone, from the ratio of the changes
        let n = [250.0, 1000.0, 2000.0];
        let e = |n: f64| 1.0 - 0.5 / n;
        let q = (e(n[1]) - e(n[0])).abs() / (e(n[2]) - e(n[1])).abs();
        assert!((self_consistent_order(n, q) - 1.0).abs() < 1e-9);
    }
}

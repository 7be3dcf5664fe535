//! One grid point compared: the exact engine against the chain at one or
//! more sizes, and a verdict on any disagreement.

use impact_chain::ChainConfig;
use impact_model::{Bilayer, Outcome, Timed};
use impact_wave::WaveConfig;
use serde::{Deserialize, Serialize};

/// What to compare and the tolerances that define agreement.
#[derive(Debug, Clone, PartialEq)]
pub struct CompareSettings {
    /// Settings of the exact engine.
    pub wave: WaveConfig,
    /// Chain settings; `masses` is replaced by each of `sizes`.
    pub chain: ChainConfig,
    /// Chain sizes, increasing.
    pub sizes: Vec<usize>,
    /// `|e_chain - e_exact|` above this is a disagreement.
    pub restitution_tolerance: f64,
    /// `|reduced t_c difference|` above this is a contact-class change.
    pub contact_time_tolerance: f64,
    /// Time each run (the times differ between runs; without timing each
    /// is written as 0, so identical runs give identical reports).
    pub timing: bool,
}

/// Why the engines disagree at a point, and so which to trust there.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Verdict {
    /// Within every tolerance.
    Agree,
    /// `|de|` beyond tolerance but shrinking with `N` as the chain converges
    /// (and the extrapolated chain is closer): the chain's finite size; trust
    /// the exact engine.
    FiniteSize,
    /// The chain counts more bounces: dispersion makes its contact flicker
    /// into flights longer than `min(t_i)`; trust the exact engine.
    SpuriousChainBounce,
    /// The chain misses a flight the exact engine resolves (typically a
    /// short, low flight smeared out by dispersion).
    MissedBounce,
    /// The chain's contact history (bounce count and contact-time class) is
    /// what the exact engine itself gives a hair away (within
    /// `boundary_distance` in `x` or `alpha`): the point sits on a regime
    /// boundary, where the chain's smoothed fronts tip a grazing contact
    /// decision. Both are right about their model; the answer is
    /// discontinuous here.
    RegimeBoundary,
    /// The final takeoff is at another wave echo (reduced `t_c` differs) with
    /// no boundary nearby.
    ContactClassFlip,
    /// Beyond tolerance with no explanation above (e.g. not converging).
    Unexplained,
    /// An engine failed; see `error`.
    Failed,
}

impl Verdict {
    /// Every verdict, in the order the report lists them.
    pub const ALL: [Verdict; 8] = [
        Verdict::Agree,
        Verdict::FiniteSize,
        Verdict::RegimeBoundary,
        Verdict::SpuriousChainBounce,
        Verdict::MissedBounce,
        Verdict::ContactClassFlip,
        Verdict::Unexplained,
        Verdict::Failed,
    ];

    /// Short name, used in tables and the JSON.
    pub fn name(self) -> &'static str {
        match self {
            Verdict::Agree => "agree",
            Verdict::FiniteSize => "finite_size",
            Verdict::RegimeBoundary => "regime_boundary",
            Verdict::SpuriousChainBounce => "spurious_chain_bounce",
            Verdict::MissedBounce => "missed_bounce",
            Verdict::ContactClassFlip => "contact_class_flip",
            Verdict::Unexplained => "unexplained",
            Verdict::Failed => "failed",
        }
    }

    /// One sentence for readers of the report.
    pub fn explanation(self) -> &'static str {
        match self {
            Verdict::Agree => "within every tolerance",
            Verdict::FiniteSize => {
                "the chain's error shrinks with N: its finite size; trust the exact engine"
            }
            Verdict::RegimeBoundary => {
                "the exact engine gives the chain's contact history a hair away: a regime boundary (discontinuous t_c or N_b), both engines right"
            }
            Verdict::SpuriousChainBounce => {
                "the chain counts a flight the exact solution does not have (dispersion); trust the exact engine"
            }
            Verdict::MissedBounce => {
                "the chain smears out a flight the exact engine resolves; trust the exact engine"
            }
            Verdict::ContactClassFlip => {
                "the final takeoff happens at another echo, with no regime boundary nearby"
            }
            Verdict::Unexplained => {
                "beyond tolerance without a finite-size, bounce or boundary explanation: look at this point"
            }
            Verdict::Failed => "an engine could not finish",
        }
    }
}

/// Everything known about one grid point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ComparePoint {
    /// Composition `x = L2 / L`.
    pub x: f64,
    /// Stiffness ratio `alpha = E2 / (E1 + E2)`.
    pub alpha: f64,
    /// The exact engine's outcome (none when it failed).
    pub exact: Option<Timed<Outcome>>,
    /// The chain at each size of `sizes`.
    pub chain: Vec<Timed<Outcome>>,
    /// Chain sizes `N`, increasing.
    pub sizes: Vec<usize>,
    /// `e_chain - e_exact` at each size.
    pub restitution_difference: Vec<f64>,
    /// Difference of `t_c / (2 sum t_i)` at each size.
    pub reduced_contact_time_difference: Vec<f64>,
    /// Difference of `n1` at each size.
    pub n1_difference: Vec<Option<f64>>,
    /// Observed order of `|e_chain - e_exact|` in `N` (last two sizes).
    pub observed_order: Option<f64>,
    /// Richardson-extrapolated chain restitution (from the chain alone:
    /// self-consistent order with three sizes or more, the observed order
    /// with two).
    pub extrapolated_restitution: Option<f64>,
    /// For contact-history disagreements: the smallest distance in `x` or
    /// `alpha` at which the exact engine reproduces the chain's bounce count
    /// and contact-time class, if within the probe.
    pub boundary_distance: Option<f64>,
    /// Why the engines disagree here, if they do.
    pub verdict: Verdict,
    /// Why an engine failed: which one (and at which `N`), in its own words.
    pub error: Option<String>,
}

impl ComparePoint {
    /// Both engines ran at every size.
    pub fn complete(&self) -> bool {
        self.exact.is_some() && self.chain.len() == self.sizes.len() && self.error.is_none()
    }

    /// The finest chain outcome (none when any size failed).
    pub fn finest(&self) -> Option<&Outcome> {
        self.chain
            .last()
            .map(|t| &t.value)
            .filter(|_| self.complete())
    }

    /// `e_chain - e_exact` at the finest size (none when any size failed).
    pub fn de(&self) -> Option<f64> {
        self.restitution_difference
            .last()
            .copied()
            .filter(|_| self.complete())
    }

    /// Filtered bounce counts agree at the finest size.
    pub fn bounces_agree(&self) -> Option<bool> {
        Some(self.exact.as_ref()?.bounces == self.finest()?.bounces)
    }
}

/// Runs both engines at one point.
pub fn compare_point(point: Bilayer, settings: &CompareSettings) -> ComparePoint {
    let mut result = ComparePoint {
        x: point.x,
        alpha: point.alpha,
        exact: None,
        chain: Vec::new(),
        sizes: settings.sizes.clone(),
        restitution_difference: Vec::new(),
        reduced_contact_time_difference: Vec::new(),
        n1_difference: Vec::new(),
        observed_order: None,
        extrapolated_restitution: None,
        boundary_distance: None,
        verdict: Verdict::Failed,
        error: None,
    };
    let rod = match point.scene().validate() {
        Ok(rod) => rod,
        Err(e) => {
            result.error = Some(e.to_string());
            return result;
        }
    };
    let clock = |o: Timed<Outcome>| if settings.timing { o } else { o.untimed() };
    let exact = match Timed::try_measure(|| impact_wave::simulate(&rod, &settings.wave)) {
        Ok(o) => clock(o),
        Err(e) => {
            result.error = Some(format!("exact engine: {e}"));
            return result;
        }
    };
    for &n in &settings.sizes {
        let config = ChainConfig {
            masses: n,
            ..settings.chain.clone()
        };
        match Timed::try_measure(|| impact_chain::simulate(&rod, &config)) {
            Ok(o) => result.chain.push(clock(o)),
            Err(e) => {
                result.error = Some(format!("chain at N = {n}: {e}"));
                result.exact = Some(exact);
                return result;
            }
        }
    }
    for c in &result.chain {
        result
            .restitution_difference
            .push(c.restitution - exact.restitution);
        result
            .reduced_contact_time_difference
            .push(c.reduced_contact_time - exact.reduced_contact_time);
        result.n1_difference.push(match (c.n1, exact.n1) {
            (Some(a), Some(b)) => Some(a - b),
            _ => None,
        });
    }
    result.observed_order = observed_order(&settings.sizes, &result.restitution_difference);
    let chain: Vec<Outcome> = result.chain.iter().map(|t| t.value.clone()).collect();
    result.extrapolated_restitution = extrapolate(&settings.sizes, &chain, result.observed_order);
    result.exact = Some(exact);
    result.boundary_distance = boundary_distance(point, &result, settings);
    result.verdict = classify(&result, settings);
    result
}

/// Distances at which the exact engine is probed around a point whose
/// contact history disagrees with the chain's.
const PROBES: [f64; 2] = [1e-4, 1e-3];

/// Probes the exact engine around `point` (cheap: microseconds a run) for
/// the chain's contact history: same filtered `N_b` and reduced `t_c` within
/// tolerance.
fn boundary_distance(point: Bilayer, p: &ComparePoint, s: &CompareSettings) -> Option<f64> {
    let (exact, chain) = (p.exact.as_ref()?, p.finest()?);
    let dtc = (chain.reduced_contact_time - exact.reduced_contact_time).abs();
    if chain.bounces == exact.bounces && dtc <= s.contact_time_tolerance {
        return None;
    }
    for h in PROBES {
        for (dx, da) in [(h, 0.0), (-h, 0.0), (0.0, h), (0.0, -h)] {
            let Ok(near) = Bilayer::new(point.x + dx, point.alpha + da) else {
                continue;
            };
            let Ok(rod) = near.scene().validate() else {
                continue;
            };
            let Ok(o) = impact_wave::simulate(&rod, &s.wave) else {
                continue;
            };
            if o.bounces == chain.bounces
                && (o.reduced_contact_time - chain.reduced_contact_time).abs()
                    <= s.contact_time_tolerance
            {
                return Some(h);
            }
        }
    }
    None
}

/// Order `p` of `|de| ~ N^-p` from the last two sizes.
fn observed_order(sizes: &[usize], de: &[f64]) -> Option<f64> {
    let k = de.len();
    if k < 2 {
        return None;
    }
    let (e1, e2) = (de[k - 2].abs(), de[k - 1].abs());
    let ratio = sizes[k - 1] as f64 / sizes[k - 2] as f64;
    (e1 > 0.0 && e2 > 0.0 && ratio > 1.0).then(|| (e1 / e2).ln() / ratio.ln())
}

/// Richardson extrapolation `e_inf = e_k + (e_k - e_{k-1}) / (r^p - 1)`.
fn extrapolate(sizes: &[usize], chain: &[Outcome], observed: Option<f64>) -> Option<f64> {
    let k = chain.len();
    if k < 2 {
        return None;
    }
    let e: Vec<f64> = chain.iter().map(|o| o.restitution).collect();
    let r = sizes[k - 1] as f64 / sizes[k - 2] as f64;
    let p = if k >= 3 {
        let (d1, d2) = ((e[k - 2] - e[k - 3]).abs(), (e[k - 1] - e[k - 2]).abs());
        let n = [
            sizes[k - 3] as f64,
            sizes[k - 2] as f64,
            sizes[k - 1] as f64,
        ];
        if d1 > 0.0 && d2 > 0.0 {
            impact_model::numerics::self_consistent_order(n, d1 / d2)
        } else {
            observed?
        }
    } else {
        observed?
    };
    let p = p.clamp(0.25, 4.0);
    Some(impact_model::numerics::richardson_step(
        e[k - 2],
        e[k - 1],
        r,
        p,
    ))
}

fn classify(p: &ComparePoint, s: &CompareSettings) -> Verdict {
    let (Some(exact), Some(chain), Some(de)) = (p.exact.as_ref(), p.finest(), p.de()) else {
        return Verdict::Failed;
    };
    let dtc = p
        .reduced_contact_time_difference
        .last()
        .copied()
        .unwrap_or(0.0);
    let e_ok = de.abs() <= s.restitution_tolerance;
    let tc_ok = dtc.abs() <= s.contact_time_tolerance;
    if e_ok && tc_ok && chain.bounces == exact.bounces {
        return Verdict::Agree;
    }
    if p.boundary_distance.is_some() {
        return Verdict::RegimeBoundary;
    }
    if chain.bounces > exact.bounces {
        return Verdict::SpuriousChainBounce;
    }
    if chain.bounces < exact.bounces {
        return Verdict::MissedBounce;
    }
    if !tc_ok {
        return Verdict::ContactClassFlip;
    }
    // e beyond tolerance with the same contact history: finite size if the
    // error shrinks with N and extrapolation moves the chain towards exact
    let shrinking = p
        .restitution_difference
        .windows(2)
        .all(|w| w[1].abs() < w[0].abs())
        && p.restitution_difference.len() >= 2;
    let closer = p
        .extrapolated_restitution
        .is_some_and(|r| (r - exact.restitution).abs() < de.abs());
    if shrinking && closer {
        Verdict::FiniteSize
    } else {
        Verdict::Unexplained
    }
}

/// Figures over all points.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Points compared.
    pub points: usize,
    /// Points where an engine failed.
    pub failed: usize,
    /// Largest `|e_chain - e_exact|` at the finest chain size.
    pub max_abs_de: f64,
    /// Median `|e_chain - e_exact|` at the finest chain size.
    pub median_abs_de: f64,
    /// Share of points where the filtered bounce counts agree.
    pub bounces_agree: f64,
    /// Share of points within every tolerance.
    pub agree: f64,
    /// How many points got each verdict.
    pub verdicts: Vec<(Verdict, usize)>,
    /// Indices of the points with the largest `|de|`, worst first.
    pub worst: Vec<usize>,
}

/// Summarises compared points (at the finest chain size).
pub fn summarize(points: &[ComparePoint]) -> Summary {
    let mut de: Vec<f64> = points.iter().filter_map(|p| p.de()).map(f64::abs).collect();
    de.sort_by(f64::total_cmp);
    let median = if de.is_empty() {
        f64::NAN
    } else if de.len() % 2 == 1 {
        de[de.len() / 2]
    } else {
        0.5 * (de[de.len() / 2 - 1] + de[de.len() / 2])
    };
    let compared = points
        .iter()
        .filter(|p| p.bounces_agree().is_some())
        .count()
        .max(1);
    let mut worst: Vec<usize> = (0..points.len())
        .filter(|&i| points[i].de().is_some())
        .collect();
    worst.sort_by(|&a, &b| {
        points[b]
            .de()
            .unwrap_or(0.0)
            .abs()
            .total_cmp(&points[a].de().unwrap_or(0.0).abs())
            .then(a.cmp(&b))
    });
    worst.truncate(12);
    Summary {
        points: points.len(),
        failed: points
            .iter()
            .filter(|p| p.verdict == Verdict::Failed)
            .count(),
        max_abs_de: de.last().copied().unwrap_or(f64::NAN),
        median_abs_de: median,
        bounces_agree: points
            .iter()
            .filter(|p| p.bounces_agree() == Some(true))
            .count() as f64
            / compared as f64,
        agree: points
            .iter()
            .filter(|p| p.verdict == Verdict::Agree)
            .count() as f64
            / points.len().max(1) as f64,
        verdicts: Verdict::ALL
            .iter()
            .map(|&v| (v, points.iter().filter(|p| p.verdict == v).count()))
            .filter(|(_, n)| *n > 0)
            .collect(),
        worst,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn order_and_extrapolation_recover_a_power_law() {
        // e(N) = 1 - 0.5 N^-0.6 against exact 1
        let sizes = vec![250, 500, 1000];
        let e = |n: f64| 1.0 - 0.5 * n.powf(-0.6);
        let de: Vec<f64> = sizes.iter().map(|&n| e(n as f64) - 1.0).collect();
        let p = observed_order(&sizes, &de).unwrap();
        assert!((p - 0.6).abs() < 1e-12);
        let mut o: Vec<Outcome> = Vec::new();
        for &n in &sizes {
            o.push(Outcome::from_history(
                impact_model::EngineKind::Chain,
                e(n as f64),
                &impact_model::ContactHistory::new(),
                &[1.0],
                1.0,
                impact_model::StopReason::Escaped,
            ));
        }
        let r = extrapolate(&sizes, &o, Some(p)).unwrap();
        assert!((r - 1.0).abs() < 1e-12, "{r}");
    }
}

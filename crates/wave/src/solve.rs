//! One impact, start to finish, with an honest error estimate: which runs to
//! make, in which arithmetic, and what their differences say.
//!
//! - Exact when it fits: most scenes (every point of the paper's grid) need
//!   at most a few times `10^4` events. Nothing is merged; the error is what
//!   dropped fronts can carry plus rounding.
//! - Otherwise merged: small fronts are deposited on a lattice of birth
//!   times in each lane (their jump and first moment kept, so momentum is
//!   exact and energy can only decrease), which bounds every lane's
//!   population and so the work and the memory; quiet fast layers leap
//!   their ringing in closed form. The merge error is measured, not
//!   assumed: each level of lattice spacings is set against the level twice
//!   as coarse (the error is of first order in the spacings) and against a
//!   run with the bottom layer's modulus changed by `1e-12` (rods that
//!   chatter for hundreds of bounces amplify any perturbation, a merge among
//!   them, chaotically: a steel base under rubber moves `e` by `1e-4` for
//!   that change). Twice the larger difference is reported. Levels halve
//!   the spacings while the estimate keeps falling and the event budget
//!   allows; the finest is reported.
//! - Rounding: estimated a priori from the number of events, unless a
//!   contact decision of an exact run came within `1e-7` of going the other
//!   way or the rod chattered; then the run is repeated in double-double
//!   arithmetic, the repeat's value is reported, and the difference says
//!   what double precision alone would have lost.

use crate::config::{Precision, Resolution, WaveConfig};
use crate::engine::{Tracer, WaveEngine};
use crate::error::WaveError;
use crate::real::Real;
use impact_model::{ErrorEstimate, Outcome, Rod, StopReason};
use std::time::Instant;
use twofloat::TwoFloat;

/// The lattice spacing of the slow lanes (fraction of the longest transit
/// time) in a merged run: a slow lane then holds at most a thousand fronts.
/// Coarser slow lattices cost accuracy where large fronts return (measured:
/// `3.5e-4` in `e` at the paper's hard corner with `1e-2`, nothing with
/// `1e-3`).
const SLOW_WINDOW: f64 = 1e-3;

/// The lattice spacing of every lane as a fraction of its own transit time
/// in a merged run. Fast layers whose neighbours stay quiet for many of
/// their round trips leap over them (see `leap`); the others ring on a
/// lattice of twenty points a transit.
const LANE_WINDOW: f64 = 0.05;

/// Relative rounding error per event assumed a priori: a few operations of
/// relative error `2^-53` each. Tested against double-double reruns.
const ROUNDING_PER_EVENT: f64 = 4.0 * f64::EPSILON;

/// Separations from which rounding may accumulate (chatter): the run is
/// checked in double-double.
const CHATTER: u32 = 100;

/// Longest run (in events) repeated in double-double (about ten times
/// slower than double).
const DOUBLE_DOUBLE_EVENTS: u64 = 1_000_000;

/// What [`solve`] returns: the outcome with its error estimate, and the
/// double-precision engine of the reported run (for its records).
pub struct Solution {
    pub outcome: Outcome,
    pub engine: WaveEngine,
}

/// Runs one impact to the end with the given settings; the outcome carries
/// its error estimate.
pub fn simulate(rod: &Rod, config: &WaveConfig) -> Result<Outcome, WaveError> {
    Ok(solve(rod, config)?.outcome)
}

/// [`simulate`], keeping the engine of the reported run.
pub fn solve(rod: &Rod, config: &WaveConfig) -> Result<Solution, WaveError> {
    let start = Instant::now();
    let mut parts = Vec::new();
    let (fine, merged) = match config.resolution {
        Resolution::Exact => (run::<f64>(rod, config.clone())?, None),
        Resolution::Merged {
            per_transit,
            per_longest,
        } => {
            let l = ladder(rod, config, per_transit, per_longest, 0, 0.0)?;
            (l.0, Some(l.1))
        }
        Resolution::Auto {
            exact_events,
            budget_events,
            target,
        } => {
            let exact = WaveConfig {
                resolution: Resolution::Exact,
                max_events: exact_events.min(config.max_events),
                ..config.clone()
            };
            match run::<f64>(rod, exact) {
                Ok(e) => (e, None),
                Err(WaveError::EventLimit { .. }) => {
                    parts.push(format!(
                        "the exact run needs more than {exact_events} events"
                    ));
                    let l = ladder(rod, config, LANE_WINDOW, SLOW_WINDOW, budget_events, target)?;
                    (l.0, Some(l.1))
                }
                Err(e) => return Err(e),
            }
        }
    };
    let mut estimate = ErrorEstimate {
        dropped: fine.dropped_error_bound(),
        ..ErrorEstimate::default()
    };
    if let Some(check) = &merged {
        estimate.merged = check.bound;
        parts.push(check.method.clone());
    }
    let mut outcome = finished(fine.outcome(), &fine)?;
    let decisions = fine.decisions();
    let risky = decisions.near_grazing > 0 || outcome.separations >= CHATTER;
    let rerun = match config.precision {
        Precision::Double => false,
        // merged runs are checked for chaos by the perturbed run;
        // double-double is for exact runs
        Precision::Checked => risky && merged.is_none() && fine.events() <= DOUBLE_DOUBLE_EVENTS,
        Precision::DoubleDouble => true,
    };
    if rerun {
        let dd_config = WaveConfig {
            resolution: match &merged {
                Some(check) => Resolution::Merged {
                    per_transit: check.per_transit,
                    per_longest: check.per_longest,
                },
                None => Resolution::Exact,
            },
            ..config.clone()
        };
        let dd = run::<TwoFloat>(rod, dd_config)?;
        let dd_outcome = finished(dd.outcome(), &dd)?;
        let loss = (dd_outcome.restitution - outcome.restitution).abs();
        estimate.double_precision_loss = Some(loss);
        // double-double has 2^-52 of double's rounding per operation: both
        // the per-event part and whatever amplified double's error shrink so
        estimate.rounding = f64::EPSILON * (ROUNDING_PER_EVENT * dd.events() as f64 + loss);
        parts.push(format!(
            "rounding: repeated in double-double ({}; double precision alone was off by {loss:.1e})",
            if risky {
                format!(
                    "{} near-grazing decisions, {} separations",
                    decisions.near_grazing, outcome.separations
                )
            } else {
                "asked for".to_string()
            }
        ));
        outcome = Outcome {
            events: outcome.events,
            truncation: outcome.truncation,
            ..dd_outcome
        };
    } else {
        estimate.rounding = ROUNDING_PER_EVENT * fine.events() as f64;
        parts.push(format!(
            "rounding: {:.0e} per event{}",
            ROUNDING_PER_EVENT,
            if risky && merged.is_some() {
                " (its amplification by chatter is measured by the perturbed run)"
            } else if risky {
                " (the run is too long to repeat in double-double)"
            } else {
                ""
            }
        ));
    }
    if estimate.dropped > 0.0 {
        parts.push("dropped: twice the impulse the dropped fronts could carry".into());
    }
    estimate.method = parts.join("; ");
    let mut outcome = outcome.with_error(estimate);
    outcome.elapsed_seconds = start.elapsed().as_secs_f64();
    Ok(Solution {
        outcome,
        engine: fine,
    })
}

/// One run in arithmetic `R`.
fn run<R: Real>(rod: &Rod, config: WaveConfig) -> Result<Tracer<R>, WaveError> {
    let mut engine = Tracer::<R>::new(rod, config)?;
    while engine.stopped().is_none() {
        engine.step()?;
    }
    Ok(engine)
}

/// What the merged runs say about the reported one.
struct MergeCheck {
    per_transit: f64,
    per_longest: f64,
    /// `|e - e(twice as coarse)|`.
    doubled: f64,
    bound: f64,
    method: String,
}

/// Merged runs from spacings `(p, l)` down by halves: each level set
/// against the one twice as coarse and against a perturbed twin, while the
/// estimate keeps falling (by at least half) and the next level fits the
/// budget of event-loop steps (0: one level only) and the bound is above
/// `target`. The finest level is reported.
fn ladder(
    rod: &Rod,
    config: &WaveConfig,
    p: f64,
    l: f64,
    budget: u64,
    target: f64,
) -> Result<(WaveEngine, MergeCheck), WaveError> {
    let at = |p: f64, l: f64| WaveConfig {
        resolution: Resolution::Merged {
            per_transit: p,
            per_longest: l,
        },
        precision: Precision::Double,
        ..config.clone()
    };
    let mut scene = rod.scene().clone();
    scene.layers[0].modulus *= 1.0 + 1e-12;
    let nudged = scene.validate().unwrap_or_else(|_| rod.clone());
    // the first level: the finest spacings (from the given ones, four times
    // coarser at each try) whose run fits a quarter of the budget; a lane
    // rings on its lattice unless its layer can leap, so the cost is not
    // known before trying
    let (mut p, mut l) = (p, l);
    let mut used = 0;
    let mut first = None;
    if budget > 0 {
        let cap = (budget / 4).max(1);
        // the level and its coarser check both stay within the coarsest
        // lattice a lane allows
        while 2.0 * p <= COARSEST {
            let capped = WaveConfig {
                max_events: cap.min(config.max_events),
                ..at(p, l)
            };
            match run::<f64>(rod, capped) {
                Ok(e) => {
                    used += e.steps();
                    first = Some(e);
                    break;
                }
                Err(WaveError::EventLimit { .. }) => {
                    used += cap;
                    if 2.0 * p >= COARSEST {
                        break;
                    }
                    // four times coarser, or as coarse as allowed
                    let grow = (4.0f64).min(COARSEST / (2.0 * p));
                    p *= grow;
                    l *= grow;
                }
                Err(e) => return Err(e),
            }
        }
    }
    // the runs of a level are independent: the coarser check (first level
    // only), the level itself and its perturbed twin run side by side
    let (coarser_first, (fine_first, twin_first)) = rayon::join(
        || run::<f64>(rod, at(2.0 * p, 2.0 * l)),
        || {
            rayon::join(
                || match first.take() {
                    Some(e) => Ok((e, 0)),
                    None => run::<f64>(rod, at(p, l)).map(|e| {
                        let steps = e.steps();
                        (e, steps)
                    }),
                },
                || run::<f64>(&nudged, at(p, l)),
            )
        },
    );
    let mut coarser = coarser_first?;
    used += coarser.steps();
    let mut pending = Some((fine_first?, twin_first?));
    let mut level = 0;
    let mut last: Option<(WaveEngine, MergeCheck)> = None;
    loop {
        let ((fine, fine_steps), twin) = match pending.take() {
            Some(runs) => runs,
            None => {
                let (fine, twin) = rayon::join(
                    || run::<f64>(rod, at(p, l)),
                    || run::<f64>(&nudged, at(p, l)),
                );
                let fine = fine?;
                let steps = fine.steps();
                ((fine, steps), twin?)
            }
        };
        used += fine_steps + twin.steps();
        let e = fine.restitution();
        let doubled = (e - coarser.restitution()).abs();
        let perturbed = (e - twin.restitution()).abs();
        // a lucky agreement with the coarser level is not trusted alone:
        // the previous level's difference counts too
        let previous = last.as_ref().map_or(0.0, |(_, c)| c.doubled);
        let bound = 2.0 * doubled.max(perturbed).max(previous);
        let check = MergeCheck {
            per_transit: p,
            per_longest: l,
            doubled,
            bound,
            method: format!(
                "merged: twice the larger difference from spacings twice as coarse ({doubled:.1e}) and from the bottom's modulus changed by 1e-12 ({perturbed:.1e}); lattice spacings {p:.3e} of each transit, {l:.1e} of the longest ({} levels, {used} event-loop steps in all)",
                level + 1
            ),
        };
        if std::env::var("LADDER").is_ok() {
            eprintln!(
                "level {level}: p {p:.2e} l {l:.2e} e {e:.12} doubled {doubled:.2e} perturbed {perturbed:.2e} steps fine {} twin {} used {used}",
                fine.steps(),
                twin.steps()
            );
        }
        // refining that no longer helps (a chaotic rod) stops; the finest
        // level is reported with its own estimate
        let improving = last.as_ref().is_none_or(|(_, c)| bound <= 0.5 * c.bound);
        if !improving {
            return Ok((fine, check));
        }
        let next_cost = 3 * (fine.steps() + twin.steps());
        let done = budget == 0 || bound <= target || used + next_cost > budget || p <= FINEST;
        if done {
            return Ok((fine, check));
        }
        coarser = fine;
        last = Some((coarser.clone(), check));
        p /= 2.0;
        l /= 2.0;
        level += 1;
    }
}

/// The finest lattice a merged ladder goes down to (fraction of a transit).
const FINEST: f64 = 1e-4;

/// The coarsest lattice a lane may have (fraction of its transit,
/// [`crate::engine`] refuses more): a front deposited on the lattice point
/// before its birth must still arrive after it was born.
pub(crate) const COARSEST: f64 = 0.5;

/// An outcome that is final, or the reason it is not.
fn finished<R: Real>(outcome: Outcome, engine: &Tracer<R>) -> Result<Outcome, WaveError> {
    if outcome.stop_reason == StopReason::HorizonInContact {
        return Err(WaveError::Unfinished {
            time: engine.time(),
            partial: outcome.restitution,
            outcome: Box::new(outcome),
        });
    }
    Ok(outcome)
}

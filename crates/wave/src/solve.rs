//! One impact, start to finish, with an honest error estimate: which runs to
//! make, in which arithmetic, and what their differences say.
//!
//! - Exact when it fits: most scenes (every point of the paper's grid) need
//!   at most a few times `10^4` events. Nothing is merged (quiet layers leap
//!   their ringing in closed form, every front kept); the error is what
//!   dropped fronts can carry plus rounding.
//! - Otherwise merged: small fronts are deposited on a lattice of birth
//!   times in each lane (their jump and first moment kept, so momentum is
//!   exact and energy can only decrease), which bounds every lane's
//!   population and so the work and the memory; quiet fast layers leap
//!   their ringing in closed form. The merge error is measured, not
//!   assumed: lattices halve from a coarse start, and each level is set
//!   against up to four coarser ones (the error is of first order in the
//!   spacings, but falls in steps, so one comparison can land on a plateau)
//!   and against a run with the bottom layer's modulus changed by `1e-12`
//!   (rods that chatter for hundreds of bounces amplify any perturbation, a
//!   merge among them, chaotically: a steel base under rubber moves `e` by
//!   `1e-4` for that change), or three such runs where the first shows
//!   contacts flipping (`twins.rs`). Twice the larger estimate is reported. Levels
//!   halve the spacings until the estimate meets the target or the event
//!   budget is spent; the finest is reported.
//! - Tolerances: an exact run that combined arrivals more than rounding
//!   apart (the simultaneity window) or took a wall strain within the
//!   grazing tolerance as zero is rerun with both tolerances tighter, and
//!   twice the change in `e` is that part of the bound.
//! - Rounding: estimated a priori from the number of events, unless a
//!   contact decision of an exact run came within `1e-7` of going the other
//!   way or the rod chattered; then the run is repeated in double-double
//!   arithmetic, the repeat's value is reported, and the difference says
//!   what double precision alone would have lost.

use crate::config::{Precision, Resolution, WaveConfig};
use crate::engine::{Decisions, Tracer, WaveEngine};
use crate::error::WaveError;
use crate::exact_again as again;
use crate::ladder::{fixed_lattice, ladder};
use crate::real::DoubleDouble;
use crate::real::Real;
use impact_model::{ErrorEstimate, Outcome, Rod, StopReason};

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
    /// The outcome, with its error estimate.
    pub outcome: Outcome,
    /// The double-precision engine of the reported run, holding its records.
    pub engine: WaveEngine,
}

/// Runs one impact to the end with the given settings; the outcome carries
/// its error estimate.
pub fn simulate(rod: &Rod, config: &WaveConfig) -> Result<Outcome, WaveError> {
    Ok(solve(rod, config)?.outcome)
}

/// What a long solve has done so far, for a caller that shows it (the
/// command line's spinner on a terminal). Only merged ladders report: an
/// exact run takes milliseconds, a ladder of a many-layer rod seconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum LadderProgress {
    /// The exact run needed more than `exact_events` events: merged
    /// lattices follow, halved from the coarsest.
    LadderStarted {
        /// The exact run's limit that was reached.
        exact_events: u64,
    },
    /// A level of the ladder finished.
    LevelDone {
        /// 1 for the coarsest.
        level: usize,
        /// Its lattice spacing, as a fraction of each lane's transit.
        per_transit: f64,
        /// Its `e`.
        restitution: f64,
        /// The bound its comparisons give (two levels at least; the
        /// refinement's part alone for a level run without its twin, the
        /// second unless it is reported; the reported bound is set when
        /// the ladder stops).
        bound: f64,
        /// Work done so far (loop iterations, and leaps' fronts and cells).
        work: u64,
    },
    /// The ladder's levels did not converge, and the first exact run's
    /// growth says an exact run may fit the ladder's budget: it is tried
    /// again, allowed that budget, and reported if it finishes.
    ExactAgain {
        /// The events it is allowed.
        events: u64,
    },
    /// The level reported differs from its twin (the bottom's modulus
    /// `1e-12` stiffer) by so much that contacts flip on a nudge: two more
    /// twins run before the bound is set (a level's run more).
    FurtherTwins {
        /// The level reported, 1 for the coarsest.
        level: usize,
        /// `|e - e(twin)|`.
        first_difference: f64,
    },
}

/// [`simulate`], keeping the engine of the reported run.
pub fn solve(rod: &Rod, config: &WaveConfig) -> Result<Solution, WaveError> {
    solve_observed(rod, config, &|_| {})
}

/// [`solve`], telling `observe` how a merged ladder gets on (see
/// [`LadderProgress`]); the result is the same.
pub fn solve_observed(
    rod: &Rod,
    config: &WaveConfig,
    observe: &dyn Fn(LadderProgress),
) -> Result<Solution, WaveError> {
    config.check()?;
    let mut parts = Vec::new();
    let (mut set_aside, mut in_vain) = (None, None);
    let (fine, merged) = match config.resolution {
        Resolution::Exact => (run::<f64>(rod, config.clone())?, None),
        Resolution::Merged {
            per_transit,
            per_longest,
        } => {
            let l = fixed_lattice(rod, config, per_transit, per_longest)?;
            (l.0, Some(l.1))
        }
        Resolution::Auto {
            exact_events,
            budget_events,
            target,
            exact_again,
        } => match again::first_run(rod, again::exact_within(config, exact_events)) {
            (Ok(e), _) => (e, None),
            (Err(WaveError::EventLimit { events, time }), halfway) => {
                parts.push(format!(
                    "the exact run needs more than {exact_events} events"
                ));
                observe(LadderProgress::LadderStarted { exact_events });
                let (fine, check) = ladder(rod, config, budget_events, target, observe)?;
                let first = halfway.map(|halfway| again::FirstRun {
                    halfway,
                    stopped: (events, time),
                });
                let after = match first.filter(|_| exact_again) {
                    Some(first) => {
                        again::after_ladder(rod, config, (&fine, &check), first, observe)
                    }
                    None => again::Again::NotTried,
                };
                match after {
                    again::Again::Finished(exact, note, ladder) => {
                        parts.push(note);
                        set_aside = Some(ladder);
                        (*exact, None)
                    }
                    again::Again::InVain(events, note) => {
                        parts.push(note);
                        in_vain = Some(events);
                        (fine, Some(check))
                    }
                    again::Again::NotTried => (fine, Some(check)),
                }
            }
            (Err(e), _) => return Err(e),
        },
    };
    let mut estimate = ErrorEstimate {
        dropped: fine.dropped_error_bound(),
        ladder_set_aside: set_aside,
        exact_again_unfinished: in_vain,
        ..ErrorEstimate::default()
    };
    if let Some(check) = &merged {
        estimate.merged = check.bound;
        estimate.merged_converging = Some(check.converging);
        estimate.merged_observed_order = check.order;
        estimate.ladder_stop = check.stop;
        parts.push(check.method.clone());
        for ((a, b), one) in fine
            .answered_blocks()
            .into_iter()
            .zip(fine.blocks_on_one_lattice())
        {
            estimate.answered_blocks.push([a, b]);
            parts.push(format!(
                "the layers of t{} to t{} answered as one block by its traced response (fast_blocks){}",
                a + 1,
                b + 1,
                if one {
                    ", traced on one lattice, its finest layer's times a power of two in every layer (one_lattice_blocks)"
                } else {
                    ""
                }
            ));
        }
        for f in fine.nested_layers() {
            estimate.nested_layers.push(f);
            parts.push(format!(
                "within it, the layer of t{} answered by its own response (nest_blocks)",
                f + 1
            ));
        }
        if let Some(((a, b), fronts)) = fine.stepped_group() {
            estimate.stepped_group = Some([a, b]);
            parts.push(format!(
                "the layers of t{} to t{} followed in steps between the wall's decisions, {fronts} of their boundary events (step_bottom_group)",
                a + 1,
                b + 1
            ));
        }
    }
    let mut outcome = finished(fine.outcome(), &fine)?;
    let decisions = fine.decisions();
    if merged.is_none() && decisions.within_tolerance > 0 {
        let (effect, method) = tolerance_effect(rod, config, &outcome, &decisions);
        estimate.tolerances = effect;
        parts.push(method);
    }
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
        let dd = run::<DoubleDouble>(rod, dd_config)?;
        let dd_outcome = finished(dd.outcome(), &dd)?;
        let loss = (dd_outcome.restitution - outcome.restitution).abs();
        estimate.double_precision_loss = Some(loss);
        // double-double has 2^-52 of double's rounding per operation: both
        // the per-event part and whatever amplified double's error shrink
        // so; the value is reported as a double, which adds an ulp of `e`
        // (found against the tracker in 40 digits: 1.1e-16 off under a
        // bound of 2e-30 before)
        estimate.rounding = f64::EPSILON
            * (ROUNDING_PER_EVENT * dd.events() as f64 + loss + dd_outcome.restitution.abs());
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
    outcome.wall_contact = rod.wall_contact();
    Ok(Solution {
        outcome,
        engine: fine,
    })
}

/// How much tighter the tolerances of the rerun that measures their effect
/// are: the configured simultaneity window and the grazing tolerance. The
/// window's rounding part stays (`window::Window`), so the rerun cannot split
/// true ties and measure its own rounding.
const TIGHTER: f64 = 1e-2;

/// What the engine's tolerances did to `e` in an exact run that used them:
/// twice the change when they are made [`TIGHTER`]. Without this, arrivals
/// `1e-10` apart combined as one, or a chatter cut short by the grazing
/// tolerance, moved `e` by up to `2e-11` on the paper's grid, thirty times
/// the rounding bound (found against `scripts/tracker.py` in 40-digit
/// arithmetic; `tests/integration/tracker.rs`). Over 874 points of the
/// grid (the 163 that use a tolerance among them) the bound now holds
/// everywhere, the closest at 0.82 of it.
fn tolerance_effect(
    rod: &Rod,
    config: &WaveConfig,
    reported: &Outcome,
    decisions: &Decisions,
) -> (f64, String) {
    let uses = format!(
        "{} arrivals combined and {} wall strains taken as zero by a tolerance",
        decisions.within_tolerance - decisions.grazed,
        decisions.grazed
    );
    let tight = WaveConfig {
        resolution: Resolution::Exact,
        simultaneity: config.simultaneity * TIGHTER,
        grazing_tolerance: config.grazing_tolerance * TIGHTER,
        ..config.clone()
    };
    match run::<f64>(rod, tight).and_then(|t| finished(t.outcome(), &t)) {
        Ok(o) => (
            2.0 * (o.restitution - reported.restitution).abs(),
            format!("tolerances: {uses}; twice the change in e with them {TIGHTER:.0e} as wide"),
        ),
        // the check could not be made: claim nothing (e and e_exact both
        // lie in [0, 1], so a bound of 1 is true and says so in a number
        // every output can carry)
        Err(e) => (
            1.0,
            format!("tolerances: {uses}, and the check with tighter ones did not finish ({e})"),
        ),
    }
}

/// One run in arithmetic `R`.
pub(crate) fn run<R: Real>(rod: &Rod, config: WaveConfig) -> Result<Tracer<R>, WaveError> {
    let mut engine = Tracer::<R>::new(rod, config)?;
    while engine.stopped().is_none() {
        engine.step()?;
    }
    Ok(engine)
}

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

//! The exact run again, where a ladder's levels do not converge.
//!
//! A merged ladder's bound is an estimate from how `e` changes between
//! lattices, and where its last three levels do not shrink at order 0.5
//! the outcome says "the merged estimate may be low, by any factor"
//! (`convergence.rs`): such bounds have been found 1.4 to 3,600 times too
//! small (README). The exact run was first allowed `exact_events`
//! (`2e5` by default, a few milliseconds), so that most scenes that merge
//! lose no time to it; but many need a few times that, and an exact run
//! leaves nothing to estimate. So where the levels do not converge, and
//! the way the first exact run's work grew says that a run within the
//! ladder's own budget may finish ([`COVERED`], [`PREDICTED_SHARE`]), the
//! exact run is tried again, allowed that budget (at most
//! [`MOST_EVENTS`]). If it finishes, its
//! outcome is reported (exact, with its own bound) and the ladder's is
//! kept beside it for comparison (`ladder_set_aside`); if not, the
//! ladder's stands as before. Converging ladders are left alone: their
//! bounds have held against every exact run and finer ladder since the
//! order rule (README), and a second run would cost them time for a bound
//! they have.
//!
//! Measured (`scripts/survey-layers.py`'s layer draws, seeds 7, 3, 29,
//! 53 and most of 41, and the materials draw's seed 13, each merged rod
//! run exactly with up to `2e7` events): of 173 merged rods, 29 finish
//! exactly, 16 of them within `4e6` events. Materials seed 13's rod 27
//! (brass and aluminium under rubber and polyurethane) reported
//! `0.6462448 ± 3.9e-4` at order `-0.3`; its exact run, 1.19 M events in
//! 68 ms, gives `0.6467884`, 1.4 bounds away.
//!
//! Everything here is counted in events, so the same scene gives the same
//! outcome on any machine and any number of threads.

use crate::config::{Resolution, WaveConfig};
use crate::engine::{Tracer, WaveEngine};
use crate::error::WaveError;
use crate::ladder::MergeCheck;
use crate::solve::{LadderProgress, run};
use impact_model::{Rod, SetAsideLadder};

/// Where the first exact run stood: the work it had done and the time it
/// had reached (scene units), at the first event past half its limit and
/// where it stopped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct FirstRun {
    pub halfway: (u64, f64),
    pub stopped: (u64, f64),
}

impl FirstRun {
    /// The work an exact run would take to reach `end`, from how the
    /// first one's work grew between its halfway point and its stop, as a
    /// power of the time covered: `n (end / t)^g`, `g = ln(n / n_half) /
    /// ln(t / t_half)`. Infinite where the time did not move.
    pub fn work_to(&self, end: f64) -> f64 {
        let ((n_half, t_half), (n, t)) = (self.halfway, self.stopped);
        if !(t > t_half && t_half > 0.0 && n > n_half) {
            return f64::INFINITY;
        }
        let power = (n as f64 / n_half as f64).ln() / (t / t_half).ln();
        n as f64 * (end / t).max(1.0).powf(power)
    }
}

/// `config` for an exact run allowed `max_events` (and no more than
/// `config`'s own limit).
pub(crate) fn exact_within(config: &WaveConfig, max_events: u64) -> WaveConfig {
    WaveConfig {
        resolution: Resolution::Exact,
        max_events: max_events.min(config.max_events),
        ..config.clone()
    }
}

/// The exact run allowed `config.max_events`, and where it stood halfway
/// through them (`None` if it finished, or stopped otherwise, first).
pub(crate) fn first_run(
    rod: &Rod,
    config: WaveConfig,
) -> (Result<WaveEngine, WaveError>, Option<(u64, f64)>) {
    let half = config.max_events / 2;
    let mut engine = match Tracer::<f64>::new(rod, config) {
        Ok(engine) => engine,
        Err(e) => return (Err(e), None),
    };
    let mut halfway = None;
    while engine.stopped().is_none() {
        if halfway.is_none() && engine.steps() >= half {
            halfway = Some((engine.steps(), engine.time()));
        }
        if let Err(e) = engine.step() {
            return (Err(e), halfway);
        }
    }
    (Ok(engine), halfway)
}

/// How much of the ladder's budget the first exact run's growth must
/// predict at most for the second to be tried: half, as the prediction
/// ([`FirstRun::work_to`]) missed the events of the surveys' exact runs
/// by up to a factor of 3.8 either way (layer survey seed 29's rod 1:
/// `1.8e6` predicted, `6.8e6` taken; seed 41's rod 11: `6.2e6`, `1.8e6`).
/// With [`COVERED`], over their 173 merged rods the gates pass 15 (every
/// rod, converging or not), of which 11 finish within `4e6` events, and
/// none of the slow rods (seed 7's rod 15 covered `0.17 %` of its run,
/// and its growth predicts `8e15` events).
pub(crate) const PREDICTED_SHARE: f64 = 0.5;

/// How much of the run the first exact run must have covered for its
/// growth to be extrapolated at all: an eighth (a prediction over more
/// than eight times the time it was fitted on is not trusted). Layer
/// survey seed 53's rod 25 covered a sixteenth; its prediction said
/// `1.5e6` events and its exact run does not finish within `2e7`, and
/// trying cost it 0.3 s and 60 MB.
pub(crate) const COVERED: f64 = 0.125;

/// The most events the exact run is allowed again, whatever the budget:
/// an exact run holds every front it has not dropped, and those stopped
/// at `4e6` events peaked at 45 to 107 MB resident, so a budget of `1e9`
/// (which a user may give the ladder, whose memory it does not grow)
/// could have let one fill the machine. `2e7` events keep it near half a
/// gigabyte and a second or two.
pub(crate) const MOST_EVENTS: u64 = 20_000_000;

/// What the exact run again came to.
pub(crate) enum Again {
    /// Not tried: the levels converge, or the first run's growth says it
    /// would not fit.
    NotTried,
    /// Tried and did not finish within the budget (its events): the words
    /// for the method (the ladder's outcome stands).
    InVain(u64, String),
    /// Finished: that run, the words for the method, and what the ladder
    /// had said.
    Finished(Box<WaveEngine>, String, SetAsideLadder),
}

/// After a ladder that reported `fine` with `check`: the exact run again,
/// allowed the ladder's budget (at most [`MOST_EVENTS`]), if its levels
/// did not converge and the first exact run's growth says that run may
/// finish ([`COVERED`], [`PREDICTED_SHARE`]).
pub(crate) fn after_ladder(
    rod: &Rod,
    config: &WaveConfig,
    (fine, check): (&WaveEngine, &MergeCheck),
    first: FirstRun,
    observe: &dyn Fn(LadderProgress),
) -> Again {
    let Resolution::Auto { budget_events, .. } = config.resolution else {
        return Again::NotTried;
    };
    let allowed = budget_events.min(MOST_EVENTS).min(config.max_events);
    // the reported level's end, in the scene's units (its outcome's `end_time`)
    let end = fine.time();
    let covered = first.stopped.1 >= COVERED * end;
    let predicted = first.work_to(end);
    if check.converging || !covered || predicted > PREDICTED_SHARE * allowed as f64 {
        return Again::NotTried;
    }
    observe(LadderProgress::ExactAgain { events: allowed });
    // any error (the limit, a time limit) leaves the ladder's outcome
    let exact = match run::<f64>(rod, exact_within(config, allowed)) {
        Ok(exact) => exact,
        Err(e) => {
            let stopped = match e {
                WaveError::EventLimit { time, .. } => {
                    format!("it stopped at t = {time:.3e}, the merged run ending at {end:.3e}")
                }
                e => e.to_string(),
            };
            return Again::InVain(
                allowed,
                format!(
                    "the merged ladder's levels did not converge, and the exact run, tried again with {allowed} events (the ladder's budget, at most {MOST_EVENTS}; its first run's growth predicted {predicted:.1e}), did not finish ({stopped})"
                ),
            );
        }
    };
    let order = check
        .order
        .map_or(String::new(), |o| format!(", order {o:.1}"));
    let note = format!(
        "the merged ladder's levels did not converge (its finest level gave e = {:.10} with a merged bound of {:.1e}{order}), so the exact run was allowed {allowed} events (the ladder's budget, at most {MOST_EVENTS}) and finished in {}",
        fine.restitution(),
        check.bound,
        exact.events()
    );
    let ladder = SetAsideLadder {
        restitution: fine.restitution(),
        merged_bound: check.bound,
        observed_order: check.order,
        exact_events: allowed,
    };
    Again::Finished(Box::new(exact), note, ladder)
}

#[cfg(test)]
mod tests {
    use super::FirstRun;

    /// Work that grows as the square of the time is predicted as such,
    /// and a run that covered no time predicts nothing.
    #[test]
    fn the_first_runs_growth_is_extrapolated_as_a_power_of_time() {
        let quadratic = FirstRun {
            halfway: (100_000, 1.0),
            stopped: (200_000, 2f64.sqrt()),
        };
        let predicted = quadratic.work_to(2.0 * 2f64.sqrt());
        assert!((predicted - 800_000.0).abs() < 1e-6, "{predicted}");
        // an end already passed predicts the work done
        assert_eq!(quadratic.work_to(1.0), 200_000.0);
        let stuck = FirstRun {
            halfway: (100_000, 1.0),
            stopped: (200_000, 1.0),
        };
        assert_eq!(stuck.work_to(2.0), f64::INFINITY);
    }
}

//! The merged ladder: lattices halved from a coarse start, each level set
//! against the coarser ones and against its perturbed twins (`twins.rs`),
//! until the error bound meets the target or the work its budget (see
//! `solve.rs` for when a run is merged, and `convergence.rs` for what the
//! levels' differences say).

use crate::config::{COARSEST, Precision, Resolution, WaveConfig};
use crate::convergence::{
    FASTEST_ORDER, LOOK_BACK, SLOWEST_ORDER, agree_by_chance, assumed_order, converging,
    observed_order, refinement_error,
};
use crate::engine::WaveEngine;
use crate::error::WaveError;
use crate::solve::{LadderProgress, run};
use crate::twins::{NUDGES, further_twins, needs_further, nudged};
use impact_model::{LadderStop, Rod};
use shared::{OFF_LATTICE, OFF_LATTICE_GAIN, shared_decisions};
use std::sync::atomic::{AtomicBool, Ordering};

mod shared;

/// What the merged runs say about the reported one.
pub(crate) struct MergeCheck {
    pub(crate) per_transit: f64,
    pub(crate) per_longest: f64,
    pub(crate) bound: f64,
    /// The last three levels' observed order (see [`observed_order`]).
    pub(crate) order: Option<f64>,
    /// Whether those levels look converging (see [`converging`]).
    pub(crate) converging: bool,
    pub(crate) method: String,
    /// Why the ladder reported this level (`None` on a fixed lattice).
    pub(crate) stop: Option<LadderStop>,
}

/// The coarsest spacing a ladder starts from: a fraction of each lane's
/// transit time, and of the longest transit time (a slow lane then holds
/// at most 250 fronts). Lattices of 0.4 transits were tried and dropped:
/// their `e` is off by `5e-2` on six-layer rods, and set against finer
/// levels it only inflated their bounds. The two halve together; their ratio keeps the
/// slow lanes fifty times finer than their own transit-relative share,
/// because coarse slow lattices cost accuracy where large fronts return
/// (measured at the paper's hard corner).
pub(crate) const LADDER_START: (f64, f64) = (0.2, 4e-3);

/// A lane's lattice spacing on the lattice `(per_transit, per_longest)`:
/// that share of its layer's transit, but no more than that share of the
/// longest transit `t_max`. One rule for the runs (`engine/setup.rs`) and
/// for the choice of blocks, which prices and probes them on the ladder's
/// lattices (`block/choice.rs`, `block/flow.rs`).
pub(crate) fn lattice_spacing(
    (per_transit, per_longest): (f64, f64),
    transit: f64,
    t_max: f64,
) -> f64 {
    (per_transit * transit).min(per_longest * t_max)
}

/// The config of a merged level on the lattice `(p, l)` (its twins run
/// on the same).
pub(crate) fn merged_at(config: &WaveConfig, p: f64, l: f64, max_events: u64) -> WaveConfig {
    WaveConfig {
        resolution: Resolution::Merged {
            per_transit: p,
            per_longest: l,
        },
        precision: Precision::Double,
        max_events: max_events.min(config.max_events),
        ..config.clone()
    }
}

/// Levels a ladder needs before its estimate is trusted: two comparisons.
const MIN_LEVELS: usize = 3;

/// The bound of a level and how it was found, from the levels' `e`
/// (coarsest first, this one last) and its twins' (each its nudge of the
/// bottom's modulus and its `e`, the first nudged by `NUDGES[0]`; none
/// for a level run without its twin).
fn merge_check(
    levels: &[f64],
    nudged_runs: &[(f64, f64)],
    off_lattice: Option<f64>,
    p: f64,
    l: f64,
    used: u64,
) -> MergeCheck {
    let fine = levels.last().copied().unwrap_or(0.0);
    let refined = refinement_error(levels);
    let off = off_lattice.map_or(0.0, |e| (e - fine).abs() * OFF_LATTICE_GAIN);
    let perturbed = nudged_runs
        .iter()
        .map(|(_, e)| (e - fine).abs())
        .fold(0.0, f64::max);
    let order = observed_order(levels);
    let converging = converging(levels);
    let seen = match (order, converging) {
        (Some(o), true) => format!("; the last three levels converge at order {o:.2}"),
        (None, true) => "; e stands still over the last levels".to_string(),
        (Some(o), false) => format!(
            "; the last three levels converge at order {o:.2}, below {SLOWEST_ORDER}: not yet seen converging, so the estimate may be low"
        ),
        (None, false) => "; no convergence is seen (fewer than three levels, or e moved after standing still): the estimate may be low".to_string(),
    };
    let chaos = match nudged_runs {
        [_] => {
            format!("the difference from the bottom's modulus changed by 1e-12 ({perturbed:.1e})")
        }
        [(_, first), ..] => format!(
            "the largest difference over {} twins, the bottom's modulus changed by {} ({perturbed:.1e}; the first twin's, {:.1e}, said contacts flip on a nudge)",
            nudged_runs.len(),
            nudged_runs
                .iter()
                .map(|(nudge, _)| format!("{nudge:+.0e}"))
                .collect::<Vec<_>>()
                .join(", "),
            (first - fine).abs(),
        ),
        [] => "no twin (not run at this level)".to_string(),
    };
    let shared = match off_lattice {
        Some(e) => format!(
            "; this level and the one before it decided their contacts at the same instants, a separation at a lattice point both hold, so a level on a lattice {OFF_LATTICE:.3} times as coarse, which holds none of their points, was run: its difference times {OFF_LATTICE_GAIN:.2} ({off:.1e}; its e {e:.10})"
        ),
        None => String::new(),
    };
    MergeCheck {
        per_transit: p,
        per_longest: l,
        bound: 2.0 * refined.max(perturbed).max(off),
        order,
        converging,
        stop: None,
        method: format!(
            "merged: twice the {} of the refinement estimate ({refined:.1e}: the largest |e - e(2^j as coarse)| over {} coarser lattices{}){}{chaos}{}; lattice spacings {p:.3e} of each transit, {l:.1e} of the longest ({used} units of work in all: loop iterations, and the fronts and lattice cells of leaps){seen}{shared}",
            if off_lattice.is_some() {
                "largest"
            } else {
                "larger"
            },
            (levels.len() - 1).min(LOOK_BACK),
            if agree_by_chance(levels) {
                format!(
                    ", undivided: the last three converge faster than order {FASTEST_ORDER}, faster than a merge does, so the last two agree in part by chance or end the fast fall of a step"
                )
            } else {
                format!(
                    ", divided by 2^(j p) - 1, p = {:.2}: the levels' order within [{SLOWEST_ORDER}, 1]",
                    assumed_order(levels)
                )
            },
            if off_lattice.is_some() { ", " } else { " and " },
            if off_lattice.is_some() {
                " and the off-lattice level's (below)"
            } else {
                ""
            },
        ),
    }
}

/// A merged run on the given lattice, checked against the lattices 2, 4,
/// 8 and 16 times as coarse (those within [`COARSEST`]) and a perturbed
/// twin, all run side by side (and the further twins after them, if the
/// twin says so).
pub(crate) fn fixed_lattice(
    rod: &Rod,
    config: &WaveConfig,
    p: f64,
    l: f64,
) -> Result<(WaveEngine, MergeCheck), WaveError> {
    use rayon::prelude::*;
    let twin_rod = nudged(rod, NUDGES[0]);
    let coarser: Vec<f64> = (1..=LOOK_BACK as i32)
        .map(|j| 2f64.powi(j))
        .filter(|f| f * p <= COARSEST)
        .collect();
    let max = config.max_events;
    let ((fine, twin), coarse) = rayon::join(
        || {
            rayon::join(
                || run::<f64>(rod, merged_at(config, p, l, max)),
                || run::<f64>(&twin_rod, merged_at(config, p, l, max)),
            )
        },
        || {
            coarser
                .par_iter()
                .rev()
                .map(|f| {
                    run::<f64>(rod, merged_at(config, f * p, f * l, max))
                        .map(|e| (e.restitution(), e.steps()))
                        .map_err(|e| e.on_lattice(f * p))
                })
                .collect::<Result<Vec<_>, _>>()
        },
    );
    let on = |e: WaveError| e.on_lattice(p);
    let (fine, twin, coarse) = (fine.map_err(on)?, twin.map_err(on)?, coarse?);
    let used = fine.steps() + twin.steps() + coarse.iter().map(|c| c.1).sum::<u64>();
    let mut levels: Vec<f64> = coarse.iter().map(|c| c.0).collect();
    levels.push(fine.restitution());
    let level = Level {
        engine: fine,
        twin: Some(twin.restitution()),
        levels,
        lattice: (p, l),
        used,
        // the coarser runs are not kept to compare their contacts
        shared: false,
    };
    level.checked(rod, config, max, None, "", &|_| {})
}

/// Merged runs from [`LADDER_START`] down by halves, each with its
/// perturbed twin, until the bound is at most `target`, the next level
/// would not fit the budget of work (see [`WaveEngine::steps`]), or the lattice reaches
/// [`FINEST`]; at least [`MIN_LEVELS`] levels are run, whatever they cost
/// (a scene finishes once two levels fit `max_events`; if they do not,
/// [`WaveError::LatticeLimit`]). The finest level is reported; if a level cannot
/// finish within `max_events`, the finest before it is, with what its
/// comparisons say (two levels at least). Whether to stop is judged on a
/// level's one twin; the level reported then runs its further twins where
/// that twin says so ([`Level::checked`]), which may raise its bound past
/// `target` and its work past `budget`: a chaotic rod's spread does not
/// shrink with the lattice.
///
/// The first two levels (of the [`MIN_LEVELS`] = 3 every ladder runs)
/// cannot end it, so they run side by side, without the first's twin (a
/// twin's difference enters only the bound of the level reported) and with
/// the second's only while it may be needed. Each level beside its twin,
/// the first level's time was added to every ladder's: a seventh of three
/// levels that each take twice the one before.
pub(crate) fn ladder(
    rod: &Rod,
    config: &WaveConfig,
    budget: u64,
    target: f64,
    observe: &dyn Fn(LadderProgress),
) -> Result<(WaveEngine, MergeCheck), WaveError> {
    let twin_rod = nudged(rod, NUDGES[0]);
    let max = config.max_events;
    let (p0, l0) = LADDER_START;
    let (p1, l1) = (p0 / 2.0, l0 / 2.0);
    // A level takes at least twice the work of the one before (2.0 to 5.4
    // times, measured over the layer survey's slowest rods), so one whose
    // predecessor's run took over half of `max_events` would run into the
    // limit: rod 12 of the survey spent 14 s of its 32 s on such a level
    // before reporting the one before it anyway. (Judged on the level's own
    // run: the second level's twin is not always run.)
    let too_long = |level: &WaveEngine| 2 * level.steps() > max;
    const { assert!(MIN_LEVELS == 3) };
    // The second level's twin is needed only if that level is reported
    // (the third would not fit `max_events`): it starts where the first
    // level ends, on the thread that would idle while the second runs,
    // and is called off as soon as the second shows it is not needed.
    let twin_needless = AtomicBool::new(false);
    let (second, (first, twin)) = rayon::join(
        || {
            let second = run::<f64>(rod, merged_at(config, p1, l1, max));
            let reported = matches!(&second, Ok(s) if too_long(s));
            twin_needless.store(!reported, Ordering::Relaxed);
            second
        },
        || {
            let first = run::<f64>(rod, merged_at(config, p0, l0, max));
            let twin = first
                .is_ok()
                .then(|| run_unless(&twin_rod, merged_at(config, p1, l1, max), &twin_needless));
            (first, twin.flatten())
        },
    );
    let first = first.map_err(|e| e.on_lattice(p0))?;
    let mut levels = vec![first.restitution()];
    let mut used = first.steps();
    observe(LadderProgress::LevelDone {
        level: 1,
        per_transit: p0,
        restitution: first.restitution(),
        bound: 0.0,
        work: used,
    });
    let second = second.map_err(|e| e.on_lattice(p1))?;
    used += second.steps();
    levels.push(second.restitution());
    // a twin that was not needed is dropped, finished or not, failed or
    // not (how far it got depends on the threads' timing)
    let twin = if too_long(&second) {
        twin.transpose().map_err(|e| e.on_lattice(p1))?
    } else {
        None
    };
    let twin = twin.map(|t| (t.restitution(), t.steps()));
    let nudged_runs: Vec<(f64, f64)> = twin.iter().map(|&(e, _)| (NUDGES[0], e)).collect();
    observe(LadderProgress::LevelDone {
        level: 2,
        per_transit: p1,
        restitution: second.restitution(),
        bound: merge_check(&levels, &nudged_runs, None, p1, l1, used).bound,
        work: used,
    });
    let reported = too_long(&second).then(|| past_the_limit(2 * second.steps(), max, 2));
    let shared = shared_decisions(&second, &first);
    let second = Level {
        shared,
        engine: second,
        twin: twin.map(|(e, _)| e),
        levels: levels.clone(),
        lattice: (p1, l1),
        // the twin's work is counted where it is used, if it was run
        used: used + twin.map_or(0, |(_, steps)| steps),
    };
    if let Some(note) = reported {
        let stop = Some(LadderStop::EventLimit);
        return second.checked(rod, config, max, stop, &note, observe);
    }
    let mut coarser = second;
    let (mut p, mut l) = (p1 / 2.0, l1 / 2.0);
    loop {
        let (fine, twin) = rayon::join(
            || run::<f64>(rod, merged_at(config, p, l, max)),
            || run::<f64>(&twin_rod, merged_at(config, p, l, max)),
        );
        let (fine, twin) = match (fine, twin) {
            (Ok(fine), Ok(twin)) => (fine, twin),
            // a level past `max_events`: the finest level that finished is
            // reported (the scene finishes), and the method says on how
            // little
            (Err(WaveError::EventLimit { .. }), _) | (_, Err(WaveError::EventLimit { .. })) => {
                let note = format!(
                    "; the next level did not finish within {max} events, so the estimate rests on {} levels",
                    levels.len()
                );
                let stop = Some(LadderStop::EventLimit);
                return coarser.checked(rod, config, max, stop, &note, observe);
            }
            (Err(e), _) | (_, Err(e)) => return Err(e),
        };
        used += fine.steps() + twin.steps();
        levels.push(fine.restitution());
        let check = merge_check(
            &levels,
            &[(NUDGES[0], twin.restitution())],
            None,
            p,
            l,
            used,
        );
        observe(LadderProgress::LevelDone {
            level: levels.len(),
            per_transit: p,
            restitution: fine.restitution(),
            bound: check.bound,
            work: used,
        });
        // events about double with each halving
        let next_cost = 2 * (fine.steps() + twin.steps());
        // Whatever else stops it, a budget is named only where it alone
        // did: one of `needed` then runs the next level.
        let stop = if check.bound <= target {
            Some((LadderStop::Target, String::new()))
        } else if p / 2.0 < FINEST {
            Some((LadderStop::FinestLattice, String::new()))
        } else if too_long(&fine) {
            let note = past_the_limit(2 * fine.steps(), max, levels.len());
            Some((LadderStop::EventLimit, note))
        } else if used + next_cost > budget {
            let needed = used + next_cost;
            Some((LadderStop::Budget { needed }, String::new()))
        } else {
            None
        };
        let level = Level {
            shared: shared_decisions(&fine, &coarser.engine),
            engine: fine,
            twin: Some(twin.restitution()),
            levels: levels.clone(),
            lattice: (p, l),
            used,
        };
        if let Some((stop, note)) = stop {
            return level.checked(rod, config, max, Some(stop), &note, observe);
        }
        coarser = level;
        p /= 2.0;
        l /= 2.0;
    }
}

/// Why a ladder stopped before a level that would take about `next_run`
/// events, for the method.
fn past_the_limit(next_run: u64, max: u64, levels: usize) -> String {
    format!(
        "; the next level would take about {next_run} events, past the limit of {max} (a level takes at least twice its predecessor's), so the estimate rests on {levels} levels"
    )
}

/// A level that finished, with what its check needs: the ladder keeps the
/// finest in case the next cannot finish. Its twin's `e` is there if that
/// was run beside it (not always for the levels that ran side by side
/// before the [`MIN_LEVELS`]-th).
struct Level {
    engine: WaveEngine,
    twin: Option<f64>,
    /// `e` of the levels up to this one, coarsest first.
    levels: Vec<f64>,
    lattice: (f64, f64),
    /// Work so far, the twin's included if it was run.
    used: u64,
    /// Whether it decided its contacts where the level before it did, a
    /// separation at a lattice point both hold (`ladder/shared.rs`).
    shared: bool,
}

impl Level {
    /// The level as reported: its check completed by its twin if it has
    /// none yet, and by the further twins where that twin says they may
    /// decide the bound (see [`needs_further`]; `observe` is told before
    /// they run), and why the ladder stopped (`stop`, and `note` added to
    /// its method).
    fn checked(
        self,
        rod: &Rod,
        config: &WaveConfig,
        max: u64,
        stop: Option<LadderStop>,
        note: &str,
        observe: &dyn Fn(LadderProgress),
    ) -> Result<(WaveEngine, MergeCheck), WaveError> {
        let (p, l) = self.lattice;
        let (twin, mut used) = match self.twin {
            Some(twin) => (twin, self.used),
            None => {
                let twin = run::<f64>(&nudged(rod, NUDGES[0]), merged_at(config, p, l, max))
                    .map_err(|e| e.on_lattice(p))?;
                (twin.restitution(), self.used + twin.steps())
            }
        };
        let levels = &self.levels;
        let fine = self.engine.restitution();
        let mut runs = vec![(NUDGES[0], twin)];
        let mut unfinished = 0;
        if needs_further((twin - fine).abs(), refinement_error(levels)) {
            observe(LadderProgress::FurtherTwins {
                level: levels.len(),
                first_difference: (twin - fine).abs(),
            });
            let (further, work) = further_twins(rod, config, (p, l), max)?;
            unfinished = NUDGES.len() - runs.len() - further.len();
            runs.extend(further);
            used += work;
        }
        let off_lattice = if self.shared {
            let (p, l) = (p * OFF_LATTICE, l * OFF_LATTICE);
            match run::<f64>(rod, merged_at(config, p, l, max)) {
                Ok(off) => {
                    used += off.steps();
                    Some(off.restitution())
                }
                // (not within `max_events`: the bound stands on the rest,
                // and the method says so below)
                Err(WaveError::EventLimit { .. }) => None,
                Err(e) => return Err(e.on_lattice(p)),
            }
        } else {
            None
        };
        let mut check = merge_check(levels, &runs, off_lattice, p, l, used);
        if self.shared && off_lattice.is_none() {
            check.method.push_str(&format!(
                "; this level and the one before it decided their contacts at the same instants, a separation at a lattice point both hold, and the level on a lattice {OFF_LATTICE:.3} times as coarse that would measure it did not finish within {max} events: the estimate may be low"
            ));
            check.converging = false;
        }
        if unfinished > 0 {
            check.method.push_str(&format!(
                "; {unfinished} further twin(s) did not finish within {max} events or the time limit and are left out"
            ));
        }
        check.method.push_str(note);
        check.stop = stop;
        Ok((self.engine, check))
    }
}

/// The finest lattice a merged ladder goes down to (fraction of a transit).
const FINEST: f64 = 1e-4;

/// A run of the double engine, called off (`None`) once `off` is set: the
/// flag is read every 1024 events.
fn run_unless(
    rod: &Rod,
    config: WaveConfig,
    off: &AtomicBool,
) -> Option<Result<WaveEngine, WaveError>> {
    let mut engine = match WaveEngine::new(rod, config) {
        Ok(engine) => engine,
        Err(e) => return Some(Err(e)),
    };
    let mut events = 0u32;
    while engine.stopped().is_none() {
        if events.is_multiple_of(1024) && off.load(Ordering::Relaxed) {
            return None;
        }
        events = events.wrapping_add(1);
        if let Err(e) = engine.step() {
            return Some(Err(e));
        }
    }
    Some(Ok(engine))
}

//! What every engine returns.

use serde::{Deserialize, Serialize};

/// Which engine produced an outcome.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum EngineKind {
    /// The exact d'Alembert front-tracing engine.
    Wave,
    /// The discrete Beeman mass-spring(-dashpot) chain.
    Chain,
    /// The rigid-bottom limit: a rigid mass under an elastic stack.
    #[serde(rename = "rigid-bottom")]
    RigidBottom,
}

/// Why a run stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StopReason {
    /// The rod is free and provably never touches the wall again
    /// (DESIGN.md §2, exact stop rule).
    Escaped,
    /// The requested horizon (e.g. the paper's `20 max(t_i)`) was reached while
    /// the rod was free.
    Horizon,
    /// The horizon was reached while the rod still touched the wall: `t_c` is
    /// then only a lower bound.
    HorizonInContact,
    /// The rod came to rest against the wall and stays there: under the
    /// paper's wall law a strong enough dashpot in the bottom element holds
    /// it (the wall pulls as it would spring off). Final: `t_c` is infinite
    /// in the model, reported as the stop time, and `e` is the final
    /// (vanishing) centre-of-mass velocity.
    RestsOnWall,
}

impl StopReason {
    /// The reason a run stopped at its horizon: in flight the paper's own
    /// stop and a result; in contact, `t_c` and `e` are not final.
    pub fn at_horizon(in_contact: bool) -> Self {
        if in_contact {
            StopReason::HorizonInContact
        } else {
            StopReason::Horizon
        }
    }
}

/// What the exact engine left out to save time, so it is never silent.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct Truncation {
    /// Fronts whose velocity jump fell under the drop tolerance.
    pub dropped_fronts: u64,
    /// Sum of the dropped fronts' velocity jumps `c |d|`, in units of `v_b`.
    pub dropped_velocity: f64,
    /// Fronts added into an earlier front of the same lane because they were
    /// born within the merge window of it.
    pub merged_fronts: u64,
}

/// Why a merged ladder stopped refining. Why it matters: a bound whose
/// levels are not yet seen converging may be low, and what checks it (a
/// finer level) depends on what stopped the ladder: a budget of work that
/// is too small, a target already met, or the limit on one run's events.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LadderStop {
    /// The bound met the target.
    Target,
    /// The next level would have taken the ladder's work past its budget;
    /// a budget of at least `needed` (events) runs it.
    Budget {
        /// The smallest budget under which the ladder runs the next level.
        needed: u64,
    },
    /// The next level would not fit one run's event limit, or did not
    /// finish within it.
    EventLimit,
    /// The lattice reached the finest the ladder goes to.
    FinestLattice,
}

/// How far the reported restitution may be from the model's exact value, and
/// where that uncertainty comes from. Each part is an estimate the engine
/// can defend: a first-order bound, a measured difference between two runs,
/// or a rerun in higher precision; `method` says which.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ErrorEstimate {
    /// The sum of the parts below: `|e - e_exact| <= bound` is the claim.
    pub bound: f64,
    /// Fronts dropped under the drop tolerance: twice the impulse their
    /// missing jumps could carry to the wall before the last separation.
    pub dropped: f64,
    /// Fronts merged to bound the work: twice the difference from a rerun
    /// with half the merge windows.
    pub merged: f64,
    /// Rounding in the arithmetic of the reported value.
    pub rounding: f64,
    /// When the run was also done in double-double arithmetic: how far plain
    /// double precision was from it (the reported value is then the
    /// double-double one). Large values say double precision is not enough
    /// for this scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub double_precision_loss: Option<f64>,
    /// A reduced model (a layer treated as rigid, a chatter taken as rest).
    pub reduced: f64,
    /// The engine's tolerances (arrivals combined within the simultaneity
    /// window, wall strains within the grazing tolerance taken as zero):
    /// twice the difference from a rerun with tolerances a thousand times
    /// tighter, when the run used them.
    #[serde(default)]
    pub tolerances: f64,
    /// Whether the merged part rests on levels seen converging (a merged
    /// ladder's last three levels; `None` for runs that merged nothing).
    /// `false`: the differences between levels did not shrink at order 0.5
    /// or faster (or there were fewer than three levels), so `e` may sit on
    /// the flat part of a step of its convergence and the merged part may
    /// be low.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub merged_converging: Option<bool>,
    /// The order of convergence the last three merged levels show,
    /// `log2(|e(4h) - e(2h)| / |e(2h) - e(h)|)` (first order: 1), when
    /// both differences are non-zero.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub merged_observed_order: Option<f64>,
    /// Why a merged ladder reported the level it did, and so what would
    /// take it a level finer (`None` for runs that merged nothing and for
    /// a lattice fixed by the caller).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ladder_stop: Option<LadderStop>,
    /// Blocks of fast layers a merged run answered by their traced
    /// response instead of following each of their fronts: the first and
    /// last layer of each, counted from 0 at the bottom (as the
    /// `transit_times` list). Their error is in the merged part.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub answered_blocks: Vec<[usize; 2]>,
    /// Layers inside those blocks that their traces answered by the
    /// layer's own response instead of following its fronts (a block
    /// within the block), counted as `answered_blocks`. Their error is in
    /// the merged part.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub nested_layers: Vec<usize>,
    /// The bottom group a merged run followed in steps between the wall's
    /// decisions instead of event by event, its first and last layer (the
    /// same lattice model: its error is in the merged part).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stepped_group: Option<[usize; 2]>,
    /// A merged ladder whose levels were not seen converging, set aside
    /// because the exact run, allowed the ladder's budget, then finished:
    /// the outcome is that exact run's, and this is what the ladder had
    /// said, for comparison (`None` otherwise).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ladder_set_aside: Option<SetAsideLadder>,
    /// Where the exact run was tried again after such a ladder and did
    /// not finish: the events it was allowed (the outcome is the
    /// ladder's; `None` otherwise).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub exact_again_unfinished: Option<u64>,
    /// How the parts were obtained, in words.
    pub method: String,
}

/// What a ladder set aside for an exact run had reported
/// ([`ErrorEstimate::ladder_set_aside`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SetAsideLadder {
    /// The finest level's `e`.
    pub restitution: f64,
    /// Its merged bound (the part its levels and twins gave).
    pub merged_bound: f64,
    /// The order its last three levels showed, when both differences
    /// were non-zero.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub observed_order: Option<f64>,
    /// The events the exact run was allowed the second time.
    pub exact_events: u64,
}

impl ErrorEstimate {
    /// Recomputes `bound` from the parts.
    pub fn total(mut self) -> Self {
        self.bound = self.dropped + self.merged + self.rounding + self.reduced + self.tolerances;
        self
    }
}

/// Result of one impact, in the scene's units: a function of the scene and
/// the settings alone. How long it took is the runner's business (a sweep's
/// row, the command line's summary), so two runs of one point compare equal.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Outcome {
    /// Which engine produced this outcome.
    pub engine: EngineKind,
    /// The wall's contact law the run used (the same physics for elastic
    /// rods, where no dashpot acts).
    #[serde(default)]
    pub wall_contact: crate::WallContact,
    /// Coefficient of restitution `e`: final centre-of-mass speed over `v_b`,
    /// from the wall impulse (paper Eq. 6).
    pub restitution: f64,
    /// `e` from the mean velocity of the masses at the end (chain only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub restitution_from_velocity: Option<f64>,
    /// `t_c`: time of the last separation from the wall.
    pub contact_time: f64,
    /// `t_c / (2 sum(t_i))`.
    pub reduced_contact_time: f64,
    /// `(t_c - 2 t2) / t1` for two-layer rods, else `None`.
    pub n1: Option<f64>,
    /// The paper's `N_b`: 1 + flights longer than `min(t_i)`.
    pub bounces: u32,
    /// Raw number of separations from the wall.
    pub separations: u32,
    /// Every contact interval `[start, end]`.
    pub contacts: Vec<[f64; 2]>,
    /// One-way transit time of each layer, bottom first.
    pub transit_times: Vec<f64>,
    /// Why the run stopped: whether `t_c` and `e` are final.
    pub stop_reason: StopReason,
    /// Time at which the run stopped.
    pub end_time: f64,
    /// Boundary events processed (wave engine).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub events: Option<u64>,
    /// Time steps taken (chain).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub steps: Option<u64>,
    /// Which kernel stepped a viscous chain's dashpots: `split` (a Beeman
    /// step of the springs, then an SDIRK2 step of the dashpots) or
    /// `implicit` (SDIRK2 on springs and dashpots together).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub viscous_kernel: Option<String>,
    /// What the exact engine dropped or merged (wave engine).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub truncation: Option<Truncation>,
    /// How far `restitution` may be from the model's exact value (the
    /// estimate's `bound`), when the engine can say. For a chain ladder
    /// (`extrapolation` set) the model is the chain's `N -> infinity` limit
    /// and the bound is the finest chain's distance from the extrapolated
    /// limit plus the extrapolation's error; one chain alone (`None`) is its
    /// own model, whose distance from the continuum nothing here measures.
    #[serde(default)]
    pub error_bound: Option<f64>,
    /// The parts of that estimate.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error_estimate: Option<ErrorEstimate>,
    /// The chain's `e` at growing `N`, extrapolated to `N -> infinity`,
    /// when the run was such a ladder (this outcome is then its finest run).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extrapolation: Option<crate::numerics::Extrapolation>,
}

impl Outcome {
    /// Attaches an error estimate (and its bound).
    pub fn with_error(mut self, estimate: ErrorEstimate) -> Self {
        let estimate = estimate.total();
        self.error_bound = Some(estimate.bound);
        self.error_estimate = Some(estimate);
        self
    }

    /// An outcome with the contact figures derived from `history` at time
    /// `end_time`: `t_c`, its reduced form, `n1` (two-layer rods), the paper's
    /// filtered `N_b` (flights longer than `min(t_i)`) and the raw count. The
    /// engine adds its own work counters.
    pub fn from_history(
        engine: EngineKind,
        restitution: f64,
        history: &crate::ContactHistory,
        transit_times: &[f64],
        end_time: f64,
        stop_reason: StopReason,
    ) -> Self {
        let contact_time = history.contact_time(end_time);
        let reduced_contact_time = contact_time / (2.0 * transit_times.iter().sum::<f64>());
        let n1 = match transit_times {
            [t1, t2] => Some((contact_time - 2.0 * t2) / t1),
            _ => None,
        };
        let min_flight = transit_times.iter().copied().fold(f64::INFINITY, f64::min);
        Outcome {
            engine,
            wall_contact: crate::WallContact::default(),
            restitution,
            restitution_from_velocity: None,
            contact_time,
            reduced_contact_time,
            n1,
            bounces: history.bounces(min_flight),
            separations: history.separations(),
            contacts: history.intervals(end_time),
            transit_times: transit_times.to_vec(),
            stop_reason,
            end_time,
            events: None,
            steps: None,
            viscous_kernel: None,
            truncation: None,
            error_bound: None,
            error_estimate: None,
            extrapolation: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ContactHistory;

    fn outcome() -> Outcome {
        let mut history = ContactHistory::new();
        history.separate(2.0);
        Outcome::from_history(
            EngineKind::Wave,
            0.9,
            &history,
            &[1.0],
            3.0,
            StopReason::Escaped,
        )
    }

    /// An outcome is a function of the scene and the settings: nothing in it
    /// measures the machine, so two runs of one point serialise alike.
    #[test]
    fn serialised_outcomes_carry_no_timing() {
        let text = serde_json::to_string(&outcome()).unwrap();
        for word in ["elapsed", "seconds", "duration", "wall_clock"] {
            assert!(!text.contains(word), "{word} in {text}");
        }
    }

    /// A runner's timing goes beside the outcome, as its last key.
    #[test]
    fn a_timed_outcome_is_the_outcome_and_elapsed_seconds_last() {
        let o = outcome();
        let timed = crate::Timed {
            value: o.clone(),
            seconds: 0.5,
        };
        let plain = serde_json::to_string(&o).unwrap();
        let text = serde_json::to_string(&timed).unwrap();
        assert_eq!(
            text,
            format!("{},\"elapsed_seconds\":0.5}}", plain.trim_end_matches('}'))
        );
        let back: crate::Timed<Outcome> = serde_json::from_str(&text).unwrap();
        assert_eq!(back, timed);
        assert_eq!(timed.restitution, 0.9);
    }
}

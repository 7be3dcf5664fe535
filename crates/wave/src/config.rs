//! Settings of the exact engine. Physical inputs live in the scene; these are
//! numerical knobs, each with the reason for its default and its range
//! (checked here, once, for the engine and for callers that want to refuse
//! bad settings before running anything).

use impact_model::{Allowed, SettingError};

/// When to stop a run.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StopRule {
    /// Stop as soon as the rod is free and provably never touches the wall
    /// again (DESIGN.md §2): exact, and usually far earlier than the paper's
    /// horizon.
    Escape,
    /// Stop at `factor * max(t_i)`, as the paper does with `factor = 20`.
    /// A run that reaches it while the rod still touches the wall has no
    /// final restitution and is reported as unfinished.
    Horizon {
        /// The multiple of the longest transit time `max(t_i)` at which to stop (the paper's is 20).
        factor: f64,
    },
}

impl StopRule {
    /// The paper's horizon, `20 max(t1, t2)`.
    pub const PAPER: StopRule = StopRule::Horizon { factor: 20.0 };
}

/// What to record beyond the observables. Nothing is recorded by default: a
/// plain run computes neither traces nor front paths.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct Record {
    /// Wall strain, bottom height and velocity at every wall event.
    pub wall: bool,
    /// Every front's path, amplitude and parents (for wave-path diagrams).
    pub fronts: bool,
}

/// How far fronts may be merged, which bounds the work of a run.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Resolution {
    /// Only fronts born at the same instant (within the simultaneity
    /// window) merge: the exact solution. A scene whose fronts multiply
    /// without bound then stops at `max_events` with an error.
    Exact,
    /// Fronts of a lane born within `min(per_transit * t_lane,
    /// per_longest * max(t_i))` of the lane's newest front merge into it,
    /// at the time of the larger of the two. A lane then holds at most
    /// `1/per_transit + 1/per_longest` fronts. The merge error is of first
    /// order in the windows.
    Merged {
        /// Window as a fraction of the lane's own transit time `t_lane`.
        per_transit: f64,
        /// Window as a fraction of the rod's longest transit time `max(t_i)`.
        per_longest: f64,
    },
    /// Exact when the exact run takes at most `exact_events`; otherwise
    /// merged, the lattice refined by halves until the measured error bound
    /// is at most `target` (in `e`) or the work reaches about
    /// `budget_events` (DESIGN: every scene finishes, with a stated and
    /// tested error bound).
    Auto {
        /// Largest number of events a run may take and still be reported exact.
        exact_events: u64,
        /// Work, in events, after which the lattice stops halving.
        budget_events: u64,
        /// Error bound in `e` at which the lattice stops halving.
        target: f64,
        /// Where the ladder's levels do not converge (its estimate may be
        /// low) and the first exact run's growth says an exact run may fit
        /// `budget_events`, the exact run again, allowed that (at most
        /// `2e7` events); reported if it finishes (`exact_again.rs`).
        /// Tests of the ladder itself turn it off.
        exact_again: bool,
    },
}

impl Resolution {
    /// The default: exact up to 2e5 events (a few milliseconds, more than
    /// any point of the paper's grid needs); else merged until the bound is
    /// `1e-5` in `e` (a hundred times below the paper's own chain at
    /// `N = 10^4`, and below any measured restitution's precision) or about
    /// 4e6 events (a tenth of a second) are spent, whatever the scene.
    pub const AUTO: Resolution = Resolution::Auto {
        exact_events: 200_000,
        budget_events: 4_000_000,
        target: 1e-5,
        exact_again: true,
    };
}

/// The arithmetic of a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Precision {
    /// Double precision only; rounding is estimated a priori.
    Double,
    /// Double precision, rerun in double-double when the run's decisions
    /// came close to grazing or were many (where rounding can be amplified):
    /// the rerun's value is reported and the difference says how much
    /// double precision alone would have lost.
    Checked,
    /// Double-double throughout (about 32 digits; 5 to 20 times slower).
    DoubleDouble,
}

/// Numerical settings of [`crate::WaveEngine`] and [`crate::simulate`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct WaveConfig {
    /// When the run ends: the exact escape rule or the paper's horizon.
    pub stop: StopRule,
    /// A front is dropped when its velocity jump `c |d|` is below
    /// `drop_tolerance * v_b`. Default `1e-16`: measured to move `e` by
    /// `3e-13` against no dropping at all at the hard corner (x = 0.995,
    /// alpha = 0.005), while cutting its events tenfold. Every drop is
    /// accounted for in the error estimate.
    pub drop_tolerance: f64,
    /// Arrivals at one boundary (and births in one lane) closer than
    /// `max(simultaneity * min(t_i), 64 ulps of (t + min(t_i)))` are one
    /// event, combined before the (nonlinear) contact decision. The second
    /// part is rounding: it grows with the time as the rounding of summed
    /// transit times does, so commensurate transit times (`t2 = n t1`) are
    /// recognised as ties however long the run, and combining within it is
    /// no approximation beyond rounding. Default `0`: nothing more. A wider
    /// window combines real near-ties, which changes `e`; the error
    /// estimate then measures by how much with a second, tighter run. The
    /// first build's `1e-9` combined arrivals `3e-12` apart at the hard
    /// corner (and at each of the grid's 20 hardest points), which cost
    /// that second run and a bound of `2.6e-11`; measured against
    /// `scripts/tracker.py` in 40 digits over 60 points where it mattered,
    /// the window of rounding alone is within `1.4e-13` of the exact `e`
    /// where `1e-9` was `2.1e-11` off.
    pub simultaneity: f64,
    /// Contact decisions treat wall strains within
    /// `grazing_tolerance * v_b / c0` of zero as zero: the rod then stays at
    /// the wall with zero force. Default `1e-12`, above rounding.
    pub grazing_tolerance: f64,
    /// How far fronts may merge. Default [`Resolution::AUTO`].
    pub resolution: Resolution,
    /// The arithmetic. Default [`Precision::Checked`].
    pub precision: Precision,
    /// Refuse to run past this much work in any one run (a run that
    /// cannot finish): loop iterations, and what leaps do in their stead
    /// (the fronts they spawn, the lattice cells they fill). With automatic resolution no scene of up to eight
    /// layers and transit-time ratios up to `10^6` comes near it.
    pub max_events: u64,
    /// Refuse to run past `max_time_factor * sum(t_i)`.
    pub max_time_factor: f64,
    /// What to record beside the outcome (wall samples, fronts); nothing by default.
    pub record: Record,
    /// Advance a layer whose neighbours stay quiet for at least eight of
    /// its round trips in closed form (`leap.rs`): the same fronts, wall
    /// impulse and contact decisions as event by event, to rounding, in a
    /// fraction of the time (its ringing is a geometric series). Default
    /// on. An exact run leaps only when nothing is recorded (a recording
    /// shows every event). Off: every boundary event goes through the
    /// loop, the reference the leaps are tested against.
    pub leap_quiet_layers: bool,
    /// Which leaps take in the fronts their neighbours' lanes already hold
    /// (`leap/arrivals.rs`), instead of stopping before the first: a fast
    /// layer between two lattices then leaps a neighbour's transit, not a
    /// lattice cell. Default [`LeapArrivals::Merged`].
    pub leap_arrivals: LeapArrivals,
    /// Answer blocks of fast layers by their response (`block.rs`, merged
    /// runs only): two or more adjacent layers above the bottom, each at
    /// most an eighth of the transit of the layers just outside, are traced
    /// once, and each front arriving at the block adds the block's
    /// response to what it sends its neighbours. Off: the loop takes every
    /// boundary event inside the block.
    pub fast_blocks: bool,
    /// Within a block's trace, answer its fastest layer by that layer's
    /// own response (`block/response/nested.rs`) where it holds most of
    /// the trace's lattice points and rings out quickly between the
    /// block's slower layers. Off: the trace follows every front of it.
    pub nest_blocks: bool,
    /// Trace a block whose fastest layer is not nested on one lattice,
    /// its finest lane's times a power of two in every lane (the largest
    /// not coarser than the lane's own), where its lanes then hold at
    /// most `2^18` points (`block/response/one_lattice.rs`): a lane's run
    /// of points then lands on its neighbours' lattices shifted, a pair
    /// of multiply-adds a point. Off: each layer's lane on its own
    /// lattice, each point placed alone.
    pub one_lattice_blocks: bool,
    /// Put a block response's large fronts that their arrival scales
    /// under what the neighbour's lane keeps apart (`keep_above`) on the
    /// port's lattice as the arrival comes, split between two points as
    /// the lane would deposit them (`block/folded.rs`): the lane receives
    /// the same deposits, summed in another order, without each being
    /// queued, delivered and spawned. Off: each is delivered at its time
    /// and deposited by the lane.
    pub fold_small_exact: bool,
    /// Step the bottom group between the wall's decisions (`group.rs`,
    /// merged runs with nothing recorded): two or more layers at the wall,
    /// each at least eight times faster than the layer above, followed in
    /// steps of their lattices instead of event by event, and given back
    /// to the loop a step before the wall could decide. Off: the loop
    /// takes every event in them.
    pub step_bottom_group: bool,
}

/// Which leaps take in their neighbours' arrivals (see
/// [`WaveConfig::leap_arrivals`]). The bottom's wall decisions are then
/// found over the fronts it holds as the leap begins, with the most the
/// arrivals could move the wall taken off (`leap/arrivals.rs`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum LeapArrivals {
    /// None: every leap stops before the first arrival from outside.
    Never,
    /// A merged run's, where the longer window pays for the arrivals.
    #[default]
    Merged,
    /// Every run's, whatever they cost: what an exact run's trains then
    /// give is tested against the event loop to rounding.
    Always,
}

impl Default for WaveConfig {
    fn default() -> Self {
        Self {
            stop: StopRule::Escape,
            drop_tolerance: 1e-16,
            simultaneity: 0.0,
            grazing_tolerance: 1e-12,
            resolution: Resolution::AUTO,
            precision: Precision::Checked,
            max_events: 200_000_000,
            max_time_factor: 1e4,
            record: Record::default(),
            leap_quiet_layers: true,
            leap_arrivals: LeapArrivals::Merged,
            fast_blocks: true,
            nest_blocks: true,
            one_lattice_blocks: true,
            fold_small_exact: true,
            step_bottom_group: true,
        }
    }
}

/// The coarsest lattice a lane may have (fraction of its transit): a front
/// deposited on the lattice point before its birth must still arrive after
/// it was born.
pub(crate) const COARSEST: f64 = 0.5;

impl WaveConfig {
    /// The ranges [`crate::simulate`] and [`crate::solve`] accept. A merged
    /// resolution's error is measured on a lattice twice as coarse, which
    /// may be at most [`COARSEST`]: its window is at most half that, and
    /// above zero (twice a zero window is no coarser lattice).
    pub fn check(&self) -> Result<(), SettingError> {
        self.check_ranges(Allowed::PositiveUpTo(COARSEST / 2.0))
    }

    /// The ranges one engine run accepts ([`crate::WaveEngine::new`]): any
    /// lattice up to [`COARSEST`], as the merged ladder's coarser levels use.
    pub(crate) fn check_engine(&self) -> Result<(), SettingError> {
        self.check_ranges(Allowed::NonNegativeUpTo(COARSEST))
    }

    fn check_ranges(&self, merge_window: Allowed) -> Result<(), SettingError> {
        Allowed::AtLeast(1).check_count("max_events", self.max_events)?;
        Allowed::NonNegative.check("drop_tolerance", self.drop_tolerance)?;
        Allowed::NonNegative.check("simultaneity", self.simultaneity)?;
        Allowed::NonNegative.check("grazing_tolerance", self.grazing_tolerance)?;
        Allowed::Positive.check("max_time_factor", self.max_time_factor)?;
        if let StopRule::Horizon { factor } = self.stop {
            Allowed::Positive.check("horizon", factor)?;
        }
        match self.resolution {
            Resolution::Exact => {}
            Resolution::Auto {
                budget_events,
                target,
                ..
            } => {
                Allowed::AtLeast(1).check_count("budget_events", budget_events)?;
                Allowed::Positive.check("target", target)?;
            }
            Resolution::Merged {
                per_transit,
                per_longest,
            } => {
                merge_window.check("per_transit", per_transit)?;
                Allowed::NonNegative.check("per_longest", per_longest)?;
            }
        }
        Ok(())
    }
}

//! Settings of the exact engine. Physical inputs live in the scene; these are
//! numerical knobs, each with the reason for its default.

/// When to stop a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StopRule {
    /// Stop as soon as the rod is free and provably never touches the wall
    /// again (DESIGN.md §2): exact, and usually far earlier than the paper's
    /// horizon.
    Escape,
    /// Stop at `factor * max(t_i)`, as the paper does with `factor = 20`.
    Horizon { factor: f64 },
}

impl StopRule {
    /// The paper's horizon, `20 max(t1, t2)`.
    pub const PAPER: StopRule = StopRule::Horizon { factor: 20.0 };
}

/// What to record beyond the observables. Nothing is recorded by default: a
/// plain run computes neither traces nor front paths.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Record {
    /// Wall strain, bottom height and velocity at every wall event.
    pub wall: bool,
    /// Every front's path, amplitude and parents (for wave-path diagrams).
    pub fronts: bool,
}

/// Numerical settings of [`crate::WaveEngine`].
#[derive(Debug, Clone, PartialEq)]
pub struct WaveConfig {
    pub stop: StopRule,
    /// A front is dropped when its velocity jump `c |d|` is below
    /// `drop_tolerance * v_b`. Default `1e-16`: measured to move `e` by
    /// `3e-13` against no dropping at all at the hard corner (x = 0.995,
    /// alpha = 0.005; see the engine tests), while cutting its events tenfold.
    pub drop_tolerance: f64,
    /// Arrivals at one boundary closer than `simultaneity * min(t_i)` are one
    /// event, combined before the (nonlinear) contact decision. Default
    /// `1e-9`: far above the rounding of summed transit times (about
    /// `1e-13 t_i` after `10^4` events) and far below any physical time, so
    /// commensurate transit times (`t2 = n t1`) are recognised as ties.
    pub simultaneity: f64,
    /// Fronts born in one lane within `merge_window * min(t_i)` of each other
    /// are merged into the earlier one (a time shift traded for fewer
    /// fronts). Default 0: only simultaneous fronts merge, which is exact.
    pub merge_window: f64,
    /// Contact decisions treat wall strains within
    /// `grazing_tolerance * v_b / c0` of zero as zero: the rod then stays at
    /// the wall with zero force. Default `1e-12`, above rounding.
    pub grazing_tolerance: f64,
    /// Refuse to run past this many events (a run that cannot finish). The
    /// paper's whole grid needs at most ~3e4 per point; `10^7` (about a second)
    /// is reached only where fronts multiply without bound (`t2 / t1 >~ 10^4`),
    /// and the error then says which setting to change.
    pub max_events: u64,
    /// Refuse to run past `max_time_factor * sum(t_i)`.
    pub max_time_factor: f64,
    pub record: Record,
}

impl Default for WaveConfig {
    fn default() -> Self {
        Self {
            stop: StopRule::Escape,
            drop_tolerance: 1e-16,
            simultaneity: 1e-9,
            merge_window: 0.0,
            grazing_tolerance: 1e-12,
            max_events: 10_000_000,
            max_time_factor: 1e4,
            record: Record::default(),
        }
    }
}

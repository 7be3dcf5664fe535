//! Numerical settings of the chain, each with the reason for its default.

/// When to stop.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ChainStop {
    /// As soon as the chain is free and provably never touches the wall again
    /// (the discrete form of DESIGN.md §2's bound, with a 5% margin for the
    /// integrator's energy fluctuation).
    Escape,
    /// At `factor * max(t_i)`; the paper uses 20.
    Horizon { factor: f64 },
}

impl ChainStop {
    pub const PAPER: ChainStop = ChainStop::Horizon { factor: 20.0 };
}

/// What to record besides the observables; nothing by default.
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct ChainRecord {
    /// Sample the wall strain every this many steps.
    pub wall_every: Option<u64>,
    /// Sample the strain field every this many steps, averaged into this many
    /// equal-height rows (for space-time pictures): `(every, rows)`.
    pub raster: Option<(u64, usize)>,
}

/// Settings of [`crate::ChainEngine`].
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ChainConfig {
    /// Number of masses. Default `10^4`, the paper's.
    pub masses: usize,
    /// Time step as a fraction of the paper's `min(2 pi sqrt(m/k_i)) / 100`.
    /// Default 1: the paper's step (`omega dt = 0.063`, far inside Beeman's
    /// elastic stability limit; dashpots are implicit, so they impose none).
    pub dt_factor: f64,
    pub stop: ChainStop,
    /// Refuse to take more steps than this.
    pub max_steps: u64,
    pub record: ChainRecord,
}

impl ChainConfig {
    /// The settings' ranges, checked once, here: by the engine, and by a
    /// caller that wants to refuse bad settings before running anything.
    pub fn check(&self) -> Result<(), crate::ChainError> {
        let bad = |field, allowed, value| {
            Err(crate::ChainError::Setting {
                field,
                allowed,
                value,
            })
        };
        if !(self.dt_factor.is_finite() && self.dt_factor > 0.0 && self.dt_factor <= 10.0) {
            return bad("dt_factor", "a number in (0, 10]", self.dt_factor);
        }
        if let ChainStop::Horizon { factor } = self.stop
            && !(factor.is_finite() && factor > 0.0)
        {
            return bad("horizon", "a finite number > 0", factor);
        }
        if self.masses == 0 {
            return bad("masses", "at least 1", 0.0);
        }
        if self.max_steps == 0 {
            return bad("max_steps", "at least 1", 0.0);
        }
        Ok(())
    }
}

impl Default for ChainConfig {
    fn default() -> Self {
        Self {
            masses: 10_000,
            dt_factor: 1.0,
            stop: ChainStop::Escape,
            max_steps: 2_000_000_000,
            record: ChainRecord::default(),
        }
    }
}

//! Numerical settings of the chain, each with the reason for its default.

use impact_model::{Allowed, SettingError};

/// When to stop.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ChainStop {
    /// As soon as the chain is free and provably never touches the wall again
    /// (the discrete form of DESIGN.md §2's bound, with a 5% margin for the
    /// integrator's energy fluctuation).
    Escape,
    /// At `factor * max(t_i)`; the paper uses 20.
    Horizon {
        /// The multiple of the longest transit time `max(t_i)` at which to stop.
        factor: f64,
    },
}

impl ChainStop {
    /// The paper's stop: `20 max(t_i)`, whether or not the rod has left.
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
    /// No wall samples or strain frames after this time: a picture of a
    /// window much shorter than the run (a stiff base that rebounds alone)
    /// samples its window finely without holding samples for the rest of
    /// the run.
    pub record_until: Option<f64>,
}

/// Which kernel steps a viscous chain. Both have the same `dt -> 0`
/// limit, the chain of the paper's model; they differ in how far from it a
/// finite step lands, and in cost.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ViscousKernel {
    /// SDIRK2 on springs and dashpots together, every mass
    /// (`crate::implicit`): stiffly accurate, within `2e-5` of the limit at
    /// the paper's step on every scene measured.
    #[default]
    Implicit,
    /// A Beeman step of the springs, then an SDIRK2 step of the dashpots
    /// (`crate::viscous`): three to four times faster than the implicit
    /// kernel stage by stage (short chains), about as fast as its two
    /// passes (long ones), but up to `6e-4` from the limit where a dashpot
    /// is stiff against the step.
    Split,
}

impl ViscousKernel {
    /// The kernel's name in outputs and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Self::Implicit => "implicit",
            Self::Split => "split",
        }
    }
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
    /// When the run ends. Default: the escape bound.
    pub stop: ChainStop,
    /// Refuse to take more steps than this.
    pub max_steps: u64,
    /// What to record besides the outcome.
    pub record: ChainRecord,
    /// Which kernel steps a viscous chain. Default: [`ViscousKernel::Implicit`].
    pub viscous_kernel: ViscousKernel,
}

impl ChainConfig {
    /// The settings' ranges, checked once, here: by the engine, and by a
    /// caller that wants to refuse bad settings before running anything.
    pub fn check(&self) -> Result<(), SettingError> {
        Allowed::PositiveUpTo(10.0).check("dt_factor", self.dt_factor)?;
        if let ChainStop::Horizon { factor } = self.stop {
            Allowed::Positive.check("horizon", factor)?;
        }
        Allowed::AtLeast(1).check_count("masses", self.masses as u64)?;
        Allowed::AtLeast(1).check_count("max_steps", self.max_steps)?;
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
            viscous_kernel: ViscousKernel::Implicit,
        }
    }
}

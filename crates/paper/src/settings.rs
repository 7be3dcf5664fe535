//! Resolutions of a reproduction: `--quick` (minutes) and `--full` (the
//! paper's).

/// Which of the resolutions below a reproduction runs at.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Resolution {
    /// Minutes on a laptop: coarser grids and smaller chains.
    Quick,
    /// The paper's own sizes.
    Full,
    /// Toy sizes for the tests.
    Tiny,
}

impl std::fmt::Display for Resolution {
    /// The name the report page and the summary line give it.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Resolution::Quick => "quick",
            Resolution::Full => "full",
            Resolution::Tiny => "tiny (tests)",
        })
    }
}

/// What to compute, and how finely.
#[derive(Debug, Clone, PartialEq)]
pub struct Settings {
    /// Which resolution these are.
    pub resolution: Resolution,
    /// Fig. 2: values of `tau c / L`.
    pub fig2_tau: Vec<f64>,
    /// Fig. 2: chain size.
    pub fig2_masses: usize,
    /// Figs. 4-6: the exact engine on this grid step (the paper's 0.005 costs
    /// a tenth of a second, so both modes use it).
    pub map_step: f64,
    /// Fig. 7: the `alpha` step.
    pub fig7_alpha_step: f64,
    /// Fig. 7: the `x` step of the scan for the minimum `e`.
    pub fig7_x_step: f64,
    /// Figs. 8-10: the layer restitutions varied.
    pub visco_values: Vec<f64>,
    /// Figs. 8-10: the `x` step.
    pub visco_x_step: f64,
    /// Figs. 8-10: chain size.
    pub visco_masses: usize,
    /// Fig. 11: chain sizes.
    pub fig11_sizes: Vec<usize>,
    /// Appendix C: the small alpha at which the exact engine is compared.
    pub appendix_alpha: f64,
}

fn log_range(from: f64, to: f64, count: usize) -> Vec<f64> {
    (0..count)
        .map(|k| from * (to / from).powf(k as f64 / (count - 1) as f64))
        .collect()
}

impl Settings {
    /// A few minutes on 2 cores: chains of a few hundred masses, coarser
    /// scans. Clearly labelled as such on every page.
    pub fn quick() -> Self {
        Self {
            resolution: Resolution::Quick,
            fig2_tau: log_range(1e-3, 1.0, 13),
            fig2_masses: 1000,
            map_step: 0.005,
            fig7_alpha_step: 0.01,
            fig7_x_step: 0.001,
            visco_values: vec![0.4, 0.6, 0.8, 1.0],
            visco_x_step: 0.05,
            visco_masses: 800,
            fig11_sizes: vec![25, 50, 100, 200, 400, 800, 1600],
            appendix_alpha: 1e-3,
        }
    }

    /// The paper's resolution: chains of 10^4 masses. Hours on 2 cores.
    pub fn full() -> Self {
        Self {
            resolution: Resolution::Full,
            fig2_tau: log_range(1e-3, 1.0, 19),
            fig2_masses: 10_000,
            map_step: 0.005,
            fig7_alpha_step: 0.005,
            fig7_x_step: 0.0005,
            visco_values: vec![0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0],
            visco_x_step: 0.025,
            visco_masses: 10_000,
            fig11_sizes: vec![25, 50, 100, 200, 400, 800, 1600, 3200, 6400, 10_000],
            appendix_alpha: 1e-3,
        }
    }

    /// Seconds, for tests: every item at a toy resolution.
    pub fn tiny() -> Self {
        Self {
            resolution: Resolution::Tiny,
            fig2_tau: vec![0.003, 0.01, 0.03, 1.0],
            fig2_masses: 100,
            map_step: 0.05,
            fig7_alpha_step: 0.1,
            fig7_x_step: 0.01,
            visco_values: vec![0.7, 1.0],
            visco_x_step: 0.2,
            visco_masses: 150,
            fig11_sizes: vec![50, 100],
            appendix_alpha: 1e-3,
        }
    }

    /// Values `step, 2 step, ... < 1`.
    pub fn unit_steps(step: f64) -> Vec<f64> {
        let n = (1.0 / step - 1e-9).floor() as usize;
        (1..=n)
            .map(|k| k as f64 * step)
            .filter(|v| *v < 1.0)
            .collect()
    }
}

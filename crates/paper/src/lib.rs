//! `impact reproduce`: every figure of the paper regenerated from our
//! engines, each set beside what the paper states about it, with a verdict
//! computed from the numbers (never written by hand).
//!
//! One module per figure group; each writes `DIR/<stem>.svg`, `.png` and
//! `.csv` and returns an [`Item`] for the report page.

#![warn(missing_docs)]

mod appendix_c;
mod claim;
mod cost;
mod fig11;
mod fig2;
mod fig3;
mod fig7;
mod maps;
mod page;
mod settings;
mod visco;

pub use claim::{Claim, Item, Verdict};
pub use settings::{Resolution, Settings};

use impact_output::ReportDir;
use std::path::Path;
use thiserror::Error;

/// Why a reproduction could not be written.
#[derive(Debug, Error)]
pub enum PaperError {
    /// A figure could not be drawn or rendered.
    #[error(transparent)]
    Plot(#[from] impact_plot::PlotError),
    /// A file could not be written.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// A scene was invalid.
    #[error(transparent)]
    Scene(#[from] impact_model::SceneError),
    /// The exact engine failed.
    #[error(transparent)]
    Wave(#[from] impact_wave::WaveError),
    /// The chain failed.
    #[error(transparent)]
    Chain(#[from] impact_chain::ChainError),
    /// The cost section failed.
    #[error(transparent)]
    Cost(#[from] impact_cost::CostError),
    /// A figure's own failure, in words.
    #[error("{0}")]
    Engine(String),
}

/// The exact engine at its default settings on the bilayer `b`: the
/// reference the figures set the paper's formulas and models against.
fn exact_bilayer(b: impact_model::Bilayer) -> Result<impact_model::Outcome, PaperError> {
    let rod = b.scene().validate()?;
    Ok(impact_wave::simulate(
        &rod,
        &impact_wave::WaveConfig::default(),
    )?)
}

/// Runs `work` on every item in parallel and keeps the order; the first
/// failure fails the whole figure, since a curve with a hole in it would
/// misreport the paper. No progress bar: the figure's label is the progress.
fn try_par_map<P: Sync, T: Send>(
    items: &[P],
    work: impl Fn(&P) -> Result<T, PaperError> + Sync,
) -> Result<Vec<T>, PaperError> {
    impact_study::par_map(items, &(), work)
        .into_iter()
        .collect()
}

/// One figure group: writes its files into the directory, returns its item.
type Step = fn(&Path, &Settings) -> Result<Item, PaperError>;

/// Every item, in the paper's order, written as the directory `target`
/// (staged beside it and renamed into place once complete: a failed run
/// leaves the previous reproduction, or nothing). `progress` is told which
/// figure starts.
pub fn reproduce(
    target: &Path,
    settings: &Settings,
    progress: &dyn Fn(&str),
) -> Result<Vec<Item>, PaperError> {
    let staged = ReportDir::create(target)?;
    let dir = staged.path();
    let steps: [(&str, Step); 9] = [
        ("Fig. 2: homogeneous viscoelastic rod", fig2::run),
        ("Fig. 3: space-time diagrams", fig3::run),
        ("Figs. 4-6: maps over (x, alpha)", maps::run),
        ("Fig. 7: x_min and e_min", fig7::run),
        ("Figs. 8-9: viscoelastic bilayers", visco::run_8_9),
        ("Fig. 10: e_1 = 0.94, e_2 = 0.72", visco::run_10),
        ("Fig. 11: finite-size error", fig11::run),
        ("Appendix C and Fig. 13: rigid bottom", appendix_c::run),
        ("What accuracy costs in time", cost::run),
    ];
    let mut items = Vec::new();
    for (label, step) in steps {
        progress(label);
        items.push(step(dir, settings)?);
    }
    std::fs::write(dir.join("index.html"), page::page(dir, settings, &items))?;
    staged.commit()?;
    Ok(items)
}

//! Library errors as the command line reports them. The engines and
//! studies speak physics and fields; only here do their errors meet the
//! flags that change them, and the exit codes (input errors exit 2).

use crate::input;
use impact_chain::ChainError;
use impact_model::SettingError;
use impact_study::{GridError, JournalError};

/// The flag that sets each settings field the engines and studies check
/// (`impact_model::SettingError::field`). A field no flag sets is reported
/// by its own name.
fn flag(field: &str) -> Option<&'static str> {
    Some(match field {
        // the chain
        "dt_factor" => "dt-factor",
        "masses" => "n",
        "max_steps" => "max-steps",
        "tau_c_over_l" => "tau-c-over-l",
        // the exact engine
        "drop_tolerance" => "drop-tolerance",
        "per_transit" => "merge-window",
        "max_events" => "max-events",
        "budget_events" => "event-budget",
        // the exact engine's automatic resolution and the chain's ladder
        "target" => "target",
        "max_masses" => "max-n",
        // every engine
        "horizon" => "horizon",
        _ => return None,
    })
}

/// A setting out of range (exit 2), worded as the flag that sets it.
pub fn setting(e: SettingError) -> anyhow::Error {
    match flag(e.field) {
        Some(flag) => input(format!("--{flag} must be {} (got {})", e.allowed, e.value)),
        None => input(e.to_string()),
    }
}

/// A malformed axis: `name` is the flag's.
pub fn grid(e: GridError) -> anyhow::Error {
    input(format!("--{e}"))
}

/// A chain that could not run (exit 2) or finish (exit 1), with the flags
/// that change that.
pub fn chain(e: ChainError) -> anyhow::Error {
    match e {
        ChainError::TooFewMasses { masses, layers } => input(format!(
            "the chain needs at least one mass per layer: --n must be >= {layers} (got {masses})"
        )),
        ChainError::Setting(e) => setting(e),
        ChainError::StepLimit { .. } => anyhow::Error::new(e)
            .context("the chain could not finish (raise --max-steps or use --horizon)"),
        ChainError::NonFinite { .. } => {
            anyhow::Error::new(e).context("the chain could not finish (lower --dt-factor)")
        }
    }
}

/// A journal's error in the command line's words.
pub fn journal_message(e: &JournalError) -> String {
    match e {
        JournalError::Shard(text) => {
            format!("--shard must be I/N with 1 <= I <= N (got '{text}')")
        }
        JournalError::Incomplete { shards, .. } => format!(
            "{e} (rerun each shard's own command with --resume; with scripts/slurm-*.sh: the same settings and INDICES={})",
            impact_study::journal::shard_ranges(shards)
        ),
        JournalError::Exists(path) => format!(
            "{} exists: add --resume to complete it, or remove it",
            path.display()
        ),
        e => e.to_string(),
    }
}

/// A journal the user can fix (exit 2) or a failure (exit 1).
pub fn journal(e: JournalError) -> anyhow::Error {
    match e {
        JournalError::Shard(_)
        | JournalError::Exists(_)
        | JournalError::Locked { .. }
        | JournalError::Mismatch { .. } => input(journal_message(&e)),
        e => anyhow::Error::new(e),
    }
}

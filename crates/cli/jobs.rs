//! What long runs share: worker threads, a progress bar on terminals, and the
//! journal that makes them shardable and resumable.

use crate::args::JournalArgs;
use crate::input;
use impact_study::{Journal, JournalHeader, Shard};
use indicatif::{ProgressBar, ProgressStyle};
use serde::de::DeserializeOwned;
use std::collections::BTreeMap;
use std::io::IsTerminal;
use std::path::Path;

/// Sets the number of worker threads (once per process).
pub fn threads(n: Option<usize>) -> anyhow::Result<()> {
    if let Some(n) = n {
        if n == 0 {
            return Err(input("--threads must be at least 1 (got 0)"));
        }
        rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build_global()?;
    }
    Ok(())
}

/// A progress bar on stderr when it is a terminal, else nothing.
pub fn progress(len: usize, what: &str) -> ProgressBar {
    if !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::new(len as u64);
    let template = format!(
        "{{elapsed_precise}} [{{bar:40}}] {{pos}}/{{len}} {what} ({{per_sec}}, eta {{eta}})"
    );
    bar.set_style(
        ProgressStyle::with_template(&template)
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar
}

/// The shard asked for (all points when none).
pub fn shard(a: &JournalArgs) -> anyhow::Result<Shard> {
    a.shard.as_deref().map_or(Ok(Shard::ALL), |s| {
        Shard::parse(s).map_err(crate::flags::journal)
    })
}

/// Opens the journal at `path`: resumed with `--resume`. Without it an
/// unsharded run starts afresh, but a shard's journal is never deleted: the
/// run stops and says to add `--resume` (hours of points may be in it). A
/// file cut before its header line ends is just started again.
pub fn open_journal<T: DeserializeOwned>(
    path: &Path,
    header: &JournalHeader,
    resume: bool,
) -> anyhow::Result<(Journal, BTreeMap<usize, T>)> {
    let torn_header = path.exists() && !std::fs::read(path)?.contains(&b'\n');
    if torn_header || (!resume && path.exists() && header.shard == impact_study::Shard::ALL) {
        std::fs::remove_file(path)?;
    }
    if resume && !path.exists() {
        eprintln!(
            "note: {} does not exist yet: starting from the beginning",
            path.display()
        );
    }
    Journal::open(path, header, resume).map_err(crate::flags::journal)
}

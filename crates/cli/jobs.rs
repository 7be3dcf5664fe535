//! What long runs share: worker threads, a progress bar on terminals, and the
//! journal that makes them shardable and resumable.

use crate::args::JournalArgs;
use crate::input;
use impact_study::{Finished, JournalPlan, Progress, Shard};
use indicatif::{ProgressBar, ProgressStyle};
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::io::IsTerminal;

/// Sets the number of worker threads (once per process).
pub fn threads(n: Option<usize>) -> anyhow::Result<()> {
    if let Some(n) = n {
        if n == 0 {
            return Err(input("--threads must be at least 1 (got 0)"));
        }
        let pool = rayon::ThreadPoolBuilder::new().num_threads(n);
        // one thread: this one (a pool of one spawned thread cost a small
        // sweep a tenth of a millisecond and a hand-over a point; the
        // commands use rayon's joins only, which this thread runs itself)
        let pool = if n == 1 {
            pool.use_current_thread()
        } else {
            pool
        };
        pool.build_global()?;
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

/// A progress bar drawn for the study runner: made when the runner says how
/// many points will run, cleared when dropped.
pub struct Bar {
    what: &'static str,
    bar: std::sync::OnceLock<ProgressBar>,
}

impl Bar {
    pub fn new(what: &'static str) -> Self {
        Self {
            what,
            bar: std::sync::OnceLock::new(),
        }
    }
}

impl Progress for Bar {
    fn start(&self, points: usize) {
        let _ = self.bar.set(progress(points, self.what));
    }
    fn finished_one(&self) {
        if let Some(bar) = self.bar.get() {
            bar.inc(1);
        }
    }
}

impl Drop for Bar {
    fn drop(&mut self) {
        if let Some(bar) = self.bar.get() {
            bar.finish_and_clear();
        }
    }
}

/// Runs the points of a journaled command through the study runner and says
/// when `--resume` found no journal to resume.
pub fn run_journaled<P: Sync, T: Serialize + DeserializeOwned + Send>(
    points: &[P],
    plan: &JournalPlan,
    work: impl Fn(usize, &P) -> T + Sync,
) -> anyhow::Result<Finished<T>> {
    let finished = impact_study::run_journaled(points, plan, &Bar::new("points"), work)
        .map_err(crate::flags::journal)?;
    if finished.started_afresh {
        eprintln!(
            "note: {} does not exist yet: starting from the beginning",
            plan.path.display()
        );
    }
    Ok(finished)
}

/// A spinner on stderr (a terminal only) while a merged ladder runs: the
/// exact engine's hard scenes take seconds, and the levels say how far the
/// error bound has come. Nothing for runs that stay exact (milliseconds).
pub struct LadderSpinner {
    bar: std::sync::OnceLock<ProgressBar>,
}

impl LadderSpinner {
    pub fn new() -> Self {
        Self {
            bar: std::sync::OnceLock::new(),
        }
    }

    /// Shows what the ladder reports.
    pub fn show(&self, progress: impact_wave::LadderProgress) {
        use impact_wave::LadderProgress::{ExactAgain, FurtherTwins, LadderStarted, LevelDone};
        if !std::io::stderr().is_terminal() {
            return;
        }
        match progress {
            LadderStarted { exact_events } => {
                let bar = ProgressBar::new_spinner();
                bar.set_style(
                    ProgressStyle::with_template("{elapsed_precise} {spinner} {msg}")
                        .unwrap_or_else(|_| ProgressStyle::default_spinner()),
                );
                bar.enable_steady_tick(std::time::Duration::from_millis(120));
                bar.set_message(format!(
                    "the exact run needs more than {exact_events} events: merged lattices, halved until the error bound meets --target"
                ));
                let _ = self.bar.set(bar);
            }
            LevelDone {
                level,
                per_transit,
                restitution,
                bound,
                work,
            } => {
                if let Some(bar) = self.bar.get() {
                    let bound = if level >= 2 {
                        format!("bound {bound:.1e}")
                    } else {
                        "no bound before two levels".to_string()
                    };
                    bar.set_message(format!(
                        "merged level {level} done (lattice {per_transit:.3} of each transit): e = {restitution:.8}, {bound}, {work} units of work"
                    ));
                }
            }
            ExactAgain { events } => {
                if let Some(bar) = self.bar.get() {
                    bar.set_message(format!(
                        "the merged levels do not converge: the exact run again, allowed the ladder's budget of {events} events"
                    ));
                }
            }
            FurtherTwins {
                level,
                first_difference,
            } => {
                if let Some(bar) = self.bar.get() {
                    bar.set_message(format!(
                        "merged level {level}: its twin with a 1e-12 stiffer bottom differs by {first_difference:.1e}, so contacts flip on a nudge: two more twins measure how far"
                    ));
                }
            }
        }
    }
}

impl Drop for LadderSpinner {
    fn drop(&mut self) {
        if let Some(bar) = self.bar.get() {
            bar.finish_and_clear();
        }
    }
}

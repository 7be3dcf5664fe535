//! One runner for every study over many points (sweep, compare, the paper's
//! figures, the calibration table): parallel, with results in the order of
//! the points whatever the number of threads, and, when given a journal,
//! sharded, resumable and safe to kill at any moment.
//!
//! Why one: the journaled loop had been written twice (sweep and compare) and
//! the figures ran loops of their own; the rules a user relies on (a shard's
//! journal is never deleted, a torn line is redone, results do not depend on
//! the thread count) now hold in one place, tested once.

use crate::journal::{Journal, JournalError, JournalHeader};
use rayon::prelude::*;
use serde::Serialize;
use serde::de::DeserializeOwned;
use std::collections::BTreeMap;
use std::path::Path;

/// Told how many points will run, then once per finished point (from the
/// worker threads). The binary draws a progress bar with it; `()` ignores it.
pub trait Progress: Sync {
    /// Called once, before any point runs, with the number of points.
    fn start(&self, _points: usize) {}
    /// Called once per finished point, from the worker thread that ran it.
    fn finished_one(&self) {}
}

impl Progress for () {}

/// Maps `work` over `items` in parallel; the results come back in the order
/// of `items`, whatever the number of threads.
pub fn par_map<P: Sync, T: Send>(
    items: &[P],
    progress: &dyn Progress,
    work: impl Fn(&P) -> T + Sync,
) -> Vec<T> {
    progress.start(items.len());
    items
        .par_iter()
        .map(|p| {
            let t = work(p);
            progress.finished_one();
            t
        })
        .collect()
}

/// Where a run keeps its journal and whether it picks up an old one.
pub struct JournalPlan<'a> {
    /// The journal file.
    pub path: &'a Path,
    /// What this run is; a journal with another header is refused.
    pub header: JournalHeader,
    /// Pick up the points an existing journal already holds.
    pub resume: bool,
}

/// What a journaled run found and did.
#[derive(Debug)]
pub struct Finished<T> {
    /// Points found in the journal, by grid index.
    pub resumed: BTreeMap<usize, T>,
    /// Points computed by this run, by grid index.
    pub fresh: BTreeMap<usize, T>,
    /// `resume` was asked for but there was no journal yet.
    pub started_afresh: bool,
}

impl<T> Finished<T> {
    /// Every point of the shard, resumed and fresh, in grid order.
    pub fn into_rows(self) -> BTreeMap<usize, T> {
        let mut rows = self.resumed;
        rows.extend(self.fresh);
        rows
    }
}

/// Runs the points of `plan.header.shard` not already in the journal, each
/// appended to it as soon as it is done.
///
/// The journal's rules are [`Journal::open`]'s: one writer at a time, a
/// shard's journal never started afresh, a torn line redone.
pub fn run_journaled<P: Sync, T: Serialize + DeserializeOwned + Send>(
    points: &[P],
    plan: &JournalPlan,
    progress: &dyn Progress,
    work: impl Fn(usize, &P) -> T + Sync,
) -> Result<Finished<T>, JournalError> {
    let (journal, done) = Journal::open::<T>(plan.path, &plan.header, plan.resume)?;
    let started_afresh = journal.started_afresh();
    let shard = plan.header.shard;
    let todo: Vec<usize> = (0..points.len())
        .filter(|&k| shard.contains(k) && !done.contains_key(&k))
        .collect();
    progress.start(todo.len());
    let fresh: BTreeMap<usize, T> = todo
        .par_iter()
        .map(|&k| {
            let row = work(k, &points[k]);
            let written = journal.append(k, &row);
            progress.finished_one();
            written.map(|()| (k, row))
        })
        .collect::<Result<_, _>>()?;
    Ok(Finished {
        resumed: done,
        fresh,
        started_afresh,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::journal::Shard;
    use std::sync::atomic::{AtomicUsize, Ordering};

    struct Count(AtomicUsize, AtomicUsize);
    impl Progress for Count {
        fn start(&self, points: usize) {
            self.0.store(points, Ordering::SeqCst);
        }
        fn finished_one(&self) {
            self.1.fetch_add(1, Ordering::SeqCst);
        }
    }

    fn tmp(name: &str) -> std::path::PathBuf {
        let p = std::env::temp_dir().join(format!("impact-runner-{}-{name}", std::process::id()));
        let _ = std::fs::remove_file(&p);
        p
    }

    #[test]
    fn par_map_keeps_the_order_whatever_the_threads() {
        let items: Vec<u64> = (0..500).collect();
        let square = |k: &u64| k * k;
        let serial: Vec<u64> = items.iter().map(square).collect();
        for threads in [1, 4] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let count = Count(AtomicUsize::new(0), AtomicUsize::new(0));
            assert_eq!(pool.install(|| par_map(&items, &count, square)), serial);
            assert_eq!(count.0.load(Ordering::SeqCst), 500);
            assert_eq!(count.1.load(Ordering::SeqCst), 500);
        }
    }

    #[test]
    fn shards_resume_and_join_into_the_whole_run() {
        let points: Vec<f64> = (0..7).map(|k| k as f64).collect();
        let work = |_: usize, p: &f64| p * 0.5;
        let paths: Vec<_> = (1..=2).map(|i| tmp(&format!("shard{i}"))).collect();
        for (i, path) in paths.iter().enumerate() {
            let shard = Shard {
                index: i as u32 + 1,
                count: 2,
            };
            let header = JournalHeader::new("sweep", serde_json::json!({}), 7, shard);
            let plan = JournalPlan {
                path,
                header,
                resume: true,
            };
            let first = run_journaled(&points, &plan, &(), work).unwrap();
            assert!(first.started_afresh && first.resumed.is_empty());
            assert!(first.fresh.keys().all(|&k| shard.contains(k)));
            // a second call redoes nothing
            let count = Count(AtomicUsize::new(9), AtomicUsize::new(0));
            let again = run_journaled(&points, &plan, &count, work).unwrap();
            assert!(again.fresh.is_empty());
            assert_eq!(again.resumed, first.fresh);
            assert_eq!(count.0.load(Ordering::SeqCst), 0);
            // without --resume a shard's journal is kept and the run refused
            let fresh = JournalPlan {
                resume: false,
                ..plan
            };
            assert!(matches!(
                run_journaled(&points, &fresh, &(), work),
                Err(JournalError::Exists(_))
            ));
        }
        let (_, rows) = crate::journal::merge::<f64>(&paths).unwrap();
        assert_eq!(rows, vec![0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0]);
    }

    #[test]
    fn an_unsharded_run_without_resume_starts_afresh() {
        let path = tmp("afresh");
        let points = [1.0f64, 2.0];
        let header = JournalHeader::new("sweep", serde_json::json!({}), 2, Shard::ALL);
        let plan = JournalPlan {
            path: &path,
            header,
            resume: false,
        };
        run_journaled(&points, &plan, &(), |_, p| *p).unwrap();
        let second = run_journaled(&points, &plan, &(), |_, p| 10.0 * p).unwrap();
        assert!(second.resumed.is_empty());
        assert_eq!(
            second.into_rows().into_values().collect::<Vec<_>>(),
            [10.0, 20.0]
        );
    }
}

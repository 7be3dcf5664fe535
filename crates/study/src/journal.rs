//! Journals: finished points appended one JSON line at a time, so that a run
//! can be split into shards, killed at any moment, resumed without redoing
//! or duplicating a point, and merged into exactly what one run writes.
//!
//! The first line is a [`JournalHeader`] (what was run); each further line is
//! `{"index": k, "row": ...}` for grid point `k`, written with one `write`
//! call. A line cut short by a kill is detected on resume (no newline, or not
//! JSON) and its point is done again.

use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::io::{Read, Seek, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use thiserror::Error;

/// Problems with a journal, each saying what to do.
#[derive(Debug, Error)]
pub enum JournalError {
    /// A shard not written `I/N` with `1 <= I <= N` (the text given).
    #[error("shard must be I/N with 1 <= I <= N (got '{0}')")]
    Shard(String),
    /// A shard's journal already has points and resuming was not asked for.
    #[error("{0} exists: resume it, or remove it")]
    Exists(PathBuf),
    /// Another process holds the journal's lock.
    #[error("{path} is being written by another process{}: wait for it to finish or stop it", holder.as_ref().map_or_else(String::new, |h| format!(" ({h})")))]
    Locked {
        /// The journal.
        path: PathBuf,
        /// Who holds the lock (PID and host from its note), when known.
        holder: Option<String>,
    },
    /// The journal's header differs from this run's: resuming or merging it would mix runs.
    #[error(
        "{path} was written by a different run ({what} differs): use the same settings, or another file"
    )]
    Mismatch {
        /// The journal.
        path: PathBuf,
        /// What differs (the command, the settings, the tool's version, ...).
        what: &'static str,
    },
    /// A line, other than a torn last one, that does not parse.
    #[error("{path} line {line} is not a journal entry: {reason}")]
    Corrupt {
        /// The journal.
        path: PathBuf,
        /// Line number, from 1.
        line: usize,
        /// Why it does not parse.
        reason: String,
    },
    /// The merged journals do not cover the grid.
    #[error(
        "the journals miss {missing} of {total} points (first missing: index {first}), in shard{} {} of {}: complete {} and merge again",
        if shards.len() == 1 { "" } else { "s" },
        shard_ranges(shards),
        shards.first().map_or(0, |s| s.count),
        if shards.len() == 1 { "it" } else { "them" }
    )]
    Incomplete {
        /// Points missing.
        missing: usize,
        /// Points in the grid.
        total: usize,
        /// Index of the first missing point.
        first: usize,
        /// The shards the missing points belong to.
        shards: Vec<Shard>,
    },
    /// One journal passed twice to a merge.
    #[error("{0} is given twice")]
    GivenTwice(PathBuf),
    /// Two journals claim the same shard.
    #[error("{first} and {second} are both shard {}/{}: give each shard once", shard.index, shard.count)]
    SameShard {
        /// The first journal.
        first: PathBuf,
        /// The second journal.
        second: PathBuf,
        /// The shard both claim.
        shard: Shard,
    },
    /// Journals of different shard counts.
    #[error(
        "{first} is shard {}/{} but {second} is shard {}/{}: merge the journals of one sharding",
        a.index, a.count, b.index, b.count
    )]
    MixedShardings {
        /// The first journal.
        first: PathBuf,
        /// The second journal.
        second: PathBuf,
        /// The first journal's shard.
        a: Shard,
        /// The second journal's shard.
        b: Shard,
    },
    /// One point with two different results: the journals were not written by one deterministic run.
    #[error("point {index} appears twice with different results (in {path})")]
    Conflict {
        /// The grid point.
        index: usize,
        /// The journal holding the second result.
        path: PathBuf,
    },
    /// A merge of no journals.
    #[error("no journal given")]
    Empty,
    /// Reading, writing or locking a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating system's error.
        source: std::io::Error,
    },
}

/// Shard indices as SLURM writes array ranges: `2-4,7`.
pub fn shard_ranges(shards: &[Shard]) -> String {
    let mut parts: Vec<String> = Vec::new();
    let mut i = 0;
    while i < shards.len() {
        let mut j = i;
        while j + 1 < shards.len() && shards[j + 1].index == shards[j].index + 1 {
            j += 1;
        }
        parts.push(if j == i {
            shards[i].index.to_string()
        } else {
            format!("{}-{}", shards[i].index, shards[j].index)
        });
        i = j + 1;
    }
    parts.join(",")
}

fn io(path: &Path) -> impl Fn(std::io::Error) -> JournalError + '_ {
    move |source| JournalError::Io {
        path: path.to_path_buf(),
        source,
    }
}

/// Shard `index` of `count` (1-based): grid point `k` belongs to shard
/// `k mod count + 1`, which spreads costly regions evenly over the shards.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Shard {
    /// This shard's number, from 1.
    pub index: u32,
    /// Number of shards the grid is split into.
    pub count: u32,
}

impl Shard {
    /// The whole grid as one shard.
    pub const ALL: Shard = Shard { index: 1, count: 1 };

    /// Parses `I/N`, refusing `I = 0` and `I > N`.
    pub fn parse(text: &str) -> Result<Self, JournalError> {
        let bad = || JournalError::Shard(text.to_string());
        let (i, n) = text.split_once('/').ok_or_else(bad)?;
        let (index, count): (u32, u32) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if index == 0 || index > count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// Whether grid point `point` (0-based) belongs to this shard.
    pub fn contains(&self, point: usize) -> bool {
        point % self.count as usize == (self.index - 1) as usize
    }
}

/// What a journal records: everything two runs must share to be resumed or
/// merged together.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JournalHeader {
    /// `"impact-journal/2"` (2: settings as serialised JSON, with the
    /// tool's version; 1 keyed them by Rust `Debug` strings).
    pub journal: String,
    /// `"sweep"` or `"compare"`.
    pub command: String,
    /// The grid and engine settings, as the command describes them.
    pub settings: serde_json::Value,
    /// Points in the whole grid (all shards).
    pub points: usize,
    /// The shard this journal holds.
    pub shard: Shard,
}

impl JournalHeader {
    /// `Ok` when `other` was written by the same run (and, with
    /// `same_shard`, the same shard of it); else the first thing that
    /// differs, as a user would name it.
    fn same_run(&self, other: &JournalHeader, same_shard: bool) -> Result<(), &'static str> {
        let version = |h: &JournalHeader| h.settings.get("version").cloned();
        let checks = [
            ("command", self.command == other.command),
            ("the tool's version", version(self) == version(other)),
            ("settings", self.settings == other.settings),
            ("grid size", self.points == other.points),
            ("shard", !same_shard || self.shard == other.shard),
        ];
        match checks.iter().find(|(_, same)| !same) {
            Some((what, _)) => Err(what),
            None => Ok(()),
        }
    }

    /// The header, in the current journal format, of `command` run with `settings` over `points` grid points.
    pub fn new(command: &str, settings: serde_json::Value, points: usize, shard: Shard) -> Self {
        Self {
            journal: "impact-journal/2".into(),
            command: command.into(),
            settings,
            points,
            shard,
        }
    }
}

#[derive(Serialize, Deserialize)]
struct Entry<T> {
    index: usize,
    row: T,
}

/// An open journal, appended to from many threads, held under an exclusive
/// lock (`crate::lock`) until dropped.
pub struct Journal {
    path: PathBuf,
    /// Dropped before `file`, whose closing releases the lock.
    _owner: crate::lock::Owner,
    file: Mutex<std::fs::File>,
    started_afresh: bool,
}

/// Reads a journal: its header and entries, dropping a torn last line
/// (returning the byte length of the good part).
fn read_entries<T: DeserializeOwned>(
    path: &Path,
) -> Result<(JournalHeader, BTreeMap<usize, T>, u64), JournalError> {
    let mut text = String::new();
    std::fs::File::open(path)
        .and_then(|mut f| f.read_to_string(&mut text))
        .map_err(io(path))?;
    parse_entries(path, &text)
}

/// [`read_entries`] of a text already read.
fn parse_entries<T: DeserializeOwned>(
    path: &Path,
    text: &str,
) -> Result<(JournalHeader, BTreeMap<usize, T>, u64), JournalError> {
    // everything after the last newline is a line cut short
    let good = text.rfind('\n').map_or(0, |i| i + 1);
    let mut lines = text[..good].lines().enumerate();
    let corrupt = |line: usize, reason: String| JournalError::Corrupt {
        path: path.to_path_buf(),
        line: line + 1,
        reason,
    };
    let (_, first) = lines
        .next()
        .ok_or_else(|| corrupt(0, "empty journal".into()))?;
    let header: JournalHeader =
        serde_json::from_str(first).map_err(|e| corrupt(0, e.to_string()))?;
    let mut entries = BTreeMap::new();
    let all: Vec<(usize, &str)> = lines.collect();
    let mut good_len = good as u64;
    for (k, (i, line)) in all.iter().enumerate() {
        match serde_json::from_str::<Entry<T>>(line) {
            Ok(e) => {
                entries.insert(e.index, e.row);
            }
            // a complete but garbled last line: also a torn write, redo it
            Err(_) if k + 1 == all.len() => good_len -= line.len() as u64 + 1,
            Err(e) => return Err(corrupt(*i, e.to_string())),
        }
    }
    Ok((header, entries, good_len))
}

impl Journal {
    /// Opens `path` for `header`, under the journal's lock (a second writer
    /// gets [`JournalError::Locked`] at once, before anything is read).
    ///
    /// A file cut before its header line ends is started again. Without
    /// `resume` an existing unsharded journal is started afresh, but a
    /// shard's is never touched ([`JournalError::Exists`]: hours of points
    /// may be in it). With `resume` an existing journal must have been
    /// written by the same run; its finished points are returned and a torn
    /// last line is cut.
    pub fn open<T: DeserializeOwned>(
        path: &Path,
        header: &JournalHeader,
        resume: bool,
    ) -> Result<(Self, BTreeMap<usize, T>), JournalError> {
        let mut file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(path)
            .map_err(io(path))?;
        let owner = crate::lock::lock(path, &file)?;
        let mut text = String::new();
        file.read_to_string(&mut text).map_err(io(path))?;
        let started = text.contains('\n');
        if started && !resume && header.shard != Shard::ALL {
            return Err(JournalError::Exists(path.to_path_buf()));
        }
        let mut entries = BTreeMap::new();
        if started && resume {
            let (found, done, good_len) = parse_entries::<T>(path, &text)?;
            found
                .same_run(header, true)
                .map_err(|what| JournalError::Mismatch {
                    path: path.to_path_buf(),
                    what,
                })?;
            file.set_len(good_len).map_err(io(path))?;
            entries = done;
        } else {
            let mut line =
                serde_json::to_string(header).map_err(|e| io(path)(std::io::Error::other(e)))?;
            line.push('\n');
            file.set_len(0).map_err(io(path))?;
            file.seek(std::io::SeekFrom::Start(0)).map_err(io(path))?;
            file.write_all(line.as_bytes()).map_err(io(path))?;
        }
        file.seek(std::io::SeekFrom::End(0)).map_err(io(path))?;
        Ok((
            Self {
                path: path.to_path_buf(),
                _owner: owner,
                file: Mutex::new(file),
                started_afresh: resume && !started,
            },
            entries,
        ))
    }

    /// `resume` was asked for, but there was no journal (or only a torn
    /// header) to resume.
    pub fn started_afresh(&self) -> bool {
        self.started_afresh
    }

    /// Appends one finished point (one `write` of a whole line).
    pub fn append<T: Serialize>(&self, index: usize, row: &T) -> Result<(), JournalError> {
        let mut line = serde_json::to_string(&Entry { index, row })
            .map_err(|e| io(&self.path)(std::io::Error::other(e)))?;
        line.push('\n');
        let mut file = self.file.lock().unwrap_or_else(|p| p.into_inner());
        file.write_all(line.as_bytes()).map_err(io(&self.path))
    }

    /// The journal's file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// Joins journals of one run into its full header (shard 1/1) and rows in
/// grid order, checking that they agree, that each shard of one sharding is
/// given once, and that no point is missing (naming the shards to rerun).
pub fn merge<T: DeserializeOwned + PartialEq>(
    paths: &[PathBuf],
) -> Result<(JournalHeader, Vec<T>), JournalError> {
    let mut header: Option<JournalHeader> = None;
    let mut seen: Vec<(PathBuf, PathBuf, Shard)> = Vec::new();
    let mut rows: BTreeMap<usize, T> = BTreeMap::new();
    for path in paths {
        let (h, entries, _) = read_entries::<T>(path)?;
        let canonical = std::fs::canonicalize(path).map_err(io(path))?;
        for (other, other_canonical, shard) in &seen {
            if *other_canonical == canonical {
                return Err(JournalError::GivenTwice(path.clone()));
            }
            if shard.count != h.shard.count {
                return Err(JournalError::MixedShardings {
                    first: other.clone(),
                    second: path.clone(),
                    a: *shard,
                    b: h.shard,
                });
            }
            if *shard == h.shard {
                return Err(JournalError::SameShard {
                    first: other.clone(),
                    second: path.clone(),
                    shard: h.shard,
                });
            }
        }
        seen.push((path.clone(), canonical, h.shard));
        if let Some(first) = &header {
            first
                .same_run(&h, false)
                .map_err(|what| JournalError::Mismatch {
                    path: path.clone(),
                    what,
                })?;
        } else {
            header = Some(h);
        }
        for (index, row) in entries {
            if let Some(old) = rows.get(&index) {
                if *old != row {
                    return Err(JournalError::Conflict {
                        index,
                        path: path.clone(),
                    });
                }
            } else {
                rows.insert(index, row);
            }
        }
    }
    let mut header = header.ok_or(JournalError::Empty)?;
    let total = header.points;
    let missing: Vec<usize> = (0..total).filter(|k| !rows.contains_key(k)).collect();
    if !missing.is_empty() || rows.keys().next_back().is_some_and(|&k| k >= total) {
        let count = header.shard.count;
        let mut shards: Vec<Shard> = missing
            .iter()
            .map(|&k| Shard {
                index: (k % count as usize) as u32 + 1,
                count,
            })
            .collect();
        shards.sort_by_key(|s| s.index);
        shards.dedup();
        return Err(JournalError::Incomplete {
            missing: missing.len(),
            total,
            first: missing.first().copied().unwrap_or(0),
            shards,
        });
    }
    header.shard = Shard::ALL;
    Ok((header, rows.into_values().collect()))
}

/// Reads only a journal's header (to tell which command wrote it).
pub fn header(path: &Path) -> Result<JournalHeader, JournalError> {
    let file = std::fs::File::open(path).map_err(io(path))?;
    let mut first = String::new();
    std::io::BufRead::read_line(&mut std::io::BufReader::new(file), &mut first)
        .map_err(io(path))?;
    serde_json::from_str(&first).map_err(|e| JournalError::Corrupt {
        path: path.to_path_buf(),
        line: 1,
        reason: e.to_string(),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tmp(name: &str) -> PathBuf {
        let p = std::env::temp_dir().join(format!("impact-journal-{}-{name}", std::process::id()));
        let _ = std::fs::remove_file(&p);
        p
    }

    fn header(shard: Shard) -> JournalHeader {
        JournalHeader::new("sweep", serde_json::json!({"x": "0.1:0.5:0.1"}), 5, shard)
    }

    #[test]
    fn shards_partition_the_grid() {
        let shards: Vec<Shard> = (1..=3).map(|i| Shard { index: i, count: 3 }).collect();
        for k in 0..100 {
            assert_eq!(shards.iter().filter(|s| s.contains(k)).count(), 1);
        }
        assert!(
            Shard::parse("0/3").is_err()
                && Shard::parse("4/3").is_err()
                && Shard::parse("a").is_err()
        );
        assert_eq!(
            Shard::parse(" 2 / 3 ").unwrap(),
            Shard { index: 2, count: 3 }
        );
    }

    #[test]
    fn a_torn_last_line_is_redone_and_nothing_is_duplicated() {
        let p = tmp("torn");
        let h = header(Shard::ALL);
        let (j, done) = Journal::open::<f64>(&p, &h, false).unwrap();
        assert!(done.is_empty());
        for k in 0..3 {
            j.append(k, &(k as f64 * 1.5)).unwrap();
        }
        drop(j);
        // a kill in the middle of the fourth write
        std::fs::OpenOptions::new()
            .append(true)
            .open(&p)
            .unwrap()
            .write_all(br#"{"index":3,"ro"#)
            .unwrap();
        let (j, done) = Journal::open::<f64>(&p, &h, true).unwrap();
        assert_eq!(done.keys().copied().collect::<Vec<_>>(), vec![0, 1, 2]);
        j.append(3, &4.5).unwrap();
        j.append(4, &6.0).unwrap();
        drop(j);
        let (merged_header, rows) = merge::<f64>(std::slice::from_ref(&p)).unwrap();
        assert_eq!(rows, vec![0.0, 1.5, 3.0, 4.5, 6.0]);
        assert_eq!(merged_header.shard, Shard::ALL);
    }

    #[test]
    fn resume_refuses_another_run_and_merge_finds_gaps() {
        let p = tmp("mismatch");
        let (j, _) = Journal::open::<f64>(&p, &header(Shard::ALL), false).unwrap();
        j.append(0, &1.0).unwrap();
        drop(j);
        let other = JournalHeader::new("sweep", serde_json::json!({"x": "0.2"}), 5, Shard::ALL);
        assert!(matches!(
            Journal::open::<f64>(&p, &other, true),
            Err(JournalError::Mismatch {
                what: "settings",
                ..
            })
        ));
        assert!(matches!(
            merge::<f64>(&[p]),
            Err(JournalError::Incomplete {
                missing: 4,
                first: 1,
                ..
            })
        ));
    }

    #[test]
    fn merge_names_the_shard_to_rerun_and_refuses_doubles_and_mixes() {
        let write = |name: &str, shard: Shard, points: &[usize]| {
            let p = tmp(name);
            let h = JournalHeader::new("sweep", serde_json::json!({}), 6, shard);
            let (j, _) = Journal::open::<f64>(&p, &h, true).unwrap();
            for &k in points {
                j.append(k, &(k as f64)).unwrap();
            }
            p
        };
        let of3 = |index| Shard { index, count: 3 };
        let one = write("m1", of3(1), &[0, 3]);
        let two = write("m2", of3(2), &[1, 4]);
        let three_cut = write("m3", of3(3), &[2]);
        match merge::<f64>(&[one.clone(), two.clone(), three_cut]) {
            Err(e @ JournalError::Incomplete { .. }) => {
                let text = e.to_string();
                assert!(text.contains("miss 1 of 6 points") && text.contains("in shard 3 of 3"));
            }
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            merge::<f64>(&[one.clone(), two.clone(), one.clone()]),
            Err(JournalError::GivenTwice(_))
        ));
        let copy = tmp("m1-copy");
        std::fs::copy(&one, &copy).unwrap();
        assert!(matches!(
            merge::<f64>(&[one.clone(), copy]),
            Err(JournalError::SameShard { .. })
        ));
        let whole = write("m-all", Shard::ALL, &[0, 1, 2, 3, 4, 5]);
        assert!(matches!(
            merge::<f64>(&[whole, one]),
            Err(JournalError::MixedShardings { .. })
        ));
    }

    #[test]
    fn shard_ranges_read_as_slurm_arrays() {
        let of = |i: &[u32]| -> Vec<Shard> {
            i.iter().map(|&index| Shard { index, count: 9 }).collect()
        };
        assert_eq!(shard_ranges(&of(&[2, 3, 4, 7])), "2-4,7");
        assert_eq!(shard_ranges(&of(&[1])), "1");
        assert_eq!(shard_ranges(&of(&[1, 3, 5, 6])), "1,3,5-6");
    }

    #[test]
    fn another_version_of_the_tool_is_named_as_the_difference() {
        let p = tmp("version");
        let of = |v: &str| {
            JournalHeader::new(
                "sweep",
                serde_json::json!({"version": v, "x": "0.5"}),
                2,
                Shard::ALL,
            )
        };
        drop(Journal::open::<f64>(&p, &of("0.1.0"), false).unwrap());
        match Journal::open::<f64>(&p, &of("0.2.0"), true) {
            Err(e @ JournalError::Mismatch { .. }) => {
                assert!(e.to_string().contains("the tool's version differs"), "{e}");
            }
            other => panic!("{:?}", other.map(|_| ())),
        }
    }
}

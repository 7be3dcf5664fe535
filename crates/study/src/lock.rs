//! One writer per journal.
//!
//! Two processes appending to one journal (a shard resubmitted while the
//! original still runs) interleave their lines and leave a file neither
//! resume nor merge can read. So a journal is opened only under an exclusive
//! advisory lock on the journal file itself (`flock` through the standard
//! library's `File::try_lock`; on Linux NFS clients emulate it with
//! cluster-wide byte-range locks). The lock is taken before the file is read,
//! so a second writer never sees, truncates or repairs a journal in use, and
//! the kernel drops it when the holder dies, however it dies: no stale lock
//! survives a `kill -9` or a lost node.
//!
//! Who holds the lock is written beside it in a hidden `.NAME.owner` file
//! (host and PID), read only to word the refusal; it is removed when the
//! holder closes the journal, and a stale one from a killed holder is simply
//! overwritten by the next.

use crate::journal::JournalError;
use std::fs::{File, TryLockError};
use std::path::{Path, PathBuf};

/// Holds the journal's lock (through the journal's open file) and owns the
/// note saying who holds it.
#[derive(Debug)]
pub(crate) struct Owner {
    note: PathBuf,
}

/// `.NAME.owner` beside the journal `NAME`.
fn note_path(journal: &Path) -> PathBuf {
    let name = journal
        .file_name()
        .map_or_else(|| "journal".into(), |n| n.to_string_lossy().into_owned());
    journal.with_file_name(format!(".{name}.owner"))
}

/// This process, as a person at another terminal would look for it.
fn this_process() -> String {
    let host = std::fs::read_to_string("/proc/sys/kernel/hostname")
        .ok()
        .or_else(|| std::env::var("HOSTNAME").ok())
        .map_or_else(|| "this host".into(), |h| h.trim().to_string());
    format!("PID {} on {host}", std::process::id())
}

/// Takes the exclusive lock on `file` (the journal at `path`) without
/// waiting, or says who holds it.
pub(crate) fn lock(path: &Path, file: &File) -> Result<Owner, JournalError> {
    let note = note_path(path);
    match file.try_lock() {
        Ok(()) => {}
        Err(TryLockError::WouldBlock) => {
            let holder = std::fs::read_to_string(&note)
                .ok()
                .map(|h| h.trim().to_string())
                .filter(|h| !h.is_empty());
            return Err(JournalError::Locked {
                path: path.to_path_buf(),
                holder,
            });
        }
        Err(TryLockError::Error(source)) => {
            return Err(JournalError::Io {
                path: path.to_path_buf(),
                source,
            });
        }
    }
    // the note only words a refusal: failing to write it is no reason to stop
    let _ = std::fs::write(&note, this_process());
    Ok(Owner { note })
}

impl Drop for Owner {
    /// Runs before the journal's file (and so its lock) is closed: the note
    /// never outlives the lock it describes, except after a kill.
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.note);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_writer_is_refused_and_told_who_holds_the_lock() {
        let dir = std::env::temp_dir().join(format!("impact-lock-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("j.jsonl");
        let open = || {
            File::options()
                .read(true)
                .write(true)
                .create(true)
                .truncate(false)
                .open(&path)
                .unwrap()
        };
        let (first, second) = (open(), open());
        let owner = lock(&path, &first).unwrap();
        match lock(&path, &second) {
            Err(JournalError::Locked { holder, .. }) => {
                let holder = holder.unwrap();
                assert!(holder.contains(&format!("PID {}", std::process::id())));
            }
            other => panic!("not refused: {other:?}"),
        }
        drop(owner);
        drop(first);
        assert!(!note_path(&path).exists(), "the note goes with the lock");
        let _again = lock(&path, &second).unwrap();
    }
}

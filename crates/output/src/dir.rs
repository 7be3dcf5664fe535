//! Report directories that appear whole or not at all: files are written
//! into a staging directory beside the report's, which is renamed into place
//! only when everything is written.

use std::io;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// A report directory being written. Write into [`ReportDir::path`], then
/// [`ReportDir::commit`]; dropped without a commit (an error, a panic) the
/// staging directory is removed and the old report, if any, is untouched.
#[derive(Debug)]
pub struct ReportDir {
    target: PathBuf,
    staging: PathBuf,
    committed: bool,
}

/// Distinguishes staging directories of one process (tests write several
/// reports at once).
static SERIAL: AtomicUsize = AtomicUsize::new(0);

/// `.NAME.WHAT-PID-SERIAL` beside `target`.
fn sibling(target: &Path, what: &str) -> io::Result<PathBuf> {
    let name = target.file_name().ok_or_else(|| {
        io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{} does not name a directory", target.display()),
        )
    })?;
    Ok(target.with_file_name(format!(
        ".{}.{what}-{}-{}",
        name.to_string_lossy(),
        std::process::id(),
        SERIAL.fetch_add(1, Ordering::Relaxed)
    )))
}

/// Hard-links (or, where links are refused, copies) `from` into `to`,
/// directories recursively; symbolic links are linked themselves.
fn link_tree(from: &Path, to: &Path) -> io::Result<()> {
    if std::fs::symlink_metadata(from)?.is_dir() {
        std::fs::create_dir(to)?;
        for entry in std::fs::read_dir(from)? {
            let entry = entry?;
            link_tree(&entry.path(), &to.join(entry.file_name()))?;
        }
        Ok(())
    } else {
        std::fs::hard_link(from, to).or_else(|_| std::fs::copy(from, to).map(|_| ()))
    }
}

impl ReportDir {
    /// Starts a report that will be `target`; its parent is created if
    /// needed. `target` may exist (it is replaced on commit) but must not be
    /// a file.
    pub fn create(target: &Path) -> io::Result<Self> {
        // `.` or `dir/..` have no name of their own: use the real one
        let target = if target.file_name().is_none() && target.exists() {
            target.canonicalize()?
        } else {
            target.to_path_buf()
        };
        if target.exists() && !target.is_dir() {
            return Err(io::Error::new(
                io::ErrorKind::AlreadyExists,
                format!("{} exists and is not a directory", target.display()),
            ));
        }
        if let Some(parent) = target.parent().filter(|p| !p.as_os_str().is_empty()) {
            std::fs::create_dir_all(parent)?;
        }
        let staging = sibling(&target, "partial")?;
        if staging.exists() {
            // left by a killed run whose process id came round again
            std::fs::remove_dir_all(&staging)?;
        }
        std::fs::create_dir(&staging)?;
        Ok(Self {
            target,
            staging,
            committed: false,
        })
    }

    /// Where the files go until the commit.
    pub fn path(&self) -> &Path {
        &self.staging
    }

    /// The report's final place.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Puts the report in place. An existing directory is replaced: what it
    /// holds that the new report does not write (a run's journal, files of
    /// the user's) is carried over by hard links first, then the old
    /// directory is renamed aside, the new one renamed in, and the old one
    /// removed. A reader sees the old report or the new one, never a mix.
    pub fn commit(mut self) -> io::Result<()> {
        if !self.target.exists() {
            std::fs::rename(&self.staging, &self.target)?;
            self.committed = true;
            return Ok(());
        }
        for entry in std::fs::read_dir(&self.target)? {
            let entry = entry?;
            let staged = self.staging.join(entry.file_name());
            if std::fs::symlink_metadata(&staged).is_err() {
                link_tree(&entry.path(), &staged)?;
            }
        }
        if self.holds_working_directory() {
            // renaming the working directory away would strand the shell
            // in a removed directory: move the files in one by one instead
            for entry in std::fs::read_dir(&self.staging)? {
                let entry = entry?;
                let target = self.target.join(entry.file_name());
                if target.is_dir() && entry.path().is_dir() {
                    std::fs::remove_dir_all(&target)?;
                }
                std::fs::rename(entry.path(), target)?;
            }
            std::fs::remove_dir(&self.staging)?;
            self.committed = true;
            return Ok(());
        }
        let aside = sibling(&self.target, "old")?;
        std::fs::rename(&self.target, &aside)?;
        if let Err(e) = std::fs::rename(&self.staging, &self.target) {
            // put the old report back; the staging directory goes on drop
            let _ = std::fs::rename(&aside, &self.target);
            return Err(e);
        }
        self.committed = true;
        // the new report is in place: a leftover old copy is only clutter
        let _ = std::fs::remove_dir_all(&aside);
        Ok(())
    }

    /// Whether the process's working directory is the target or inside it.
    fn holds_working_directory(&self) -> bool {
        match (
            std::env::current_dir().and_then(|d| d.canonicalize()),
            self.target.canonicalize(),
        ) {
            (Ok(cwd), Ok(target)) => cwd.starts_with(target),
            _ => false,
        }
    }
}

impl Drop for ReportDir {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("impact-output-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn names(dir: &Path) -> Vec<String> {
        let mut n: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        n.sort();
        n
    }

    #[test]
    fn nothing_appears_before_the_commit() {
        let root = scratch("commit");
        let target = root.join("report");
        let dir = ReportDir::create(&target).unwrap();
        std::fs::write(dir.path().join("index.html"), "new").unwrap();
        std::fs::create_dir(dir.path().join("cost")).unwrap();
        std::fs::write(dir.path().join("cost/a.csv"), "x\n").unwrap();
        assert!(!target.exists());
        dir.commit().unwrap();
        assert_eq!(names(&root), ["report"]);
        assert_eq!(names(&target), ["cost", "index.html"]);
        assert_eq!(
            std::fs::read_to_string(target.join("cost/a.csv")).unwrap(),
            "x\n"
        );
    }

    #[test]
    fn a_failed_run_leaves_no_partial_directory_and_the_old_report() {
        let root = scratch("abort");
        let target = root.join("report");
        std::fs::create_dir(&target).unwrap();
        std::fs::write(target.join("index.html"), "old").unwrap();
        let run = || -> io::Result<()> {
            let dir = ReportDir::create(&target)?;
            std::fs::write(dir.path().join("index.html"), "new")?;
            // a write that fails: its directory does not exist
            std::fs::write(dir.path().join("missing/points.csv"), "x")?;
            dir.commit()
        };
        assert!(run().is_err());
        assert_eq!(names(&root), ["report"]);
        assert_eq!(
            std::fs::read_to_string(target.join("index.html")).unwrap(),
            "old"
        );
        // a run that never had a report leaves nothing at all
        let fresh = root.join("fresh");
        drop(ReportDir::create(&fresh).unwrap());
        assert_eq!(names(&root), ["report"]);
    }

    #[test]
    fn a_rerun_replaces_the_report_and_keeps_what_it_does_not_write() {
        let root = scratch("rerun");
        let target = root.join("report");
        std::fs::create_dir_all(target.join("cost")).unwrap();
        std::fs::write(target.join("index.html"), "old").unwrap();
        std::fs::write(target.join("cost/stale.csv"), "old").unwrap();
        std::fs::write(target.join("points.jsonl"), "journal\n").unwrap();
        let dir = ReportDir::create(&target).unwrap();
        std::fs::write(dir.path().join("index.html"), "new").unwrap();
        std::fs::create_dir(dir.path().join("cost")).unwrap();
        dir.commit().unwrap();
        assert_eq!(names(&root), ["report"]);
        assert_eq!(names(&target), ["cost", "index.html", "points.jsonl"]);
        assert_eq!(
            std::fs::read_to_string(target.join("index.html")).unwrap(),
            "new"
        );
        assert_eq!(
            std::fs::read_to_string(target.join("points.jsonl")).unwrap(),
            "journal\n"
        );
        // a directory the new report writes is the new one, whole
        assert!(names(&target.join("cost")).is_empty());
    }

    #[test]
    fn a_file_in_the_way_is_refused() {
        let root = scratch("file");
        let target = root.join("report");
        std::fs::write(&target, "a file").unwrap();
        assert!(ReportDir::create(&target).is_err());
        assert_eq!(names(&root), ["report"]);
    }
}

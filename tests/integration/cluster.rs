//! What clusters rely on beyond sharding: one writer per journal.

use crate::support::*;

/// Two processes on one shard (a resubmitted task while the original still
/// runs): the second is refused at once, with exit 2 and the holder named,
/// and the first finishes a journal that merges into what one run writes.
#[test]
fn a_second_writer_on_a_shard_is_refused_and_the_journal_stays_intact() {
    let dir = scratch("two-writers");
    let journal = dir.join("j.jsonl");
    let j = journal.to_str().unwrap();
    let grid = "sweep --x 0.05:0.95:0.05 --alpha 0.2:0.8:0.2 --engine chain --n 600 --no-timing";
    let mut args: Vec<&str> = grid.split(' ').collect();
    args.extend(["--threads", "1", "--shard", "1/1", "--resume", "--out", j]);
    let mut first = start_until_lines(&args, &journal, 3);
    // (were the first done already, the second would succeed: a failure here)
    let second = impact(&args);
    assert_eq!(second.status.code(), Some(2), "{}", stderr(&second));
    let err = stderr(&second);
    assert!(
        err.contains("being written by another process")
            && err.contains(&format!("PID {}", first.id())),
        "{err}"
    );
    assert!(first.wait().unwrap().success());
    assert!(
        !dir.join(".j.jsonl.owner").exists(),
        "the owner note is gone"
    );
    let merged = dir.join("merged.csv");
    let out = impact_words("merge", &[j, "--out", merged.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    let whole = dir.join("whole.csv");
    let out = impact_words(grid, &["--out", whole.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(
        std::fs::read(&whole).unwrap(),
        std::fs::read(&merged).unwrap()
    );
}

//! The docs stay true: every path ARCHITECTURE.md names exists, and the
//! README's commands are the ones CI runs.

use crate::support::repo;

#[test]
fn architecture_names_only_existing_paths() {
    let text = std::fs::read_to_string(repo().join("ARCHITECTURE.md")).unwrap();
    let mut crate_dir = String::new();
    for line in text.lines() {
        if let Some(path) = line.strip_prefix("### `").and_then(|l| l.strip_suffix('`')) {
            assert!(repo().join(path).exists(), "ARCHITECTURE.md names {path}");
            crate_dir = path.to_string();
        }
        // file names in backquotes within a crate's paragraph
        for (i, piece) in line.split('`').enumerate() {
            if i % 2 == 1 && piece.ends_with(".rs") && piece.contains('/') {
                assert!(repo().join(piece).exists(), "ARCHITECTURE.md names {piece}");
            } else if i % 2 == 1 && piece.ends_with(".rs") && crate_dir.starts_with("crates/") {
                let src = repo().join(&crate_dir).join("src").join(piece);
                let bin = repo().join(&crate_dir).join(piece);
                assert!(
                    src.exists() || bin.exists(),
                    "ARCHITECTURE.md names {crate_dir}/{piece}"
                );
            }
        }
    }
}

#[test]
fn ci_runs_the_readme_test_command() {
    let readme = std::fs::read_to_string(repo().join("README.md")).unwrap();
    let ci = std::fs::read_to_string(repo().join(".ci/run")).unwrap();
    assert!(readme.contains("cargo test --workspace"));
    assert!(ci.contains("cargo test --workspace"));
}

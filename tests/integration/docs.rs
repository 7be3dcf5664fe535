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

/// The engines and studies speak physics: no string literal in their
/// sources names a command-line flag or command (comments may). The binary
/// alone (`crates/cli/flags.rs`) maps their errors to flags.
#[test]
fn libraries_name_no_flags() {
    fn sources(dir: &std::path::Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                sources(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    let mut files = Vec::new();
    for krate in ["model", "wave", "chain", "study", "rigid"] {
        sources(&repo().join("crates").join(krate).join("src"), &mut files);
    }
    assert!(files.len() > 20);
    let mut found = Vec::new();
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        for (n, line) in text.lines().enumerate() {
            let code = line.trim_start();
            if code.starts_with("//") {
                continue;
            }
            // the quoted parts of the line
            for (i, literal) in code.split('"').enumerate() {
                let flag = literal
                    .match_indices("--")
                    .any(|(at, _)| literal[at + 2..].starts_with(|c: char| c.is_ascii_lowercase()));
                if i % 2 == 1 && (flag || literal.contains("impact ")) {
                    found.push(format!("{}:{}: {literal}", file.display(), n + 1));
                }
            }
        }
    }
    assert!(
        found.is_empty(),
        "flags named in libraries:\n{}",
        found.join("\n")
    );
}

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub fn impact(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(args)
        .current_dir(repo())
        .output()
        .expect("the impact binary runs")
}

pub fn repo() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// A fresh scratch directory for one test.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("impact-e2e-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// A steel base (by material, 0.6 long) under two layers of gel (modulus
/// 0.05, density 1) in reduced units, written to `dir`: the steel's transit
/// is `1.2e-4` of the gel's, so it rebounds alone. `top_restitution` makes
/// the top layer viscous. Returns the scene's path.
pub fn steel_under_gel(dir: &Path, top_restitution: Option<f64>) -> PathBuf {
    let viscous = top_restitution.map_or(String::new(), |e| format!(", \"restitution\": {e}"));
    let path = dir.join("steel-under-gel.json");
    let scene = format!(
        r#"{{"impact_speed": 1.0, "layers": [
            {{"material": "steel", "length": 0.6}},
            {{"length": 0.4, "modulus": 0.05, "density": 1.0}},
            {{"length": 0.5, "modulus": 0.05, "density": 1.0{viscous}}}]}}"#
    );
    std::fs::write(&path, scene).unwrap();
    path
}

/// A JSON array of numbers as a vector; anything else fails the test.
pub fn numbers<T: serde::de::DeserializeOwned>(v: &serde_json::Value) -> Vec<T> {
    serde_json::from_value(v.clone())
        .unwrap_or_else(|e| panic!("not an array of numbers: {v}: {e}"))
}

/// The measures of one impact: `run --json` keys and `sweep` columns carry
/// them under the same names, so the two tests check one list.
pub const MEASURES: [&str; 6] = [
    "restitution",
    "contact_time",
    "reduced_contact_time",
    "n1",
    "bounces",
    "separations",
];

pub fn files_in(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Runs the binary with `words` split on whitespace, then `rest` as they are
/// (paths, and anything after them): one line per command in the tests.
pub fn impact_words(words: &str, rest: &[&str]) -> Output {
    let mut args: Vec<&str> = words.split_whitespace().collect();
    args.extend_from_slice(rest);
    impact(&args)
}

/// Runs `words` followed by a fresh path `file` in the scratch directory
/// `test`, insists on success, and returns the path and the output.
pub fn writes(test: &str, file: &str, words: &str) -> (PathBuf, Output) {
    let path = scratch(test).join(file);
    let out = impact_words(words, &[path.to_str().unwrap()]);
    assert!(out.status.success(), "{words}: {}", stderr(&out));
    (path, out)
}

/// Bad input: exit status 2, one line on stderr containing `needle`, nothing
/// on stdout, no panic.
pub fn assert_input_error(args: &[&str], needle: &str) {
    let out = impact(args);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
    assert!(stdout(&out).is_empty(), "{args:?} printed on stdout");
    let err = stderr(&out);
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "{args:?}: not one line:\n{err}"
    );
    assert!(err.contains(needle), "{args:?}: '{needle}' not in {err}");
    assert!(!err.contains("panicked") && !err.contains("backtrace"));
}

/// Starts the binary with `args` in the background and returns once `file`
/// has at least `lines` lines (or after 60 s): a run caught in the middle.
pub fn start_until_lines(args: &[&str], file: &Path, lines: usize) -> std::process::Child {
    let child = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(args)
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("the impact binary starts");
    let start = std::time::Instant::now();
    while std::fs::read_to_string(file).map_or(0, |t| t.lines().count()) < lines
        && start.elapsed().as_secs() < 60
    {
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    child
}

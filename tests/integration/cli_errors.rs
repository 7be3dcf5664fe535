//! Bad input: exit status 2, one line on stderr naming the field and the
//! allowed range, nothing on stdout, no file written.

use crate::support::*;

fn assert_input_error(args: &[&str], needle: &str) {
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

#[test]
fn out_of_range_bilayer_parameters() {
    assert_input_error(
        &["run", "--x", "0", "--alpha", "0.3"],
        "x must be a number in (0, 1) (got 0)",
    );
    assert_input_error(
        &["run", "--x", "0.3", "--alpha", "1"],
        "alpha must be a number in (0, 1) (got 1)",
    );
    assert_input_error(
        &["run", "--x", "-0.5", "--alpha", "0.3"],
        "x must be a number in (0, 1)",
    );
    assert_input_error(
        &["run", "--x", "NaN", "--alpha", "0.3"],
        "x must be a number in (0, 1) (got NaN)",
    );
    assert_input_error(&["run", "--x", "0.3"], "--alpha");
    assert_input_error(&["run", "--x", "abc", "--alpha", "0.3"], "--x");
    assert_input_error(&["run"], "give a scene file or both --x and --alpha");
}

#[test]
fn bad_engine_settings() {
    assert_input_error(
        &[
            "run",
            "--x",
            "0.3",
            "--alpha",
            "0.3",
            "--drop-tolerance",
            "-1",
        ],
        "--drop-tolerance must be a finite number >= 0",
    );
    assert_input_error(
        &["run", "--x", "0.3", "--alpha", "0.3", "--horizon", "0"],
        "--horizon must be a finite number > 0",
    );
    assert_input_error(
        &["run", "--x", "0.3", "--alpha", "0.3", "--engine", "magic"],
        "magic",
    );
}

#[test]
fn bad_scene_files() {
    let dir = scratch("scenes");
    let cases = [
        (
            "unknown.json",
            r#"{"impact_speed": 1, "layers": [{"length": 1, "modulus": 1, "density": 1, "colour": 3}]}"#,
            "unknown field `colour`",
        ),
        (
            "length.json",
            r#"{"impact_speed": 1, "layers": [{"length": 0, "modulus": 1, "density": 1}]}"#,
            "layers[0].length must be a finite number > 0 (got 0)",
        ),
        (
            "modulus.json",
            r#"{"impact_speed": 1, "layers": [{"length": 1, "modulus": 1, "density": 1}, {"length": 1, "modulus": -2, "density": 1}]}"#,
            "layers[1].modulus must be a finite number > 0 (got -2)",
        ),
        (
            "density.json",
            r#"{"impact_speed": 1, "layers": [{"length": 1, "modulus": 1, "density": 0}]}"#,
            "layers[0].density must be a finite number > 0",
        ),
        (
            "speed.json",
            r#"{"impact_speed": -1, "layers": [{"length": 1, "modulus": 1, "density": 1}]}"#,
            "impact_speed must be a finite number > 0",
        ),
        (
            "empty.json",
            r#"{"impact_speed": 1, "layers": []}"#,
            "layers must list at least one layer",
        ),
        (
            "malformed.json",
            r#"{"impact_speed": 1, "layers": ["#,
            "scene JSON",
        ),
        (
            "missing.json",
            r#"{"layers": [{"length": 1, "modulus": 1, "density": 1}]}"#,
            "missing field `impact_speed`",
        ),
    ];
    for (name, text, needle) in cases {
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        assert_input_error(&["run", path.to_str().unwrap()], needle);
    }
    assert_input_error(&["run", "/no/such/scene.json"], "cannot read scene");
}

#[test]
fn bad_sweeps_write_no_file() {
    let dir = scratch("badsweep");
    let out = dir.join("grid.csv");
    let o = out.to_str().unwrap();
    assert_input_error(
        &["sweep", "--x", "0:0.5:0.1", "--out", o],
        "--x values must be numbers in (0, 1) (got 0)",
    );
    assert_input_error(
        &["sweep", "--alpha", "0.5:0.1:0.1", "--out", o],
        "--alpha must have STEP > 0",
    );
    assert_input_error(
        &["sweep", "--x", "a:b:c", "--out", o],
        "--x must be START:STOP:STEP",
    );
    assert_input_error(
        &["sweep", "--out", o, "--merge-window", "-1"],
        "--merge-window",
    );
    assert_input_error(&["sweep", "--x", "0.5"], "--out");
    assert!(files_in(&dir).is_empty(), "{:?}", files_in(&dir));
}

#[test]
fn a_run_that_cannot_finish_says_why_with_status_1() {
    let out = impact(&[
        "run",
        "--x",
        "0.999",
        "--alpha",
        "0.0001",
        "--max-events",
        "100000",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stdout(&out).is_empty());
    let err = stderr(&out);
    assert!(
        err.contains("--merge-window") && err.contains("--max-events"),
        "{err}"
    );
    // and the remedy it names works
    let out = impact(&[
        "run",
        "--x",
        "0.999",
        "--alpha",
        "0.0001",
        "--merge-window",
        "1e-2",
        "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
}

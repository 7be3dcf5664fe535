//! Bad input: exit status 2, one line on stderr naming the field and the
//! allowed range, nothing on stdout, no file written.

use crate::support::*;

#[test]
fn out_of_range_bilayer_parameters() {
    for (x, alpha, needle) in [
        ("0", "0.3", "x must be a number in (0, 1) (got 0)"),
        ("0.3", "1", "alpha must be a number in (0, 1) (got 1)"),
        ("-0.5", "0.3", "x must be a number in (0, 1)"),
        ("NaN", "0.3", "x must be a number in (0, 1) (got NaN)"),
    ] {
        assert_input_error(&["run", "--x", x, "--alpha", alpha], needle);
    }
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

/// A heavy top on a soft layer over light fast layers at the bottom: the
/// contact lasts about 22 time units and the fastest layer rings every
/// `2.1e-7`, so even the merged ladder's coarsest run spends the events
/// it is given (`crates/wave/tests/hard_cases.rs` says why). The message
/// names the merged run and the flag that helps, not the merging that was
/// already done.
#[test]
fn a_merged_run_that_cannot_finish_names_the_event_limit() {
    let dir = scratch("long-contact");
    let path = dir.join("hammer.json");
    std::fs::write(
        &path,
        r#"{"impact_speed": 1, "layers": [
            {"length": 0.449, "modulus": 636000, "density": 0.00904},
            {"length": 0.482, "modulus": 45400, "density": 9.89e-7},
            {"length": 1.17, "modulus": 2.84e9, "density": 9.55e-5},
            {"length": 0.338, "modulus": 4.11, "density": 0.0475},
            {"length": 0.722, "modulus": 212000, "density": 859}]}"#,
    )
    .unwrap();
    let out = impact_words("run --max-events 1e6 --json", &[path.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stdout(&out).is_empty());
    let err = stderr(&out);
    assert!(
        err.contains("--max-events")
            && err.contains("merged run on the lattice of 0.2")
            && err.contains("events per unit of time")
            && !err.contains("--resolution"),
        "{err}"
    );
    assert_eq!(err.trim().lines().count(), 1, "{err}");
}

#[test]
fn a_run_that_cannot_finish_says_why_with_status_1() {
    // exact fronts only, and too few events for a scene whose fronts multiply
    let out = impact_words(
        "run --x 0.999 --alpha 0.0001 --resolution exact --max-events 100000",
        &[],
    );
    assert_eq!(out.status.code(), Some(1));
    assert!(stdout(&out).is_empty());
    let err = stderr(&out);
    assert!(
        err.contains("--resolution") && err.contains("--max-events"),
        "{err}"
    );
    // and the remedy it names works: by default the run finishes, with a bound
    let out = impact(&["run", "--x", "0.999", "--alpha", "0.0001", "--json"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    let bound = v["error_bound"].as_f64().unwrap();
    assert!(bound > 0.0 && bound < 1e-3, "{v}");
}

/// A horizon shorter than the contact is not a result: no restitution may
/// come out of it that a script could mistake for a final one.
#[test]
fn a_horizon_reached_in_contact_is_not_a_result() {
    // (a horizon reached in flight is the paper's own stop, and a result)
    let out = impact_words("run --x 0.4 --alpha 0.05 --horizon 0.5 --json", &[]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stdout(&out).is_empty());
    assert!(stderr(&out).contains("--horizon"), "{}", stderr(&out));
}

/// Derived quantities out of double precision, unknown materials and
/// engines that cannot take a scene are input errors naming the field.
#[test]
fn impossible_scenes_and_engine_mismatches_are_input_errors() {
    let dir = scratch("impossible");
    let cases = [
        (
            r#"{"impact_speed": 1.0, "layers": [{"length": 1.0, "modulus": 1e300, "density": 1e-320}, {"length": 1.0, "modulus": 1.0, "density": 1.0}]}"#,
            "layers[0].density must be at least 2.2e-308",
        ),
        (
            r#"{"impact_speed": 1.0, "layers": [{"length": 1.0, "material": "unobtainium"}]}"#,
            "unknown material",
        ),
        (
            r#"{"impact_speed": 1.0, "layers": [{"length": 1.0, "modulus": 1.0}]}"#,
            "density",
        ),
    ];
    for (i, (text, needle)) in cases.iter().enumerate() {
        let path = dir.join(format!("scene{i}.json"));
        std::fs::write(&path, text).unwrap();
        let out = impact(&["run", path.to_str().unwrap()]);
        assert_eq!(out.status.code(), Some(2), "{text}: {}", stderr(&out));
        let err = stderr(&out);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(needle), "{text}: {err}");
    }
    let out = impact_words(
        "run --x 0.4 --alpha 0.05 --e1 0.9 --engine rigid-bottom",
        &[],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("--engine rigid-bottom"));
}

/// The engines check their own ranges and name fields; the binary words
/// them as the flags that set those fields, before any run starts.
#[test]
fn engine_ranges_are_worded_as_flags() {
    let bilayer = ["run", "--x", "0.3", "--alpha", "0.3"];
    let cases: [(&[&str], &str); 6] = [
        (
            &["--merge-window", "0.3"],
            "--merge-window must be a number in (0, 0.25] (got 0.3)",
        ),
        (
            &["--event-budget", "0"],
            "--event-budget must be at least 1 (got 0)",
        ),
        (
            &["--max-events", "0"],
            "--max-events must be at least 1 (got 0)",
        ),
        (
            &["--engine", "rigid-bottom", "--horizon", "-2"],
            "--horizon must be a finite number > 0 (got -2)",
        ),
        (
            &["--engine", "chain", "--dt-factor", "0"],
            "--dt-factor must be a number in (0, 10] (got 0)",
        ),
        (
            &["--e2", "0.8", "--target", "0"],
            "--target must be a finite number > 0 (got 0)",
        ),
    ];
    for (extra, needle) in cases {
        let args: Vec<&str> = bilayer.iter().chain(extra).copied().collect();
        assert_input_error(&args, needle);
    }
}

/// Counts may be written as physicists write budgets (`1e8`), but must
/// name a whole number: a fraction or a negative count is refused, naming
/// the flag.
#[test]
fn counts_take_scientific_notation_but_only_whole_numbers() {
    let bilayer = ["run", "--x", "0.3", "--alpha", "0.3", "--json"];
    let plain = impact(&bilayer);
    for extra in [
        &["--event-budget", "4e6"][..],
        &["--max-events", "2e8", "--event-budget", "4_000_000"],
    ] {
        let args: Vec<&str> = bilayer.iter().chain(extra).copied().collect();
        let out = impact(&args);
        assert!(out.status.success(), "{extra:?}: {}", stderr(&out));
        let (a, b): (serde_json::Value, serde_json::Value) = (
            serde_json::from_str(&stdout(&out)).unwrap(),
            serde_json::from_str(&stdout(&plain)).unwrap(),
        );
        // the defaults written another way: the same numbers
        assert_eq!(a["restitution"], b["restitution"], "{extra:?}");
        assert_eq!(a["error_bound"], b["error_bound"], "{extra:?}");
    }
    for (flag, value) in [
        ("--event-budget", "1.5"),
        ("--max-events", "-1e3"),
        ("--max-events", "1e20"),
        ("--event-budget", "lots"),
    ] {
        let args: Vec<&str> = bilayer.iter().chain(&[flag, value]).copied().collect();
        assert_input_error(&args, flag);
        assert_input_error(&args, "not a whole number from 0 to 1.8e19");
    }
    let chain = [
        "run", "--x", "0.3", "--alpha", "0.3", "--engine", "chain", "--n", "2e2", "--json",
    ];
    let out = impact(&chain);
    assert!(out.status.success(), "{}", stderr(&out));
}

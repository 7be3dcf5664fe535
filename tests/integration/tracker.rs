//! The independent Python front tracker (`scripts/tracker.py`, written from
//! the paper, not from `crates/wave`) and the exact engine agree on `e` and
//! on the paper's bounce count. Skipped, saying so, where `python3` is absent.

use crate::support::*;
use serde_json::Value;
use std::io::Write;
use std::process::{Command, Stdio};

/// Fig. 3(b) and 3(c), a commensurate point (`t2 = 2 t1` up to rounding, so
/// fronts reach the wall together), and one of the paper's hardest points.
const POINTS: [(&str, &str); 4] = [
    ("0.3", "0.3"),
    ("0.4", "0.05"),
    ("0.5", "0.2"),
    ("0.95", "0.005"),
];

fn python3() -> Option<Command> {
    let found = Command::new("python3")
        .arg("--version")
        .output()
        .is_ok_and(|o| o.status.success());
    found.then(|| Command::new("python3"))
}

/// The tracker's JSON line for each point, in order.
fn tracker(mut python: Command, points: &str) -> Vec<Value> {
    let mut child = python
        .args(["scripts/tracker.py", "--points", "-"])
        .current_dir(repo())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .expect("python3 starts");
    child
        .stdin
        .take()
        .unwrap()
        .write_all(points.as_bytes())
        .unwrap();
    let out = child.wait_with_output().unwrap();
    assert!(out.status.success(), "scripts/tracker.py failed");
    stdout(&out)
        .lines()
        .map(|line| serde_json::from_str(line).unwrap())
        .collect()
}

#[test]
fn python_tracker_agrees_with_the_exact_engine() {
    let Some(python) = python3() else {
        println!("skipped: python3 not found, scripts/tracker.py not checked");
        return;
    };
    let points: String = POINTS.iter().map(|(x, a)| format!("{x} {a}\n")).collect();
    let runs = tracker(python, &points);
    assert_eq!(runs.len(), POINTS.len());
    for ((x, alpha), py) in POINTS.iter().zip(&runs) {
        let out = impact(&["run", "--x", x, "--alpha", alpha, "--json"]);
        assert!(out.status.success(), "{}", stderr(&out));
        let rs: Value = serde_json::from_str(&stdout(&out)).unwrap();
        let e = |v: &Value| v["restitution"].as_f64().unwrap();
        assert!(
            (e(&rs) - e(py)).abs() <= 1e-9,
            "x = {x}, alpha = {alpha}: impact e = {}, tracker e = {}",
            e(&rs),
            e(py)
        );
        assert_eq!(rs["bounces"], py["bounces"], "x = {x}, alpha = {alpha}");
        let tc = |v: &Value| v["contact_time"].as_f64().unwrap();
        assert!((tc(&rs) - tc(py)).abs() <= 1e-9, "x = {x}, alpha = {alpha}");
    }
}

//! `impact compare`, sharding, resuming and merging, end to end.

use crate::support::*;
use serde_json::Value;
use std::path::Path;

/// Runs `words` (split on whitespace) then `rest`, and insists on success.
fn ok(words: &str, rest: &[&str]) -> std::process::Output {
    let out = impact_words(words, rest);
    assert!(out.status.success(), "{words} {rest:?}: {}", stderr(&out));
    out
}

/// The whole grid in one uninterrupted, unsharded run (`command_and_grid`,
/// then `--out out`): what a sharded, merged or resumed run must equal.
fn whole_run(command_and_grid: &str, out: &Path) {
    ok(command_and_grid, &["--out", out.to_str().unwrap()]);
}

/// Two files are the same byte for byte.
fn same_bytes(a: &Path, b: &Path) {
    assert_eq!(std::fs::read(a).unwrap(), std::fs::read(b).unwrap());
}

fn report(dir: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap()
}

const REPORT_FILES: [&str; 7] = [
    "report.json",
    "points.csv",
    "index.html",
    "heatmap-de.svg",
    "heatmap-de.png",
    "heatmap-bounces.svg",
    "heatmap-bounces.png",
];

#[test]
fn small_compare_writes_every_file_with_the_numbers_of_separate_runs() {
    let dir = scratch("cmp-small");
    let out = dir.join("r");
    ok(
        "compare --x 0.2:0.4:0.2 --alpha 0.05:0.3:0.25 --n 200 --no-timing --out",
        &[out.to_str().unwrap()],
    );
    for f in REPORT_FILES {
        assert!(out.join(f).metadata().unwrap().len() > 0, "{f}");
    }
    let r = report(&out);
    let points = r["points"].as_array().unwrap();
    assert_eq!(points.len(), 4);
    for p in points {
        let (x, a) = (
            p["x"].as_f64().unwrap().to_string(),
            p["alpha"].as_f64().unwrap().to_string(),
        );
        let run = |extra: &[&str]| -> Value {
            let mut rest = vec!["--x", &x, "--alpha", &a, "--json"];
            rest.extend_from_slice(extra);
            serde_json::from_str(&stdout(&ok("run", &rest))).unwrap()
        };
        let exact = run(&[]);
        let chain = run(&["--engine", "chain", "--n", "200"]);
        assert_eq!(p["exact"]["restitution"], exact["restitution"], "{x} {a}");
        assert_eq!(
            p["chain"][0]["restitution"], chain["restitution"],
            "{x} {a}"
        );
        assert_eq!(p["chain"][0]["bounces"], chain["bounces"]);
        let de = p["restitution_difference"][0].as_f64().unwrap();
        assert_eq!(
            de,
            chain["restitution"].as_f64().unwrap() - exact["restitution"].as_f64().unwrap()
        );
    }
}

/// The issue's acceptance figure: at N = 1000, on a grid through every region
/// (lower, central, upper, multiple bounces), |de| < 0.01 everywhere and the
/// filtered bounce counts agree on at least 95% of points.
#[test]
fn at_n_1000_the_engines_agree_across_all_regions() {
    let dir = scratch("cmp-regions");
    let out = dir.join("r");
    ok(
        "compare --x 0.1:0.9:0.2 --alpha 0.03:0.93:0.15 --n 1000 --no-timing --out",
        &[out.to_str().unwrap()],
    );
    let s = &report(&out)["summary"];
    let (max, share) = (
        s["max_abs_de"].as_f64().unwrap(),
        s["bounces_agree"].as_f64().unwrap(),
    );
    println!(
        "N = 1000, 35 points: max |de| = {max:.4e}, median {:.4e}, N_b equal on {:.1}%",
        s["median_abs_de"].as_f64().unwrap(),
        100.0 * share
    );
    assert!(max < 0.01, "max |de| = {max}");
    assert!(share >= 0.95, "N_b agreement {share}");
}

#[test]
fn disagreement_shrinks_as_n_grows() {
    let dir = scratch("cmp-shrink");
    let mut shares = Vec::new();
    for n in ["125", "1000"] {
        let out = dir.join(n);
        ok(
            "compare --x 0.1:0.9:0.2 --alpha 0.05:0.85:0.2 --n",
            &[
                n,
                "--tolerance",
                "0.003",
                "--no-timing",
                "--out",
                out.to_str().unwrap(),
            ],
        );
        let s = &report(&out)["summary"];
        shares.push((
            1.0 - s["agree"].as_f64().unwrap(),
            s["max_abs_de"].as_f64().unwrap(),
        ));
    }
    println!(
        "share beyond |de| = 0.003 and max |de|: N = 125 {:?}, N = 1000 {:?}",
        shares[0], shares[1]
    );
    assert!(shares[1].0 < shares[0].0, "{shares:?}");
    assert!(shares[1].1 < shares[0].1, "{shares:?}");
}

#[test]
fn several_sizes_give_orders_and_extrapolation() {
    let dir = scratch("cmp-orders");
    let out = dir.join("r");
    ok(
        "compare --x 0.3 --alpha 0.3 --n 250,500,1000 --no-timing --out",
        &[out.to_str().unwrap()],
    );
    let p = &report(&out)["points"][0];
    let order = p["observed_order"].as_f64().unwrap();
    assert!(order > 0.3 && order < 1.5, "{order}");
    let exact = p["exact"]["restitution"].as_f64().unwrap();
    let finest = p["chain"][2]["restitution"].as_f64().unwrap();
    let extrapolated = p["extrapolated_restitution"].as_f64().unwrap();
    assert!(
        (extrapolated - exact).abs() < (finest - exact).abs(),
        "{extrapolated} vs {finest} (exact {exact})"
    );
}

fn same_files(a: &Path, b: &Path, files: &[&str]) {
    for f in files {
        let (x, y) = (
            std::fs::read(a.join(f)).unwrap(),
            std::fs::read(b.join(f)).unwrap(),
        );
        assert!(
            x == y,
            "{f} differs between {} and {}",
            a.display(),
            b.display()
        );
    }
}

#[test]
fn sharded_and_merged_compare_equals_unsharded() {
    let dir = scratch("cmp-shards");
    let grid = "--x 0.2:0.8:0.3 --alpha 0.1:0.7:0.3 --n 150 --no-timing";
    let whole = dir.join("whole");
    whole_run(&format!("compare {grid}"), &whole);
    let parts = dir.join("parts");
    for s in ["1/3", "2/3", "3/3"] {
        ok(
            &format!("compare {grid}"),
            &["--out", parts.to_str().unwrap(), "--shard", s],
        );
    }
    assert!(
        !parts.join("report.json").exists(),
        "a shard writes only its journal"
    );
    let merged = dir.join("merged");
    let journals: Vec<String> = (1..=3)
        .map(|i| {
            parts
                .join(format!("points-shard-{i}-of-3.jsonl"))
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    let mut rest = vec!["--out", merged.to_str().unwrap()];
    rest.extend(journals.iter().map(String::as_str));
    ok("merge", &rest);
    same_files(&whole, &merged, &REPORT_FILES);
    // a missing shard is an input error that names what is missing
    let out = impact(&[
        "merge",
        &journals[0],
        &journals[1],
        "--out",
        dir.join("bad").to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("miss"), "{}", stderr(&out));
}

#[test]
fn sharded_and_merged_sweep_equals_unsharded() {
    let dir = scratch("sweep-shards");
    let grid = "--x 0.05:0.95:0.1 --alpha 0.05:0.95:0.15 --no-timing";
    let whole = dir.join("whole.csv");
    whole_run(&format!("sweep {grid}"), &whole);
    let mut journals = Vec::new();
    for i in 1..=2 {
        let j = dir.join(format!("part{i}.jsonl"));
        let shard = format!("{i}/2");
        ok(
            &format!("sweep {grid}"),
            &["--out", j.to_str().unwrap(), "--shard", &shard],
        );
        journals.push(j.to_string_lossy().into_owned());
    }
    let merged = dir.join("merged.csv");
    ok(
        "merge",
        &[
            &journals[0],
            &journals[1],
            "--out",
            merged.to_str().unwrap(),
        ],
    );
    same_bytes(&whole, &merged);
}

/// A kill can land anywhere, including in the middle of a line: a resumed run
/// must end with exactly the points of an uninterrupted one, none twice.
#[test]
fn killed_then_resumed_equals_uninterrupted() {
    let dir = scratch("cmp-resume");
    let grid = "--x 0.2:0.8:0.3 --alpha 0.1:0.7:0.3 --n 150 --no-timing";
    let whole = dir.join("whole");
    whole_run(&format!("compare {grid}"), &whole);
    // the journal as a kill would leave it: 4 of 9 points and a torn fifth line
    let cut = dir.join("cut");
    std::fs::create_dir_all(&cut).unwrap();
    let text = std::fs::read_to_string(whole.join("points.jsonl")).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let mut partial = lines[..5].join("\n");
    partial.push('\n');
    partial.push_str(&lines[5][..lines[5].len() / 2]);
    std::fs::write(cut.join("points.jsonl"), partial).unwrap();
    ok(
        &format!("compare {grid}"),
        &["--out", cut.to_str().unwrap(), "--resume"],
    );
    same_files(&whole, &cut, &REPORT_FILES);
    let journal = std::fs::read_to_string(cut.join("points.jsonl")).unwrap();
    let mut indices: Vec<u64> = journal
        .lines()
        .skip(1)
        .map(|l| {
            serde_json::from_str::<Value>(l).unwrap()["index"]
                .as_u64()
                .unwrap()
        })
        .collect();
    indices.sort();
    assert_eq!(
        indices,
        (0..9).collect::<Vec<u64>>(),
        "each point exactly once"
    );
}

/// The same with a real SIGKILL of a running sweep.
#[test]
fn a_real_kill_mid_run_resumes_cleanly() {
    let dir = scratch("sweep-kill");
    let journal = dir.join("j.jsonl");
    let grid =
        "--x 0.05:0.95:0.05 --alpha 0.2:0.8:0.2 --engine chain --n 300 --no-timing --threads 1";
    let mut args = vec!["sweep"];
    args.extend(grid.split_whitespace());
    args.extend(["--out", journal.to_str().unwrap(), "--shard", "1/1"]);
    let mut child = start_until_lines(&args, &journal, 6);
    child.kill().unwrap();
    child.wait().unwrap();
    let before = std::fs::read_to_string(&journal).unwrap().lines().count() - 1;
    assert!(
        before < 76,
        "the run finished before the kill: nothing was tested"
    );
    ok(
        &format!("sweep {grid}"),
        &[
            "--out",
            journal.to_str().unwrap(),
            "--shard",
            "1/1",
            "--resume",
        ],
    );
    let merged = dir.join("resumed.csv");
    ok(
        "merge",
        &[journal.to_str().unwrap(), "--out", merged.to_str().unwrap()],
    );
    let whole = dir.join("whole.csv");
    whole_run(&format!("sweep {grid}"), &whole);
    same_bytes(&whole, &merged);
}

#[test]
fn the_page_is_well_formed_and_self_contained() {
    let dir = scratch("cmp-html");
    let out = dir.join("r");
    ok(
        "compare --x 0.1:0.3:0.1 --alpha 0.3 --n 100 --out",
        &[out.to_str().unwrap()],
    );
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    // settings as readable JSON, never Rust Debug strings; grid values as
    // the grid writes them
    assert!(!html.contains("ChainConfig {") && !html.contains("WaveConfig {"));
    assert!(html.contains("&quot;masses&quot;: 0") || html.contains("\"masses\": 0"));
    let noisy = html
        .split(|c: char| !(c.is_ascii_digit() || c == '.'))
        .find(|t| t.contains('.') && (t.contains("0000000") || t.contains("9999999")));
    assert!(
        noisy.is_none(),
        "a number printed with rounding noise: {noisy:?}"
    );
    let body = html.trim_start_matches("<!DOCTYPE html>");
    let mut reader = quick_xml::Reader::from_str(body);
    let mut depth = 0i32;
    let mut svgs = 0;
    loop {
        match reader.read_event() {
            Ok(quick_xml::events::Event::Start(e)) => {
                depth += 1;
                if e.name().as_ref() == b"svg" {
                    svgs += 1;
                }
                for a in e.attributes() {
                    let a = a.unwrap();
                    let key = String::from_utf8_lossy(a.key.as_ref()).into_owned();
                    let value = String::from_utf8_lossy(&a.value).into_owned();
                    assert!(
                        key == "xmlns" || !value.contains("://"),
                        "external reference {key}={value}"
                    );
                    assert!(
                        key != "src" && key != "href" || value.starts_with('#'),
                        "{key}={value}"
                    );
                }
            }
            Ok(quick_xml::events::Event::End(_)) => depth -= 1,
            Ok(quick_xml::events::Event::Eof) => break,
            Ok(_) => {}
            Err(e) => panic!(
                "index.html is not well-formed at {}: {e}",
                reader.buffer_position()
            ),
        }
    }
    assert_eq!(depth, 0);
    assert_eq!(svgs, 2, "both maps are inlined");
    assert!(!html.contains("<script") && !html.contains("<link") && !html.contains("<img"));
}

#[test]
fn fail_above_gives_a_non_zero_exit() {
    let dir = scratch("cmp-fail");
    let grid = "compare --x 0.3 --alpha 0.3 --n 100 --fail-above";
    let out = impact_words(grid, &["1e-6", "--out", dir.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("|de| > 0.000001"), "{}", stderr(&out));
    ok(grid, &["0.1", "--out", dir.to_str().unwrap()]);
}

#[test]
fn bad_compare_and_shard_input() {
    let dir = scratch("cmp-bad");
    let o = dir.join("r");
    let o = o.to_str().unwrap();
    for (args, needle) in [
        (
            vec!["compare", "--out", o, "--n", "1000,500"],
            "--n must be chain sizes",
        ),
        (
            vec!["compare", "--out", o, "--shard", "3/2"],
            "--shard must be I/N",
        ),
        (
            vec!["compare", "--out", o, "--tolerance", "0"],
            "--tolerance must be",
        ),
        (
            vec!["sweep", "--out", o, "--shard", "1/2"],
            "--out must end in .jsonl",
        ),
    ] {
        let out = impact(&args);
        assert_eq!(out.status.code(), Some(2), "{args:?}");
        assert!(stderr(&out).contains(needle), "{args:?}: {}", stderr(&out));
    }
    assert!(!Path::new(o).exists(), "nothing written for bad input");
}

/// Forgetting --resume on a shard must not delete its finished points.
#[test]
fn rerunning_a_shard_without_resume_keeps_its_journal() {
    let dir = scratch("shard-keep");
    let j = dir.join("part.jsonl");
    let words = "sweep --x 0.2:0.6:0.2 --alpha 0.3 --shard 1/2 --out";
    ok(words, &[j.to_str().unwrap()]);
    let before = std::fs::read(&j).unwrap();
    let out = impact_words(words, &[j.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--resume"), "{}", stderr(&out));
    assert_eq!(
        std::fs::read(&j).unwrap(),
        before,
        "the journal is untouched"
    );
    // a journal cut inside its header line is started again
    std::fs::write(&j, br#"{"journal":"impact-jou"#).unwrap();
    ok(words, &[j.to_str().unwrap(), "--resume"]);
    assert!(std::fs::read_to_string(&j).unwrap().lines().count() >= 2);
}

/// A report directory appears whole: a re-run replaces the report (the
/// second run's sizes are in it), keeps what the report does not write, and
/// leaves no staging directory beside it.
#[test]
fn a_rerun_replaces_the_report_and_leaves_nothing_beside_it() {
    let dir = scratch("cmp-rerun");
    let out = dir.join("r");
    for n in ["60", "80"] {
        let rest = [n, "--no-timing", "--out", out.to_str().unwrap()];
        ok("compare --x 0.3 --alpha 0.3 --n", &rest);
        std::fs::write(out.join("notes.txt"), "mine").unwrap();
    }
    assert_eq!(files_in(&dir), ["r"]);
    let mut expected: Vec<&str> = REPORT_FILES.to_vec();
    expected.extend(["notes.txt", "points.jsonl"]);
    expected.sort();
    assert_eq!(files_in(&out), expected);
    assert_eq!(report(&out)["settings"]["sizes"][0], 80);
    // a report that cannot be written (its place is a file) leaves nothing
    let blocked = dir.join("blocked");
    std::fs::write(&blocked, "a file").unwrap();
    let journal = out.join("points.jsonl");
    let o = impact_words(
        "merge",
        &[
            journal.to_str().unwrap(),
            "--out",
            blocked.to_str().unwrap(),
        ],
    );
    assert!(!o.status.success());
    assert_eq!(files_in(&dir), ["blocked", "r"]);
}

//! The chain through the binary: engine choice, viscosity flags, calibration.

use crate::support::*;
use serde_json::Value;

fn json(args: &[&str]) -> Value {
    let out = impact(args);
    assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    serde_json::from_str(&stdout(&out)).unwrap()
}

#[test]
fn chain_run_reports_steps_and_both_restitutions() {
    let v = json(&[
        "run", "--x", "0.4", "--alpha", "0.05", "--engine", "chain", "--n", "400", "--json",
    ]);
    assert_eq!(v["engine"], "chain");
    assert!(v["steps"].as_u64().unwrap() > 0);
    assert!(v.get("events").is_none());
    let (e, ev) = (
        v["restitution"].as_f64().unwrap(),
        v["restitution_from_velocity"].as_f64().unwrap(),
    );
    assert!((e - ev).abs() < 1e-9);
    // close to the exact engine's 0.70456 (N = 400: |de| ~ 8e-3)
    assert!((e - 0.704_56).abs() < 0.01, "{e}");
}

#[test]
fn auto_picks_the_chain_for_viscous_layers_and_wave_refuses_them() {
    let v = json(&[
        "run", "--x", "0.4", "--alpha", "0.05", "--e2", "0.72", "--n", "200", "--json",
    ]);
    assert_eq!(v["engine"], "chain");
    let v = json(&["run", "--x", "0.4", "--alpha", "0.05", "--json"]);
    assert_eq!(v["engine"], "wave");
    let out = impact(&[
        "run", "--x", "0.4", "--alpha", "0.05", "--tau1", "0.1", "--engine", "wave",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("viscous"), "{}", stderr(&out));
}

#[test]
fn few_masses_per_layer_warn_and_too_few_fail() {
    let out = impact(&[
        "run", "--x", "0.1", "--alpha", "0.3", "--engine", "chain", "--n", "100", "--json",
    ]);
    assert!(out.status.success());
    assert!(
        stderr(&out).contains("warning: layer 1 has 10 masses"),
        "{}",
        stderr(&out)
    );
    let too_few = "run --x 0.1 --alpha 0.3 --engine chain --n 1";
    assert_input_error(&too_few.split(' ').collect::<Vec<_>>(), "--n must be >= 2");
}

#[test]
fn bad_viscosity_input() {
    for (args, needle) in [
        (vec!["--e1", "1.5"], "layers[0].restitution"),
        (vec!["--e2", "0"], "layers[1].restitution"),
        (
            vec!["--tau1", "-1"],
            "layers[0].relaxation_time must be a finite number >= 0",
        ),
        (
            vec!["--dt-factor", "0"],
            "--dt-factor must be a number in (0, 10]",
        ),
    ] {
        let mut all = vec![
            "run", "--x", "0.4", "--alpha", "0.05", "--engine", "chain", "--n", "100",
        ];
        all.extend(args);
        let out = impact(&all);
        assert_eq!(out.status.code(), Some(2), "{all:?}");
        assert!(stderr(&out).contains(needle), "{all:?}: {}", stderr(&out));
        assert_eq!(stderr(&out).trim_end().lines().count(), 1);
    }
}

#[test]
fn calibration_round_trip() {
    let v = json(&["calibrate", "--restitution", "0.72", "--json"]);
    let t = v["tau_c_over_l"].as_f64().unwrap();
    let back = json(&["calibrate", "--tau-c-over-l", &t.to_string(), "--json"]);
    assert!((back["restitution"].as_f64().unwrap() - 0.72).abs() < 1e-9);
    // the paper's wall reaches e = 0.0087 at tau c/L = 1, and holds the rod
    // beyond; the unilateral wall keeps e above 0.01 up to tau c/L = 3
    let out = impact(&["calibrate", "--restitution", "0.005"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("calibrated range"));
    let unilateral = ["calibrate", "--wall-contact", "unilateral"];
    let out = impact(&[&unilateral[..], &["--restitution", "0.01"]].concat());
    assert_eq!(out.status.code(), Some(2));
    // the laws give different viscosities for one restitution
    let law = |name: &str| {
        json(&[
            "calibrate",
            "--wall-contact",
            name,
            "--restitution",
            "0.2",
            "--json",
        ])["tau_c_over_l"]
            .as_f64()
            .unwrap()
    };
    assert!(law("unilateral") > 1.3 * law("paper"));
    let sticky = [
        "calibrate",
        "--wall-contact",
        "sticky",
        "--restitution",
        "0.4",
    ];
    assert_input_error(&sticky, "'paper' or 'unilateral'");
}

#[test]
fn the_calibration_gives_the_layer_restitution_it_promises() {
    // A homogeneous rod of restitution 0.72 given the paper's way must rebound
    // with e = 0.72 (to the chain's finite-size error at N = 1000, ~1e-3).
    let dir = scratch("calibrated");
    let path = dir.join("rod.json");
    std::fs::write(&path, r#"{"impact_speed": 1, "layers": [{"length": 2, "modulus": 3, "density": 1.5, "restitution": 0.72}]}"#).unwrap();
    let v = json(&["run", path.to_str().unwrap(), "--n", "1000", "--json"]);
    assert_eq!(v["engine"], "chain");
    assert!(
        (v["restitution"].as_f64().unwrap() - 0.72).abs() < 2e-3,
        "{v}"
    );
}

#[test]
fn chain_sweep() {
    let words = "sweep --x 0.2:0.4:0.2 --alpha 0.05 --engine chain --n 200 --out";
    let (path, _) = writes("chainsweep", "g.csv", words);
    let text = std::fs::read_to_string(&path).unwrap();
    assert_eq!(text.lines().count(), 3);
    assert!(text.lines().nth(1).unwrap().contains(",chain,"));
}

/// The wall's contact law is named in every output and changes only what a
/// viscous bottom does: the JSON and the sweep CSV carry it, an elastic rod
/// gives the same `e` under both laws, a viscous bottom does not.
#[test]
fn the_wall_contact_law_is_named_and_matters_only_for_a_viscous_bottom() {
    let e = |extra: &[&str], law: &str| {
        let mut args = vec![
            "run",
            "--x",
            "0.5",
            "--alpha",
            "0.3",
            "--engine",
            "chain",
            "--n",
            "200",
            "--json",
            "--wall-contact",
            law,
        ];
        args.extend(extra);
        let v = json(&args);
        assert_eq!(v["wall_contact"], law);
        v["restitution"].as_f64().unwrap()
    };
    assert_eq!(e(&[], "paper"), e(&[], "unilateral"));
    let viscous = ["--tau1", "0.08"];
    let gap = (e(&viscous, "paper") - e(&viscous, "unilateral")).abs();
    assert!(gap > 1e-3, "{gap}");
    // the default is the paper's law, and the summary says so
    let out = impact(&[
        "run", "--x", "0.5", "--alpha", "0.3", "--engine", "chain", "--n", "200",
    ]);
    assert!(stdout(&out).contains("wall contact         paper (Sec. III"));
    // the sweep CSV has a column for it
    let dir = scratch("law-sweep");
    let csv = dir.join("grid.csv");
    let out = impact_words(
        "sweep --x 0.5 --alpha 0.3 --wall-contact unilateral --out",
        &[csv.to_str().unwrap()],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = header.iter().position(|h| *h == "wall_contact").unwrap();
    assert_eq!(row[column], "unilateral");
}

/// A viscous `impact run` without `--n` answers for `N -> infinity`: three
/// chains, their order and the extrapolated `e` with an error estimate, in
/// JSON and the summary; the finest chain's figures stay alongside. With
/// `--n` it is one chain, and `--target` cannot go with it.
#[test]
fn a_viscous_run_extrapolates_to_the_continuum_by_default() {
    let args = [
        "run", "--x", "0.5", "--alpha", "0.3", "--tau1", "0.08", "--tau2", "0.5", "--json",
    ];
    let v = json(&args);
    let x = &v["extrapolation"];
    let sizes: Vec<u64> = numbers(&x["sizes"]);
    assert_eq!(sizes, [250, 500, 1000]);
    let values: Vec<f64> = numbers(&x["values"]);
    assert_eq!(values[2], v["restitution"].as_f64().unwrap());
    let (value, error) = (x["value"].as_f64().unwrap(), x["error"].as_f64().unwrap());
    assert!(error > 0.0 && error < 1e-3, "{x}");
    // the correction goes the way the chains converge
    assert!((value - values[2]) * (values[2] - values[1]) > 0.0, "{x}");
    // `restitution` is the finest chain's, and its bound reaches the limit
    // and the limit's own estimate beyond it
    let bound = v["error_bound"].as_f64().unwrap();
    assert!(
        bound >= (value - values[2]).abs() + 0.99 * error,
        "{bound} {x}"
    );
    assert!(
        bound <= (value - values[2]).abs() + 1.01 * error,
        "{bound} {x}"
    );
    let out = impact(&args[..args.len() - 1]);
    let text = stdout(&out);
    assert!(text.contains("(N -> infinity, Richardson)"), "{text}");
    assert!(text.contains("observed order in N"), "{text}");
    assert!(text.contains("|e - e(N -> infinity)| <= "), "{text}");
    // an elastic top keeps sharp fronts: said, and the estimate widened
    let elastic_top = json(&[
        "run", "--x", "0.5", "--alpha", "0.3", "--tau1", "0.08", "--json",
    ]);
    let note = elastic_top["extrapolation"]["note"].as_str().unwrap();
    assert!(note.contains("elastic layer"), "{note}");
    assert!(elastic_top["extrapolation"]["error"].as_f64().unwrap() > error);
    // one chain with --n
    let one = json(&[
        "run", "--x", "0.5", "--alpha", "0.3", "--tau1", "0.08", "--n", "300", "--json",
    ]);
    assert!(one.get("extrapolation").is_none());
    // one chain's distance from the continuum is not measured, and says so
    assert!(one["error_bound"].is_null(), "{one}");
    let text = stdout(&impact(&[
        "run", "--x", "0.5", "--alpha", "0.3", "--tau1", "0.08", "--n", "300",
    ]));
    assert!(
        text.contains("error bound          not estimated"),
        "{text}"
    );
    let bad = impact(&[
        "run", "--x", "0.5", "--alpha", "0.3", "--tau1", "0.08", "--n", "300", "--target", "1e-4",
    ]);
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--target"));
}

/// The viscous kernel is named in the JSON and the summary: the implicit
/// one by default, the split one when asked; both give the same chain to
/// within their step errors (here `3e-5` apart, a viscous bottom at
/// `N = 200`), and an elastic chain names none.
#[test]
fn the_viscous_kernel_is_named_and_chosen_by_flag() {
    let run = |extra: &[&str]| {
        let mut args = vec![
            "run", "--x", "0.5", "--alpha", "0.3", "--tau1", "0.08", "--n", "200", "--json",
        ];
        args.extend(extra);
        json(&args)
    };
    let (implicit, split) = (run(&[]), run(&["--viscous-kernel", "split"]));
    assert_eq!(implicit["viscous_kernel"], "implicit");
    assert_eq!(split["viscous_kernel"], "split");
    let gap =
        (implicit["restitution"].as_f64().unwrap() - split["restitution"].as_f64().unwrap()).abs();
    assert!(gap > 0.0 && gap < 3e-5, "{gap}");
    let elastic = json(&[
        "run", "--x", "0.5", "--alpha", "0.3", "--engine", "chain", "--n", "200", "--json",
    ]);
    assert!(elastic.get("viscous_kernel").is_none(), "{elastic}");
    assert_input_error(
        &[
            "run",
            "--x",
            "0.5",
            "--alpha",
            "0.3",
            "--tau1",
            "0.08",
            "--viscous-kernel",
            "sticky",
        ],
        "possible values: implicit, split",
    );
}

/// A steel base under soft viscous layers: the chains of 250 to 1000
/// masses rise towards 1 so slowly (order 0.47) that their extrapolation
/// passes it. Energy forbids `e > 1` (springs store, dashpots take), so
/// the run says the extrapolation is not clean, why, and widens its
/// estimate back below 1.
#[test]
fn an_extrapolated_e_above_one_is_flagged() {
    let path = steel_under_gel(&scratch("above-one"), Some(0.72));
    let v = json(&["run", path.to_str().unwrap(), "--json"]);
    let x = &v["extrapolation"];
    let (value, error) = (x["value"].as_f64().unwrap(), x["error"].as_f64().unwrap());
    assert!(value > 1.0, "{x}");
    assert_eq!(x["clean"], false, "{x}");
    let note = x["note"].as_str().unwrap();
    assert!(note.contains("which energy forbids"), "{note}");
    assert!(value - error < 1.0, "{x}");
    // every chain itself stays under 1
    assert!(numbers::<f64>(&x["values"]).iter().all(|&e| e < 1.0), "{x}");
}

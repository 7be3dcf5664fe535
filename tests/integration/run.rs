use crate::support::*;
use impact_model::{Bilayer, Scene};
use impact_wave::{WaveConfig, simulate};
use serde_json::Value;

fn run_json(args: &[&str]) -> Value {
    let mut all = args.to_vec();
    all.push("--json");
    let out = impact(&all);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert_eq!(text.lines().count(), 1, "one JSON object on one line");
    serde_json::from_str(&text).unwrap()
}

#[test]
fn json_has_the_documented_keys_and_the_engine_numbers() {
    let v = run_json(&["run", "--x", "0.4", "--alpha", "0.05"]);
    let more = [
        "engine",
        "contacts",
        "transit_times",
        "elapsed_seconds",
        "events",
        "error_bound",
        "error_estimate",
    ];
    for key in MEASURES.iter().chain(&more) {
        assert!(v.get(key).is_some(), "missing {key}: {v}");
    }
    assert_eq!(v["engine"], "wave");
    let rod = Bilayer::new(0.4, 0.05).unwrap().scene().validate().unwrap();
    let o = simulate(&rod, &WaveConfig::default()).unwrap();
    assert_eq!(v["restitution"].as_f64().unwrap(), o.restitution);
    assert_eq!(v["contact_time"].as_f64().unwrap(), o.contact_time);
    assert_eq!(v["bounces"].as_u64().unwrap(), u64::from(o.bounces));
    assert_eq!(v["contacts"].as_array().unwrap().len(), o.contacts.len());
}

#[test]
fn figure_3_scene_files_equal_the_canonical_bilayers() {
    for (name, x, alpha) in [
        ("fig3a", 0.2, 0.05),
        ("fig3b", 0.3, 0.3),
        ("fig3c", 0.4, 0.05),
        ("fig3d", 0.6, 0.8),
    ] {
        let file = format!("data/scenes/{name}.json");
        let from_file = run_json(&["run", &file]);
        let canonical = run_json(&["run", "--x", &x.to_string(), "--alpha", &alpha.to_string()]);
        let e = |v: &Value| v["restitution"].as_f64().unwrap();
        assert!((e(&from_file) - e(&canonical)).abs() < 1e-12, "{name}");
        assert_eq!(from_file["bounces"], canonical["bounces"], "{name}");
    }
}

#[test]
fn every_example_scene_runs_and_is_physical() {
    let dir = repo().join("data/scenes");
    let mut count = 0;
    for entry in std::fs::read_dir(&dir).unwrap() {
        let path = entry.unwrap().path();
        let text = std::fs::read_to_string(&path).unwrap();
        let scene = Scene::from_json(&text).unwrap();
        if scene.layers.iter().any(|l| l.is_viscous()) {
            continue;
        }
        let v = run_json(&["run", path.to_str().unwrap()]);
        let e = v["restitution"].as_f64().unwrap();
        assert!((0.0..=1.0).contains(&e), "{path:?}: {e}");
        count += 1;
    }
    assert!(count >= 5);
}

#[test]
fn three_layer_steel_base_leaves_alone() {
    // The steel base is ~10^4 times stiffer than the core: it bounces off after
    // one transit carrying only its own momentum, e = (m1 - m2 - m3) / M.
    let v = run_json(&["run", "data/scenes/three-layers.json"]);
    let (m1, m2, m3) = (0.01 * 7850.0, 0.015 * 1200.0, 0.005 * 2700.0);
    let expected = (m1 - m2 - m3) / (m1 + m2 + m3);
    assert!((v["restitution"].as_f64().unwrap() - expected).abs() < 1e-9);
    assert_eq!(v["n1"], Value::Null, "n1 is for two-layer rods only");
}

#[test]
fn human_summary_names_the_observables() {
    let out = impact(&["run", "--x", "0.6", "--alpha", "0.8"]);
    assert!(out.status.success());
    let text = stdout(&out);
    for needle in [
        "restitution e",
        "contact time t_c",
        "n1 = 3.5",
        "bounces N_b",
        "free for good",
    ] {
        assert!(text.contains(needle), "{needle} missing from\n{text}");
    }
}

/// The bound is on `e`: a merged run's bounce count is its lattice's (the
/// steel base under rubber counts 149 to 239 bounces over four lattices
/// while `e` moves by `5e-6`), and the summary says so; an exact run's
/// count is the rod's and carries no such words.
#[test]
fn a_merged_runs_bounce_count_is_marked_as_the_lattices() {
    let words = "counted on the merged lattice, not bounded";
    let merged = impact(&["run", "data/scenes/steel-under-rubber.json"]);
    assert!(merged.status.success());
    let text = stdout(&merged);
    let line = text.lines().find(|l| l.contains("bounces N_b")).unwrap();
    assert!(line.contains(words), "{line}");
    let exact = impact(&["run", "data/scenes/fig3c.json"]);
    assert!(!stdout(&exact).contains(words), "{}", stdout(&exact));
}

#[test]
fn wall_trace_is_written_only_when_asked() {
    let (path, _) = writes("trace", "wall.csv", "run --x 0.4 --alpha 0.05 --wall-trace");
    let text = std::fs::read_to_string(&path).unwrap();
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("time,strain,height,velocity"));
    let first: Vec<f64> = lines
        .next()
        .unwrap()
        .split(',')
        .map(|c| c.parse().unwrap())
        .collect();
    // at impact the wall strain is -v_b / c1
    assert_eq!(first[0], 0.0);
    assert!((first[1] + 1.0 / 0.95f64.sqrt()).abs() < 1e-15);
    assert_eq!(files_in(path.parent().unwrap()), vec!["wall.csv"]);
}

#[test]
fn paper_horizon_option() {
    let v = run_json(&["run", "--x", "0.4", "--alpha", "0.05", "--horizon", "20"]);
    assert_eq!(v["stop_reason"], "horizon");
    let t: Vec<f64> = numbers(&v["transit_times"]);
    assert!((v["end_time"].as_f64().unwrap() - 20.0 * t[0].max(t[1])).abs() < 1e-12);
}

/// A layer may name a material: the run equals the one with the table's
/// numbers written out.
#[test]
fn named_materials_equal_their_numbers() {
    let dir = scratch("materials");
    let named = dir.join("named.json");
    let numbers = dir.join("numbers.json");
    std::fs::write(
        &named,
        r#"{"impact_speed": 1.0, "layers": [{"length": 0.01, "material": "steel"}, {"length": 0.02, "material": "pmma"}]}"#,
    )
    .unwrap();
    let steel = impact_model::materials::find("steel").unwrap();
    let pmma = impact_model::materials::find("pmma").unwrap();
    std::fs::write(
        &numbers,
        format!(
            r#"{{"impact_speed": 1.0, "layers": [{{"length": 0.01, "modulus": {}, "density": {}}}, {{"length": 0.02, "modulus": {}, "density": {}}}]}}"#,
            steel.modulus, steel.density, pmma.modulus, pmma.density
        ),
    )
    .unwrap();
    let a = run_json(&["run", named.to_str().unwrap()]);
    let b = run_json(&["run", numbers.to_str().unwrap()]);
    assert_eq!(a["restitution"], b["restitution"]);
    assert_eq!(a["contacts"], b["contacts"]);
}

/// The rigid-bottom model through the command line: the paper's lower
/// region, where the stiff base leaves alone after one transit, gives
/// Eq. 15's `e = 1 - 2x` in the limit; the exact engine approaches it.
#[test]
fn rigid_bottom_engine_gives_the_lower_region_limit() {
    let v = run_json(&[
        "run",
        "--x",
        "0.2",
        "--alpha",
        "0.0001",
        "--engine",
        "rigid-bottom",
    ]);
    assert_eq!(v["engine"], "rigid-bottom");
    assert!(
        (v["restitution"].as_f64().unwrap() - 0.6).abs() < 1e-9,
        "{v}"
    );
    assert!(v["error_bound"].as_f64().unwrap() < 1e-9);
    let exact = run_json(&["run", "--x", "0.2", "--alpha", "0.0001"]);
    let diff = (exact["restitution"].as_f64().unwrap() - 0.6).abs();
    assert!(diff < 1e-9, "{diff}");
}

/// `--max-events` bounds the rigid-bottom model too: a point of the paper's
/// grid whose base lands hundreds of times (597 events) stops at 100, exit
/// 1, and the message says what to raise and which engine bounds the work;
/// given its 597, it finishes.
#[test]
fn max_events_bounds_the_rigid_bottom_model() {
    let point = [
        "run",
        "--x",
        "0.9",
        "--alpha",
        "0.001",
        "--engine",
        "rigid-bottom",
    ];
    let out = impact(&[&point[..], &["--max-events", "100"]].concat());
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let err = stderr(&out);
    for needle in ["after 100 events", "raise --max-events", "--engine wave"] {
        assert!(err.contains(needle), "{needle}: {err}");
    }
    assert!(stdout(&out).is_empty());
    let v = run_json(&[&point[..], &["--max-events", "597"]].concat());
    assert_eq!(v["events"], 597);
}

/// Two five- and six-layer rods of the layer survey (`scripts/survey-layers.py`,
/// seed 7, rods 2 and 3) that need the merged ladder: one whose last three
/// levels' differences grow, one whose shrink. The outcome carries what the
/// levels showed, and the summary warns exactly when they did not converge.
#[test]
fn a_merged_outcome_says_whether_its_levels_converge() {
    let dir = scratch("merged-convergence");
    let growing = r#"{"impact_speed": 1.0, "layers": [{"length": 0.24958931338977147, "modulus": 1324775.909843706, "density": 0.2767984455773927}, {"length": 0.3331748164416051, "modulus": 2120843.944515068, "density": 0.689093394914303}, {"length": 0.7709136896467343, "modulus": 201626165.64701295, "density": 1.319819540603312}, {"length": 0.30305571244359136, "modulus": 249.3797035121228, "density": 1.3880617373316597}, {"length": 0.2974305759947334, "modulus": 15726824.814739376, "density": 2.655960008715463}]}"#;
    let shrinking = r#"{"impact_speed": 1.0, "layers": [{"length": 0.40595871281932655, "modulus": 310389.92387135676, "density": 2.2950911925748465}, {"length": 0.5141471703767915, "modulus": 406758.1313031702, "density": 1.4829405028289155}, {"length": 0.49976699686368237, "modulus": 947746453.1580232, "density": 3.8793499916440046}, {"length": 0.4440965107221529, "modulus": 2826216.751810704, "density": 1.4087937638394294}, {"length": 1.075137495573429, "modulus": 8206.231371372458, "density": 2.876673541372195}, {"length": 1.1801748474925822, "modulus": 17931.037463601337, "density": 0.17223902425235}]}"#;
    let warning = "the merged estimate may be low";
    let mut said = [false; 2];
    for (k, scene) in [growing, shrinking].into_iter().enumerate() {
        let path = dir.join(format!("rod{k}.json"));
        std::fs::write(&path, scene).unwrap();
        let path = path.to_str().unwrap();
        let v = run_json(&["run", path]);
        let est = &v["error_estimate"];
        assert!(
            est["merged"].as_f64().unwrap() > 0.0,
            "a merged ladder: {v}"
        );
        let converging = est["merged_converging"].as_bool().expect("said");
        let order = est["merged_observed_order"].as_f64().expect("three levels");
        // the rule: the differences shrink at order 0.5 or faster
        assert_eq!(converging, order >= 0.5, "{est}");
        let method = est["method"].as_str().unwrap();
        assert_eq!(method.contains("may be low"), !converging, "{method}");
        let out = impact(&["run", path]);
        assert!(out.status.success(), "{}", stderr(&out));
        assert_eq!(stdout(&out).contains(warning), !converging);
        // and says how to check it: the budget that runs the next level,
        // where the budget stopped the ladder
        let stop = &est["ladder_stop"];
        if let Some(needed) = stop["budget"]["needed"].as_u64() {
            let advice = format!("--event-budget {needed} or more runs the next level");
            assert_eq!(stdout(&out).contains(&advice), !converging, "{stop}");
            assert!(needed > v["events"].as_u64().unwrap(), "{v}");
        } else {
            assert!(stop.is_string(), "a ladder's stop is said: {est}");
        }
        said[k] = !converging;
    }
    // the first rod's differences grow, the second's shrink
    assert_eq!(said, [true, false]);
}

/// Survey rod 20 (seed 7): four fast layers and a top a hundred times
/// slower over a slow bottom. The merged run answers the five as one block
/// by its traced response; the outcome lists the block (layers counted
/// from 0, as `transit_times`), the method says so in words, and the
/// summary names the block by its transit times.
#[test]
fn a_block_answered_by_its_response_is_reported() {
    let dir = scratch("blocks");
    let rod = r#"{"impact_speed": 1.0, "layers": [{"length": 0.4954541110415926, "modulus": 188.6900167559795, "density": 8.347365412239864}, {"length": 1.1185481502738823, "modulus": 9414877211.070044, "density": 0.28648883899932903}, {"length": 0.2840612669703682, "modulus": 25979164416.074642, "density": 0.3498170036734888}, {"length": 0.38155139141117106, "modulus": 22329567728.11959, "density": 3.247529431968498}, {"length": 1.0495878272608952, "modulus": 505785077767.1679, "density": 2.248781579086109}, {"length": 0.6059478279156085, "modulus": 1780693.6578908376, "density": 1.1835804440683804}]}"#;
    let path = dir.join("rod20.json");
    std::fs::write(&path, rod).unwrap();
    let path = path.to_str().unwrap();
    let v = run_json(&["run", path]);
    let est = &v["error_estimate"];
    assert_eq!(est["answered_blocks"], serde_json::json!([[1, 5]]), "{est}");
    let method = est["method"].as_str().unwrap();
    assert!(
        method.contains("t2 to t6 answered as one block"),
        "{method}"
    );
    let out = impact(&["run", path]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stdout(&out).contains("the layers of t2 to t6 answered as one block"));
    // a bilayer has no block: the key is absent
    let bilayer = run_json(&["run", "data/scenes/fig3c.json"]);
    assert!(
        bilayer["error_estimate"].get("answered_blocks").is_none(),
        "{bilayer}"
    );
}

//! `impact cost` through the binary.

use crate::support::*;

#[test]
fn quick_cost_study_writes_its_report() {
    let words = "cost --quick --x 0.2 --alpha 0.05 --target 5e-3 --out";
    let (out, o) = writes("cost", "c", words);
    assert!(stderr(&o).contains("headline"));
    for f in [
        "index.html",
        "cost.json",
        "pareto.svg",
        "pareto.png",
        "chain.csv",
        "exact.csv",
        "growth.csv",
    ] {
        assert!(out.join(f).exists(), "{f}");
    }
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("cost.json")).unwrap()).unwrap();
    // the exact engine's reference is the engine's own answer
    let run: serde_json::Value = serde_json::from_str(&stdout(&impact(&[
        "run", "--x", "0.2", "--alpha", "0.05", "--json",
    ])))
    .unwrap();
    assert_eq!(r["exact_e"], run["restitution"]);
}

#[test]
fn bad_cost_input() {
    let dir = scratch("cost-bad");
    let o = impact_words(
        "cost data/scenes/viscous-bilayer.json --out",
        &[dir.join("c").to_str().unwrap()],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("elastic scene"));
    let o = impact_words("cost --target 0 --out", &[dir.join("c").to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--target must be"));
    assert!(files_in(&dir).is_empty());
}

use crate::support::*;

#[test]
fn sweep_writes_one_row_per_point_in_grid_order() {
    let words = "sweep --x 0.1:0.9:0.1 --alpha 0.05:0.95:0.15 --out";
    let (path, out) = writes("sweep", "grid.csv", words);
    assert!(stdout(&out).is_empty());
    let text = std::fs::read_to_string(&path).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let more = ["x", "alpha", "events", "elapsed_seconds"];
    for col in MEASURES.iter().chain(&more) {
        assert!(header.contains(col), "missing column {col}");
    }
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 9 * 7);
    // alpha outer, x inner
    assert_eq!((rows[0][0], rows[0][1]), ("0.1", "0.05"));
    assert_eq!(rows[1][1], "0.05");
    assert_eq!(rows[9][1], "0.2");
    // the row at x = 0.2, alpha = 0.05 is the lower region: e = 1 - 2x
    let e: f64 = rows[1][header.iter().position(|h| *h == "restitution").unwrap()]
        .parse()
        .unwrap();
    assert!((e - 0.6).abs() < 1e-12);
    assert_eq!(files_in(path.parent().unwrap()), vec!["grid.csv"]);
}

#[test]
fn sweep_output_is_identical_whatever_the_thread_count() {
    let dir = scratch("threads");
    let mut texts = Vec::new();
    for threads in ["1", "2", "3"] {
        let path = dir.join(format!("grid-{threads}.csv"));
        let out = impact_words(
            "sweep --x 0.05:0.95:0.05 --alpha 0.005:0.105:0.02 --no-timing --threads",
            &[threads, "--out", path.to_str().unwrap()],
        );
        assert!(out.status.success(), "{}", stderr(&out));
        texts.push(std::fs::read_to_string(&path).unwrap());
    }
    assert_eq!(texts[0], texts[1]);
    assert_eq!(texts[0], texts[2]);
    assert!(!texts[0].contains("elapsed_seconds"));
    // `--out -`: the same CSV on standard output, and no file
    for threads in ["1", "2"] {
        let out = impact_words(
            "sweep --x 0.05:0.95:0.05 --alpha 0.005:0.105:0.02 --no-timing --out - --threads",
            &[threads],
        );
        assert!(out.status.success(), "{}", stderr(&out));
        assert_eq!(String::from_utf8_lossy(&out.stdout), texts[0]);
    }
    assert!(!std::path::Path::new("-").exists());
    // a journal is a file
    let out = impact_words("sweep --x 0.5 --alpha 0.5 --resume --out -", &[]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stderr(&out).contains("--out must end in .jsonl"));
}

#[test]
fn jsonl_rows_match_csv_rows() {
    let dir = scratch("jsonl");
    let csv = dir.join("g.csv");
    let jsonl = dir.join("g.jsonl");
    for p in [&csv, &jsonl] {
        let out = impact_words(
            "sweep --x 0.2:0.6:0.2 --alpha 0.3 --out",
            &[p.to_str().unwrap()],
        );
        assert!(out.status.success(), "{}", stderr(&out));
    }
    let rows: Vec<serde_json::Value> = std::fs::read_to_string(&jsonl)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let csv_text = std::fs::read_to_string(&csv).unwrap();
    let header: Vec<&str> = csv_text.lines().next().unwrap().split(',').collect();
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let csv_rows: Vec<Vec<String>> = csv_text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    assert_eq!(rows.len(), 3);
    for (j, c) in rows.iter().zip(&csv_rows) {
        assert_eq!(
            j["restitution"].as_f64().unwrap(),
            c[col("restitution")].parse::<f64>().unwrap()
        );
        assert_eq!(
            j["bounces"].as_u64().unwrap(),
            c[col("bounces")].parse::<u64>().unwrap()
        );
    }
}

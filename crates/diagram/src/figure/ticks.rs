//! Tick labels at the rod's characteristic times, so a reader sees where
//! `2 t1`, `2 t1 + 2 t2`, ... fall.

/// Tick labels at the rod's characteristic times: `2 t1`, `2 t1 + 2 t2`, ...
pub(super) fn transit_ticks(transits: &[f64], t0: f64, t1: f64) -> Vec<(f64, String)> {
    let mut out: Vec<(f64, String, u32)> = Vec::new();
    let sum: f64 = transits.iter().sum();
    match transits {
        [a, b] => {
            for i in 0..=8u32 {
                for j in 0..=4u32 {
                    let t = f64::from(i) * a + f64::from(j) * b;
                    if i + j == 0 || i % 2 == 1 && j == 0 || j % 2 == 1 {
                        continue;
                    }
                    let label = match (i, j) {
                        (i, 0) => format!("{i}t1"),
                        (0, j) => format!("{j}t2"),
                        (1, j) => format!("t1+{j}t2"),
                        (i, j) => format!("{i}t1+{j}t2"),
                    };
                    out.push((t, label, i + j));
                }
            }
        }
        _ => {
            out.push((2.0 * transits[0], "2t1".into(), 1));
            for k in 1..=4u32 {
                out.push((2.0 * f64::from(k) * sum, format!("{}Σt", 2 * k), k + 1));
            }
        }
    }
    out.retain(|(t, _, _)| *t >= t0 && *t <= t1);
    out.sort_by(|a, b| a.2.cmp(&b.2).then(a.0.total_cmp(&b.0)));
    // keep labels at least 7% of the window apart, simplest first
    let mut kept: Vec<(f64, String)> = Vec::new();
    for (t, label, _) in out {
        if kept.iter().all(|(k, _)| (k - t).abs() > 0.07 * (t1 - t0)) {
            kept.push((t, label));
        }
    }
    kept.sort_by(|a, b| a.0.total_cmp(&b.0));
    kept
}

//! Isolines of a gridded field (marching squares), as line segments.

/// Segments where the field crosses `level`. `values[row * nc + col]` at
/// `(columns[col], rows[row])`; non-finite cells are skipped.
pub fn contour(columns: &[f64], rows: &[f64], values: &[f64], level: f64) -> Vec<Vec<(f64, f64)>> {
    let nc = columns.len();
    let mut out = Vec::new();
    if nc < 2 || rows.len() < 2 {
        return out;
    }
    let at = |r: usize, c: usize| values[r * nc + c];
    for r in 0..rows.len() - 1 {
        for c in 0..nc - 1 {
            // corners counter-clockwise from bottom-left
            let corners = [(r, c), (r, c + 1), (r + 1, c + 1), (r + 1, c)];
            let v: Vec<f64> = corners.iter().map(|&(a, b)| at(a, b)).collect();
            if v.iter().any(|x| !x.is_finite()) {
                continue;
            }
            let mut points = Vec::new();
            for k in 0..4 {
                let (a, b) = (k, (k + 1) % 4);
                let (va, vb) = (v[a] - level, v[b] - level);
                if (va < 0.0) != (vb < 0.0) {
                    let s = va / (va - vb);
                    let (pa, pb) = (corners[a], corners[b]);
                    let x = columns[pa.1] + s * (columns[pb.1] - columns[pa.1]);
                    let y = rows[pa.0] + s * (rows[pb.0] - rows[pa.0]);
                    points.push((x, y));
                }
            }
            // 2 crossings: one segment; 4 (saddle): two segments
            for pair in points.chunks(2) {
                if pair.len() == 2 {
                    out.push(vec![pair[0], pair[1]]);
                }
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_linear_field_has_a_straight_isoline() {
        let xs: Vec<f64> = (0..5).map(f64::from).collect();
        let ys = xs.clone();
        let values: Vec<f64> = ys.iter().flat_map(|_| xs.iter().copied()).collect();
        let segs = contour(&xs, &ys, &values, 1.5);
        assert_eq!(segs.len(), 4);
        for s in &segs {
            assert!(s.iter().all(|p| (p.0 - 1.5).abs() < 1e-12));
        }
    }
}

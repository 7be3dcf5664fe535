//! Spearman's rank correlation: how monotone one sequence is in another,
//! whatever their scales (a staircase `N_b(x)` with single-step dips).

/// The ranks of `v` from 0, tied values sharing their average rank.
pub fn ranks(v: &[f64]) -> Vec<f64> {
    let mut idx: Vec<usize> = (0..v.len()).collect();
    idx.sort_by(|&a, &b| v[a].total_cmp(&v[b]));
    let mut r = vec![0.0; v.len()];
    let mut start = 0;
    while start < idx.len() {
        let mut end = start + 1;
        while end < idx.len() && v[idx[end]] == v[idx[start]] {
            end += 1;
        }
        let mean = 0.5 * (start + end - 1) as f64;
        for &i in &idx[start..end] {
            r[i] = mean;
        }
        start = end;
    }
    r
}

/// Spearman's rho of `a` and `b` (same length): the Pearson correlation of
/// their ranks. NaN when either is constant.
pub fn spearman(a: &[f64], b: &[f64]) -> f64 {
    let (ra, rb) = (ranks(a), ranks(b));
    let n = ra.len() as f64;
    let (ma, mb) = (ra.iter().sum::<f64>() / n, rb.iter().sum::<f64>() / n);
    let cov: f64 = ra.iter().zip(&rb).map(|(x, y)| (x - ma) * (y - mb)).sum();
    cov / (ra.iter().map(|x| (x - ma).powi(2)).sum::<f64>().sqrt()
        * rb.iter().map(|y| (y - mb).powi(2)).sum::<f64>().sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn monotone_sequences_correlate_fully() {
        let x = [0.1, 0.2, 0.5, 0.9, 3.0, 7.0];
        let up = [1.0, 4.0, 9.0, 16.0, 25.0, 1e6];
        let down: Vec<f64> = up.iter().map(|v| -v).collect();
        assert!((spearman(&x, &up) - 1.0).abs() < 1e-15);
        assert!((spearman(&x, &down) + 1.0).abs() < 1e-15);
    }

    /// y = 2, 1, 4, 3, 5 against x = 1..5: rank differences -1, 1, -1, 1,
    /// 0, so rho = 1 - 6 * 4 / (5 * 24) = 0.8.
    #[test]
    fn five_points_by_hand() {
        let rho = spearman(&[1.0, 2.0, 3.0, 4.0, 5.0], &[2.0, 1.0, 4.0, 3.0, 5.0]);
        assert!((rho - 0.8).abs() < 1e-15, "{rho}");
    }

    /// y = 1, 2, 2, 3, 5: ranks 0, 1.5, 1.5, 3, 4 (the tie shares 1.5).
    /// Against 0..4, both means are 2, cov = 4 + 0.5 + 0 + 1 + 4 = 9.5,
    /// var(x) = 10, var(y) = 4 + 0.25 + 0.25 + 1 + 4 = 9.5, so
    /// rho = 9.5 / sqrt(10 * 9.5) = sqrt(0.95).
    #[test]
    fn ties_share_their_average_rank() {
        let y = [1.0, 2.0, 2.0, 3.0, 5.0];
        assert_eq!(ranks(&y), vec![0.0, 1.5, 1.5, 3.0, 4.0]);
        let rho = spearman(&[1.0, 2.0, 3.0, 4.0, 5.0], &y);
        assert!((rho - 0.95f64.sqrt()).abs() < 1e-15, "{rho}");
    }
}

//! The Pareto front of a trade between two costs (time and error): the
//! settings worth choosing.

/// The points `(cost, error, label)` that no other point beats on both:
/// sorted by cost, error strictly decreasing along the front. Of points
/// equal in cost the most accurate is kept; a point no more accurate than
/// a cheaper one is dropped.
pub fn pareto_front<T: Clone>(points: &[(f64, f64, T)]) -> Vec<(f64, f64, T)> {
    let mut sorted: Vec<&(f64, f64, T)> = points.iter().collect();
    sorted.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut front: Vec<(f64, f64, T)> = Vec::new();
    for p in sorted {
        if front.last().is_none_or(|last| p.1 < last.1) {
            front.push(p.clone());
        }
    }
    front
}

#[cfg(test)]
mod tests {
    use super::*;

    /// By hand: a (1, 0.5) is cheapest; b (2, 0.6) is slower and worse
    /// (dropped); c (2, 0.1) and d (2, 0.2) tie in time, c more accurate;
    /// e (3, 0.1) is no better than c; f (5, 0.01) is slowest and best.
    #[test]
    fn a_hand_made_set() {
        let pts = [
            (3.0, 0.1, 'e'),
            (1.0, 0.5, 'a'),
            (2.0, 0.6, 'b'),
            (5.0, 0.01, 'f'),
            (2.0, 0.2, 'd'),
            (2.0, 0.1, 'c'),
        ];
        let labels: Vec<char> = pareto_front(&pts).iter().map(|p| p.2).collect();
        assert_eq!(labels, vec!['a', 'c', 'f']);
    }

    #[test]
    fn an_empty_set_has_an_empty_front() {
        assert!(pareto_front::<()>(&[]).is_empty());
    }
}

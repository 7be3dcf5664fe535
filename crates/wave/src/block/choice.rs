//! Which layers make blocks, and where answering them pays.

/// A layer is in a block when its transit is at most this share of the
/// shortest transit of the layers just outside the block.
pub(crate) const FAST: f64 = 1.0 / 8.0;

/// A layer whose neighbours' transits are both at least this many times
/// its own leaps long windows (`leap.rs`) and is left out of blocks: its
/// ringing would make the block's response last as long as the run.
pub(crate) const LEAPS_WELL: f64 = 64.0;

/// What a multiply-add of a port's sums costs, in nanoseconds: 0.33 on
/// survey rod 12's third level (1.5 G of them in 0.5 s, dense dot products,
/// `inputs.rs`); the first build's deque took 4.
pub(crate) const NS_PER_ADD: f64 = 0.33;

/// The candidate blocks of a rod, by its layers' transit times: runs of
/// two or more layers above the bottom, each layer at most [`FAST`] of the
/// shortest transit just outside the run and none that leaps well; the
/// longest first.
pub(crate) fn candidates(transits: &[f64]) -> Vec<(usize, usize)> {
    let n = transits.len();
    let leaps_well = |m: usize| {
        let below = transits[m - 1];
        let above = transits.get(m + 1).copied().unwrap_or(f64::INFINITY);
        below.min(above) >= LEAPS_WELL * transits[m]
    };
    let mut runs = Vec::new();
    for a in 1..n {
        if leaps_well(a) {
            continue;
        }
        for b in a + 1..n {
            if leaps_well(b) {
                break;
            }
            let outside = [Some(a - 1), (b + 1 < n).then_some(b + 1)];
            let slowest_fast = transits[a..=b].iter().copied().fold(0.0, f64::max);
            let quickest_outside = outside
                .iter()
                .flatten()
                .map(|&j| transits[j])
                .fold(f64::INFINITY, f64::min);
            if slowest_fast <= FAST * quickest_outside {
                runs.push((a, b));
            }
        }
    }
    runs.sort_by_key(|&(a, b)| (std::cmp::Reverse(b - a), a));
    runs
}

/// The run a block is priced over: eight times the rod's summed transits.
pub(crate) fn priced_run(transits: &[f64]) -> f64 {
    8.0 * transits.iter().sum::<f64>()
}

/// How long block `run`'s response may ring for answering it to be
/// expected to pay, judged on the ladder's third lattice (the least a
/// ladder runs). The loop may take up to `2 / s` events a unit of time in
/// each of the block's lanes (spacing `s`, about a microsecond each; fewer
/// where the lanes are not full, which cannot be foreseen); the trace
/// follows as many fronts at a fiftieth of the price, but only while the
/// block rings; and each lattice point a port delivers sums the arrivals
/// whose response still rings, at [`NS_PER_ADD`] each: `L / (h_out h_in)`
/// a unit of time for a response of length `L`, which grows with the run
/// where the block rings as long. The sums must stay under a sixty-fourth
/// of the loop's most: at a quarter, survey rod 13 (whose loop lanes are
/// far from full) took twice as long. Only the speed depends on this
/// choice, never the honesty of the result: the ladder measures the error
/// either way.
pub(crate) fn allowance(transits: &[f64], (a, b): (usize, usize)) -> f64 {
    let (start, longest) = crate::ladder::LADDER_START;
    let t_max = transits.iter().copied().fold(0.0, f64::max);
    let third = (start / 4.0, longest / 4.0);
    let spacing = |m: usize| crate::ladder::lattice_spacing(third, transits[m], t_max);
    let loop_rate: f64 = (a..=b).map(|m| 2.0 / spacing(m)).sum();
    let ports: Vec<usize> = [Some(a - 1), (b + 1 < transits.len()).then_some(b + 1)]
        .into_iter()
        .flatten()
        .collect();
    let sums_per_length: f64 = ports
        .iter()
        .flat_map(|&o| ports.iter().map(move |&i| (o, i)))
        .map(|(o, i)| NS_PER_ADD * 1e-3 / (spacing(o) * spacing(i)))
        .sum();
    loop_rate / 64.0 / sums_per_length
}

/// Whether `run` neither overlaps nor touches any of `chosen`: a block's
/// neighbours are slow layers, never another block's.
pub(crate) fn apart(run: (usize, usize), chosen: &[(usize, usize)]) -> bool {
    chosen.iter().all(|&(a, b)| run.1 + 1 < a || b + 1 < run.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether answering block `run` pays even if its response rings as
    /// long as the run, as `flow.rs` judges it before any probe.
    fn pays(transits: &[f64], run: (usize, usize)) -> bool {
        priced_run(transits) < allowance(transits, run)
    }

    /// Layer survey rod 12 (seed 7): layers 3 and 4 (transits `3.4e-5`,
    /// `2.8e-6`) between layers of `0.38` and `7.7e-3`; the fast top
    /// (`1.6e-6` under `2.8e-2`) leaps well on its own and the bottom is
    /// never in a block.
    const ROD_12: [f64; 8] = [
        1.3e-5, 7.37e-4, 0.378, 3.35e-5, 2.76e-6, 7.71e-3, 2.78e-2, 1.6e-6,
    ];

    #[test]
    fn the_fast_pair_between_slow_layers_is_the_block() {
        let runs = candidates(&ROD_12);
        assert_eq!(runs.first(), Some(&(3, 4)), "{runs:?}");
        assert!(runs.iter().all(|&(a, b)| a >= 1 && b < 7), "{runs:?}");
        assert!(pays(&ROD_12, (3, 4)));
    }

    /// A block only a few hundred times faster than its slow neighbours,
    /// whose lanes a delivery's sums would cost more than the loop: the
    /// four-layer rod whose block took 25 times the loop's time.
    #[test]
    fn a_block_that_would_cost_more_than_the_loop_is_left_to_it() {
        let transits = [0.586, 1.57e-3, 2.67e-3, 1.02];
        assert_eq!(candidates(&transits), vec![(1, 2)]);
        assert!(!pays(&transits, (1, 2)));
    }

    /// Priced as the dense sums cost, a block the deque's sums did not pay
    /// for: layer survey seed 3's rod 3 (layers of `2.9e-6` and `6.4e-6`
    /// between `5.5e-3` and `0.125`), whose ladder ran 3.4 s in the loop
    /// and 1.0 s with the block. Survey rod 13 (seed 7), whose loop lanes
    /// are far from full and which took twice as long with its block, is
    /// still left to the loop.
    #[test]
    fn the_sums_are_priced_as_dense_dot_products() {
        let rod_3 = [0.00994, 0.00555, 2.95e-6, 6.41e-6, 0.125, 3.96e-6, 0.0416];
        assert_eq!(candidates(&rod_3).first(), Some(&(2, 3)));
        assert!(pays(&rod_3, (2, 3)));
        let rod_13 = [
            0.00174, 0.161, 0.0375, 0.000167, 1.34e-5, 0.205, 0.245, 9.18e-5,
        ];
        assert_eq!(candidates(&rod_13).first(), Some(&(3, 4)));
        assert!(!pays(&rod_13, (3, 4)));
    }

    /// A pair beside a fast bottom (the fast-bottom survey's rod 17, seed
    /// 11: `1.1e-6` and `1.5e-5` on a bottom of `2.4e-4`): its port on
    /// the bottom's lattice delivers so often that sums over a response
    /// as long as the run would cost more than the loop, so it is taken
    /// only where its response is seen to ring out sooner, within a run
    /// of its allowance (`flow.rs`, `tests/blocks.rs`).
    #[test]
    fn a_pair_beside_a_fast_bottom_pays_only_if_it_rings_out() {
        let rod_17 = [2.446e-4, 1.089e-6, 1.541e-5, 8.46e-2];
        assert_eq!(candidates(&rod_17), vec![(1, 2)]);
        assert!(!pays(&rod_17, (1, 2)));
        let allowance = allowance(&rod_17, (1, 2));
        assert!(allowance < priced_run(&rod_17), "{allowance}");
        // a response ringing out within a few hundred bottom transits
        assert!(allowance > 300.0 * rod_17[0], "{allowance}");
    }

    #[test]
    fn blocks_neither_overlap_nor_touch() {
        assert!(apart((3, 4), &[(6, 7)]));
        assert!(!apart((3, 4), &[(5, 6)]));
        assert!(!apart((3, 4), &[(1, 2)]));
        assert!(apart((3, 4), &[(0, 1)]));
    }
}

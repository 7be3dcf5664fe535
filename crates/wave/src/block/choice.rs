//! Which layers make blocks, and where answering them pays.

use super::partitioned::adds_per_point;

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
/// whose response still rings, at [`NS_PER_ADD`] a multiply-add: `L / h_in`
/// of them for a response of length `L` summed directly, and past a few
/// hundred taps the partitioned FFT's count ([`adds_per_point`]), which
/// grows with the logarithm of `L` and then by an eighth of a multiply-add
/// a thousand taps. The sums must stay under a sixty-fourth of the loop's
/// most: at a quarter, survey rod 13 (whose loop lanes are far from full)
/// took twice as long. Only the speed depends on this choice, never the
/// honesty of the result: the ladder measures the error either way.
pub(crate) fn allowance(transits: &[f64], run: (usize, usize)) -> f64 {
    longest_within(transits, run, adds_per_point)
}

/// The longest response whose sums, at `adds(reach)` multiply-adds a
/// delivered point for arrivals reaching `reach` taps back, stay within a
/// sixty-fourth of what the loop may spend on block `run`'s lanes (see
/// [`allowance`]).
fn longest_within(transits: &[f64], (a, b): (usize, usize), adds: impl Fn(f64) -> f64) -> f64 {
    let (start, longest) = crate::ladder::LADDER_START;
    let t_max = transits.iter().copied().fold(0.0, f64::max);
    let third = (start / 4.0, longest / 4.0);
    let spacing = |m: usize| crate::ladder::lattice_spacing(third, transits[m], t_max);
    let loop_rate: f64 = (a..=b).map(|m| 2.0 / spacing(m)).sum();
    let ports: Vec<f64> = [Some(a - 1), (b + 1 < transits.len()).then_some(b + 1)]
        .into_iter()
        .flatten()
        .map(spacing)
        .collect();
    // microseconds a unit of time of the sums of a response `length` long,
    // every port summing every input's arrivals
    let sums_rate = |length: f64| -> f64 {
        ports
            .iter()
            .flat_map(|&h_out| ports.iter().map(move |&h_in| (h_out, h_in)))
            .map(|(h_out, h_in)| NS_PER_ADD * 1e-3 * adds(length / h_in) / h_out)
            .sum()
    };
    let budget = loop_rate / 64.0;
    // doubled past the budget, then the gap halved (the rate grows with
    // the length)
    let (mut within, mut beyond) = (0.0, ports.iter().copied().fold(f64::INFINITY, f64::min));
    while sums_rate(beyond) <= budget && beyond < f64::MAX / 4.0 {
        within = beyond;
        beyond *= 2.0;
    }
    for _ in 0..64 {
        let mid = 0.5 * (within + beyond);
        if sums_rate(mid) <= budget {
            within = mid;
        } else {
            beyond = mid;
        }
    }
    within
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
    /// are far from full and which took twice as long with its block summed
    /// directly, was left to the loop at that price; its probe took it at
    /// the last stop (0.86 -> 0.65 s), and the partitioned sums' price
    /// takes it over the whole run.
    #[test]
    fn the_sums_are_priced_as_they_cost() {
        let rod_3 = [0.00994, 0.00555, 2.95e-6, 6.41e-6, 0.125, 3.96e-6, 0.0416];
        assert_eq!(candidates(&rod_3).first(), Some(&(2, 3)));
        assert!(pays(&rod_3, (2, 3)));
        let rod_13 = [
            0.00174, 0.161, 0.0375, 0.000167, 1.34e-5, 0.205, 0.245, 9.18e-5,
        ];
        assert_eq!(candidates(&rod_13).first(), Some(&(3, 4)));
        assert!(pays(&rod_13, (3, 4)));
    }

    /// Blocks beside a fast bottom whose response rings through the run
    /// (the fast-bottom survey's rods 13, 31, 11 and 27, seed 11: fast
    /// layers of `7.5e-8` to `1.2e-5` on bottoms of `8e-6` to `3.1e-4`,
    /// under slow tops). Summed directly, a response as long as the run
    /// cost more than the loop, and answering them anyway took 1 to 2.3
    /// times as long as the loop (19, 45, 3.3 and 18 s); the sums were four
    /// fifths of that. Summed by the partitioned FFT their price is within
    /// the loop's sixty-fourth over the whole run, and answered they took
    /// 3.1, 7.2, 1.6 and 3.3 s against the loop's 18 to 21, 14 and 16 s.
    /// The dense price (`L / h_in` a point) would still refuse them.
    #[test]
    fn blocks_ringing_through_the_run_beside_a_fast_bottom_pay_when_summed_by_fft() {
        let rods: [(&[f64], (usize, usize)); 4] = [
            (&[7.954e-6, 1.885e-7, 7.5e-8, 0.0268, 0.0355], (1, 2)),
            (&[2.195e-5, 2.453e-7, 1.862e-7, 6.669e-7, 0.113], (1, 3)),
            (&[3.067e-4, 3.709e-6, 1.228e-5, 7.212e-6, 0.575], (1, 3)),
            (
                &[1.527e-4, 3.454e-6, 9.338e-7, 3.637e-6, 0.564, 0.073],
                (1, 3),
            ),
        ];
        for (transits, run) in rods {
            assert_eq!(candidates(transits).first(), Some(&run), "{transits:?}");
            assert!(pays(transits, run), "{transits:?}");
            // the dense price: the response's points, each delivered point
            let dense = dense_allowance(transits, run);
            assert!(dense < priced_run(transits), "{transits:?}: {dense}");
        }
    }

    /// [`allowance`] as it was with every tap summed directly.
    fn dense_allowance(transits: &[f64], run: (usize, usize)) -> f64 {
        longest_within(transits, run, |reach| reach.max(0.0))
    }

    /// The allowance grows past the dense one by the partitioned sums'
    /// saving: on the fast-bottom survey's rod 17 (seed 11: a pair of
    /// `1.1e-6` and `1.5e-5` on a bottom of `2.4e-4` under a slow top),
    /// whose response rings out within a few hundred bottom transits and
    /// which pays now over the whole run, it is nearly two thousand times
    /// the dense one (404 time units against 0.21; the run is priced at
    /// 0.68).
    #[test]
    fn the_allowance_grows_by_what_the_partitioned_sums_save() {
        let rod_17 = [2.446e-4, 1.089e-6, 1.541e-5, 8.46e-2];
        assert_eq!(candidates(&rod_17), vec![(1, 2)]);
        let (dense, fft) = (dense_allowance(&rod_17, (1, 2)), allowance(&rod_17, (1, 2)));
        assert!(fft > 1_000.0 * dense, "{fft} against {dense}");
        assert!(pays(&rod_17, (1, 2)));
    }

    #[test]
    fn blocks_neither_overlap_nor_touch() {
        assert!(apart((3, 4), &[(6, 7)]));
        assert!(!apart((3, 4), &[(5, 6)]));
        assert!(!apart((3, 4), &[(1, 2)]));
        assert!(apart((3, 4), &[(0, 1)]));
    }
}

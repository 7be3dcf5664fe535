//! What a merged ladder's levels say about its finest one: the error
//! estimate from how `e` changes as the lattice halves, and whether the
//! levels are seen converging at all (an estimate taken on the flat part of
//! a step of the convergence can be low).

/// How many coarser levels the reported one is set against: a merged `e`
/// converges at first order on average but in steps (measured on a
/// six-layer rod: the error stays put for two halvings, then falls eight
/// times), so a level equal to the one twice as coarse says little alone.
pub(crate) const LOOK_BACK: usize = 4;

/// The refinement part of a merged bound from the values of `e` on
/// lattices that halve (coarsest first): for convergence at order `p`,
/// `|e(h) - e(2^j h)| / (2^(j p) - 1)` estimates the error at `h` from
/// each coarser level `j`; the largest of them over [`LOOK_BACK`] levels
/// is taken, so that a plateau of the staircase cannot hide the next step.
/// `p` is [`assumed_order`]: first order, the merge error's, unless the
/// levels shrink more slowly. Taken as first order, levels that shrink at
/// order 0.52 left the layer survey's rod 7 (seed 7) 1.3 times its bound
/// from its exact `e`: at order `p` the error is `1 / (2^p - 1)` times the
/// last difference, 2.3 times at 0.52, not once.
///
/// Where the last three levels' differences shrink faster than
/// [`FASTEST_ORDER`], the last two agree in part by chance, and each
/// difference is taken undivided: the finest level no closer to `e` than
/// to the coarser ones.
pub(crate) fn refinement_error(levels: &[f64]) -> f64 {
    let Some((&fine, coarser)) = levels.split_last() else {
        return 0.0;
    };
    let p = assumed_order(levels);
    let by_chance = agree_by_chance(levels);
    coarser
        .iter()
        .rev()
        .take(LOOK_BACK)
        .zip(1..)
        .map(|(&e, j)| {
            let gain = if by_chance {
                1.0
            } else {
                2f64.powf(f64::from(j) * p) - 1.0
            };
            (fine - e).abs() / gain
        })
        .fold(0.0, f64::max)
}

/// The fastest observed order taken at its word. A merge's error is of
/// first order (second where only the deposits' smoothing counts: they
/// keep each front's jump and first moment), so differences that shrink
/// more than fourfold in one halving are a coincidence of the last two
/// levels, or the fast fall of a step before the next flat part: a stack
/// of real materials (aluminium, rubber, polyurethane, rubber;
/// `scripts/survey-layers.py --materials --seed 8`, rod 21) showed the
/// order 5.1, its levels `1.9e-7`, `1.09e-6` and `1.08e-6` from its exact
/// `e`, and the estimate at first order, `3.0e-7`, left it 1.8 times its
/// bound away. It was 3 (eightfold) until the layer survey's seed 3, rod
/// 31 (seven layers, transit ratio `1.5e5`) showed the order 2.37 at its
/// third level (`0.5823275386`, `0.5830287880`, `0.5831641495`, then
/// `0.5833670142`, `0.5835441532`, `0.5840036958` and `0.5842618621` on
/// lattices down to 0.0016 of a transit, `level_probe` example; the two
/// between at 0.0063 and 0.0008 chatter, their twins `5e-2` apart): taken
/// as first order, its bound `5.6e-4` lay `1.1e-3` from the finest.
pub const FASTEST_ORDER: f64 = 2.0;

/// Whether the last three levels' observed order is past
/// [`FASTEST_ORDER`] (see [`refinement_error`]).
pub(crate) fn agree_by_chance(levels: &[f64]) -> bool {
    observed_order(levels).is_some_and(|o| o > FASTEST_ORDER)
}

/// The order of convergence the refinement estimate assumes: the last
/// three levels' observed order, but no faster than first (faster is no
/// risk to the estimate, which looks back over four levels) and no slower
/// than [`SLOWEST_ORDER`] (slower is not seen converging, and said); first
/// order where the levels show none (fewer than three, or `e` standing
/// still).
pub(crate) fn assumed_order(levels: &[f64]) -> f64 {
    observed_order(levels).map_or(1.0, |p| p.clamp(SLOWEST_ORDER, 1.0))
}

/// The slowest observed order taken as convergence: a merged `e` converges
/// at first order once the lattice is fine enough, but falls in steps
/// before, and an estimate taken on a step's flat part is low (a plateau
/// over four halvings on a five-layer rod: the levels differed by `1e-7`
/// while the error stayed `2.0e-6`; its last three levels show the order
/// `-0.6`). Faster than first order is no risk to the estimate: it looks
/// back over four levels, and the fall behind it counts.
pub const SLOWEST_ORDER: f64 = 0.5;

/// `log2(|e(4h) - e(2h)| / |e(2h) - e(h)|)` over the last three levels
/// (coarsest first): 1 for first-order convergence; `None` with fewer than
/// three levels or a zero difference.
pub(crate) fn observed_order(levels: &[f64]) -> Option<f64> {
    let [.., coarse, middle, fine] = levels else {
        return None;
    };
    let (before, last) = ((middle - coarse).abs(), (fine - middle).abs());
    (before > 0.0 && last > 0.0).then(|| (before / last).log2())
}

/// Whether the last three levels look converging: their differences
/// shrink at [`SLOWEST_ORDER`] or faster, or `e` no longer moves at all
/// between them (within 64 ulps: nothing the lattice does reaches it).
/// Fewer than three levels show nothing.
pub(crate) fn converging(levels: &[f64]) -> bool {
    let [.., coarse, middle, fine] = levels else {
        return false;
    };
    let still = 64.0 * f64::EPSILON * fine.abs();
    let (before, last) = ((middle - coarse).abs(), (fine - middle).abs());
    match (before <= still, last <= still) {
        (true, true) => true,
        // it moved after standing still: a step has begun
        (true, false) => false,
        // it stopped after moving: the look-back holds the fall
        (false, true) => true,
        (false, false) => (before / last).log2() >= SLOWEST_ORDER,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Levels `e_exact + C h` on halving lattices, coarsest first.
    fn first_order(n: usize) -> Vec<f64> {
        (0..n).map(|k| 0.5 + 1e-3 / 2f64.powi(k as i32)).collect()
    }

    #[test]
    fn first_order_levels_show_order_one_and_their_error() {
        let levels = first_order(5);
        let order = observed_order(&levels).unwrap();
        assert!((order - 1.0).abs() < 1e-9, "{order}");
        assert!(converging(&levels));
        // the finest level's error is exactly 1e-3 / 16
        let error = refinement_error(&levels);
        assert!((error - 1e-3 / 16.0).abs() < 1e-15, "{error}");
    }

    /// Levels converging at half an order: the estimate takes the
    /// observed order and finds the finest level's error, where first
    /// order would give 0.41 of it; anything slower is taken at half an
    /// order, and anything faster at first order.
    #[test]
    fn slow_levels_are_estimated_at_their_order() {
        let half: Vec<f64> = (0..5)
            .map(|k| 0.5 + 1e-3 * 0.5f64.powf(0.5 * k as f64))
            .collect();
        let order = observed_order(&half).unwrap();
        assert!((order - 0.5).abs() < 1e-9, "{order}");
        assert!((assumed_order(&half) - 0.5).abs() < 1e-9);
        let error = refinement_error(&half);
        let exact = 1e-3 * 0.25;
        assert!((error - exact).abs() < 1e-12, "{error} against {exact}");
        let plateau = [0.5 - 2.23e-6, 0.5 - 2.61e-6, 0.5 - 2.02e-6];
        assert_eq!(assumed_order(&plateau), SLOWEST_ORDER);
        assert_eq!(assumed_order(&first_order(4)), 1.0);
        assert_eq!(assumed_order(&[0.5 + 1e-4, 0.5 + 1e-6, 0.5 + 1e-8]), 1.0);
        assert_eq!(assumed_order(&[0.5, 0.5 + 1e-6]), 1.0);
    }

    /// Levels whose last difference shrank more than eightfold: the
    /// estimate takes each difference undivided. The materials survey's
    /// rod (seed 8, rod 21): levels `1.9e-7`, `1.09e-6` and `1.08e-6`
    /// below its exact `e`.
    #[test]
    fn levels_agreeing_by_chance_are_taken_undivided() {
        let exact = 0.6806513448;
        let levels = [exact - 1.9e-7, exact - 1.09e-6, exact - 1.08e-6];
        let order = observed_order(&levels).unwrap();
        assert!(order > FASTEST_ORDER, "{order}");
        assert!(agree_by_chance(&levels));
        let error = refinement_error(&levels);
        assert!((error - 0.89e-6).abs() < 1e-12, "{error}");
        // the fine level's error is within twice the estimate, as the
        // bound takes it, where first order gave a third of the estimate
        assert!(1.08e-6 <= 2.0 * error);
        assert!(!agree_by_chance(&first_order(4)));
    }

    /// The layer survey's seed 3, rod 31: its first three levels shrink
    /// fivefold (order 2.37), then `e` goes on rising by about `2e-4` a
    /// halving. Taken undivided, its bound holds against the finest level
    /// run (0.0016 of a transit: 0.66 of it); at first order that level lay
    /// twice the bound away.
    #[test]
    fn levels_shrinking_faster_than_a_merge_are_taken_undivided() {
        let levels = [0.5823275386, 0.5830287880, 0.5831641495];
        let finest = 0.5842618621;
        let order = observed_order(&levels).unwrap();
        assert!(order > FASTEST_ORDER && order < 3.0, "{order}");
        let bound = 2.0 * refinement_error(&levels);
        let off = (levels[2] - finest).abs();
        assert!(off <= bound, "{off:e} {bound:e}");
        // at first order, the look-back's difference divided by three
        let first_order = 2.0 * (levels[2] - levels[0]).abs() / 3.0;
        assert!(off > 1.9 * first_order, "{off:e} {first_order:e}");
    }

    #[test]
    fn a_plateau_or_a_step_beginning_is_not_converging() {
        // the five-layer rod's first three levels: errors -2.23e-6,
        // -2.61e-6, -2.02e-6 (differences growing: order -0.6)
        let plateau = [0.5 - 2.23e-6, 0.5 - 2.61e-6, 0.5 - 2.02e-6];
        assert!(observed_order(&plateau).unwrap() < 0.0);
        assert!(!converging(&plateau));
        // standing still, then moving: a step has begun
        let step = [0.5, 0.5, 0.5 + 1e-6];
        assert_eq!(observed_order(&step), None);
        assert!(!converging(&step));
        // two levels show nothing
        assert!(!converging(&[0.5, 0.5 + 1e-6]));
    }

    #[test]
    fn a_fall_then_stillness_or_no_movement_at_all_is_converging() {
        // moved, then stood still: the look-back carries the fall
        let fell = [0.5 + 1e-4, 0.5, 0.5];
        assert!(converging(&fell));
        assert!(refinement_error(&fell) >= 0.999 * 1e-4 / 3.0);
        // nothing the lattice does reaches e (within 64 ulps)
        let still = [0.5, 0.5 + 2.0 * f64::EPSILON, 0.5];
        assert!(converging(&still));
        // faster than first order is no risk: the fall is looked back on
        let fast = [0.5 + 1e-4, 0.5 + 1e-6, 0.5 + 1e-8];
        assert!(converging(&fast));
        assert!(refinement_error(&fast) >= 0.999 * (1e-4 - 1e-8) / 3.0);
    }
}

//! Decisions a ladder's levels share: where its comparisons are blind to
//! the lattice.
//!
//! The levels' lattices are nested: births at `k h`, `h` halved from one
//! level to the next, so every point of a level's lattice is a point of
//! every finer one. A separation decided at the arrival of a lattice
//! deposit happens at a lattice point, and a finer level may decide it at
//! the same point, with the same contacts before it: the two levels then
//! give nearly the same `e`, and their difference says nothing of how far
//! the lattice moved that instant. 8.7 cm of hydrogel under 0.15 mm of
//! tungsten carbide separated at `0.0323219` s on every level, the exact
//! rod at `0.0323243` s: `e` `4.3e-7` off under a bound of `8.5e-10`
//! (`tests/finishes.rs::a_separation_on_a_shared_lattice_point_is_within_the_bound`).
//!
//! Where the reported level and the one before it have the same contacts
//! and a separation at a lattice point, one more run, on a lattice
//! `2^(1/2)` times as coarse as the reported one (which shares no point
//! with the ladder's lattices but the origin), decides its separations at
//! other instants, and its difference enters the bound. It samples how far
//! the lattice moves a decision, as a twin samples chaos: a sample can
//! fall low. Coarser, not finer: it costs about 0.7 of the reported
//! level's run instead of 1.4 (21 of 280 survey rods run it; seed 29's
//! rod 22 took 4.7 s instead of 2.5 with the finer one), and its larger
//! error only widens the bound.

use crate::engine::WaveEngine;

/// The off-lattice level's spacing, as a multiple of the reported level's.
pub(crate) const OFF_LATTICE: f64 = std::f64::consts::SQRT_2;

/// What the off-lattice level's difference is multiplied by to estimate
/// the reported level's error, as if first order: `e(2^(1/2) h) - e(h)`
/// is `2^(1/2) - 1` times `e(h) - e(0)`.
pub(crate) const OFF_LATTICE_GAIN: f64 = 1.0 / (OFF_LATTICE - 1.0);

/// Whether `fine` decided a separation at a lattice point and has the same
/// contacts as `coarse`, every start and end within `1e-12` of each other
/// (relative).
pub(crate) fn shared_decisions(fine: &WaveEngine, coarse: &WaveEngine) -> bool {
    if fine.decisions().separations_on_lattice == 0 {
        return false;
    }
    let (a, b) = (fine.outcome().contacts, coarse.outcome().contacts);
    let same = |x: f64, y: f64| (x - y).abs() <= 1e-12 * x.abs().max(y.abs());
    a.len() == b.len()
        && a.iter()
            .zip(&b)
            .all(|(x, y)| same(x[0], y[0]) && same(x[1], y[1]))
}

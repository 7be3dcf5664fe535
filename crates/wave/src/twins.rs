//! A merged level's perturbed twins: the same rod with its bottom's modulus
//! nudged by a few `1e-12`, run on the same lattice. Rods that chatter for
//! hundreds of bounces amplify any perturbation, a merge among them,
//! chaotically: a grazing contact goes either way on a rounding, and each
//! way leads on to other contacts (a steel base under rubber moves `e` by
//! `1e-4`). How far the twins' `e` lie from the level's measures that.
//!
//! One twin is one sample of that spread, and a sample can fall far inside
//! it. Seed 3's rod 33 of the layer survey, run on its reported lattice
//! with 25 nudges `k 1e-12`, `k = -12..12` (`nudge_spread` example),
//! spreads `e` over `9.3e-3` with a standard deviation of `2.6e-3`; its
//! one twin's difference was `4.3e-4`. Over 20,000 random draws from those
//! 25 runs, the bound `2 max_k |e_k - e|` of one twin covers on average
//! 71 % of the other runs' `e`, of three twins 93 %, of five 97 % (seed 3's
//! rod 5, the other chattering rod measured: 72, 95 and 99 %). So a level
//! whose first twin says its contacts flip, where that may decide the
//! bound, gets two more: three twins, for one more run's time on two
//! cores.
//!
//! Fourteen more rods whose first twin says so (the layer survey's seeds
//! 7, 3 and 29 and the materials draw's seed 9: seed 7's rods 15, 16, 26,
//! 28 and 34, seed 3's 18 and 39, seed 29's 0, 1, 12, 14 and 20, the
//! materials' 33 and 38), run the same way on their reported lattices,
//! give the same shares whatever their spread (`1.5e-8` to `5.8e-2`):
//! one twin 70 to 73 %, three 91 to 96 %, five 95 to 99 %. With the
//! bound's refinement part, three twins' bound covers 95 % or more on
//! every one (seed 29's rod 0, whose refinement estimate is a ninth of
//! its spread, 95 %; nine of them 100 %). The shares are what the
//! largest of a few draws covers of the others, whatever the rod.

use crate::config::WaveConfig;
use crate::error::WaveError;
use crate::ladder::merged_at;
use crate::solve::run;
use impact_model::Rod;

/// The relative nudges of the bottom's modulus in a level's twins, the
/// first run beside every reported level, the others only where
/// [`needs_further`] says so.
pub(crate) const NUDGES: [f64; 3] = [1e-12, -1e-12, 2e-12];

/// A twin's difference above which `e` is not a smooth function of the
/// modulus at the nudge's scale: a hundred times the nudge. A smooth `e`
/// moves by `de/d(ln E)` times the nudge, and `de/d(ln E)` is of order
/// one (rounding alone moved seed 3's rod 1, of 2.4 M events, by
/// `4.9e-12`); what moves it more is a contact that flipped.
const AMPLIFIED: f64 = 1e-10;

/// How far one twin's difference may fall below the spread of many, for
/// the further twins to be skipped: on the two chattering rods measured
/// first (see the module's doc), one twin's difference was under a
/// thirtieth of the largest over the other 24 runs for 4 % (seed 3's rod
/// 33) and 6 % (seed 3's rod 5) of the pairs; on the fourteen measured
/// since, for 3 to 11 %. A larger factor does not close that tail: the
/// nudged runs fall in clusters, and a twin in the level's own cluster
/// differs little (the materials' rod 38: under a hundredth of the
/// largest for 8 % of the pairs). Where the twin falls so low, the bound
/// rests on its refinement part, and what decides is how far under that
/// part the twin falls: over 96 rods of eleven draws whose twin flips
/// contacts (`scripts/twin-coverage.py`, 24 nudged runs each on the
/// reported lattice), a one-twin bound left nudged runs outside only
/// where the refinement estimate was under 170 times the twin's
/// difference (layer survey seed 67's rod 22 at 164: 14 of 24 outside,
/// the furthest at 1.4 of the bound; seed 41's rod 1 at 67: one, at 1.0),
/// and on the 40 rods above 300 times the furthest lay at 0.28 of it. At
/// thirty, the factor until then, neither ran its further twins.
const ONE_SAMPLE_LOW: f64 = 300.0;

/// The rod with its bottom layer's modulus changed by `nudge`, relative
/// (the rod itself if that is not a valid scene, which a nudge of a few
/// `1e-12` cannot make of a valid one).
pub(crate) fn nudged(rod: &Rod, nudge: f64) -> Rod {
    let mut scene = rod.scene().clone();
    scene.layers[0].modulus *= 1.0 + nudge;
    scene.validate().unwrap_or_else(|_| rod.clone())
}

/// Whether a level whose first twin differs by `first` needs the further
/// twins: its contacts flip on a nudge, and the spread they sample could
/// exceed the refinement estimate `refined` (a rod whose chaos is far
/// under its refinement error is left with its one twin).
pub(crate) fn needs_further(first: f64, refined: f64) -> bool {
    first > AMPLIFIED && ONE_SAMPLE_LOW * first > refined
}

/// The further twins on the lattice `(p, l)`, side by side: each one's
/// nudge and `e`, and the work they took. A twin that does not finish
/// within `max_events` or the time limit (its contacts went another way)
/// is left out, and the caller says so; its work is not counted.
pub(crate) fn further_twins(
    rod: &Rod,
    config: &WaveConfig,
    (p, l): (f64, f64),
    max: u64,
) -> Result<(Vec<(f64, f64)>, u64), WaveError> {
    use rayon::prelude::*;
    let runs: Vec<Result<(f64, f64, u64), WaveError>> = NUDGES[1..]
        .par_iter()
        .map(|&nudge| {
            run::<f64>(&nudged(rod, nudge), merged_at(config, p, l, max))
                .map(|twin| (nudge, twin.restitution(), twin.steps()))
        })
        .collect();
    let mut twins = Vec::new();
    let mut work = 0;
    for run in runs {
        match run {
            Ok((nudge, e, steps)) => {
                twins.push((nudge, e));
                work += steps;
            }
            Err(WaveError::EventLimit { .. } | WaveError::TimeLimit { .. }) => {}
            Err(e) => return Err(e.on_lattice(p)),
        }
    }
    Ok((twins, work))
}

//! Which instants are one event: the simultaneity window.

use crate::real::Real;

/// How close two instants must be to be one: within `fixed` (the
/// configured simultaneity window), or within `ulps` of the instant and of
/// the shortest transit `scale` (`ulps (|t| + scale)`), where rounding
/// alone could have split a true tie. The second part grows with the time,
/// as the rounding of summed transit times does: a fixed window small
/// enough to leave real near-ties apart early splits true ties late in a
/// long run (and their fronts multiply); one wide enough for late ties
/// combines real near-ties early, which the error estimate must then
/// measure by a second run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Window<R> {
    /// The configured window (`WaveConfig::simultaneity` times the
    /// shortest transit).
    pub fixed: R,
    /// The rounding part's relative width (`TIE_ULPS` ulps).
    pub ulps: R,
    /// The shortest transit: rounding's scale near `t = 0`.
    pub scale: R,
}

impl<R: Real> Window<R> {
    /// A window of `fixed` alone.
    #[cfg(test)]
    pub fn fixed(fixed: f64) -> Self {
        Self {
            fixed: R::of(fixed),
            ulps: R::zero(),
            scale: R::zero(),
        }
    }

    /// The window at instant `t`. (A comparison, not `max`: the same
    /// value, since `fixed` is never NaN, without `max`'s handling of NaN,
    /// four instructions on every event and push.)
    #[inline(always)]
    pub fn at(&self, t: R) -> R {
        let rounding = self.ulps * (t.abs() + self.scale);
        if rounding > self.fixed {
            rounding
        } else {
            self.fixed
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lane::{Direction, Lane, MergeRule, Pushed};

    /// The window of rounding grows with the instant: late in a long run
    /// two births a few ulps apart (a tie that rounding split) are one,
    /// where a fixed window of a fraction of the shortest transit, small
    /// enough to leave near-ties early in the run apart, would split them.
    #[test]
    fn the_window_of_rounding_grows_with_the_time() {
        let rounding = Window {
            fixed: 0.0,
            ulps: 64.0 * f64::EPSILON,
            scale: 1.0,
        };
        let late = 1e6;
        let tie = late + 8.0 * late * f64::EPSILON;
        assert!(tie - late <= rounding.at(tie));
        assert!(tie - late > Window::<f64>::fixed(1e-12).at(tie));
        // early, arrivals 1e-12 of the shortest transit apart stay apart
        assert!(1e-12 > rounding.at(1.0));
        // and a configured window adds to it
        let wide = Window {
            fixed: 1e-9,
            ..rounding
        };
        assert_eq!(wide.at(1.0), 1e-9);
        assert_eq!(wide.at(late), rounding.at(late));
        let mut lane = Lane::new(
            0,
            Direction::Up,
            2.0,
            MergeRule::Simultaneous { window: rounding },
        );
        lane.push(late, 0.5, 0);
        assert!(matches!(lane.push(tie, 0.25, 1), Pushed::Merged { .. }));
        assert_eq!(lane.len(), 1);
    }
}

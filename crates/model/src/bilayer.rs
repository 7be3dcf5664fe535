//! The paper's canonical bilayer, parametrised by composition `x` and stiffness
//! ratio `alpha`.

use crate::scene::{Layer, Scene, SceneError, check};

/// Composition `x = L2 / L` and stiffness ratio `alpha = E2 / (E1 + E2)`.
///
/// The canonical scene is `L = 1`, `rho = 1`, `E1 = 1 - alpha`, `E2 = alpha`,
/// `v_b = 1` (DESIGN.md §1): `e`, `t_c / (2 t1 + 2 t2)` and the bounce count do
/// not depend on these choices, and times scale with `L`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bilayer {
    /// Composition `x = L2 / L`: the top layer's share of the rod's length, in `(0, 1)`.
    pub x: f64,
    /// Stiffness ratio `alpha = E2 / (E1 + E2)`, in `(0, 1)`: small means a soft top on a stiff bottom.
    pub alpha: f64,
}

impl Bilayer {
    /// Checks `0 < x < 1` and `0 < alpha < 1` (both layers must exist).
    pub fn new(x: f64, alpha: f64) -> Result<Self, SceneError> {
        let open = "a number in (0, 1)";
        check("x", x, open, |v| v > 0.0 && v < 1.0)?;
        check("alpha", alpha, open, |v| v > 0.0 && v < 1.0)?;
        Ok(Self { x, alpha })
    }

    /// The canonical elastic scene: bottom `P1` of length `1 - x`, modulus
    /// `1 - alpha`; top `P2` of length `x`, modulus `alpha`.
    pub fn scene(&self) -> Scene {
        let mut p1 = Layer::elastic(1.0 - self.x, 1.0 - self.alpha, 1.0);
        p1.name = Some("P1".into());
        let mut p2 = Layer::elastic(self.x, self.alpha, 1.0);
        p2.name = Some("P2".into());
        Scene {
            impact_speed: 1.0,
            layers: vec![p1, p2],
            wall_contact: None,
        }
    }

    /// One-way transit times `[t1, t2] = [(1 - x) / sqrt(1 - alpha),
    /// x / sqrt(alpha)]` (unit length, density and `E1 + E2`), as the
    /// general scene computes them:
    /// ```
    /// # use impact_model::Bilayer;
    /// let b = Bilayer::new(0.3, 0.2).unwrap();
    /// let general = b.scene().validate().unwrap().transit_times();
    /// for (t, g) in b.transit_times().iter().zip(&general) {
    ///     assert!((t - g).abs() < 1e-15);
    /// }
    /// ```
    pub fn transit_times(&self) -> [f64; 2] {
        [
            (1.0 - self.x) / (1.0 - self.alpha).sqrt(),
            self.x / self.alpha.sqrt(),
        ]
    }

    /// The reduced contact time `t_c / (2 t1 + 2 t2)` of a rod that leaves
    /// at `2 t1`: `t1 / (t1 + t2)`.
    pub fn first_echo_reduced_time(&self) -> f64 {
        let [t1, t2] = self.transit_times();
        t1 / (t1 + t2)
    }

    /// Transit-time ratio `t2 / t1 = x sqrt(1 - alpha) / ((1 - x) sqrt(alpha))`.
    pub fn transit_ratio(&self) -> f64 {
        self.x * (1.0 - self.alpha).sqrt() / ((1.0 - self.x) * self.alpha.sqrt())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn canonical_scene_matches_the_paper() {
        let b = Bilayer::new(0.3, 0.2).unwrap();
        let rod = b.scene().validate().unwrap();
        let t = rod.transit_times();
        assert!((t[1] / t[0] - b.transit_ratio()).abs() < 1e-14);
        assert!((rod.mass() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn bounds_are_open() {
        for (x, a) in [
            (0.0, 0.5),
            (1.0, 0.5),
            (0.5, 0.0),
            (0.5, 1.0),
            (f64::NAN, 0.5),
        ] {
            let err = Bilayer::new(x, a).unwrap_err().to_string();
            assert!(err.contains("must be a number in (0, 1)"), "{err}");
        }
    }
}

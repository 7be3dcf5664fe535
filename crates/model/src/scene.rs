//! Scenes as users write them, and their validation into a [`Rod`].

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// One homogeneous layer, as written in a scene file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Layer {
    /// Optional label, used in summaries and figures.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Undeformed length (> 0).
    pub length: f64,
    /// Young's modulus (> 0).
    pub modulus: f64,
    /// Mass density (> 0).
    pub density: f64,
    /// Kelvin-Voigt relaxation time `tau = eta / E` (>= 0). Absent or 0: elastic.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub relaxation_time: Option<f64>,
    /// Viscosity given as the paper does (Sec. VII): the restitution, in (0, 1],
    /// of a homogeneous rod of the whole length made of this layer alone.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub restitution: Option<f64>,
}

impl Layer {
    /// An elastic layer.
    pub fn elastic(length: f64, modulus: f64, density: f64) -> Self {
        Self {
            name: None,
            length,
            modulus,
            density,
            relaxation_time: None,
            restitution: None,
        }
    }

    /// True when the layer dissipates (a positive relaxation time, or a layer
    /// restitution below one).
    pub fn is_viscous(&self) -> bool {
        self.relaxation_time.is_some_and(|t| t > 0.0) || self.restitution.is_some_and(|e| e < 1.0)
    }
}

/// A projectile and its impact: layers from the wall (index 0) to the free top.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Speed towards the wall just before impact (> 0).
    pub impact_speed: f64,
    /// Layers, bottom (touching the wall) first.
    pub layers: Vec<Layer>,
}

/// Why a scene is not a valid projectile. Every message names the field and the
/// allowed range, so a user knows what to change.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SceneError {
    /// A number outside its allowed range (NaN and infinities included).
    #[error("{field} must be {allowed} (got {value})")]
    OutOfRange {
        field: String,
        allowed: &'static str,
        value: f64,
    },
    /// A scene with no layer.
    #[error("layers must list at least one layer (got none)")]
    NoLayers,
    /// Both ways of giving viscosity at once.
    #[error("layers[{index}] gives both relaxation_time and restitution: give at most one")]
    ConflictingViscosity { index: usize },
    /// Malformed scene text.
    #[error("scene JSON: {0}")]
    Json(String),
}

/// Checks that `value` is finite and inside `allowed`, described for the user.
pub(crate) fn check(
    field: impl Into<String>,
    value: f64,
    allowed: &'static str,
    ok: impl Fn(f64) -> bool,
) -> Result<f64, SceneError> {
    if value.is_finite() && ok(value) {
        Ok(value)
    } else {
        Err(SceneError::OutOfRange {
            field: field.into(),
            allowed,
            value,
        })
    }
}

impl Scene {
    /// Parses a scene from JSON text; unknown fields are errors.
    pub fn from_json(text: &str) -> Result<Self, SceneError> {
        serde_json::from_str(text).map_err(|e| SceneError::Json(e.to_string()))
    }

    /// Validates the scene and derives every quantity the engines need.
    pub fn validate(&self) -> Result<Rod, SceneError> {
        check(
            "impact_speed",
            self.impact_speed,
            "a finite number > 0",
            |v| v > 0.0,
        )?;
        if self.layers.is_empty() {
            return Err(SceneError::NoLayers);
        }
        let mut props = Vec::with_capacity(self.layers.len());
        let mut bottom = 0.0;
        for (i, layer) in self.layers.iter().enumerate() {
            let f = |name: &str| format!("layers[{i}].{name}");
            let positive = "a finite number > 0";
            let length = check(f("length"), layer.length, positive, |v| v > 0.0)?;
            let modulus = check(f("modulus"), layer.modulus, positive, |v| v > 0.0)?;
            let density = check(f("density"), layer.density, positive, |v| v > 0.0)?;
            if let Some(tau) = layer.relaxation_time {
                check(f("relaxation_time"), tau, "a finite number >= 0", |v| {
                    v >= 0.0
                })?;
            }
            if let Some(e) = layer.restitution {
                check(f("restitution"), e, "a number in (0, 1]", |v| {
                    v > 0.0 && v <= 1.0
                })?;
            }
            if layer.relaxation_time.is_some() && layer.restitution.is_some() {
                return Err(SceneError::ConflictingViscosity { index: i });
            }
            if let Some(e) = layer.restitution {
                let (lowest, _) = crate::calibration::range();
                check(f("restitution"), e, "a number in [the calibration's lowest, 1] (see impact calibrate)", |v| v >= lowest)
                    .map_err(|_| SceneError::OutOfRange {
                        field: f("restitution"),
                        allowed: "a number in (0, 1] reachable by the calibration table (impact calibrate --help)",
                        value: e,
                    })?;
            }
            let wave_speed = (modulus / density).sqrt();
            props.push(LayerProps {
                bottom,
                top: bottom + length,
                length,
                modulus,
                density,
                wave_speed,
                impedance: density * wave_speed,
                transit_time: length / wave_speed,
            });
            bottom += length;
        }
        Ok(Rod {
            scene: self.clone(),
            layers: props,
        })
    }
}

/// Derived, validated properties of one layer (unit cross-section).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LayerProps {
    /// Height of the layer's bottom in the undeformed rod.
    pub bottom: f64,
    /// Height of the layer's top.
    pub top: f64,
    pub length: f64,
    pub modulus: f64,
    pub density: f64,
    /// `c = sqrt(E / rho)`.
    pub wave_speed: f64,
    /// `Z = rho c`: what the interface scattering depends on.
    pub impedance: f64,
    /// One-way transit time `L / c`.
    pub transit_time: f64,
}

impl LayerProps {
    /// Mass per unit cross-section.
    pub fn mass(&self) -> f64 {
        self.density * self.length
    }
}

/// A validated scene with its derived quantities. Engines take a `Rod`, never a
/// raw [`Scene`].
#[derive(Debug, Clone, PartialEq)]
pub struct Rod {
    scene: Scene,
    layers: Vec<LayerProps>,
}

impl Rod {
    /// The scene this rod was validated from.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Derived layer properties, bottom first.
    pub fn layers(&self) -> &[LayerProps] {
        &self.layers
    }

    pub fn impact_speed(&self) -> f64 {
        self.scene.impact_speed
    }

    pub fn total_length(&self) -> f64 {
        self.layers.last().map_or(0.0, |l| l.top)
    }

    pub fn mass(&self) -> f64 {
        self.layers.iter().map(LayerProps::mass).sum()
    }

    /// One-way transit time of each layer, bottom first.
    pub fn transit_times(&self) -> Vec<f64> {
        self.layers.iter().map(|l| l.transit_time).collect()
    }

    /// The shortest transit time: the smallest physical time of the rod, used by
    /// the paper's bounce filter.
    pub fn min_transit_time(&self) -> f64 {
        self.layers
            .iter()
            .map(|l| l.transit_time)
            .fold(f64::INFINITY, f64::min)
    }

    /// The longest transit time: the paper's horizon is 20 times this.
    pub fn max_transit_time(&self) -> f64 {
        self.layers
            .iter()
            .map(|l| l.transit_time)
            .fold(0.0, f64::max)
    }

    /// Kelvin-Voigt relaxation time `tau = eta / E` of layer `i`: given
    /// directly, or from the layer's restitution `e_i` through the
    /// calibration (`tau c_i / L = f(e_i)`, `L` the whole rod's length).
    pub fn relaxation_time(&self, i: usize) -> f64 {
        let layer = &self.scene.layers[i];
        if let Some(tau) = layer.relaxation_time {
            return tau;
        }
        match layer.restitution {
            Some(e) if e < 1.0 => {
                let scaled = crate::calibration::tau_c_over_l(e).unwrap_or(f64::NAN);
                scaled * self.total_length() / self.layers[i].wave_speed
            }
            _ => 0.0,
        }
    }

    /// Kinetic energy before impact, `M v_b^2 / 2`.
    pub fn initial_energy(&self) -> f64 {
        0.5 * self.mass() * self.impact_speed().powi(2)
    }

    /// True when any layer dissipates.
    pub fn is_viscous(&self) -> bool {
        self.scene.layers.iter().any(Layer::is_viscous)
    }

    /// `integral(m(s)^2 / E(s) ds)` over the rod, with `m(s)` the mass above
    /// height `s`. Bounds how far the bottom can sit below the centre of mass
    /// for a given internal energy (DESIGN.md §2, exact stop rule).
    pub fn compliance_moment(&self) -> f64 {
        let mut above = 0.0;
        let mut sum = 0.0;
        for l in self.layers.iter().rev() {
            let below = above + l.mass();
            // (1/E) * integral_0^L (above + rho u)^2 du
            sum += (below.powi(3) - f64::powi(above, 3)) / (3.0 * l.density * l.modulus);
            above = below;
        }
        sum
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn two_layers() -> Scene {
        Scene {
            impact_speed: 2.0,
            layers: vec![Layer::elastic(0.7, 4.0, 1.0), Layer::elastic(0.3, 1.0, 4.0)],
        }
    }

    #[test]
    fn derived_quantities() {
        let rod = two_layers().validate().unwrap();
        let l = rod.layers();
        assert_eq!(l[0].wave_speed, 2.0);
        assert_eq!(l[1].wave_speed, 0.5);
        assert_eq!(l[1].impedance, 2.0);
        assert!((l[1].transit_time - 0.6).abs() < 1e-15);
        assert!((rod.mass() - 1.9).abs() < 1e-15);
        assert!((rod.total_length() - 1.0).abs() < 1e-15);
        assert!((rod.initial_energy() - 3.8).abs() < 1e-12);
    }

    #[test]
    fn compliance_moment_of_a_homogeneous_rod() {
        // m(s) = rho (L - s): integral = rho^2 L^3 / (3 E)
        let scene = Scene {
            impact_speed: 1.0,
            layers: vec![Layer::elastic(2.0, 3.0, 5.0)],
        };
        let rod = scene.validate().unwrap();
        let expected = 25.0 * 8.0 / 9.0;
        assert!((rod.compliance_moment() - expected).abs() < 1e-12);
        // splitting the same rod in two layers changes nothing
        let split = Scene {
            impact_speed: 1.0,
            layers: vec![Layer::elastic(0.5, 3.0, 5.0), Layer::elastic(1.5, 3.0, 5.0)],
        };
        let split = split.validate().unwrap();
        assert!((split.compliance_moment() - expected).abs() < 1e-12);
    }

    #[test]
    fn errors_name_the_field_and_range() {
        let mut s = two_layers();
        s.layers[1].modulus = -1.0;
        let msg = s.validate().unwrap_err().to_string();
        assert_eq!(
            msg,
            "layers[1].modulus must be a finite number > 0 (got -1)"
        );
        let mut s = two_layers();
        s.layers[0].length = f64::NAN;
        assert!(
            s.validate()
                .unwrap_err()
                .to_string()
                .starts_with("layers[0].length")
        );
        let mut s = two_layers();
        s.impact_speed = 0.0;
        assert!(
            s.validate()
                .unwrap_err()
                .to_string()
                .starts_with("impact_speed")
        );
        let s = Scene {
            impact_speed: 1.0,
            layers: vec![],
        };
        assert_eq!(s.validate().unwrap_err(), SceneError::NoLayers);
        let mut s = two_layers();
        s.layers[0].relaxation_time = Some(0.1);
        s.layers[0].restitution = Some(0.9);
        assert_eq!(
            s.validate().unwrap_err(),
            SceneError::ConflictingViscosity { index: 0 }
        );
    }

    #[test]
    fn unknown_fields_are_rejected() {
        let text = r#"{"impact_speed": 1, "layers": [{"length": 1, "modulus": 1, "density": 1, "colour": 3}]}"#;
        let err = Scene::from_json(text).unwrap_err().to_string();
        assert!(err.contains("unknown field `colour`"), "{err}");
    }
}

//! Scenes as users write them, and their validation into a [`Rod`].

use crate::WallContact;
use crate::escape::Arithmetic;
use crate::units::Units;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// One homogeneous layer, as written in a scene file.
///
/// The modulus and density may come from a named material
/// (`"material": "steel"`, see [`crate::materials`]); numbers the layer gives
/// itself override the material's.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawLayer", into = "RawLayer")]
pub struct Layer {
    /// Optional label, used in summaries and figures.
    pub name: Option<String>,
    /// The named material the modulus and density were taken from, if any.
    pub material: Option<String>,
    /// Undeformed length (> 0).
    pub length: f64,
    /// Young's modulus (> 0).
    pub modulus: f64,
    /// Mass density (> 0).
    pub density: f64,
    /// Kelvin-Voigt relaxation time `tau = eta / E` (>= 0). Absent or 0: elastic.
    pub relaxation_time: Option<f64>,
    /// Viscosity given as the paper does (Sec. VII): the restitution, in (0, 1],
    /// of a homogeneous rod of the whole length made of this layer alone.
    pub restitution: Option<f64>,
}

/// A layer exactly as written: modulus and density may be left to a material.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLayer {
    #[serde(default, skip_serializing_if = "Option::is_none")]
    name: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    material: Option<String>,
    length: f64,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    modulus: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    density: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    relaxation_time: Option<f64>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    restitution: Option<f64>,
}

impl TryFrom<RawLayer> for Layer {
    type Error = String;

    fn try_from(raw: RawLayer) -> Result<Self, String> {
        let named = match &raw.material {
            Some(m) => Some(crate::materials::find(m).ok_or_else(|| {
                format!(
                    "unknown material '{m}' (known: {}; or give modulus and density)",
                    crate::materials::names()
                )
            })?),
            None => None,
        };
        let take = |own: Option<f64>, field: &str, from: Option<f64>| {
            own.or(from).ok_or_else(|| {
                format!(
                    "a layer needs a {field} (or a material that gives it, see data/materials.json)"
                )
            })
        };
        Ok(Layer {
            modulus: take(raw.modulus, "modulus", named.map(|m| m.modulus))?,
            density: take(raw.density, "density", named.map(|m| m.density))?,
            name: raw.name,
            material: raw.material,
            length: raw.length,
            relaxation_time: raw.relaxation_time,
            restitution: raw.restitution,
        })
    }
}

impl From<Layer> for RawLayer {
    fn from(l: Layer) -> Self {
        RawLayer {
            name: l.name,
            material: l.material,
            length: l.length,
            modulus: Some(l.modulus),
            density: Some(l.density),
            relaxation_time: l.relaxation_time,
            restitution: l.restitution,
        }
    }
}

impl Layer {
    /// An elastic layer.
    pub fn elastic(length: f64, modulus: f64, density: f64) -> Self {
        Self {
            name: None,
            material: None,
            length,
            modulus,
            density,
            relaxation_time: None,
            restitution: None,
        }
    }

    /// An elastic layer of a named material, or `None` if the table lacks it.
    pub fn of_material(name: &str, length: f64) -> Option<Self> {
        let m = crate::materials::find(name)?;
        Some(Self {
            name: Some(name.to_string()),
            material: Some(name.to_string()),
            ..Self::elastic(length, m.modulus, m.density)
        })
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
    /// The wall's contact law (absent: the paper's, see [`WallContact`]).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall_contact: Option<WallContact>,
}

/// Why a scene is not a valid projectile. Every message names the field and the
/// allowed range, so a user knows what to change.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum SceneError {
    /// A number outside its allowed range (NaN and infinities included).
    #[error("{field} must be {allowed} (got {value})")]
    OutOfRange {
        /// The offending field, as written in the scene (`layers[1].modulus`).
        field: String,
        /// The allowed range, in words.
        allowed: &'static str,
        /// The value the scene gave.
        value: f64,
    },
    /// A scene with no layer.
    #[error("layers must list at least one layer (got none)")]
    NoLayers,
    /// Both ways of giving viscosity at once.
    #[error("layers[{index}] gives both relaxation_time and restitution: give at most one")]
    ConflictingViscosity {
        /// Index of the layer, bottom first.
        index: usize,
    },
    /// A derived quantity that double precision cannot hold.
    #[error("{field}: {quantity} = {value:e} ({hint})")]
    Derived {
        /// The layer (`layers[i]`) or the whole rod (`layers`) the quantity belongs to.
        field: String,
        /// The derived quantity's name (wave speed, impedance, mass, ...).
        quantity: &'static str,
        /// Its value in the scene's units.
        value: f64,
        /// What to change: other units, or the layer's numbers.
        hint: &'static str,
    },
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
    /// A stack of elastic layers `(length, modulus, density)`, bottom
    /// first, hitting the wall at `impact_speed` under the paper's contact
    /// law (not yet validated).
    pub fn elastic_stack(impact_speed: f64, layers: &[(f64, f64, f64)]) -> Self {
        Self {
            impact_speed,
            layers: layers
                .iter()
                .map(|&(length, modulus, density)| Layer::elastic(length, modulus, density))
                .collect(),
            wall_contact: None,
        }
    }

    /// Parses a scene from JSON text; unknown fields are errors.
    pub fn from_json(text: &str) -> Result<Self, SceneError> {
        serde_json::from_str(text).map_err(|e| SceneError::Json(e.to_string()))
    }

    /// Validates the scene and derives every quantity the engines need, in
    /// the scene's units and in internal units (see [`crate::units`]). A
    /// derived quantity that double precision cannot hold (a wave speed of
    /// `1e400`, a mass of `1e-400`) is an input error naming the layer, never
    /// a silently wrong run.
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
        for (i, layer) in self.layers.iter().enumerate() {
            let f = |name: &str| format!("layers[{i}].{name}");
            let positive = "a finite number > 0";
            // subnormal numbers hold too few digits to compute with
            let normal = "at least 2.2e-308 (the smallest double with full precision)";
            for (name, v) in [
                ("length", layer.length),
                ("modulus", layer.modulus),
                ("density", layer.density),
            ] {
                check(f(name), v, positive, |v| v > 0.0)?;
                check(f(name), v, normal, f64::is_normal)?;
            }
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
                let (lowest, _) = crate::calibration::range(self.wall_contact.unwrap_or_default());
                if e < lowest {
                    return Err(SceneError::OutOfRange {
                        field: f("restitution"),
                        allowed: "a number in (0, 1] reachable by the calibration table (see data/calibration)",
                        value: e,
                    });
                }
            }
        }
        let column = |g: fn(&Layer) -> f64| self.layers.iter().map(g).collect::<Vec<f64>>();
        let units = Units::new(
            &column(|l| l.length),
            &column(|l| l.density),
            &column(|l| l.modulus),
            self.impact_speed,
        );
        let mut scaled = Vec::with_capacity(self.layers.len());
        let mut layers = Vec::with_capacity(self.layers.len());
        let mut bottom = 0.0;
        for (i, layer) in self.layers.iter().enumerate() {
            let s = LayerProps::derive(
                bottom,
                layer.length / units.length,
                layer.modulus / units.modulus,
                layer.density / units.density,
            );
            bottom = s.top;
            // internal units: every layer within ~1e300 of the whole rod
            for (quantity, value) in s.named() {
                if !value.is_normal() {
                    return Err(SceneError::Derived {
                        field: format!("layers[{i}]"),
                        quantity,
                        value: value * s.unit_of(quantity, &units),
                        hint: "this layer differs from the rest of the rod by more than double precision can span; check its numbers",
                    });
                }
            }
            let scene = s.in_units(&units);
            for (quantity, value) in scene.named() {
                if !value.is_normal() {
                    return Err(SceneError::Derived {
                        field: format!("layers[{i}]"),
                        quantity,
                        value,
                        hint: "not representable in double precision in these units; write the scene in other units",
                    });
                }
            }
            scaled.push(s);
            layers.push(scene);
        }
        let rod = Rod {
            scene: self.clone(),
            layers,
            scaled,
            units,
        };
        for (quantity, value) in [("total length", rod.total_length()), ("mass", rod.mass())] {
            if !value.is_normal() {
                return Err(SceneError::Derived {
                    field: "layers".into(),
                    quantity,
                    value,
                    hint: "not representable in double precision in these units; write the scene in other units",
                });
            }
        }
        Ok(rod)
    }
}

/// Derived, validated properties of one layer (unit cross-section).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LayerProps {
    /// Height of the layer's bottom in the undeformed rod.
    pub bottom: f64,
    /// Height of the layer's top.
    pub top: f64,
    /// `L_i`, the undeformed length.
    pub length: f64,
    /// Young's modulus `E_i`.
    pub modulus: f64,
    /// Density `rho_i` (mass per unit volume; the cross-section is one).
    pub density: f64,
    /// `c = sqrt(E / rho)`.
    pub wave_speed: f64,
    /// `Z = rho c`: what the interface scattering depends on.
    pub impedance: f64,
    /// One-way transit time `L / c`.
    pub transit_time: f64,
}

/// A layer's wave speed, impedance and transit time from its length,
/// modulus and density, in any arithmetic: [`LayerProps`] holds them in
/// doubles, and an engine running in double-double derives its own by the
/// same operations.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WaveConstants<T> {
    /// `c = sqrt(E / rho)`.
    pub wave_speed: T,
    /// `Z = rho c`.
    pub impedance: T,
    /// `L / c`.
    pub transit_time: T,
}

impl<T: Arithmetic> WaveConstants<T> {
    /// The constants of a layer of `length`, `modulus` and `density`.
    pub fn of(length: T, modulus: T, density: T) -> Self {
        let wave_speed = (modulus / density).sqrt();
        Self {
            wave_speed,
            impedance: density * wave_speed,
            transit_time: length / wave_speed,
        }
    }
}

impl LayerProps {
    /// Every derived quantity of a layer of the given length, modulus and
    /// density whose bottom sits at `bottom`.
    fn derive(bottom: f64, length: f64, modulus: f64, density: f64) -> Self {
        let waves = WaveConstants::of(length, modulus, density);
        LayerProps {
            bottom,
            top: bottom + length,
            length,
            modulus,
            density,
            wave_speed: waves.wave_speed,
            impedance: waves.impedance,
            transit_time: waves.transit_time,
        }
    }

    /// The same layer in a scene's units, from internal units: each
    /// quantity times its scale, a power of two, so the result equals a
    /// direct computation in the scene's units wherever that one does not
    /// over- or underflow.
    fn in_units(&self, u: &Units) -> Self {
        LayerProps {
            bottom: self.bottom * u.length,
            top: self.top * u.length,
            length: self.length * u.length,
            modulus: self.modulus * u.modulus,
            density: self.density * u.density,
            wave_speed: self.wave_speed * u.speed,
            impedance: self.impedance * (u.density * u.speed),
            transit_time: self.transit_time * u.time,
        }
    }

    /// The quantities that must be representable, by name.
    fn named(&self) -> [(&'static str, f64); 8] {
        [
            ("length", self.length),
            ("modulus", self.modulus),
            ("density", self.density),
            ("wave speed sqrt(modulus / density)", self.wave_speed),
            ("impedance density * wave speed", self.impedance),
            ("transit time length / wave speed", self.transit_time),
            ("mass per unit area density * length", self.mass()),
            ("top height", self.top),
        ]
    }

    /// The scale of a named quantity (for messages about internal units).
    fn unit_of(&self, quantity: &str, u: &Units) -> f64 {
        match quantity {
            q if q.starts_with("wave speed") => u.speed,
            q if q.starts_with("impedance") => u.density * u.speed,
            q if q.starts_with("transit") => u.time,
            q if q.starts_with("mass") => u.mass,
            "modulus" => u.modulus,
            "density" => u.density,
            _ => u.length,
        }
    }

    /// Mass per unit cross-section.
    pub fn mass(&self) -> f64 {
        self.density * self.length
    }
}

/// A validated scene with its derived quantities, in the scene's units and in
/// internal units. Engines take a `Rod`, never a raw [`Scene`].
#[derive(Debug, Clone, PartialEq)]
pub struct Rod {
    scene: Scene,
    layers: Vec<LayerProps>,
    scaled: Vec<LayerProps>,
    units: Units,
}

impl Rod {
    /// The scene this rod was validated from.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Derived layer properties in the scene's units, bottom first.
    pub fn layers(&self) -> &[LayerProps] {
        &self.layers
    }

    /// Derived layer properties in internal units (every scale of order
    /// one), bottom first: what the engines compute with.
    pub fn scaled_layers(&self) -> &[LayerProps] {
        &self.scaled
    }

    /// The wall's contact law: the scene's, or the paper's by default.
    pub fn wall_contact(&self) -> WallContact {
        self.scene.wall_contact.unwrap_or_default()
    }

    /// The scales between the scene's units and internal units.
    pub fn units(&self) -> &Units {
        &self.units
    }

    /// `v_b`, the speed at which the rod hits the wall, in the scene's units.
    pub fn impact_speed(&self) -> f64 {
        self.scene.impact_speed
    }

    /// The impact speed in internal units (between 0.7 and 1.5).
    pub fn scaled_impact_speed(&self) -> f64 {
        self.scene.impact_speed / self.units.amplitude
    }

    /// Total length `L`, in the scene's units.
    pub fn total_length(&self) -> f64 {
        self.layers.last().map_or(0.0, |l| l.top)
    }

    /// Total mass `M` per unit cross-section, in the scene's units.
    pub fn mass(&self) -> f64 {
        self.scaled_mass() * self.units.mass
    }

    /// Total mass per unit cross-section in internal units.
    pub fn scaled_mass(&self) -> f64 {
        self.scaled.iter().map(LayerProps::mass).sum()
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

    /// Largest over smallest transit time: how stiff the problem is for the
    /// exact engine.
    pub fn transit_ratio(&self) -> f64 {
        let t = self.scaled.iter().map(|l| l.transit_time);
        t.clone().fold(0.0, f64::max) / t.fold(f64::INFINITY, f64::min)
    }

    /// Kelvin-Voigt relaxation time `tau = eta / E` of layer `i` in the
    /// scene's units: given directly, or from the layer's restitution `e_i`
    /// through the calibration (`tau c_i / L = f(e_i)`, `L` the whole rod's
    /// length).
    pub fn relaxation_time(&self, i: usize) -> f64 {
        self.scaled_relaxation_time(i) * self.units.time
    }

    /// [`Rod::relaxation_time`] in internal units.
    pub fn scaled_relaxation_time(&self, i: usize) -> f64 {
        let layer = &self.scene.layers[i];
        if let Some(tau) = layer.relaxation_time {
            return tau / self.units.time;
        }
        match layer.restitution {
            Some(e) if e < 1.0 => {
                let scaled =
                    crate::calibration::tau_c_over_l(self.wall_contact(), e).unwrap_or(f64::NAN);
                let total: f64 = self.scaled.last().map_or(0.0, |l| l.top);
                scaled * total / self.scaled[i].wave_speed
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

    /// `integral(m(s)^2 / E(s) ds)` over the rod in internal units, with
    /// `m(s)` the mass above height `s`. Bounds how far the bottom can sit
    /// below the centre of mass for a given internal energy (DESIGN.md §2,
    /// exact stop rule).
    pub fn scaled_compliance_moment(&self) -> f64 {
        let mut above = 0.0;
        let mut sum = 0.0;
        for l in self.scaled.iter().rev() {
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
            wall_contact: None,
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
        // m(s) = rho (L - s): integral = rho^2 L^3 / (3 E), in internal units
        let scene = Scene {
            impact_speed: 1.0,
            layers: vec![Layer::elastic(2.0, 3.0, 5.0)],
            wall_contact: None,
        };
        let rod = scene.validate().unwrap();
        let l = rod.scaled_layers()[0];
        let expected = l.density.powi(2) * l.length.powi(3) / (3.0 * l.modulus);
        assert!((rod.scaled_compliance_moment() - expected).abs() < 1e-12 * expected);
        // splitting the same rod in two layers changes nothing
        let split = Scene {
            impact_speed: 1.0,
            layers: vec![Layer::elastic(0.5, 3.0, 5.0), Layer::elastic(1.5, 3.0, 5.0)],
            wall_contact: None,
        };
        let split = split.validate().unwrap();
        // internal units follow the layers, so compare in scene units:
        // the moment scales as mass^2 * length / modulus
        let in_scene = |r: &Rod| {
            let u = r.units();
            r.scaled_compliance_moment() * u.density.powi(2) * u.length.powi(3) / u.modulus
        };
        let whole = in_scene(&rod);
        assert!((in_scene(&split) - whole).abs() < 1e-12 * whole);
        assert!((whole - 25.0 * 8.0 / 9.0).abs() < 1e-12 * whole);
    }

    #[test]
    fn scene_units_equal_a_direct_computation() {
        let rod = two_layers().validate().unwrap();
        for l in rod.layers() {
            let c = (l.modulus / l.density).sqrt();
            assert_eq!(l.wave_speed, c);
            assert_eq!(l.impedance, l.density * c);
            assert_eq!(l.transit_time, l.length / c);
        }
        // SI steel under rubber: internal units of order one
        let si = Scene {
            impact_speed: 0.3,
            layers: vec![
                Layer::elastic(0.001, 200e9, 7850.0),
                Layer::elastic(0.1, 2e6, 1100.0),
            ],
            wall_contact: None,
        }
        .validate()
        .unwrap();
        assert!((0.5..2.0).contains(&si.scaled_layers()[1].top));
        assert!((0.7..1.5).contains(&si.scaled_impact_speed()));
        assert_eq!(
            si.layers()[0].transit_time,
            0.001 / (200e9f64 / 7850.0).sqrt()
        );
    }

    #[test]
    fn derived_quantities_out_of_range_are_input_errors() {
        // wave speed sqrt(1e-300 / 1e-300) = 1 and transit time 1e-100 are
        // fine; the mass density * length = 1e-300 * 1e-100 is not
        let s = Scene {
            impact_speed: 1.0,
            layers: vec![Layer::elastic(1e-100, 1e-300, 1e-300)],
            wall_contact: None,
        };
        let msg = s.validate().unwrap_err().to_string();
        assert!(msg.starts_with("layers[0]: mass per unit area"), "{msg}");
        // two layers 1e310 apart in modulus cannot share one computation
        let s = Scene {
            impact_speed: 1.0,
            layers: vec![
                Layer::elastic(1.0, 1e300, 1.0),
                Layer::elastic(1.0, 1e-20, 1.0),
            ],
            wall_contact: None,
        };
        let msg = s.validate().unwrap_err().to_string();
        assert!(msg.starts_with("layers[1]: "), "{msg}");
    }

    #[test]
    fn layers_may_name_a_material() {
        let text = r#"{"impact_speed": 1, "layers": [
            {"material": "steel", "length": 0.001},
            {"material": "silicone", "length": 0.04, "density": 1000}]}"#;
        let scene = Scene::from_json(text).unwrap();
        let steel = crate::materials::find("steel").unwrap();
        assert_eq!(scene.layers[0].modulus, steel.modulus);
        assert_eq!(scene.layers[0].density, steel.density);
        // a number the layer gives itself wins
        assert_eq!(scene.layers[1].density, 1000.0);
        // a name as a user writes it
        let rubber = Scene::from_json(
            r#"{"impact_speed": 1, "layers": [{"material": "Natural rubber", "length": 1}]}"#,
        )
        .unwrap();
        let table = crate::materials::find("natural-rubber").unwrap();
        assert_eq!(rubber.layers[0].modulus, table.modulus);
        // round trip through JSON
        let again = Scene::from_json(&serde_json::to_string(&scene).unwrap()).unwrap();
        assert_eq!(again, scene);
        let err = Scene::from_json(
            r#"{"impact_speed": 1, "layers": [{"material": "stel", "length": 1}]}"#,
        )
        .unwrap_err()
        .to_string();
        assert!(
            err.contains("unknown material 'stel'") && err.contains("steel"),
            "{err}"
        );
        let err =
            Scene::from_json(r#"{"impact_speed": 1, "layers": [{"length": 1, "modulus": 1}]}"#)
                .unwrap_err()
                .to_string();
        assert!(err.contains("needs a density"), "{err}");
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
            wall_contact: None,
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

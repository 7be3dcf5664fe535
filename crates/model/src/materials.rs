//! Named materials, because users think in materials: `data/materials.json`,
//! read at compile time. Each entry gives a representative small-strain
//! Young's modulus and density in SI units, what grade or form they stand
//! for, and where the values come from. A scene layer may name a material
//! instead of (or besides) giving its modulus and density; numbers the layer
//! gives itself win.

use serde::Deserialize;
use std::sync::OnceLock;

/// One entry of the table.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct Material {
    /// The name a scene uses (`"steel"`, `"pmma"`, ...).
    pub name: String,
    /// The grade or form the numbers stand for.
    pub description: String,
    /// Young's modulus, Pa.
    pub modulus: f64,
    /// Typical range of the modulus over grades and formulations, Pa.
    #[serde(default)]
    pub modulus_range: Option<[f64; 2]>,
    /// Density, kg/m^3.
    pub density: f64,
    /// Where the numbers come from.
    pub source: String,
}

#[derive(Deserialize)]
struct Table {
    #[allow(dead_code)]
    about: String,
    materials: Vec<Material>,
}

/// Every material of the table, in the file's order.
pub fn all() -> &'static [Material] {
    static TABLE: OnceLock<Vec<Material>> = OnceLock::new();
    TABLE.get_or_init(|| {
        serde_json::from_str::<Table>(include_str!("../../../data/materials.json"))
            .map(|t| t.materials)
            // the file is part of the source tree and tested; an unreadable
            // table leaves no material to name
            .unwrap_or_default()
    })
}

/// The material called `name`, if the table has it: its name in the
/// table in any case, with spaces or underscores for its hyphens
/// (`"Natural rubber"`, `"PMMA"`, `"tungsten_carbide"`), and `"aluminum"`
/// for aluminium, as users write them.
pub fn find(name: &str) -> Option<&'static Material> {
    let key: String = name
        .trim()
        .chars()
        .map(|c| match c {
            ' ' | '_' => '-',
            c => c.to_ascii_lowercase(),
        })
        .collect();
    let key = if key == "aluminum" { "aluminium" } else { &key };
    all().iter().find(|m| m.name == key)
}

/// The names, comma-separated, for error messages.
pub fn names() -> String {
    all()
        .iter()
        .map(|m| m.name.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_found_as_users_write_them() {
        for (written, name) in [
            ("Natural rubber", "natural-rubber"),
            ("natural_rubber", "natural-rubber"),
            ("PMMA", "pmma"),
            (" Tungsten Carbide ", "tungsten-carbide"),
            ("aluminum", "aluminium"),
            ("Aluminium", "aluminium"),
        ] {
            assert_eq!(
                find(written).map(|m| m.name.as_str()),
                Some(name),
                "{written}"
            );
        }
        for unknown in ["rubber", "natural  rubber", "unobtainium", ""] {
            assert!(find(unknown).is_none(), "{unknown}");
        }
    }

    #[test]
    fn the_table_has_the_materials_users_ask_for() {
        for name in [
            "steel",
            "aluminium",
            "tungsten-carbide",
            "pmma",
            "polyurethane",
            "silicone",
            "natural-rubber",
            "hydrogel",
            "polymer-foam",
        ] {
            let m = find(name).unwrap_or_else(|| panic!("{name} missing"));
            assert!(m.modulus > 0.0 && m.modulus.is_finite(), "{name}");
            assert!(m.density > 0.0 && m.density.is_finite(), "{name}");
            assert!(!m.source.trim().is_empty(), "{name} has no source");
            if let Some([lo, hi]) = m.modulus_range {
                assert!(lo <= m.modulus && m.modulus <= hi, "{name}: range");
            }
        }
    }

    #[test]
    fn wave_speeds_are_physical() {
        // every solid here carries sound between ~10 m/s (foams, gels) and
        // ~7000 m/s (tungsten carbide)
        for m in all() {
            let c = (m.modulus / m.density).sqrt();
            assert!((1.0..10_000.0).contains(&c), "{}: c = {c}", m.name);
        }
    }
}

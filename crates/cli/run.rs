//! `impact run`: one impact.

use crate::args::{EngineChoice, RunArgs};
use crate::input;
use crate::output::{summary, write_atomically};
use anyhow::Context;
use impact_model::{Bilayer, Scene};
use impact_wave::{Record, WaveEngine};
use std::io::Write;

/// Reads and validates a scene file; every failure is an input error.
pub fn read_scene(path: &std::path::Path) -> anyhow::Result<Scene> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| input(format!("cannot read scene {}: {e}", path.display())))?;
    Scene::from_json(&text).map_err(|e| input(format!("{}: {e}", path.display())))
}

pub fn run(a: RunArgs) -> anyhow::Result<()> {
    let (scene, title) = match (&a.scene, a.x, a.alpha) {
        (Some(path), _, _) => (read_scene(path)?, format!("Scene {}", path.display())),
        (None, Some(x), Some(alpha)) => {
            let b = Bilayer::new(x, alpha).map_err(|e| input(e.to_string()))?;
            (
                b.scene(),
                format!(
                    "Canonical bilayer x = {x}, alpha = {alpha} (L = 1, rho = 1, E1 = 1 - alpha, E2 = alpha, v_b = 1)"
                ),
            )
        }
        _ => {
            return Err(input(
                "give a scene file or both --x and --alpha (see --help)",
            ));
        }
    };
    let rod = scene.validate().map_err(|e| input(e.to_string()))?;
    let record = Record {
        wall: a.wall_trace.is_some(),
        fronts: false,
    };
    let config = a.wave.config(record)?;
    match a.engine {
        EngineChoice::Auto | EngineChoice::Wave => {
            if let Some(i) = rod.scene().layers.iter().position(|l| l.is_viscous()) {
                return Err(input(format!(
                    "layers[{i}] is viscous: the exact engine handles elastic layers only (the chain engine is not available yet)"
                )));
            }
        }
    }
    let mut engine = WaveEngine::new(&rod, config).map_err(|e| input(e.to_string()))?;
    let outcome = engine.run().context("the exact engine could not finish")?;
    if let Some(path) = &a.wall_trace {
        write_atomically(path, |w| {
            writeln!(w, "time,strain,height,velocity")?;
            for s in &engine.recording().wall {
                writeln!(w, "{},{},{},{}", s.time, s.strain, s.height, s.velocity)?;
            }
            Ok(())
        })?;
    }
    let mut stdout = std::io::stdout().lock();
    if a.json {
        writeln!(stdout, "{}", serde_json::to_string(&outcome)?)?;
    } else {
        write!(stdout, "{}", summary(&title, &outcome))?;
    }
    Ok(())
}

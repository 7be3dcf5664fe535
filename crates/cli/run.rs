//! `impact run`: one impact.

use crate::args::RunArgs;
use crate::input;
use crate::output::{summary, write_atomically};
use anyhow::Context;
use impact_chain::{ChainEngine, ChainLayout, ChainRecord};
use impact_model::Scene;
use impact_study::Engine;
use impact_wave::{Record, WaveEngine};
use std::io::Write;

/// Reads and validates a scene file; every failure is an input error.
pub fn read_scene(path: &std::path::Path) -> anyhow::Result<Scene> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| input(format!("cannot read scene {}: {e}", path.display())))?;
    Scene::from_json(&text).map_err(|e| input(format!("{}: {e}", path.display())))
}

pub fn run(a: RunArgs) -> anyhow::Result<()> {
    if a.subject.scene.is_some() && a.viscosity.given() {
        return Err(input(
            "--tau1/--tau2/--e1/--e2 apply to --x/--alpha only: give viscosity in the scene file",
        ));
    }
    let (scene, bilayer, name) = a.subject.load()?;
    let (scene, title) = match bilayer {
        Some(b) => (
            a.viscosity.viscosity().scene(b),
            format!(
                "Canonical bilayer {name} (L = 1, rho = 1, E1 = 1 - alpha, E2 = alpha, v_b = 1)"
            ),
        ),
        None => (scene, format!("Scene {name}")),
    };
    let rod = scene.validate().map_err(|e| input(e.to_string()))?;
    let trace = a.wall_trace.is_some();
    let wave_record = Record {
        wall: trace,
        fronts: false,
    };
    let chain_record = ChainRecord {
        wall_every: trace.then_some(16),
        raster: None,
    };
    let engine = a
        .engine
        .engine(rod.is_viscous(), a.masses, wave_record, chain_record)?;
    let (outcome, wall): (_, Vec<[f64; 4]>) = match engine {
        Engine::Wave(config) => {
            let mut e = WaveEngine::new(&rod, config).map_err(|e| input(e.to_string()))?;
            let o = e.run().context("the exact engine could not finish")?;
            let wall = e
                .recording()
                .wall
                .iter()
                .map(|s| [s.time, s.strain, s.height, s.velocity])
                .collect();
            (o, wall)
        }
        Engine::Chain(config) => {
            let layout = ChainLayout::new(&rod, config.masses).map_err(|e| input(e.to_string()))?;
            for (layer, count) in layout.thin_layers() {
                eprintln!(
                    "warning: layer {layer} has {count} masses (< 50, the paper's minimum for ~1% accuracy); raise --n"
                );
            }
            let mut e = ChainEngine::new(&rod, config).map_err(|e| input(e.to_string()))?;
            let o = e.run().context("the chain could not finish")?;
            (o, e.recording().wall.clone())
        }
    };
    if let Some(path) = &a.wall_trace {
        write_atomically(path, |w| {
            writeln!(w, "time,strain,height,velocity")?;
            for s in &wall {
                writeln!(w, "{},{},{},{}", s[0], s[1], s[2], s[3])?;
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

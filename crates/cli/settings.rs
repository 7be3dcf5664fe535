//! What the user typed, turned into validated library settings: the
//! high-level half of the flags (ripgrep's low-args -> high-args split).
//! `args.rs` declares the flags as `clap` sees them; this module checks them
//! and builds the engines' settings, so the engines never see a flag. Where
//! a library check fails, `flags.rs` words its error as the flag.

use crate::args::{
    EngineArgs, EngineChoice, PrecisionChoice, ResolutionChoice, SceneArgs, ViscosityArgs, WaveArgs,
};
use crate::input;
use impact_chain::{ChainConfig, ChainRecord, ChainStop};
use impact_rigid::{RigidConfig, RigidStop};
use impact_study::{BilayerViscosity, Engine};
use impact_wave::{Precision, Record, Resolution, StopRule, WaveConfig};

impl EngineArgs {
    /// The exact engine with validated settings, whatever `--engine` says.
    pub fn wave_engine(&self, record: Record) -> anyhow::Result<Engine> {
        self.forced(EngineChoice::Wave)
            .engine(false, 2, record, ChainRecord::default())
    }

    /// The chain of `masses` with validated settings, whatever `--engine` says.
    pub fn chain_engine(&self, masses: usize, record: ChainRecord) -> anyhow::Result<Engine> {
        self.forced(EngineChoice::Chain)
            .engine(false, masses, Record::default(), record)
    }

    /// These settings with the engine chosen.
    fn forced(&self, engine: EngineChoice) -> EngineArgs {
        EngineArgs {
            engine,
            ..self.clone()
        }
    }

    /// The engine to run for a scene (`viscous`: any layer dissipates), with
    /// validated settings (by the engine's own check, before any run).
    /// `auto` picks the exact engine for elastic scenes and the chain
    /// otherwise; the exact engine refuses viscous scenes.
    pub fn engine(
        &self,
        viscous: bool,
        masses: usize,
        wave_record: Record,
        chain_record: ChainRecord,
    ) -> anyhow::Result<Engine> {
        let horizon = self.horizon;
        let engine = match (self.engine, viscous) {
            (EngineChoice::Wave, true) => {
                return Err(input(
                    "--engine wave: the scene has a viscous layer, and the exact engine handles elastic layers only (use --engine chain or auto)",
                ));
            }
            (EngineChoice::Wave, false) | (EngineChoice::Auto, false) => {
                let mut config = self.wave.config(wave_record)?;
                if let Some(factor) = horizon {
                    config.stop = StopRule::Horizon { factor };
                }
                Engine::Wave(config)
            }
            (EngineChoice::RigidBottom, true) => {
                return Err(input(
                    "--engine rigid-bottom: the scene has a viscous layer, and the rigid-bottom model handles elastic layers only (use --engine chain or auto)",
                ));
            }
            (EngineChoice::RigidBottom, false) => Engine::RigidBottom(RigidConfig {
                stop: horizon.map_or(RigidStop::Escape, |factor| RigidStop::Horizon { factor }),
                // its events cost more than the exact engine's: its own
                // budget, unless the flag asks for less
                max_events: self.wave.max_events.min(RigidConfig::default().max_events),
                ..RigidConfig::default()
            }),
            (EngineChoice::Chain, _) | (EngineChoice::Auto, true) => {
                let c = &self.chain;
                Engine::Chain(ChainConfig {
                    masses,
                    dt_factor: c.dt_factor,
                    stop: horizon.map_or(ChainStop::Escape, |factor| ChainStop::Horizon { factor }),
                    max_steps: c.max_steps,
                    record: chain_record,
                    viscous_kernel: c.viscous_kernel.into(),
                })
            }
        };
        // the engine's own ranges, checked before any work starts
        engine.check().map_err(crate::flags::setting)?;
        Ok(engine)
    }
}

impl ViscosityArgs {
    pub fn given(&self) -> bool {
        self.tau1.is_some() || self.tau2.is_some() || self.e1.is_some() || self.e2.is_some()
    }

    /// Checked by the scene's own validation when the bilayer is built.
    pub fn viscosity(&self) -> BilayerViscosity {
        BilayerViscosity {
            tau: [self.tau1, self.tau2],
            restitution: [self.e1, self.e2],
            wall_contact: self.wall_contact,
        }
    }
}

impl WaveArgs {
    /// Exact-engine settings (stop rule: see `EngineArgs`; ranges: checked
    /// by the engine's own rule in `EngineArgs::engine`).
    pub fn config(&self, record: Record) -> anyhow::Result<WaveConfig> {
        let resolution = match (self.resolution, self.merge_window) {
            (ResolutionChoice::Exact, Some(_)) => {
                return Err(input(
                    "--merge-window merges fronts: it cannot go with --resolution exact",
                ));
            }
            (ResolutionChoice::Exact, None) => Resolution::Exact,
            (ResolutionChoice::Auto, None) => Resolution::Auto {
                exact_events: 200_000,
                budget_events: self.event_budget,
                target: self.target.unwrap_or(1e-5),
                exact_again: true,
            },
            (_, window) => {
                let w = window.unwrap_or(1e-2);
                Resolution::Merged {
                    per_transit: w,
                    per_longest: w.min(1e-3),
                }
            }
        };
        Ok(WaveConfig {
            stop: StopRule::Escape,
            drop_tolerance: self.drop_tolerance,
            resolution,
            precision: match self.precision {
                PrecisionChoice::Checked => Precision::Checked,
                PrecisionChoice::Double => Precision::Double,
                PrecisionChoice::DoubleDouble => Precision::DoubleDouble,
            },
            max_events: self.max_events,
            record,
            ..WaveConfig::default()
        })
    }
}

impl SceneArgs {
    /// The scene file read and parsed, or the canonical bilayer (not yet
    /// validated), with a title. Every failure is an input error.
    /// `given` stands in for them when the caller already holds the scene
    /// (the explorer: a scene sent over HTTP, never a file).
    pub fn load(
        &self,
        given: Option<impact_model::Scene>,
    ) -> anyhow::Result<(impact_model::Scene, Option<impact_model::Bilayer>, String)> {
        if let Some(scene) = given {
            return Ok((scene, None, "scene".to_string()));
        }
        match (&self.scene, self.x, self.alpha) {
            (Some(path), _, _) => Ok((
                crate::run::read_scene(path)?,
                None,
                path.display().to_string(),
            )),
            (None, Some(x), Some(alpha)) => {
                let b = impact_model::Bilayer::new(x, alpha).map_err(|e| input(e.to_string()))?;
                Ok((b.scene(), Some(b), format!("x = {x}, alpha = {alpha}")))
            }
            _ => Err(input(
                "give a scene file or both --x and --alpha (see --help)",
            )),
        }
    }
}

//! A request as a command: the query's keys become the flags of `impact
//! run` or `impact diagram`, parsed by the command line's own clap structs,
//! and the work asked for is held within the explorer's caps.

use super::api::ApiError;
use crate::args::{Cli, Command, RunArgs};
use axum::extract::Query;
use axum::extract::rejection::QueryRejection;
use clap::Parser;
use impact_model::Scene;

/// The query of a request, as axum hands it over.
pub type RawQuery = Result<Query<Vec<(String, String)>>, QueryRejection>;

/// What one request may ask for: beyond these the command line is the
/// tool (the messages say so).
pub struct Caps {
    /// Layers of a scene.
    pub layers: usize,
    /// Masses of one chain.
    pub masses: usize,
    /// Masses of the largest chain of a viscous run's extrapolation.
    pub ladder_masses: usize,
    /// Events of one exact run.
    pub events: u64,
    /// Events the merged runs of one point may take.
    pub event_budget: u64,
    /// Mass-steps of one chain (its steps times its masses).
    pub mass_steps: u64,
    /// Bytes of a request body.
    pub body_bytes: usize,
}

/// The explorer's caps.
pub const CAPS: Caps = Caps {
    layers: 16,
    masses: 20_000,
    ladder_masses: 16_000,
    events: 20_000_000,
    event_budget: 4_000_000,
    mass_steps: 40_000_000_000,
    body_bytes: 1 << 20,
};

/// Query keys of `/api/run`, each the flag of the same name.
pub const RUN_KEYS: &[&str] = &[
    "x",
    "alpha",
    "engine",
    "n",
    "wall-contact",
    "e1",
    "e2",
    "tau1",
    "tau2",
    "horizon",
    "target",
    "max-n",
    "resolution",
    "precision",
    "merge-window",
    "drop-tolerance",
    "event-budget",
    "max-events",
    "dt-factor",
    "max-steps",
];
/// Query keys of `/api/diagram` (values), and its switches.
pub const DIAGRAM_KEYS: &[&str] = &[
    "x",
    "alpha",
    "engine",
    "n",
    "t-start",
    "t-end",
    "strain-scale",
];
pub const DIAGRAM_SWITCHES: &[&str] = &["side-by-side", "no-fronts"];

/// The query as the words of a command: `key=value` becomes `--key value`
/// (`_` read as `-`), a switch `--key` when true; anything else is refused.
pub fn words(query: RawQuery, keys: &[&str], switches: &[&str]) -> Result<Vec<String>, ApiError> {
    let Query(pairs) = query.map_err(|e| ApiError::bad(e.body_text()))?;
    let mut words = Vec::new();
    for (key, value) in pairs {
        let flag = key.replace('_', "-");
        if switches.contains(&flag.as_str()) {
            match value.as_str() {
                "" | "true" | "1" => words.push(format!("--{flag}")),
                "false" | "0" => {}
                _ => {
                    return Err(ApiError::bad(format!(
                        "{key} is a switch: true or false (got '{value}')"
                    )));
                }
            }
        } else if keys.contains(&flag.as_str()) {
            // a value is never read as a flag (`alpha=--wall-trace` would
            // smuggle a file into the command): a leading `-` only on a number
            if value.starts_with('-') && value.parse::<f64>().is_err() {
                return Err(ApiError::bad(format!(
                    "{key} takes a value, not a flag (got '{value}')"
                )));
            }
            words.push(format!("--{flag}"));
            words.push(value);
        } else {
            let mut allowed: Vec<&str> = keys.iter().chain(switches).copied().collect();
            allowed.sort_unstable();
            return Err(ApiError::bad(format!(
                "unknown parameter '{key}' (allowed: {})",
                allowed.join(", ")
            )));
        }
    }
    Ok(words)
}

/// Parses `impact SUBCOMMAND WORDS...` as the command line does.
pub fn parse(subcommand: &str, words: &[String], extra: &[&str]) -> Result<Command, ApiError> {
    let argv = ["impact", subcommand]
        .into_iter()
        .map(str::to_string)
        .chain(words.iter().cloned())
        .chain(extra.iter().map(|w| w.to_string()));
    Cli::try_parse_from(argv)
        .map(|cli| cli.command)
        .map_err(|e| ApiError::bad(crate::clap_message(&e)))
}

/// The command a user types for the same result (`scene.json` standing for
/// the scene sent in the body).
pub fn command_line(subcommand: &str, words: &[String], scene: bool, extra: &[&str]) -> String {
    let mut line = format!("impact {subcommand}");
    if scene {
        line.push_str(" scene.json");
    }
    for w in words
        .iter()
        .map(String::as_str)
        .chain(extra.iter().copied())
    {
        line.push(' ');
        if w.chars()
            .all(|c| c.is_ascii_alphanumeric() || "-_.:+/=,".contains(c))
        {
            line.push_str(w);
        } else {
            line.push_str(&format!("'{}'", w.replace('\'', r"'\''")));
        }
    }
    line
}

/// The scene of a request body, within the caps.
pub fn body_scene(body: &str) -> Result<Scene, ApiError> {
    if body.len() > CAPS.body_bytes {
        return Err(ApiError::bad(format!(
            "scene: the explorer takes scenes of at most {} bytes (got {})",
            CAPS.body_bytes,
            body.len()
        )));
    }
    let scene = Scene::from_json(body).map_err(|e| ApiError::bad(format!("scene: {e}")))?;
    if scene.layers.len() > CAPS.layers {
        return Err(ApiError::bad(format!(
            "layers: the explorer takes at most {} layers (got {}); run larger scenes with impact run",
            CAPS.layers,
            scene.layers.len()
        )));
    }
    Ok(scene)
}

/// A setting above the explorer's cap is refused when the request gave it,
/// lowered to the cap when it is the command line's default.
pub fn cap<T: PartialOrd + Copy + std::fmt::Display>(
    words: &[String],
    flag: &str,
    value: &mut T,
    most: T,
) -> Result<(), ApiError> {
    if *value <= most {
        return Ok(());
    }
    if words.iter().any(|w| w == &format!("--{flag}")) {
        return Err(ApiError::bad(format!(
            "--{flag} must be at most {most} in the explorer (got {value}); run larger jobs with the command line"
        )));
    }
    *value = most;
    Ok(())
}

/// `impact run` within the caps.
pub fn capped_run(words: &[String], mut a: RunArgs) -> Result<RunArgs, ApiError> {
    if let Some(n) = a.masses.as_mut() {
        cap(words, "n", n, CAPS.masses)?;
    }
    cap(words, "max-n", &mut a.max_n, CAPS.ladder_masses)?;
    cap(
        words,
        "max-events",
        &mut a.engine.wave.max_events,
        CAPS.events,
    )?;
    cap(
        words,
        "event-budget",
        &mut a.engine.wave.event_budget,
        CAPS.event_budget,
    )?;
    let largest = a.masses.unwrap_or(10_000).max(a.max_n).max(1) as u64;
    cap(
        words,
        "max-steps",
        &mut a.engine.chain.max_steps,
        CAPS.mass_steps / largest,
    )?;
    Ok(a)
}

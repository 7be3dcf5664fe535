//! The explorer's HTTP API: each request becomes the words of an `impact`
//! command, parsed and run by the command line's own code.
//!
//! - `GET /api/run?x=X&alpha=A[&engine=...]`: what `impact run --x X
//!   --alpha A --json` prints; `POST /api/run` with a scene as the body
//!   does the same for the scene. The header `x-impact-command` carries the
//!   command.
//! - `GET|POST /api/diagram`: the figure of `impact diagram` (SVG), its
//!   outcome and its fronts.
//! - `GET /api/map?step=S`: the canonical bilayer's map at grid step S.
//! - `GET /api/materials`, `GET /api/scene`: the materials table, and the
//!   scene the server was started with.
//!
//! Bad input is HTTP 400 with `{"error": "<the command line's message>"}`;
//! a run that cannot finish is 422 with the command line's message.

use super::map::Maps;
use super::request::{
    CAPS, DIAGRAM_KEYS, DIAGRAM_SWITCHES, RUN_KEYS, RawQuery, body_scene, cap, capped_run,
    command_line, parse, words,
};
use super::{APP_CSS, SCRIPTS, index_page};
use crate::args::{Command, DiagramArgs};
use axum::extract::{DefaultBodyLimit, Query, State};
use axum::http::{HeaderValue, StatusCode, header};
use axum::response::{Html, IntoResponse, Response};
use axum::routing::get;
use axum::{Json, Router};
use impact_diagram::Picture;
use impact_model::Scene;
use impact_wave::Direction;
use serde::Serialize;
use std::sync::Arc;

/// The server's state: the scene it was started with, and the maps computed
/// so far.
pub struct App {
    scene: Option<serde_json::Value>,
    maps: Maps,
}

impl App {
    /// A server showing `scene` first (the canonical bilayer when `None`).
    pub fn new(scene: Option<serde_json::Value>) -> Self {
        Self {
            scene,
            maps: Maps::default(),
        }
    }
}

/// A request the explorer refuses or could not answer.
#[derive(Debug)]
pub struct ApiError {
    status: StatusCode,
    message: String,
}

impl ApiError {
    /// Bad input: HTTP 400.
    pub fn bad(message: impl Into<String>) -> Self {
        Self {
            status: StatusCode::BAD_REQUEST,
            message: message.into(),
        }
    }

    /// A command's failure: its input errors are 400, a run that could not
    /// finish 422, each with the message the command line prints.
    fn from_command(e: anyhow::Error) -> Self {
        if e.is::<crate::InputError>() {
            Self::bad(e.to_string())
        } else {
            Self {
                status: StatusCode::UNPROCESSABLE_ENTITY,
                message: format!("{e:#}"),
            }
        }
    }

    pub fn internal(e: impl std::fmt::Display) -> Self {
        Self {
            status: StatusCode::INTERNAL_SERVER_ERROR,
            message: e.to_string(),
        }
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        (
            self.status,
            Json(serde_json::json!({ "error": self.message })),
        )
            .into_response()
    }
}

type Reply = Result<Response, ApiError>;

/// The explorer's routes.
pub fn router(app: App) -> Router {
    let mut router = Router::new().route("/", get(|| async { Html(index_page()) }));
    for (path, script) in SCRIPTS {
        router = router.route(
            path,
            get(move || async move {
                (
                    [(header::CONTENT_TYPE, "text/javascript; charset=utf-8")],
                    script,
                )
            }),
        );
    }
    router
        .route(
            "/app.css",
            get(|| async { ([(header::CONTENT_TYPE, "text/css; charset=utf-8")], APP_CSS) }),
        )
        .route("/api/run", get(run_query).post(run_scene))
        .route("/api/diagram", get(diagram_query).post(diagram_scene))
        .route("/api/map", get(map))
        .route("/api/materials", get(materials))
        .route("/api/scene", get(scene))
        // bodies up to 8 times the cap reach `body_scene`, which refuses
        // them with the API's own message
        .layer(DefaultBodyLimit::max(8 * CAPS.body_bytes))
        .with_state(Arc::new(app))
}

async fn run_query(State(_): State<Arc<App>>, query: RawQuery) -> Reply {
    run(words(query, RUN_KEYS, &[])?, None).await
}

async fn run_scene(State(_): State<Arc<App>>, query: RawQuery, body: String) -> Reply {
    let words = words(query, RUN_KEYS, &[])?;
    run(words, Some(body_scene(&body)?)).await
}

async fn run(words: Vec<String>, scene: Option<Scene>) -> Reply {
    let command = command_line("run", &words, scene.is_some(), &[]);
    let Command::Run(a) = parse("run", &words, &["--json"])? else {
        return Err(ApiError::internal("not a run"));
    };
    let a = capped_run(&words, a)?;
    let computed = tokio::task::spawn_blocking(move || crate::run::compute(&a, scene))
        .await
        .map_err(ApiError::internal)?
        .map_err(ApiError::from_command)?;
    let json = serde_json::to_string(&computed.outcome).map_err(ApiError::internal)?;
    Ok(json_with_command(json, &command))
}

fn json_with_command(json: String, command: &str) -> Response {
    let mut response = ([(header::CONTENT_TYPE, "application/json")], json).into_response();
    if let Ok(value) = HeaderValue::from_str(command) {
        response.headers_mut().insert("x-impact-command", value);
    }
    response
}

/// One front of a diagram, for the page's event table and ancestry.
#[derive(Serialize)]
struct FrontRow {
    id: u32,
    /// Layer, bottom first, from 1.
    layer: usize,
    direction: &'static str,
    born: f64,
    arrives: f64,
    /// Height of its birth.
    place: f64,
    jump: f64,
    parents: Vec<u32>,
}

#[derive(Serialize)]
struct DiagramReply {
    title: String,
    svg: String,
    outcome: impact_model::Outcome,
    /// The fronts drawn (the strongest, as the figure draws them), in
    /// order of birth.
    fronts: Vec<FrontRow>,
    /// How many fronts the run had.
    fronts_total: usize,
    /// The fronts of the path that triggers the final takeoff.
    takeoff_path: Vec<u32>,
    command: String,
}

async fn diagram_query(State(_): State<Arc<App>>, query: RawQuery) -> Reply {
    diagram(words(query, DIAGRAM_KEYS, DIAGRAM_SWITCHES)?, None).await
}

async fn diagram_scene(State(_): State<Arc<App>>, query: RawQuery, body: String) -> Reply {
    let words = words(query, DIAGRAM_KEYS, DIAGRAM_SWITCHES)?;
    diagram(words, Some(body_scene(&body)?)).await
}

async fn diagram(words: Vec<String>, scene: Option<Scene>) -> Reply {
    const OUT: [&str; 2] = ["--out", "diagram.svg"];
    let command = command_line("diagram", &words, scene.is_some(), &OUT);
    let Command::Diagram(mut a) = parse("diagram", &words, &OUT)? else {
        return Err(ApiError::internal("not a diagram"));
    };
    cap(&words, "n", &mut a.masses, CAPS.masses)?;
    let reply = tokio::task::spawn_blocking(move || draw(&a, scene, command))
        .await
        .map_err(ApiError::internal)??;
    let json = serde_json::to_string(&reply).map_err(ApiError::internal)?;
    Ok(json_with_command(json, &reply.command))
}

fn draw(a: &DiagramArgs, scene: Option<Scene>, command: String) -> Result<DiagramReply, ApiError> {
    let (d, options) = crate::diagram::build(a, scene).map_err(ApiError::from_command)?;
    let svg = d.to_svg(&impact_diagram::DiagramOptions {
        tooltips: true,
        ..options.clone()
    });
    let (mut fronts, mut total, mut path) = (Vec::new(), 0, Vec::new());
    let layers = d.rod.layers();
    for (_, picture) in &d.pictures {
        let Picture::Exact {
            fronts: all,
            path: takeoff,
            ..
        } = picture
        else {
            continue;
        };
        total = all.len();
        path.clone_from(takeoff);
        let mut strongest: Vec<_> = all.iter().collect();
        strongest.sort_by(|a, b| b.jump.abs().total_cmp(&a.jump.abs()));
        strongest.truncate(options.max_fronts);
        strongest.sort_by(|a, b| a.born.total_cmp(&b.born).then(a.id.cmp(&b.id)));
        fronts = strongest
            .into_iter()
            .map(|f| FrontRow {
                id: f.id,
                layer: f.layer + 1,
                direction: match f.direction {
                    Direction::Up => "up",
                    Direction::Down => "down",
                },
                born: f.born,
                arrives: f.arrives,
                place: match f.direction {
                    Direction::Up => layers[f.layer].bottom,
                    Direction::Down => layers[f.layer].top,
                },
                jump: f.jump,
                parents: f.parents.clone(),
            })
            .collect();
    }
    Ok(DiagramReply {
        title: d.title.clone(),
        svg,
        outcome: d.outcome,
        fronts,
        fronts_total: total,
        takeoff_path: path,
        command,
    })
}

async fn map(State(app): State<Arc<App>>, query: RawQuery) -> Reply {
    let Query(pairs) = query.map_err(|e| ApiError::bad(e.body_text()))?;
    let mut step = None;
    for (key, value) in pairs {
        match key.as_str() {
            "step" => step = Some(value),
            _ => {
                return Err(ApiError::bad(format!(
                    "unknown parameter '{key}' (allowed: step)"
                )));
            }
        }
    }
    let step = step.unwrap_or_else(|| "0.05".into());
    let app = Arc::clone(&app);
    let json = tokio::task::spawn_blocking(move || app.maps.get(&step))
        .await
        .map_err(ApiError::internal)??;
    Ok((
        [(header::CONTENT_TYPE, "application/json")],
        (*json).clone(),
    )
        .into_response())
}

async fn materials() -> Response {
    Json(
        impact_model::materials::all()
            .iter()
            .map(|m| {
                serde_json::json!({
                    "name": m.name,
                    "description": m.description,
                    "modulus": m.modulus,
                    "density": m.density,
                    "source": m.source,
                })
            })
            .collect::<Vec<_>>(),
    )
    .into_response()
}

async fn scene(State(app): State<Arc<App>>) -> Response {
    Json(app.scene.clone().unwrap_or(serde_json::Value::Null)).into_response()
}

#[cfg(test)]
mod tests;

//! The API contract, request by request, against the command line's own
//! code (`run::compute`, clap) and the engines called directly.

use super::*;
use crate::args::RunArgs;
use axum::body::{Body, to_bytes};
use axum::http::Request;
use impact_model::Bilayer;
use tower::ServiceExt;

async fn send(request: Request<Body>) -> (StatusCode, Option<String>, serde_json::Value) {
    let response = router(App::new(None)).oneshot(request).await.unwrap();
    let status = response.status();
    let command = response
        .headers()
        .get("x-impact-command")
        .map(|v| v.to_str().unwrap().to_string());
    let bytes = to_bytes(response.into_body(), usize::MAX).await.unwrap();
    (status, command, serde_json::from_slice(&bytes).unwrap())
}

async fn get(uri: &str) -> (StatusCode, Option<String>, serde_json::Value) {
    send(Request::get(uri).body(Body::empty()).unwrap()).await
}

async fn post(uri: &str, body: &str) -> (StatusCode, Option<String>, serde_json::Value) {
    send(
        Request::post(uri)
            .body(Body::from(body.to_string()))
            .unwrap(),
    )
    .await
}

/// `impact run WORDS` as clap parses it.
fn run_args(words: &[&str]) -> RunArgs {
    let Command::Run(a) = parse("run", &[], words).unwrap() else {
        panic!("not a run")
    };
    a
}

/// What `impact run WORDS --json` prints, without its timing.
fn cli_json(words: &[&str]) -> serde_json::Value {
    let outcome = crate::run::compute(&run_args(words), None).unwrap().outcome;
    without_timing(serde_json::to_value(outcome).unwrap())
}

fn without_timing(mut json: serde_json::Value) -> serde_json::Value {
    json.as_object_mut().unwrap().remove("elapsed_seconds");
    json
}

#[tokio::test]
async fn a_point_is_what_impact_run_prints() {
    for (query, words) in [
        ("x=0.4&alpha=0.05", vec!["--x", "0.4", "--alpha", "0.05"]),
        (
            "x=0.995&alpha=0.005",
            vec!["--x", "0.995", "--alpha", "0.005"],
        ),
        (
            "x=0.6&alpha=0.8&engine=rigid-bottom",
            vec!["--x", "0.6", "--alpha", "0.8", "--engine", "rigid-bottom"],
        ),
        (
            "x=0.4&alpha=0.05&engine=chain&n=300",
            vec![
                "--x", "0.4", "--alpha", "0.05", "--engine", "chain", "--n", "300",
            ],
        ),
    ] {
        let (status, command, json) = get(&format!("/api/run?{query}")).await;
        assert_eq!(status, StatusCode::OK, "{json}");
        assert!(json["elapsed_seconds"].is_number());
        assert_eq!(without_timing(json), cli_json(&words), "{query}");
        assert_eq!(command.unwrap(), format!("impact run {}", words.join(" ")));
    }
    // Fig. 3(c) against the paper's picture: two bounces
    let (_, _, json) = get("/api/run?x=0.4&alpha=0.05").await;
    assert_eq!(json["bounces"], 2);
}

#[tokio::test]
async fn a_scene_is_what_impact_run_prints_for_its_file() {
    let text = include_str!("../../../../data/scenes/three-layers.json");
    let (status, command, json) = post("/api/run", text).await;
    assert_eq!(status, StatusCode::OK, "{json}");
    let scene = Scene::from_json(text).unwrap();
    let direct = crate::run::compute(&run_args(&[]), Some(scene))
        .unwrap()
        .outcome;
    assert_eq!(
        without_timing(json),
        without_timing(serde_json::to_value(direct).unwrap())
    );
    assert_eq!(command.unwrap(), "impact run scene.json");
    // e = (m_steel - m_rest) / M, the README's closed form for this rod
    let (status, _, json) = post("/api/run?engine=wave", text).await;
    assert_eq!(status, StatusCode::OK);
    assert!((json["restitution"].as_f64().unwrap() - 0.427_272_727_273).abs() < 1e-12);
}

#[tokio::test]
async fn bad_input_is_400_with_the_command_lines_message() {
    for (uri, message) in [
        (
            "/api/run?x=1.5&alpha=0.05",
            "x must be a number in (0, 1) (got 1.5)",
        ),
        (
            "/api/run?x=0.4&alpha=nan",
            "alpha must be a number in (0, 1) (got NaN)",
        ),
        (
            "/api/run?x=0.4&alpha=0.05&engine=warp",
            "invalid value 'warp' for '--engine <ENGINE>'",
        ),
        (
            "/api/run?x=0.4",
            "the following required arguments were not provided: --alpha <ALPHA>",
        ),
        (
            "/api/run?x=0.4&alpha=0.05&drop-tolerance=-1",
            "--drop-tolerance must be",
        ),
        (
            "/api/run?x=0.4&alpha=0.05&engine=chain&n=0",
            "--n must be at least 1",
        ),
        (
            "/api/run?x=0.4&alpha=0.05&wall_trace=f.csv",
            "unknown parameter 'wall_trace'",
        ),
        ("/api/run?scene=/etc/passwd", "unknown parameter 'scene'"),
        (
            "/api/run?x=0.4&alpha=--wall-trace&engine=/tmp/f.csv",
            "alpha takes a value, not a flag (got '--wall-trace')",
        ),
        (
            "/api/run?x=-h&alpha=0.05",
            "x takes a value, not a flag (got '-h')",
        ),
        (
            "/api/diagram?x=0.4&alpha=0.05&out=x.svg",
            "unknown parameter 'out'",
        ),
        (
            "/api/diagram?x=0.4&alpha=0.05&side-by-side=maybe",
            "side-by-side is a switch",
        ),
        (
            "/api/diagram?x=0.4&alpha=0.05&t-end=-1",
            "--t-end must be a finite number > 0",
        ),
        (
            "/api/map?step=0.3",
            "step must be one of 0.05, 0.02, 0.01, 0.005",
        ),
        ("/api/map?resolution=1", "unknown parameter 'resolution'"),
    ] {
        refused(get(uri).await, message);
    }
    let bad_scene =
        r#"{"impact_speed": 1, "layers": [{"length": 1, "modulus": -5, "density": 1}]}"#;
    let (status, _, json) = post("/api/run", bad_scene).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert_eq!(
        json["error"],
        "layers[0].modulus must be a finite number > 0 (got -5)"
    );
    let (status, _, json) = post("/api/diagram", "{not json").await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(json["error"].as_str().unwrap().starts_with("scene: "));
    // the command line words the same scene the same way
    let cli = crate::run::compute(&run_args(&[]), Some(Scene::from_json(bad_scene).unwrap()));
    assert_eq!(cli.err().unwrap().to_string(), json_error(bad_scene).await);
}

async fn json_error(scene: &str) -> String {
    let (_, _, json) = post("/api/run", scene).await;
    json["error"].as_str().unwrap().to_string()
}

/// A 400 whose one-line error contains `needle`.
fn refused(reply: (StatusCode, Option<String>, serde_json::Value), needle: &str) {
    let (status, _, json) = reply;
    assert_eq!(status, StatusCode::BAD_REQUEST, "{json}");
    let error = json["error"].as_str().unwrap();
    assert!(error.contains(needle), "'{needle}' not in {error}");
    assert!(!error.contains('\n'), "one line: {error}");
}

#[tokio::test]
async fn work_is_capped_with_messages_that_say_so() {
    refused(
        get("/api/run?x=0.4&alpha=0.05&engine=chain&n=50000").await,
        "--n must be at most 20000 in the explorer (got 50000); run larger jobs with the command line",
    );
    refused(
        get("/api/run?x=0.4&alpha=0.05&max-events=1000000000").await,
        "--max-events must be at most 20000000",
    );
    refused(
        get("/api/diagram?x=0.4&alpha=0.05&engine=chain&n=30000").await,
        "--n must be at most 20000",
    );
    let layer = r#"{"length": 0.1, "modulus": 1, "density": 1}"#;
    let many = format!(
        r#"{{"impact_speed": 1, "layers": [{}]}}"#,
        vec![layer; 17].join(",")
    );
    refused(post("/api/run", &many).await, "at most 16 layers (got 17)");
    let huge = format!(
        "{{\"impact_speed\": 1, \"layers\": [], \"pad\": \"{}\"}}",
        "x".repeat(CAPS.body_bytes)
    );
    refused(post("/api/run", &huge).await, "at most 1048576 bytes");
    // a default above the cap is lowered, not refused: the corner still runs
    let (status, _, _) = get("/api/run?x=0.995&alpha=0.005").await;
    assert_eq!(status, StatusCode::OK);
    let a = capped_run(&[], run_args(&["--x", "0.4", "--alpha", "0.05"])).unwrap();
    assert_eq!(a.engine.wave.max_events, CAPS.events);
    assert_eq!(a.max_n, CAPS.ladder_masses);
    assert!(a.engine.chain.max_steps * a.max_n as u64 <= CAPS.mass_steps);
}

#[tokio::test]
async fn a_run_that_cannot_finish_is_422_with_the_reason() {
    // a horizon shorter than the contact: no restitution
    let (status, _, json) = get("/api/run?x=0.4&alpha=0.05&horizon=0.5").await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{json}");
    assert!(json["error"].as_str().unwrap().contains("could not finish"));
}

#[tokio::test]
async fn the_diagram_is_the_renderers_with_its_fronts() {
    let (status, command, json) = get("/api/diagram?x=0.4&alpha=0.05").await;
    assert_eq!(status, StatusCode::OK, "{json}");
    assert_eq!(
        command.unwrap(),
        "impact diagram --x 0.4 --alpha 0.05 --out diagram.svg"
    );
    let svg = json["svg"].as_str().unwrap();
    assert!(svg.starts_with("<svg"));
    // the same picture `impact diagram` draws, with tooltips
    let b = Bilayer::new(0.4, 0.05).unwrap();
    let run = impact_diagram::exact_run(&b.scene().validate().unwrap()).unwrap();
    let Picture::Exact { fronts, path, .. } = &run.picture else {
        panic!("not exact")
    };
    assert_eq!(json["fronts_total"], fronts.len());
    assert_eq!(json["fronts"].as_array().unwrap().len(), fronts.len());
    let ids: Vec<u64> = json["takeoff_path"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_u64().unwrap())
        .collect();
    assert_eq!(ids, path.iter().map(|&i| u64::from(i)).collect::<Vec<_>>());
    for f in fronts {
        assert!(svg.contains(&format!(r#"data-id="{}""#, f.id)));
    }
    // two separations drawn: one separation and the final takeoff
    assert_eq!(svg.matches(r#"class="event separation""#).count(), 1);
    assert_eq!(svg.matches(r#"class="event takeoff""#).count(), 1);
    // parents come before their children
    for f in json["fronts"].as_array().unwrap() {
        for p in f["parents"].as_array().unwrap() {
            assert!(p.as_u64().unwrap() < f["id"].as_u64().unwrap());
        }
    }
    // a window and the chain beside it
    let (status, _, json) =
        get("/api/diagram?x=0.4&alpha=0.05&t-start=1&t-end=3&side-by-side=true&n=400").await;
    assert_eq!(status, StatusCode::OK, "{json}");
    assert!(
        json["svg"]
            .as_str()
            .unwrap()
            .contains(r#"data-engine="chain, N = 400""#)
    );
}

/// A scene whose fronts multiply (a stiff plate ringing under rubber):
/// `impact run` merges them and answers, the diagram, which draws every
/// front, stops at its cap with a message instead of filling memory.
#[tokio::test]
async fn a_diagram_whose_fronts_multiply_is_refused_quickly() {
    let text = include_str!("../../../../data/scenes/steel-under-rubber.json");
    let (status, _, json) = post("/api/run", text).await;
    assert_eq!(status, StatusCode::OK, "{json}");
    let (status, _, json) = post("/api/diagram", text).await;
    assert_eq!(status, StatusCode::UNPROCESSABLE_ENTITY, "{json}");
    let error = json["error"].as_str().unwrap();
    assert!(
        error.contains("fronts multiply beyond 1000000 events"),
        "{error}"
    );
    assert!(error.contains("--engine chain"), "{error}");
}

#[tokio::test]
async fn the_map_is_the_sweep_of_the_canonical_bilayer() {
    let (status, _, json) = get("/api/map?step=0.05").await;
    assert_eq!(status, StatusCode::OK);
    let (x, alpha) = (
        json["x"].as_array().unwrap(),
        json["alpha"].as_array().unwrap(),
    );
    assert_eq!((x.len(), alpha.len()), (19, 19));
    assert_eq!(x[18], 0.95);
    // alpha outer, x inner: point (x = 0.4, alpha = 0.05) is row 0, column 7
    let k = 7;
    let direct = impact_wave::simulate(
        &Bilayer::new(0.4, 0.05).unwrap().scene().validate().unwrap(),
        &impact_wave::WaveConfig::default(),
    )
    .unwrap();
    assert_eq!(json["restitution"][k].as_f64().unwrap(), direct.restitution);
    assert_eq!(json["bounces"][k], 2);
    // Eq. 11's region: e from the map equals the closed form at x = 0.3, alpha = 0.3
    let k = 5 * 19 + 5;
    let closed = impact_model::theory::central_restitution(Bilayer::new(0.3, 0.3).unwrap());
    assert!((json["restitution"][k].as_f64().unwrap() - closed).abs() < 1e-12);
    let overlays = &json["overlays"];
    // the root of 1 + 2 R12 - 2 T21 T12 with R12 = (sqrt a - sqrt(1 - a)) /
    // (sqrt a + sqrt(1 - a)), computed apart (Python, 200 bisections): 0.8227809556
    assert!((overlays["upper_boundary"].as_f64().unwrap() - 0.822_780_955_6).abs() < 1e-9);
    assert_eq!(overlays["x_n"][0].as_array().unwrap().len(), 19);
}

#[tokio::test]
async fn a_slow_chain_does_not_hold_up_the_map() {
    let app = router(App::new(None));
    let viscous = r#"{"impact_speed": 1, "layers": [
        {"length": 0.5, "modulus": 0.995, "density": 1, "restitution": 0.94},
        {"length": 0.5, "modulus": 0.005, "density": 1, "restitution": 0.72}]}"#;
    let chain = tokio::spawn(
        app.clone()
            .oneshot(Request::post("/api/run").body(Body::from(viscous)).unwrap()),
    );
    let map = app
        .oneshot(
            Request::get("/api/map?step=0.05")
                .body(Body::empty())
                .unwrap(),
        )
        .await
        .unwrap();
    assert_eq!(map.status(), StatusCode::OK);
    assert!(!chain.is_finished(), "the map waited for the chain");
    let chain = chain.await.unwrap().unwrap();
    assert_eq!(chain.status(), StatusCode::OK);
}

#[tokio::test]
async fn the_page_is_served_from_the_binary_and_fetches_nothing_else() {
    let response = router(App::new(None))
        .oneshot(Request::get("/").body(Body::empty()).unwrap())
        .await
        .unwrap();
    assert_eq!(response.status(), StatusCode::OK);
    let texts = SCRIPTS.iter().map(|(_, s)| *s);
    for text in texts.chain([super::super::BODY_HTML, APP_CSS]) {
        for external in ["http://", "https://", "//cdn", "@import"] {
            assert!(!text.contains(external), "{external}");
        }
    }
    for asset in SCRIPTS.iter().map(|(path, _)| *path).chain(["/app.css"]) {
        let response = router(App::new(None))
            .oneshot(Request::get(asset).body(Body::empty()).unwrap())
            .await
            .unwrap();
        assert_eq!(response.status(), StatusCode::OK);
    }
}

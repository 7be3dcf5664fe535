//! `impact explore`: the map, any impact's wave paths and a scene editor in
//! the browser, served from a local HTTP server (axum on tokio).
//!
//! The explorer is a second front end to the same commands, not a second
//! implementation: every API request is turned into the words of an
//! `impact run` or `impact diagram` command, parsed by the same clap
//! structs and run by the same code (`run::compute`, `diagram::build`), so
//! its JSON and its one-line error messages are the command line's by
//! construction, and "copy the command" shows exactly what was run. A scene
//! sent in a request body stands in for the scene file; requests never
//! touch the file system. Heavy work runs on tokio's blocking pool (the
//! engines' own parallel loops on rayon's), so a slow chain never holds up
//! the map, and each request's work is capped (`api::Caps`).

mod api;
mod map;
mod request;

use crate::args::ExploreArgs;
use crate::input;
use anyhow::Context;
use std::net::SocketAddr;

/// The page's content, served from the binary in the one page shell of the
/// tree (`impact_output::page`), as its script and style are: nothing is
/// fetched from anywhere else. The style sheet is linked from the body, so
/// its rules come after the shell's shared ones and override them.
pub const BODY_HTML: &str = include_str!("page/body.html");
/// The page's scripts, JavaScript modules: the entry (`app.js`: wiring),
/// the state kept in the URL, the map, the scene editor and the point.
pub const SCRIPTS: [(&str, &str); 5] = [
    ("/app.js", include_str!("page/app.js")),
    ("/state.js", include_str!("page/state.js")),
    ("/map.js", include_str!("page/map.js")),
    ("/editor.js", include_str!("page/editor.js")),
    ("/point.js", include_str!("page/point.js")),
];
/// The page's style.
pub const APP_CSS: &str = include_str!("page/app.css");

pub fn explore(a: ExploreArgs) -> anyhow::Result<()> {
    let scene = match &a.scene {
        Some(path) => {
            let (text, scene) = crate::run::read_scene_text(path)?;
            scene
                .validate()
                .map_err(|e| input(format!("{}: {e}", path.display())))?;
            Some(serde_json::from_str::<serde_json::Value>(&text)?)
        }
        None => None,
    };
    if !a.bind.is_loopback() {
        eprintln!(
            "warning: --bind {} serves the explorer beyond this machine: anyone who can reach it can run simulations on it",
            a.bind
        );
    }
    let runtime = tokio::runtime::Builder::new_multi_thread()
        .enable_all()
        .build()
        .context("cannot start the server's runtime")?;
    runtime.block_on(async move {
        let listener = tokio::net::TcpListener::bind(SocketAddr::new(a.bind, a.port))
            .await
            .map_err(|e| {
                input(format!(
                    "--port: cannot listen on {}:{} ({e}); choose another with --port, or 0 for any free port",
                    a.bind, a.port
                ))
            })?;
        let address = listener.local_addr()?;
        let host = if address.ip().is_unspecified() {
            "127.0.0.1".to_string()
        } else {
            address.ip().to_string()
        };
        let url = format!("http://{host}:{}/", address.port());
        // Ctrl-C is caught from before the URL is printed: whoever reads
        // the URL may stop the server at once (a test does)
        let stop = interrupted()?;
        println!("impact explore: {url}  (Ctrl-C stops the server)");
        if a.open {
            open_browser(&url);
        }
        axum::serve(listener, api::router(api::App::new(scene)))
            .with_graceful_shutdown(async {
                stop.await;
                eprintln!("impact explore: stopping");
            })
            .await
            .context("the server failed")
    })
}

/// Resolves at Ctrl-C (SIGINT). On Unix the handler is installed here, not
/// when the future is first polled, so a signal sent as soon as the URL is
/// out is not the default one that kills the process.
#[cfg(unix)]
fn interrupted() -> anyhow::Result<impl Future<Output = ()>> {
    use tokio::signal::unix::{SignalKind, signal};
    let mut sigint = signal(SignalKind::interrupt()).context("cannot catch Ctrl-C")?;
    Ok(async move {
        sigint.recv().await;
    })
}

#[cfg(not(unix))]
fn interrupted() -> anyhow::Result<impl Future<Output = ()>> {
    Ok(async {
        let _ = tokio::signal::ctrl_c().await;
    })
}

/// The page: the shell's head and the explorer's body.
pub fn index_page() -> String {
    let head = impact_output::Head {
        title: "impact explore",
        style: impact_output::Stylesheet::shared(),
        layout: impact_output::Layout::Spread,
    };
    impact_output::page(&head, BODY_HTML)
}

/// Opens `url` in the user's browser (`xdg-open`, `open` on macOS); a
/// machine without one only loses the convenience.
fn open_browser(url: &str) {
    let opener = if cfg!(target_os = "macos") {
        "open"
    } else {
        "xdg-open"
    };
    if std::process::Command::new(opener).arg(url).spawn().is_err() {
        eprintln!("warning: --open: could not start {opener}; open {url} by hand");
    }
}

//! `impact explore` as a process: it prints its URL, answers over real
//! HTTP, refuses what it cannot serve, and stops cleanly on Ctrl-C.

use crate::support::{assert_input_error, stderr};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::TcpStream;
use std::process::{Child, Command, Stdio};

/// Starts the explorer on a free port; returns it and its `host:port`.
fn start(extra: &[&str]) -> (Child, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_impact"))
        .args(["explore", "--port", "0"])
        .args(extra)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut line = String::new();
    BufReader::new(child.stdout.take().unwrap())
        .read_line(&mut line)
        .unwrap();
    let url = line
        .split_whitespace()
        .find(|w| w.starts_with("http://"))
        .unwrap_or_else(|| panic!("no URL in {line:?}"));
    let address = url.trim_start_matches("http://").trim_end_matches('/');
    (child, address.to_string())
}

/// One HTTP/1.1 request written by hand: the status and the body.
fn request(address: &str, method: &str, path: &str, body: &str) -> (u16, String) {
    let mut stream = TcpStream::connect(address).unwrap();
    write!(
        stream,
        "{method} {path} HTTP/1.1\r\nHost: {address}\r\nConnection: close\r\nContent-Length: {}\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    let mut response = String::new();
    stream.read_to_string(&mut response).unwrap();
    let status = response[9..12].parse().unwrap();
    let body = response.split_once("\r\n\r\n").unwrap().1.to_string();
    (status, body)
}

/// Sends SIGINT, as Ctrl-C does; the server must exit with success. Returns
/// what it wrote on stderr.
fn interrupt(mut child: Child) -> String {
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let exit = child.wait().unwrap();
    assert!(exit.success(), "{exit:?}");
    let mut err = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut err)
        .unwrap();
    err
}

#[test]
fn serves_the_page_and_the_api_and_stops_on_ctrl_c() {
    let (child, address) = start(&[]);
    assert!(address.starts_with("127.0.0.1:"), "{address}");
    let (status, page) = request(&address, "GET", "/", "");
    assert_eq!(status, 200);
    assert!(page.contains("<title>impact explore</title>"));
    let (status, json) = request(&address, "GET", "/api/run?x=0.4&alpha=0.05", "");
    assert_eq!(status, 200);
    let api: serde_json::Value = serde_json::from_str(&json).unwrap();
    let cli = crate::support::impact(&["run", "--x", "0.4", "--alpha", "0.05", "--json"]);
    let cli: serde_json::Value = serde_json::from_slice(&cli.stdout).unwrap();
    assert_eq!(api["restitution"], cli["restitution"]);
    assert_eq!(api["contacts"], cli["contacts"]);
    let (status, json) = request(&address, "GET", "/api/run?x=2&alpha=0.05", "");
    assert_eq!(
        (status, json.as_str()),
        (400, r#"{"error":"x must be a number in (0, 1) (got 2)"}"#)
    );
    let (status, _) = request(
        &address,
        "POST",
        "/api/run",
        r#"{"impact_speed": 1, "layers": [{"length": 1, "material": "steel"}]}"#,
    );
    assert_eq!(status, 200);
    let err = interrupt(child);
    assert!(err.contains("stopping"), "{err}");
}

#[test]
fn binding_beyond_loopback_warns() {
    let (child, _) = start(&["--bind", "0.0.0.0"]);
    let err = interrupt(child);
    assert!(
        err.contains("warning: --bind 0.0.0.0 serves the explorer beyond this machine"),
        "{err}"
    );
}

#[test]
fn bad_start_up_is_an_input_error() {
    assert_input_error(&["explore", "--bind", "localhost:80"], "--bind");
    assert_input_error(&["explore", "--port", "70000"], "--port");
    assert_input_error(&["explore", "no-such-scene.json"], "cannot read scene");
    let taken = std::net::TcpListener::bind("127.0.0.1:0").unwrap();
    let port = taken.local_addr().unwrap().port().to_string();
    assert_input_error(
        &["explore", "--port", &port],
        "--port: cannot listen on 127.0.0.1:",
    );
    let out = crate::support::impact(&["explore", "--help"]);
    assert!(out.status.success());
    assert!(
        String::from_utf8_lossy(&out.stdout).contains("/api/run"),
        "{}",
        stderr(&out)
    );
}

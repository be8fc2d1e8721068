//! The page's pictures are the command line's: for one run, the SVG documents the exported
//! API returns with a `:simulate` reply (`charts`) are, byte for byte, the files
//! `lagrange simulate --plot q.svg --phase p.svg` writes. Both are drawn by `lagrange::chart`;
//! this test runs the real CLI binary (built by cargo for the same profile first) beside the
//! real `Engine`, natively (a wasm32 test cannot start a process).
#![cfg(not(target_arch = "wasm32"))]

use std::path::PathBuf;
use std::process::Command;

use lagrange_web::Engine;
use serde_json::Value;

/// The `lagrange` binary of this test's profile, built now if needed (cargo does nothing when
/// it is up to date): the test executable is `<target>/<profile>/deps/…`.
fn cli() -> PathBuf {
    let exe = std::env::current_exe().expect("the test's path");
    let dir = exe
        .parent()
        .and_then(|deps| deps.parent())
        .expect("<target>/<profile>/deps");
    let profile = match dir.file_name().and_then(|n| n.to_str()) {
        Some("debug") | None => "dev".to_string(),
        Some(other) => other.to_string(),
    };
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let status = Command::new(cargo)
        .args(["build", "--quiet", "-p", "lagrange", "--bin", "lagrange"])
        .args(["--profile", &profile])
        .status()
        .expect("cargo runs");
    assert!(status.success(), "cargo build of the CLI failed");
    dir.join(format!("lagrange{}", std::env::consts::EXE_SUFFIX))
}

#[test]
fn the_pages_charts_are_the_clis_picture_files() {
    let mut e = Engine::new();
    e.handle(":open simple-pendulum");
    let r: Value = serde_json::from_str(&e.handle(":simulate --t-end 3")).expect("JSON");
    let charts = r["charts"].as_array().expect("charts");
    assert_eq!(charts.len(), 2);
    // The same run told to the CLI: the page's start (the problem's θ = 1), its parameters
    // (the problem's suggestions), its 400 samples.
    let d = std::env::temp_dir().join(format!("lagrange-web-cli-agrees-{}", std::process::id()));
    std::fs::create_dir_all(&d).expect("temp dir");
    let (q, p) = (d.join("q.svg"), d.join("p.svg"));
    let out = Command::new(cli())
        .args([
            "simulate",
            "simple-pendulum",
            "--t-end",
            "3",
            "--samples",
            "400",
        ])
        .args(["--init", "theta=1", "--params", "m=1, l=1, g=9.81"])
        .arg("--plot")
        .arg(&q)
        .arg("--phase")
        .arg(&p)
        .output()
        .expect("the CLI runs");
    let read = |path: &PathBuf| std::fs::read_to_string(path).unwrap_or_default();
    let (q_text, p_text) = (read(&q), read(&p));
    let _ = std::fs::remove_dir_all(&d);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(charts[0].as_str(), Some(q_text.as_str()));
    assert_eq!(charts[1].as_str(), Some(p_text.as_str()));
    assert!(q_text.contains(">θ / rad</text>") && p_text.contains(">θ\u{307} / rad s⁻¹</text>"));
}

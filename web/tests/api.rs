//! Tests of the exported API in WebAssembly, run in Node by wasm-bindgen-test-runner:
//! `cargo test -p lagrange-web --target wasm32-unknown-unknown --profile wasm` with
//! `CARGO_TARGET_WASM32_UNKNOWN_UNKNOWN_RUNNER=wasm-bindgen-test-runner` (as `.ci/run` does).
//! They read the JSON the page reads, so they check the data, not its drawing.
#![cfg(target_arch = "wasm32")]

use lagrange_web::{Engine, MAX_LINE_CHARS};
use serde_json::Value;
use wasm_bindgen_test::wasm_bindgen_test;

fn parse(s: &str) -> Value {
    serde_json::from_str(s).expect("the engine answers JSON")
}

#[wasm_bindgen_test]
fn opening_and_answering_give_the_repl_protocol_objects() {
    let mut e = Engine::new();
    let r = parse(&e.handle(":open simple-pendulum"));
    assert_eq!(r["kind"], "statement");
    assert_eq!(r["id"], "simple-pendulum");
    assert_eq!(r["more"][0]["kind"], "part");
    assert_eq!(r["more"][0]["part"], "kinetic");

    let wrong = parse(&e.handle("1/2*m*l*theta'^2"));
    assert_eq!(wrong["kind"], "verdict");
    assert_eq!(wrong["status"], "incorrect");
    let codes: Vec<&str> = wrong["diagnoses"]
        .as_array()
        .map(|a| a.iter().filter_map(|d| d["code"].as_str()).collect())
        .unwrap_or_default();
    assert_eq!(codes, ["dimension", "wrong-factor"]);

    let right = parse(&e.handle("1/2*m*l^2*theta'^2"));
    assert_eq!(right["status"], "correct");
    assert_eq!(right["score"], 1.0);
    assert_eq!(right["more"][0]["part"], "potential");
    assert_eq!(parse(&e.handle("")), serde_json::json!({"kind": "none"}));
}

#[wasm_bindgen_test]
fn an_unreadable_answer_is_positioned_and_not_an_attempt() {
    let mut e = Engine::new();
    e.handle(":open simple-pendulum");
    // θ is two bytes but one UTF-16 unit: the span is in the page's units.
    let r = parse(&e.handle("1/2*m*(l*θ'^2"));
    assert_eq!(r["status"], "invalid");
    assert_eq!(r["error_span"], serde_json::json!([6, 7]));
    let r = parse(&e.handle("1/2*m*l^2*theta'^2"));
    assert_eq!(r["attempts"], 1, "the unreadable line was no attempt");
}

#[wasm_bindgen_test]
fn the_preview_reads_typesets_and_positions() {
    let mut e = Engine::new();
    e.handle(":open simple-pendulum");
    let r = parse(&e.preview("1/2*m*l^2*theta'^2"));
    assert_eq!(r["kind"], "reading");
    assert_eq!(r["latex"], "\\frac{1}{2} m l^{2} \\dot{\\theta}^{2}");
    assert_eq!(r["dimension"]["known"], "M L² T⁻²");
    let r = parse(&e.preview("sin(theta"));
    assert_eq!(r["kind"], "error");
    assert_eq!((r["start"].as_u64(), r["end"].as_u64()), (Some(3), Some(4)));
    assert_eq!(parse(&e.preview(":hint"))["kind"], "command");
    assert_eq!(parse(&e.preview("   "))["kind"], "empty");
    let long = "x+".repeat(MAX_LINE_CHARS);
    assert_eq!(parse(&e.preview(&long))["kind"], "error");
    assert_eq!(parse(&e.handle(&long))["code"], "too-long");
}

#[wasm_bindgen_test]
fn completion_names_the_open_problems_symbols() {
    let mut e = Engine::new();
    e.handle(":open double-pendulum");
    let r = parse(&e.complete("m1*the"));
    assert_eq!(r["start"], 3);
    assert_eq!(r["candidates"], serde_json::json!(["theta1", "theta2"]));
    let r = parse(&e.complete(":ope"));
    assert_eq!(r["candidates"], serde_json::json!([":open "]));
}

#[wasm_bindgen_test]
fn progress_is_the_repl_format_and_imports_back() {
    let mut e = Engine::new();
    e.handle(":open simple-pendulum");
    e.handle("1/2*m*l^2*theta'^2");
    let saved = e.progress();
    let json = parse(&saved);
    assert_eq!(json["version"], 1);
    assert_eq!(
        json["problems"]["simple-pendulum"]["parts"]["kinetic"]["solved"],
        true
    );

    let mut fresh = Engine::new();
    assert_eq!(parse(&fresh.import_progress(&saved))["ok"], true);
    let r = parse(&fresh.handle(":open simple-pendulum"));
    assert_eq!(r["current"], "potential", "the solved part is skipped");
    let bad = parse(&fresh.import_progress("{\"version\": 1, \"problems\": 3"));
    assert_eq!(bad["code"], "bad-progress");
    assert_eq!(
        parse(&fresh.progress()),
        json,
        "a bad import changes nothing"
    );
}

#[wasm_bindgen_test]
fn problem_files_are_verified_and_added() {
    let mut e = Engine::new();
    let broken = "id = \"b\"\ntitle = \"B\"\nstatement = \"s\"\ncoordinates = [{ name = \"x\" }\nlagrangian = \"x'^2\"\n";
    let good = include_str!("../../problems/simple-pendulum.toml")
        .replace("id = \"simple-pendulum\"", "id = \"copy\"");
    let same = include_str!("../../problems/simple-pendulum.toml");
    let files = serde_json::json!([
        {"name": "broken.toml", "text": broken},
        {"name": "copy.toml", "text": good},
        {"name": "same.toml", "text": same},
    ]);
    let r = parse(&e.add_problems(&files.to_string()));
    let f = &r["files"];
    assert_eq!(f[0]["added"], false);
    assert_eq!(f[0]["findings"][0]["code"], "toml-syntax");
    assert_eq!(f[0]["findings"][0]["line"], 5);
    assert_eq!(f[1]["added"], true);
    assert_eq!(f[2]["added"], false, "a bank id is not taken over");
    assert_eq!(f[2]["findings"][0]["code"], "duplicate-id");
    assert_eq!(e.added_problems(), ["copy"]);
    assert_eq!(parse(&e.handle(":open copy"))["id"], "copy");
    assert_eq!(
        parse(&e.handle(":open simple-pendulum"))["id"],
        "simple-pendulum"
    );
    assert_eq!(parse(&e.add_problems("{}"))["code"], "bad-files");
}

#[wasm_bindgen_test]
fn a_simulation_carries_its_grid() {
    let mut e = Engine::new();
    e.handle(":open simple-pendulum");
    let r = parse(&e.handle(":simulate --t-end 2"));
    assert_eq!(r["kind"], "analysis");
    let s = &r["series"];
    assert_eq!(s["names"], serde_json::json!(["theta"]));
    let t = s["t"].as_array().map_or(0, Vec::len);
    assert!(t > 100, "{t} samples");
    assert_eq!(s["q"][0].as_array().map_or(0, Vec::len), t);
    // Starts at rest at θ = 1 (the problem's suggested start).
    assert_eq!(s["q"][0][0], 1.0);
    assert_eq!(s["v"][0][0], 0.0);
    assert_eq!(s["units"]["coordinates"][0], "rad");
    assert!(r["text"].as_str().is_some_and(|t| t.contains("dop853")));
    // Shown as the REPL shows them: θ and θ̇ in the labels and the summary, never `theta`.
    assert_eq!(s["labels"], serde_json::json!(["θ"]));
    assert_eq!(s["rate_labels"], serde_json::json!(["θ\u{307}"]));
    let text = r["text"].as_str().unwrap_or_default();
    assert!(text.contains("θ = 1") && !text.contains("theta"), "{text}");
}

#[wasm_bindgen_test]
fn a_double_pendulums_coordinates_are_shown_with_subscripts() {
    let mut e = Engine::new();
    e.handle(":open double-pendulum");
    let r = parse(&e.handle(":simulate --t-end 1"));
    assert_eq!(r["series"]["labels"], serde_json::json!(["θ₁", "θ₂"]));
    assert_eq!(
        r["series"]["rate_labels"],
        serde_json::json!(["θ\u{307}₁", "θ\u{307}₂"])
    );
}

#[wasm_bindgen_test]
fn state_follows_the_tutor() {
    let mut e = Engine::new();
    e.handle(":open simple-pendulum");
    e.handle(":tutor");
    let s = parse(&e.state());
    assert_eq!(s["tutor"], true);
    assert_eq!(s["step"], "position:1");
    let r = parse(&e.handle("l*sin(theta), -l*cos(theta)"));
    assert_eq!(r["status"], "correct");
    assert_eq!(r["next"]["step"], "speed-squared:1");
}

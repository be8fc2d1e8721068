//! The browser face of lagrange: the library's tutor [`Session`] exported to JavaScript with
//! wasm-bindgen. Every line the page sends goes through [`Session::handle`], and every answer
//! comes back as the same JSON object the REPL's `--json` protocol prints
//! (docs/repl-protocol.md), built by [`json_object`]; the page only draws it, so no mathematics
//! lives in JavaScript. What the terminal faces compute on their side is added here as data:
//! a simulation's even grid and its q(t) and phase-portrait pictures as SVG text, an
//! analysis's text and LaTeX, the position of an unreadable answer's error, and the live
//! reading of a half-typed line ([`Engine::preview`]).
//!
//! Problem files a student opens in the page ([`Engine::add_problems`]) are read by the
//! library's loader and verifier, as `lagrange problems verify` does; a file with findings is
//! reported with their lines and not added.

use lagrange::bank::{Bank, Finding, embedded, load_str, verify::verify};
use lagrange::chart::unicode;
use lagrange::expr::Style;
use lagrange::problem::variant;
use lagrange::report::{Plain, ReadOptions, reading};
use lagrange::tutor::response::{AnalysisReport, json_object};
use lagrange::tutor::{Progress, Response, Session};
use serde_json::{Map, Value, json};
use wasm_bindgen::prelude::*;

/// The longest line the page sends (the REPL reads lines of any length, but a browser text
/// box pasted with megabytes must not freeze the page in the reader).
pub const MAX_LINE_CHARS: usize = 4000;

/// Said to the student in place of a check when a line is longer than [`MAX_LINE_CHARS`].
fn too_long(line: &str) -> Option<String> {
    let n = line.chars().count();
    (n > MAX_LINE_CHARS)
        .then(|| format!("this line has {n} characters; at most {MAX_LINE_CHARS} are read"))
}

#[wasm_bindgen]
extern "C" {
    /// The page's panic reporter (`globalThis.lagrangeEnginePanic`), told the panic's message
    /// before the module traps, so the page can say what failed.
    #[wasm_bindgen(js_namespace = globalThis, js_name = lagrangeEnginePanic)]
    fn report_panic(message: &str);
}

/// Installs the panic hook that tells the page (once per module instance).
#[wasm_bindgen(start)]
pub fn start() {
    #[cfg(target_arch = "wasm32")]
    std::panic::set_hook(Box::new(|info| report_panic(&info.to_string())));
}

/// The library's version, shown in the page's footer.
#[wasm_bindgen]
pub fn version() -> String {
    env!("CARGO_PKG_VERSION").to_string()
}

/// Panics on purpose: the end-to-end test's way to prove the page survives an engine panic
/// (the page catches the trap, says so and reloads the module).
#[wasm_bindgen(js_name = panicForTest)]
pub fn panic_for_test() {
    panic!("a panic asked for by the page's test hook");
}

/// A practice session over the embedded bank and the problem files the student opened.
#[wasm_bindgen]
pub struct Engine {
    session: Session,
    /// Problems from the student's own files, in the order they were added.
    extra: Vec<lagrange::Problem>,
}

impl Default for Engine {
    fn default() -> Self {
        Engine::new()
    }
}

#[wasm_bindgen]
impl Engine {
    /// A session over the embedded bank with no progress.
    #[wasm_bindgen(constructor)]
    pub fn new() -> Engine {
        Engine {
            session: Session::new(embedded::bank(), Progress::new()),
            extra: Vec::new(),
        }
    }

    /// Answers one line as the REPL's `--json` protocol does: one JSON object, its further
    /// responses in `"more"`. A simulation adds `series` (its even grid) and `charts` (its
    /// pictures as SVG documents, [`lagrange::chart`]), an analysis `text`
    /// (and `latex` for `:read` and `:derive`), a verdict `reading_tex` (or, unreadable,
    /// `error_span`), and a statement, part or hint the file's own `$…$` text (`*_tex`).
    pub fn handle(&mut self, line: &str) -> String {
        let responses = match too_long(line) {
            Some(message) => vec![Response::error("too-long", message, None)],
            None => self.session.handle(line),
        };
        // A verdict's reading typeset: the line read as the preview reads it (same problem).
        let judged = responses
            .iter()
            .any(|r| matches!(r, Response::Verdict(_) | Response::StepVerdict(_)));
        let reading_tex = judged
            .then(|| reading(line, &self.read_options()).ok())
            .flatten()
            .map(|r| r.forms.latex);
        let bank = self.session.bank();
        let progress = self.session.progress();
        let seed = |id: &str| progress.problems.get(id).and_then(|p| p.variant_seed);
        let value = json_object(&responses, |r, map| {
            extend(r, map, line);
            with_tex(r, map, bank, &seed);
            if let (Response::Verdict(_) | Response::StepVerdict(_), Some(t)) = (r, &reading_tex) {
                map.insert("reading_tex".into(), json!(t));
            }
        })
        .unwrap_or_else(|e| json!({"kind": "error", "code": "internal", "message": e.to_string()}));
        value.to_string()
    }

    /// How the line typed so far will be read, for the live preview: `{"kind":"reading",
    /// "latex", "unicode", "dimension"}`, `{"kind":"command"}` for a `:` command or a word
    /// command, `{"kind":"empty"}`, or `{"kind":"error","message","start","end"}` with the
    /// error's span in UTF-16 units of `line` (JavaScript's string indices).
    pub fn preview(&self, line: &str) -> String {
        let t = line.trim();
        if t.is_empty() {
            return json!({"kind": "empty"}).to_string();
        }
        if t.starts_with(':') || matches!(t, "help" | "hint" | "quit" | "exit") {
            return json!({"kind": "command"}).to_string();
        }
        if let Some(message) = too_long(line) {
            return json!({"kind": "error", "message": message, "start": 0, "end": 0}).to_string();
        }
        match reading(line, &self.read_options()) {
            Ok(r) => json!({
                "kind": "reading",
                "latex": r.forms.latex,
                "unicode": r.forms.unicode,
                "what": r.kind,
                "dimension": serde_json::to_value(&r.dimension).unwrap_or(Value::Null),
            })
            .to_string(),
            Err(e) => {
                let (start, end) = utf16_span(line, e.span.clone());
                json!({"kind": "error", "message": e.kind.to_string(), "help": e.help(),
                       "start": start, "end": end})
                .to_string()
            }
        }
    }

    /// Completion of the word before the cursor (`line` is the text before it):
    /// `{"start": UTF-16 index where the word starts, "candidates": [...]}`.
    pub fn complete(&self, line: &str) -> String {
        let (start, candidates) = self.session.complete(line);
        let (start, _) = utf16_span(line, start..start);
        json!({"start": start, "candidates": candidates}).to_string()
    }

    /// Where the session is: `{"problem", "part", "step", "tutor"}` (null when none).
    pub fn state(&self) -> String {
        json!({
            "problem": self.session.current_problem(),
            "part": self.session.current_part(),
            "step": self.session.current_step(),
            "tutor": self.session.in_tutor(),
        })
        .to_string()
    }

    /// The progress as the REPL's progress file holds it (`progress.json`).
    pub fn progress(&self) -> String {
        self.session.progress().to_json()
    }

    /// Continues from progress in the REPL's format (the page's saved progress or an
    /// imported file). `{"ok": true}`, or an error object whose message gives the line and
    /// column; on an error the session's progress is unchanged. The open problem is closed.
    #[wasm_bindgen(js_name = importProgress)]
    pub fn import_progress(&mut self, text: &str) -> String {
        match Progress::from_json(text) {
            Ok(p) => {
                self.session = Session::new(self.bank(), p);
                json!({"ok": true}).to_string()
            }
            Err(e) => json!({"kind": "error", "code": "bad-progress", "message": e.to_string()})
                .to_string(),
        }
    }

    /// Reads, verifies and adds problem files: `files` is a JSON array of `{"name", "text"}`.
    /// Returns `{"files": [{"name", "problem", "added", "findings": [{"line", "code",
    /// "part", "message"}]}]}`. A file that does not load, or whose stated answers the
    /// verifier cannot prove, is not added; a file defining an id already in the bank
    /// replaces an earlier file of the student's with that id, never a bank problem. The
    /// progress is kept; the open problem is closed.
    #[wasm_bindgen(js_name = addProblems)]
    pub fn add_problems(&mut self, files: &str) -> String {
        let files: Vec<Value> = match serde_json::from_str(files) {
            Ok(Value::Array(a)) => a,
            _ => {
                return json!({"kind": "error", "code": "bad-files",
                              "message": "expected a JSON array of {name, text}"})
                .to_string();
            }
        };
        let mut reports = Vec::new();
        for f in &files {
            let name = f
                .get("name")
                .and_then(Value::as_str)
                .unwrap_or("problem.toml");
            let text = f.get("text").and_then(Value::as_str).unwrap_or("");
            reports.push(self.add_file(name, text));
        }
        let progress = self.session.progress().clone();
        self.session = Session::new(self.bank(), progress);
        json!({"files": reports}).to_string()
    }

    /// The ids of the problems added from the student's files.
    #[wasm_bindgen(js_name = addedProblems)]
    pub fn added_problems(&self) -> Vec<String> {
        self.extra.iter().map(|p| p.id.clone()).collect()
    }
}

impl Engine {
    /// The session, read-only (for tests and host tools).
    pub fn session(&self) -> &Session {
        &self.session
    }

    /// The embedded bank with the student's problems after it.
    fn bank(&self) -> Bank {
        let mut bank = embedded::bank();
        for p in &self.extra {
            let file = p.file.clone();
            bank.add(p.clone(), file);
        }
        bank
    }

    /// One file: loaded, verified, added when it holds.
    fn add_file(&mut self, name: &str, text: &str) -> Value {
        let problem = match load_str(name, text) {
            Ok(p) => p,
            Err(f) => {
                return json!({"name": name, "problem": f.problem, "added": false,
                                    "findings": [finding(&f)]});
            }
        };
        let mut findings: Vec<Value> = verify(&problem).iter().map(finding).collect();
        if findings.is_empty() && embedded::problem(&problem.id).is_some() {
            findings.push(json!({"line": 1, "code": "duplicate-id", "part": null,
                "message": format!("the bank already has a problem `{}`: give this one another id", problem.id)}));
        }
        let added = findings.is_empty();
        let id = problem.id.clone();
        if added {
            self.extra.retain(|p| p.id != id);
            self.extra.push(problem);
        }
        json!({"name": name, "problem": id, "added": added, "findings": findings})
    }

    /// The read options of `:read` in the session: the open problem's coordinates and its
    /// symbols' dimensions (every name open when no problem is).
    fn read_options(&self) -> ReadOptions {
        let mut opts = ReadOptions::default();
        if let Some(p) = self.session.problem() {
            let sys = &p.system;
            opts.coords = sys.coordinates.iter().map(|c| c.name.clone()).collect();
            let names = sys.coordinates.iter().map(|c| &c.name);
            let names = names.chain(sys.parameters.iter().map(|q| &q.name));
            opts.dims = names
                .filter_map(|n| Some((n.clone(), p.dims.get(n)?)))
                .collect();
        }
        opts
    }
}

/// A finding as data for the page.
fn finding(f: &Finding) -> Value {
    json!({"line": f.line, "code": f.code, "part": f.part, "message": f.message})
}

/// `span` (bytes of `line`) as UTF-16 indices, clamped to the line and to char boundaries.
fn utf16_span(line: &str, span: std::ops::Range<usize>) -> (usize, usize) {
    let at = |b: usize| {
        line.char_indices()
            .take_while(|(i, _)| *i < b)
            .map(|(_, c)| c.len_utf16())
            .sum::<usize>()
    };
    let (s, e) = (at(span.start), at(span.end.max(span.start)));
    (s, e)
}

/// Adds to a response's object what the page draws and the terminal faces compute themselves.
fn extend(r: &Response, map: &mut Map<String, Value>, line: &str) {
    match r {
        Response::Analysis(a) => {
            let (text, latex) = match &a.report {
                AnalysisReport::Read(r) => (
                    r.render(&Plain, "dimensions come from the open problem"),
                    Some(r.forms.latex.clone()),
                ),
                AnalysisReport::Derive(r) => (
                    r.render(Style::Unicode, &Plain),
                    Some(r.render(Style::Latex, &Plain)),
                ),
                AnalysisReport::Modes(r) => (r.render(Style::Unicode, &Plain), None),
                // The REPL's summary, with the coordinates' Unicode names (θ, θ̇).
                AnalysisReport::Simulate(r) => {
                    map.insert("series".into(), series(r));
                    map.insert("charts".into(), charts(r));
                    (r.render_unicode(&Plain), None)
                }
            };
            map.insert("text".into(), Value::String(text));
            if let Some(l) = latex {
                map.insert("latex".into(), Value::String(l));
            }
        }
        Response::Verdict(v) => error_span(v.verdict.parse_error.as_ref(), map, line),
        Response::StepVerdict(v) => error_span(v.verdict.parse_error.as_ref(), map, line),
        _ => {}
    }
}

/// The problem file's own text with its `$…$` mathematics, beside the Unicode rendering the
/// protocol carries (made for a terminal): `statement_tex` and each part's `prompt_tex` on a
/// statement, `prompt_tex` on a part, `hint_tex` on a part's hint. The page typesets them.
/// A problem with variants has its `{{name}}` filled with the numbers being practised (the
/// seed `seed` gives for the problem, as `:variant` keeps it), or with the names without one.
fn with_tex(
    r: &Response,
    map: &mut Map<String, Value>,
    bank: &Bank,
    seed: &dyn Fn(&str) -> Option<u64>,
) {
    let part_of = |problem: &str, part: &str| {
        bank.problem(problem)
            .and_then(|p| p.parts.iter().find(|q| q.id == part))
    };
    let practised = |p: &lagrange::Problem| seed(&p.id).and_then(|s| variant::pick_own(p, s));
    match r {
        Response::Statement(s) => {
            let Some(p) = bank.problem(&s.sheet.id) else {
                return;
            };
            let v = practised(p);
            let fill = |text: &str| variant::fill(text, &p.variants, v.as_ref());
            map.insert("statement_tex".into(), json!(fill(p.statement.trim())));
            let prompts: Vec<String> = p.parts.iter().map(|q| fill(&q.prompt)).collect();
            map.insert("prompts_tex".into(), json!(prompts));
        }
        Response::Part(q) => {
            if let (Some(p), Some(part)) = (bank.problem(&q.problem), part_of(&q.problem, &q.part))
            {
                let v = practised(p);
                let text = variant::fill(&part.prompt, &p.variants, v.as_ref());
                map.insert("prompt_tex".into(), json!(text));
            }
        }
        // A tutor's hint (`reveal` is `:show`) is generated from the physics, not the file.
        Response::Hint(h) if h.reveal == ":solution" => {
            let raw = part_of(&h.problem, &h.part)
                .and_then(|part| part.hints.get(h.number.checked_sub(1)?));
            if let (Some(raw), Some(_), Some(p)) = (raw, &h.hint, bank.problem(&h.problem)) {
                let v = practised(p);
                map.insert(
                    "hint_tex".into(),
                    json!(variant::fill(raw, &p.variants, v.as_ref())),
                );
            }
        }
        _ => {}
    }
}

/// An unreadable answer's error position in the line, in UTF-16 units.
fn error_span(e: Option<&lagrange::ParseError>, map: &mut Map<String, Value>, line: &str) {
    if let Some(e) = e {
        let (s, end) = utf16_span(line, e.span.clone());
        map.insert("error_span".into(), json!([s, end]));
    }
}

/// A simulation's even grid for drawing: `t`, per coordinate `q` and `v` (its rate), `h`,
/// the coordinates' names as typed (`names`) and as shown ([`lagrange::chart::unicode`],
/// as the REPL and the charts name them: `labels`: `θ₁`; `rate_labels`: `θ̇₁`), and the axes'
/// units. Non-finite samples become null.
fn series(r: &lagrange::report::SimulationReport) -> Value {
    let n = r.grid.first().map_or(0, |row| row.1.len() / 2);
    let num = |x: f64| if x.is_finite() { json!(x) } else { Value::Null };
    let column = |i: usize| -> Vec<Value> {
        r.grid
            .iter()
            .map(|(_, y, _)| y.get(i).copied().map_or(Value::Null, num))
            .collect()
    };
    json!({
        "names": r.names.iter().take(n).collect::<Vec<_>>(),
        "labels": r.names.iter().take(n).map(|q| unicode(q)).collect::<Vec<_>>(),
        "rate_labels": r.names.iter().take(n).map(|q| unicode(&[q, "'"].concat())).collect::<Vec<_>>(),
        "t": r.grid.iter().map(|row| num(row.0)).collect::<Vec<_>>(),
        "q": (0..n).map(column).collect::<Vec<_>>(),
        "v": (n..2 * n).map(column).collect::<Vec<_>>(),
        "h": r.grid.iter().map(|row| num(row.2)).collect::<Vec<_>>(),
        "units": {
            "time": r.units.time,
            "coordinates": r.units.coordinates,
            "velocities": r.units.velocities,
            "energy": r.units.energy,
        },
    })
}

/// The simulation's pictures as SVG documents, drawn by the library as the CLI's `--plot` and
/// `--phase` files are (the same bytes for the same run): q(t) of every coordinate, then their
/// phase portraits. The page inserts them as they are.
fn charts(r: &lagrange::report::SimulationReport) -> Value {
    json!([
        lagrange::chart::qt(r).to_svg(),
        lagrange::chart::phase(r).to_svg()
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utf16_spans_count_code_units() {
        // θ is one UTF-16 unit and two bytes; 𝜃 (U+1D703) is two units and four bytes.
        assert_eq!(utf16_span("θ+(", 3..4), (2, 3));
        assert_eq!(utf16_span("𝜃(", 4..5), (2, 3));
        assert_eq!(utf16_span("ab", 7..9), (2, 2));
    }
}

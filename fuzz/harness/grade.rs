//! Target `grade`: class files, wide and long, as spreadsheets and hostile students write
//! them (quotes, CRLF and CR-only endings, a byte-order mark or UTF-16, `;` delimiters,
//! formula cells, huge fields, wrong field counts, and byte mutations down to invalid UTF-8),
//! graded by the `lagrange grade` binary in a temporary folder.
//!
//! An input is a first line of settings, `#fuzz-grade rows=N lms=L flags=F`, then the class
//! file's bytes. `rows` is the number of rows results.csv must hold (every data record of the
//! long format, every non-empty part cell of the wide one, one error row per record with the
//! wrong number of fields: docs/grading.md), or `?` after byte mutations. Oracles: the
//! process exits 0 or 2 and never panics; a generated file without mutations is graded
//! (exit 0; a Moodle key mix may be refused); after exit 0 results.csv holds the rows, in
//! input order, on lines the file has; after exit 2 no output was written; and no file
//! outside `--out` is created, changed or removed, nor any file in it that grade does not name.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use super::inputs::{Rng, below, chance, pick};

/// The settings line's start.
const MARK: &str = "#fuzz-grade";

/// Parts of the embedded bank with answers right, wrong and unreadable.
const PARTS: &[(&str, &[&str])] = &[
    (
        "simple-pendulum/kinetic",
        &[
            "1/2 m l^2 theta'^2",
            "1/2 m l theta'^2",
            "½·m·l²·θ̇²",
            "m l^2 θ'^2/2",
        ],
    ),
    (
        "simple-pendulum/potential",
        &[
            "-m g l cos(theta)",
            "m g l cos θ",
            "-m*g*l*cos(theta)",
            "=-m g l cos θ",
        ],
    ),
    (
        "simple-pendulum/eom",
        &[
            "m l^2 theta'' + m g l sin(theta) = 0",
            "theta'' = -g/l sin(theta)",
            "theta'' = g/l theta",
        ],
    ),
    (
        "simple-pendulum/equilibria",
        &[
            "0, pi",
            "theta = 0 (stable), theta = pi (unstable)",
            "0 (unstable)",
        ],
    ),
    (
        "double-pendulum/eom",
        &["theta1'' = 0; theta2'' = 0", "x'' = 0"],
    ),
    ("atwood/eom", &["x'' = (m1 - m2)/(m1 + m2) g", "x'' = g"]),
    ("nope/eom", &["x"]),
    ("simple-pendulum/nope", &["x"]),
];

/// Answers any part may get: junk, formulas, separators, quotes and line breaks.
const ANY: &[&str] = &[
    "",
    " ",
    "=HYPERLINK(\"http://x\",\"y\")",
    "+1",
    "-m g l",
    "@SUM(A1)",
    "'=1+1",
    "\tx",
    "a, b; c",
    "he said \"no\"",
    "line one\nline two",
    "x\r\ny",
    "θ̇²\u{202e}",
    "\u{0}",
    "sin(",
    "1/0",
];

/// Student keys.
const STUDENTS: &[&str] = &[
    "ada@uni.example",
    "Ada@Uni.example",
    " ada@uni.example ",
    "ben@uni.example",
    "s1234",
    "=cmd|' /C calc'!A0",
    "-chen",
    "dora; jones",
    "\"quoted\"",
    "",
    "émile@uni.example",
    "\rcarl",
    "\tdee",
];

/// One generated class file before rendering.
struct Class {
    /// The header's cells.
    header: Vec<String>,
    /// The records (each a list of cells, possibly of the wrong length).
    records: Vec<Vec<String>>,
    /// The rows results.csv must hold.
    rows: usize,
}

/// One input: a class file rendered as some spreadsheet would, sometimes mutated.
pub fn generate(r: &mut Rng) -> Vec<u8> {
    let mut class = if chance(r, 0.5) { wide(r) } else { long(r) };
    // A trailing delimiter on every line (an empty last column), as some exports write.
    if chance(r, 0.1) {
        class.header.push(String::new());
        for cells in &mut class.records {
            cells.push(String::new());
        }
    }
    let delimiter = if chance(r, 0.25) { ';' } else { ',' };
    let ending = *pick(r, &["\n", "\r\n", "\r"]);
    let mut text = String::new();
    let mut lines = vec![class.header.clone()];
    lines.extend(class.records.iter().cloned());
    for (k, cells) in lines.iter().enumerate() {
        let always = chance(r, 0.2);
        let shown: Vec<String> = cells.iter().map(|c| cell(c, delimiter, always)).collect();
        text.push_str(&shown.join(&delimiter.to_string()));
        if k + 1 < lines.len() || chance(r, 0.8) {
            text.push_str(ending);
        }
        // Blank lines are not records (the CSV reader skips them).
        if k > 0 && chance(r, 0.1) {
            text.push_str(ending);
        }
    }
    let mut bytes = match below(r, 10) {
        0 => [b"\xef\xbb\xbf".as_slice(), text.as_bytes()].concat(),
        1 => utf16(&text, true),
        2 => utf16(&text, false),
        _ => text.into_bytes(),
    };
    let mut rows = class.rows.to_string();
    if chance(r, 0.3) {
        for _ in 0..1 + below(r, 3) {
            mutate(r, &mut bytes);
        }
        rows = "?".into();
    }
    let lms = *pick(r, &["none", "none", "canvas", "moodle", "gradescope"]);
    let flags = *pick(r, &["-", "-", "-", "best", "follow"]);
    let mut input = format!("{MARK} rows={rows} lms={lms} flags={flags}\n").into_bytes();
    input.extend(bytes);
    input
}

/// A long-format class: `student,problem,part,answer` in some order, maybe an extra column.
fn long(r: &mut Rng) -> Class {
    let mut header: Vec<String> = ["student", "problem", "part", "answer"]
        .iter()
        .map(|h| spelled(r, h))
        .collect();
    if chance(r, 0.3) {
        header.push("timestamp".into());
    }
    if chance(r, 0.3) {
        let k = below(r, header.len());
        let j = below(r, header.len());
        header.swap(k, j);
    }
    let names: Vec<String> = header.iter().map(|h| h.trim().to_lowercase()).collect();
    let mut records = Vec::new();
    for _ in 0..below(r, 10) {
        let (id, answers) = *pick(r, PARTS);
        let (problem, part) = id.split_once('/').unwrap_or((id, ""));
        let mut cells: Vec<String> = names
            .iter()
            .map(|n| match n.as_str() {
                "student" => pick(r, STUDENTS).to_string(),
                "problem" => problem.to_string(),
                "part" => part.to_string(),
                "answer" => answer(r, answers),
                _ => "2024-01-01 10:00".into(),
            })
            .collect();
        miscount(r, &mut cells);
        records.push(cells);
    }
    // One row per record, whatever it holds.
    let rows = records.len();
    Class {
        header,
        records,
        rows,
    }
}

/// A wide-format class: `student` plus part columns (maybe unknown ones, or repeated).
fn wide(r: &mut Rng) -> Class {
    let mut header = vec![spelled(r, "student")];
    let columns = 1 + below(r, 4);
    let mut answers = Vec::new();
    for _ in 0..columns {
        let (id, a) = *pick(r, PARTS);
        header.push(if chance(r, 0.2) {
            id.replace('/', " / ")
        } else {
            id.to_string()
        });
        answers.push(a);
    }
    if chance(r, 0.3) {
        header.insert(below(r, header.len() + 1), "Email".into());
    }
    let student_at = header
        .iter()
        .position(|h| h.trim().eq_ignore_ascii_case("student"));
    let mut records = Vec::new();
    let mut rows = 0;
    for _ in 0..below(r, 8) {
        let mut part = 0;
        let mut cells = Vec::new();
        for (k, h) in header.iter().enumerate() {
            if Some(k) == student_at {
                cells.push(pick(r, STUDENTS).to_string());
            } else if h.contains('/') {
                cells.push(if chance(r, 0.3) {
                    String::new()
                } else {
                    answer(r, answers[part])
                });
                part += 1;
            } else {
                cells.push("x@y".into());
            }
        }
        let width = cells.len();
        miscount(r, &mut cells);
        rows += if cells.len() != width {
            1
        } else {
            header
                .iter()
                .zip(&cells)
                .filter(|(h, c)| h.contains('/') && !unquoted(c).trim().is_empty())
                .count()
        };
        records.push(cells);
    }
    Class {
        header,
        records,
        rows,
    }
}

/// The text grade reads from a cell: one `'` before a formula start is removed.
fn unquoted(c: &str) -> &str {
    let formula = |s: &str| s.starts_with(['=', '+', '-', '@', '\t', '\r']);
    let mut s = c;
    let mut quotes = 0;
    while let Some(rest) = s.strip_prefix('\'') {
        s = rest;
        quotes += 1;
    }
    if quotes > 0 && formula(s) { &c[1..] } else { c }
}

/// A column name as exports spell it: case and spaces vary.
fn spelled(r: &mut Rng, name: &str) -> String {
    match below(r, 4) {
        0 => name.to_uppercase(),
        1 => format!(" {name} "),
        _ => name.to_string(),
    }
}

/// An answer: one of the part's, a hostile one, or a huge one.
fn answer(r: &mut Rng, answers: &[&str]) -> String {
    match below(r, 10) {
        0..=5 => pick(r, answers).to_string(),
        6..=8 => pick(r, ANY).to_string(),
        _ => "m*g*l + ".repeat(1 + below(r, 4000)) + "1",
    }
}

/// Sometimes a field too many or too few (an error row, never a lost one).
fn miscount(r: &mut Rng, cells: &mut Vec<String>) {
    if chance(r, 0.1) {
        cells.push("extra".into());
    } else if chance(r, 0.1) && cells.len() > 2 {
        // (Never down to one cell: an empty one would be a blank line, not a record.)
        cells.pop();
    }
}

/// A cell in CSV: quoted when it must be (or `always`), quotes doubled.
fn cell(c: &str, delimiter: char, always: bool) -> String {
    if always || c.contains([delimiter, '"', '\r', '\n']) {
        format!("\"{}\"", c.replace('"', "\"\""))
    } else {
        c.to_string()
    }
}

/// The text in UTF-16 with a byte-order mark.
fn utf16(text: &str, little: bool) -> Vec<u8> {
    let mut out = if little {
        vec![0xff, 0xfe]
    } else {
        vec![0xfe, 0xff]
    };
    for u in text.encode_utf16() {
        out.extend(if little {
            u.to_le_bytes()
        } else {
            u.to_be_bytes()
        });
    }
    out
}

/// One byte-level change: invalid UTF-8, a stray quote or line break, a cut, a NUL.
fn mutate(r: &mut Rng, bytes: &mut Vec<u8>) {
    let at = below(r, bytes.len() + 1);
    match below(r, 8) {
        7 => {
            // A quoted field over the line limit: refused, never read as one answer.
            let field = format!("\"{}\"", "x\n".repeat(101));
            bytes.splice(at..at, field.into_bytes());
        }
        0 => bytes.insert(at, *pick(r, &[0xff, 0xc3, 0x80, 0xfe])),
        1 => bytes.insert(at, b'"'),
        2 => bytes.insert(at, b'\r'),
        3 => bytes.truncate(at),
        4 => bytes.insert(at, 0),
        5 if at < bytes.len() => {
            bytes.remove(at);
        }
        _ => {
            let end = (at + below(r, 40)).min(bytes.len());
            let copy = bytes[at..end].to_vec();
            bytes.splice(at..at, copy);
        }
    }
}

/// The settings of an input and its class file.
struct Case<'a> {
    rows: Option<usize>,
    lms: &'a str,
    flags: &'a str,
    file: &'a [u8],
}

fn case(input: &[u8]) -> Option<Case<'_>> {
    let nl = input.iter().position(|&b| b == b'\n')?;
    let first = std::str::from_utf8(&input[..nl]).ok()?;
    let mut words = first.strip_prefix(MARK)?.split_whitespace();
    let mut get = |k: &str| words.next()?.strip_prefix(k);
    let rows = get("rows=")?;
    let lms = get("lms=")?;
    let flags = get("flags=")?;
    Some(Case {
        rows: rows.parse().ok(),
        lms,
        flags,
        file: &input[nl + 1..],
    })
}

/// The `lagrange` binary: the one cargo built beside this test, or beside the fuzzer
/// (`target/release/lagrange` for `target/release/examples/fuzz`; build it first).
fn binary() -> PathBuf {
    if let Some(p) = option_env!("CARGO_BIN_EXE_lagrange") {
        return PathBuf::from(p);
    }
    let exe = std::env::current_exe().unwrap_or_default();
    let dir = exe
        .parent()
        .and_then(Path::parent)
        .unwrap_or(Path::new("."));
    dir.join("lagrange")
}

/// Every file under `dir` with its bytes.
fn snapshot(dir: &Path) -> BTreeMap<PathBuf, Vec<u8>> {
    let mut out = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p.clone());
            }
            out.insert(p.clone(), std::fs::read(&p).unwrap_or_default());
        }
    }
    out
}

/// The names grade may write in `--out`.
const OUTPUTS: &[&str] = &[
    "results.csv",
    "gradebook.csv",
    "review.csv",
    "summary.md",
    "summary.json",
    "canvas.csv",
    "moodle.csv",
    "gradescope.csv",
];

/// Grades the class file and applies the oracles.
pub fn execute(input: &[u8]) -> Result<(), String> {
    let Some(c) = case(input) else {
        return Ok(());
    };
    let bin = binary();
    if !bin.is_file() {
        return Err(format!(
            "setup: no binary at {} (cargo build --release first)",
            bin.display()
        ));
    }
    let work = tempfile::tempdir().map_err(|e| format!("setup: {e}"))?;
    let logs = tempfile::tempdir().map_err(|e| format!("setup: {e}"))?;
    let root = work.path();
    let out = root.join("out");
    std::fs::create_dir_all(&out).map_err(|e| format!("setup: {e}"))?;
    std::fs::write(root.join("class.csv"), c.file).map_err(|e| format!("setup: {e}"))?;
    std::fs::write(root.join("notes.txt"), "mine").map_err(|e| format!("setup: {e}"))?;
    std::fs::write(out.join("keep.txt"), "mine too").map_err(|e| format!("setup: {e}"))?;
    let before = snapshot(root);
    let mut cmd = Command::new(&bin);
    cmd.current_dir(root)
        .args(["grade", "class.csv", "--out", "out"])
        .env("NO_COLOR", "1")
        .stdin(Stdio::null());
    // Half the inputs as a class of many different answers would be graded: checked in
    // windows of 2, the words kept in the nameless scratch file (which must leave nothing).
    if input.len() % 2 == 1 {
        cmd.env("LAGRANGE_GRADE_WINDOW", "2");
    }
    if c.lms != "none" {
        cmd.args(["--lms", c.lms]);
    }
    match c.flags {
        "best" => {
            cmd.arg("--best");
        }
        "follow" => {
            cmd.arg("--follow-through");
        }
        _ => {}
    }
    let stderr_path = logs.path().join("stderr");
    let stderr = std::fs::File::create(&stderr_path).map_err(|e| format!("setup: {e}"))?;
    let stdout =
        std::fs::File::create(logs.path().join("stdout")).map_err(|e| format!("setup: {e}"))?;
    let mut child = cmd
        .stdout(stdout)
        .stderr(stderr)
        .spawn()
        .map_err(|e| format!("setup: {e}"))?;
    let start = Instant::now();
    let status = loop {
        match child.try_wait() {
            Ok(Some(s)) => break s,
            Ok(None) if start.elapsed() > Duration::from_secs(30) => {
                let _ = child.kill();
                let _ = child.wait();
                return Err("hang: grade ran over 30 s".into());
            }
            Ok(None) => std::thread::sleep(Duration::from_millis(2)),
            Err(e) => return Err(format!("setup: {e}")),
        }
    };
    let err = std::fs::read_to_string(&stderr_path).unwrap_or_default();
    let first = err.lines().next().unwrap_or("").to_string();
    let code = status.code();
    if err.contains("panicked") || !matches!(code, Some(0 | 2)) {
        return Err(format!("crash: exit {code:?}: {}", err.trim()));
    }
    super::no_raw_controls(&err, "stderr")?;
    let after = snapshot(root);
    // Nothing outside `--out` changes; inside it, only the files grade names.
    for (p, bytes) in &before {
        if after.get(p) != Some(bytes) && !p.starts_with(&out) {
            return Err(format!("touched: {} changed or vanished", p.display()));
        }
    }
    for p in after.keys().filter(|p| !before.contains_key(*p)) {
        let named = p.parent() == Some(out.as_path())
            && p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| OUTPUTS.contains(&n));
        if !named {
            return Err(format!("touched: {} was created", p.display()));
        }
    }
    if after.get(&out.join("keep.txt")) != before.get(&out.join("keep.txt")) {
        return Err("touched: out/keep.txt changed".into());
    }
    let results = out.join("results.csv");
    if code == Some(2) {
        if results.exists() {
            return Err(format!(
                "refused-but-wrote: exit 2 ({first}) left results.csv"
            ));
        }
        if c.rows.is_some() && c.lms != "moodle" {
            return Err(format!(
                "refused: a well-formed class file was refused: {first}"
            ));
        }
        return Ok(());
    }
    rows_out(&std::fs::read(&results).unwrap_or_default(), &c)
}

/// results.csv against the class file: the row count when known, rows in input order, on
/// lines the file has, each with a known status.
fn rows_out(results: &[u8], c: &Case<'_>) -> Result<(), String> {
    let mut reader = csv::ReaderBuilder::new().from_reader(results);
    let header = reader
        .headers()
        .map_err(|e| format!("results: unreadable header: {e}"))?
        .clone();
    let at = |n: &str| header.iter().position(|h| h == n);
    let (Some(row_at), Some(status_at)) = (at("row"), at("status")) else {
        return Err("results: no `row` or `status` column".into());
    };
    let lines = c.file.split(|&b| b == b'\n' || b == b'\r').count() as u64 + 1;
    let mut count = 0;
    let mut last = 0u64;
    for record in reader.records() {
        let record = record.map_err(|e| format!("results: unreadable row: {e}"))?;
        count += 1;
        let row: u64 = record
            .get(row_at)
            .and_then(|v| v.parse().ok())
            .ok_or_else(|| format!("results: row {count} has no line number"))?;
        if row < 2 || row > lines || row < last {
            return Err(format!(
                "line-numbers: results row {count} says line {row} (after {last}; the file has at most {lines})"
            ));
        }
        last = row;
        let status = record.get(status_at).unwrap_or("");
        if !["correct", "incorrect", "invalid", "error"].contains(&status) {
            return Err(format!("results: row {count} has status `{status}`"));
        }
    }
    match c.rows {
        Some(want) if want != count => Err(format!(
            "rows-lost: {want} rows in, {count} rows in results.csv"
        )),
        _ => Ok(()),
    }
}

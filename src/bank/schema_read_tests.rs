//! The schema reader against serde's derive (kept for tests only): on every problem file of
//! the repository and on thousands of variations of them — each value replaced by values of
//! every TOML type, out-of-range numbers and date-times, each line removed, each key renamed —
//! both readers give the same problem file, or the same message at the same span.

use std::path::{Path, PathBuf};

use super::*;
use crate::bank::schema::ProblemFile;

/// Every `.toml` problem file under the repository's problem, example and test folders.
fn corpus() -> Vec<(PathBuf, String)> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for e in entries.flatten() {
            let p = e.path();
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|x| x == "toml") {
                out.push(p);
            }
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    for dir in ["problems", "examples", "tests", "web/e2e/fixtures"] {
        walk(&root.join(dir), &mut files);
    }
    files.sort();
    files
        .into_iter()
        .filter_map(|p| Some((p.clone(), std::fs::read_to_string(&p).ok()?)))
        .collect()
}

/// Both readers' outcome on `text`: the file's debug form, or the message and span.
fn both(text: &str) -> (Result<String, ReadError>, Result<String, ReadError>) {
    let ours = from_str::<ProblemFile>(text).map(|p| format!("{p:?}"));
    let serde = toml::from_str::<ProblemFile>(text)
        .map(|p| format!("{p:?}"))
        .map_err(|e| ReadError {
            message: e.message().to_string(),
            span: e.span(),
        });
    (ours, serde)
}

/// Values of every TOML type, and numbers at and past the limits of the schema's types.
const VALUES: &[&str] = &[
    "3",
    "-1",
    "0",
    "1.5",
    "-2.0",
    "true",
    "\"x\"",
    "\"\"",
    "[]",
    "[1, 2]",
    "[\"a\", \"b\"]",
    "[[\"a\"]]",
    "[1.5, \"x\"]",
    "[true]",
    "[{ a = 1 }]",
    "{}",
    "{ a = 1 }",
    "{ name = \"q\" }",
    "1979-05-27",
    "1979-05-27T07:32:00Z",
    "07:32:00",
    "4294967296",
    "9223372036854775808",
    "99999999999999999999",
    "999999999999999999999999999999999999999999",
    "1e999",
    "inf",
    "nan",
    "0x10",
    "[\"point\", \"m\", [\"x\", \"y\"]]",
    "[1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23]",
];

/// The byte ranges of the simple values in `text` (`key = value`, at any depth of inline
/// tables and arrays): strings, numbers, booleans and arrays without nested arrays.
fn value_spans(text: &str) -> Vec<std::ops::Range<usize>> {
    let b = text.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i + 2 < b.len() {
        if b[i] == b'=' && b[i + 1] == b' ' && i > 0 && b[i - 1] == b' ' {
            let start = i + 2;
            let mut end = start;
            match b.get(start) {
                Some(b'"') if !text[start..].starts_with("\"\"\"") => {
                    end += 1;
                    while end < b.len() && b[end] != b'"' && b[end] != b'\n' {
                        end += usize::from(b[end] == b'\\') + 1;
                    }
                    end += 1;
                }
                Some(b'[') => {
                    while end < b.len() && b[end] != b']' && b[end] != b'\n' {
                        end += 1;
                    }
                    end += 1;
                }
                Some(_) => {
                    while end < b.len() && !b",}]\n #".contains(&b[end]) {
                        end += 1;
                    }
                }
                None => {}
            }
            if end > start && end <= b.len() && text.is_char_boundary(end) {
                out.push(start..end);
            }
        }
        i += 1;
    }
    out
}

#[test]
fn the_reader_agrees_with_serde_on_every_file_and_variation() {
    let files = corpus();
    assert!(
        files.len() >= 40,
        "the corpus is found ({} files)",
        files.len()
    );
    let (mut cases, mut errors) = (0usize, 0usize);
    // Unoptimised (the CI's `cargo test`), one variation in three is read: every file, value
    // and line still, about 30 s instead of 90. `cargo test --release` reads them all.
    let stride = if cfg!(debug_assertions) { 3 } else { 1 };
    let mut seen = 0usize;
    let mut check = |name: &str, text: &str| {
        seen += 1;
        if !seen.is_multiple_of(stride) && !name.ends_with(".toml") {
            return;
        }
        let (ours, serde) = both(text);
        assert_eq!(ours, serde, "{name}");
        cases += 1;
        errors += usize::from(ours.is_err());
    };
    for (path, text) in &files {
        let name = path.display().to_string();
        check(&name, text);
        for span in value_spans(text) {
            for v in VALUES {
                let changed = format!("{}{v}{}", &text[..span.start], &text[span.end..]);
                check(&format!("{name} with {v} at {span:?}"), &changed);
            }
        }
        let lines: Vec<&str> = text.lines().collect();
        for i in 0..lines.len() {
            let mut without = lines.clone();
            without.remove(i);
            check(
                &format!("{name} without line {}", i + 1),
                &without.join("\n"),
            );
            if let Some((key, rest)) = lines[i].split_once(" = ") {
                let mut renamed = lines.clone();
                let line = format!("{key}_zz = {rest}");
                renamed[i] = &line;
                check(
                    &format!("{name} line {} renamed", i + 1),
                    &renamed.join("\n"),
                );
            }
        }
    }
    // The variations reached the readers' error paths, not only the parser's.
    assert!(
        cases * stride > 10_000 && errors * stride > 5_000,
        "{cases} cases, {errors} errors"
    );
}

#[test]
fn a_struct_is_read_from_an_array_field_by_field_as_serde_does() {
    // `name`, then `periodic` (a default), then `range` (an Option, but no default): missing.
    let text = "id = \"a\"\ntitle = \"t\"\ncoordinates = [[\"q\", true]]\nparts = []\n";
    let (ours, serde) = both(text);
    assert_eq!(ours, serde);
    let text = "id = \"a\"\ntitle = \"t\"\ncoordinates = [[\"q\"]]\nparts = []\n";
    let (ours, serde) = both(text);
    assert_eq!(ours, serde);
    assert!(ours.is_err_and(
        |e| e.message == "invalid length 2, expected struct CoordinateSpec with 6 elements"
    ));
}

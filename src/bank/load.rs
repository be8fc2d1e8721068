//! Loading problem files: from text, from a folder, or the embedded bank. A file that
//! cannot be read becomes a finding with its line; the other files load regardless.

use std::path::Path;

use super::build::build;
use super::finding::{Finding, line_of};
use super::schema::ProblemFile;
use crate::problem::Problem;

/// Largest problem file read, in bytes.
pub const MAX_FILE_BYTES: usize = 1 << 20;
/// Deepest nesting of arrays and tables accepted.
pub const MAX_NESTING: usize = 32;

/// Loaded problems and the files that failed to load.
#[derive(Debug, Default)]
pub struct Bank {
    pub problems: Vec<Problem>,
    pub failures: Vec<Finding>,
}

impl Bank {
    /// The problem with this id.
    pub fn problem(&self, id: &str) -> Option<&Problem> {
        self.problems.iter().find(|p| p.id == id)
    }
}

/// Loads one problem from TOML text; `file` names it in findings.
pub fn load_str(file: &str, text: &str) -> Result<Problem, Finding> {
    let fail = |line: usize, code: &'static str, message: String| Finding {
        file: file.to_string(),
        problem: None,
        part: None,
        line,
        code,
        message,
    };
    if text.len() > MAX_FILE_BYTES {
        return Err(fail(
            1,
            "too-large",
            format!(
                "the file is {} bytes; at most {MAX_FILE_BYTES} are read",
                text.len()
            ),
        ));
    }
    if let Some(at) = too_deep(text) {
        return Err(fail(
            line_of(text, at),
            "too-deep",
            format!("arrays and tables are nested more than {MAX_NESTING} deep"),
        ));
    }
    let pf: ProblemFile = toml::from_str(text).map_err(|e| {
        let line = e.span().map_or(1, |s| line_of(text, s.start));
        let msg = e.message().trim().to_string();
        let code = if msg.contains("unknown field") {
            "unknown-key"
        } else if msg.contains("missing field") {
            "missing-key"
        } else if msg.contains("invalid type") {
            "wrong-type"
        } else {
            "toml-syntax"
        };
        fail(line, code, msg)
    })?;
    build(file, text, pf)
}

/// The byte offset where nesting first exceeds the limit (outside strings and comments).
fn too_deep(text: &str) -> Option<usize> {
    let mut depth = 0usize;
    let mut in_str: Option<u8> = None;
    let mut comment = false;
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if comment {
            if c == b'\n' {
                comment = false;
            }
        } else if let Some(q) = in_str {
            if c == b'\\' && q == b'"' {
                i += 1;
            } else if c == q {
                in_str = None;
            }
        } else {
            match c {
                b'"' | b'\'' => in_str = Some(c),
                b'#' => comment = true,
                b'[' | b'{' => {
                    depth += 1;
                    if depth > MAX_NESTING {
                        return Some(i);
                    }
                }
                b']' | b'}' => depth = depth.saturating_sub(1),
                _ => {}
            }
        }
        i += 1;
    }
    None
}

/// Loads every `*.toml` file in `dir` (sorted by name).
pub fn load_dir(dir: &Path) -> Result<Bank, String> {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .map_err(|e| format!("cannot read {}: {e}", dir.display()))?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    entries.sort();
    let mut bank = Bank::default();
    for path in entries {
        let name = path.display().to_string();
        let text = match std::fs::read(&path) {
            Ok(bytes) => match String::from_utf8(bytes) {
                Ok(t) => t,
                Err(_) => {
                    bank.failures.push(Finding {
                        file: name,
                        problem: None,
                        part: None,
                        line: 1,
                        code: "not-utf8",
                        message: "the file is not UTF-8 text".into(),
                    });
                    continue;
                }
            },
            Err(e) => {
                bank.failures.push(Finding {
                    file: name,
                    problem: None,
                    part: None,
                    line: 1,
                    code: "unreadable-file",
                    message: e.to_string(),
                });
                continue;
            }
        };
        match load_str(&name, &text) {
            Ok(p) => {
                if bank.problem(&p.id).is_some() {
                    bank.failures.push(Finding {
                        file: name,
                        problem: Some(p.id.clone()),
                        part: None,
                        line: 1,
                        code: "duplicate-id",
                        message: format!("another file already defines `{}`", p.id),
                    });
                } else {
                    bank.problems.push(p);
                }
            }
            Err(f) => bank.failures.push(f),
        }
    }
    Ok(bank)
}

//! The student options of `problems show` and `check` (`--student KEY --seed S`) and
//! `lagrange problems export-sheets`: every student's sheets written as Markdown and LaTeX,
//! from a list of keys (one a line) or a class CSV's `student` column, through the safe
//! output writer (`src/outfile.rs`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;

use lagrange::bank::Problem;
use lagrange::problem::variant::normalise_key;
use lagrange::report::sheets::{latex, markdown};

/// The largest student list read.
const MAX_LIST_BYTES: u64 = 64 * 1024 * 1024;

/// Whose numbers: a student's key and the course seed.
#[derive(Args, Debug, Clone)]
pub struct StudentArgs {
    /// The student whose numbers to use (their key as in the class file: trimmed, case
    /// ignored).
    #[arg(long, value_name = "KEY")]
    pub student: Option<String>,
    /// The course seed: with the student's key it decides their numbers.
    #[arg(long, value_name = "S", default_value_t = 0)]
    pub seed: u64,
}

/// `lagrange problems export-sheets PROBLEM… --students FILE [--seed S] [--out DIR]`.
#[derive(Args, Debug)]
pub struct ExportArgs {
    /// The problem ids, in the order of the sheet.
    // Not `problems`: clap would mistake it for the global `--problems DIR`.
    #[arg(required = true, value_name = "PROBLEM")]
    ids: Vec<String>,
    /// The students: a file with one key a line, or a class CSV with a `student` column.
    #[arg(long, value_name = "FILE")]
    students: PathBuf,
    /// The course seed.
    #[arg(long, value_name = "S", default_value_t = 0)]
    seed: u64,
    /// The folder for the sheets (created if needed).
    #[arg(long, value_name = "DIR", default_value = "sheets")]
    out: PathBuf,
}

/// Writes `KEY.md` and `KEY.tex` per student and `index.csv` (student, files) into the folder.
pub fn export(args: &ExportArgs, dir: Option<&Path>) -> anyhow::Result<ExitCode> {
    let fail = |m: String| {
        eprintln!("error: {m}");
        Ok(ExitCode::from(2))
    };
    let mut problems: Vec<Problem> = Vec::new();
    for id in &args.ids {
        match crate::face::find_problem(dir, id).map_err(anyhow::Error::msg)? {
            Some(p) => problems.push(p),
            None => {
                return fail(format!(
                    "no problem `{}`\n  help: `lagrange problems list` shows the ids",
                    lagrange::expr::error::visible(id)
                ));
            }
        }
    }
    let students = match read_students(&args.students) {
        Ok(s) if s.is_empty() => {
            return fail(format!(
                "{} lists no student\n  help: one key a line, or a CSV with a `student` column",
                args.students.display()
            ));
        }
        Ok(s) => s,
        Err(m) => return fail(m),
    };
    let refs: Vec<&Problem> = problems.iter().collect();
    let names = file_names(&students);
    let mut index = String::from("student,markdown,latex\n");
    let mut files: Vec<(String, Vec<u8>)> = Vec::new();
    for (key, name) in students.iter().zip(&names) {
        let (md, tex) = (format!("{name}.md"), format!("{name}.tex"));
        index.push_str(&format!("{},{md},{tex}\n", csv_field(key)));
        files.push((md, markdown(&refs, key, args.seed).into_bytes()));
        files.push((tex, latex(&refs, key, args.seed).into_bytes()));
    }
    files.push(("index.csv".into(), index.into_bytes()));
    let all: Vec<&str> = files.iter().map(|(n, _)| n.as_str()).collect();
    let written = (|| {
        let folder = crate::face::outfile::Folder::open(&args.out, &all)?;
        let mut staged = Vec::with_capacity(files.len());
        for (name, bytes) in &files {
            staged.push(folder.stage(name, bytes)?);
        }
        crate::face::outfile::commit(staged)
    })();
    match written {
        Ok(w) => {
            println!(
                "{} students: {} files written to {}",
                students.len(),
                w.len(),
                args.out.display()
            );
            Ok(ExitCode::SUCCESS)
        }
        Err(m) => fail(m),
    }
}

/// The distinct student keys of `path` (trimmed; keys equal but for case are one, under the
/// first spelling), in order.
fn read_students(path: &Path) -> Result<Vec<String>, String> {
    let meta =
        std::fs::metadata(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    if meta.len() > MAX_LIST_BYTES {
        return Err(format!(
            "{} is over {} MB: not a student list",
            path.display(),
            MAX_LIST_BYTES >> 20
        ));
    }
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read {}: {e}", path.display()))?;
    let text = String::from_utf8(bytes)
        .map_err(|_| format!("{} is not UTF-8: save it as UTF-8 text", path.display()))?;
    Ok(students_of(text.trim_start_matches('\u{feff}')))
}

/// The keys of a list: a CSV's `student` column when its first line names one, else every
/// non-empty line.
fn students_of(text: &str) -> Vec<String> {
    let mut lines = text.lines();
    let header = lines.next().unwrap_or("");
    let delimiter = if header.matches(';').count() > header.matches(',').count() {
        ';'
    } else {
        ','
    };
    let column = split(header, delimiter)
        .iter()
        .position(|c| c.trim().eq_ignore_ascii_case("student"));
    let keys: Vec<String> = match column {
        Some(c) => lines
            .map(|l| split(l, delimiter).get(c).cloned().unwrap_or_default())
            .collect(),
        None => text.lines().map(str::to_string).collect(),
    };
    let mut seen = std::collections::BTreeSet::new();
    keys.into_iter()
        .map(|k| k.trim().to_string())
        .filter(|k| !k.is_empty() && seen.insert(normalise_key(k)))
        .collect()
}

/// The fields of one CSV line, honouring double quotes (`""` is a quote inside one).
fn split(line: &str, delimiter: char) -> Vec<String> {
    let mut out = vec![String::new()];
    let mut quoted = false;
    let mut chars = line.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '"' if quoted && chars.peek() == Some(&'"') => {
                chars.next();
                if let Some(f) = out.last_mut() {
                    f.push('"');
                }
            }
            '"' => quoted = !quoted,
            c if c == delimiter && !quoted => out.push(String::new()),
            c => {
                if let Some(f) = out.last_mut() {
                    f.push(c);
                }
            }
        }
    }
    out
}

/// One safe file name per student: the key lower-cased, characters other than letters,
/// digits, `.`, `-`, `_` and `@` made `_`, and a `-2`, `-3`… where two would collide.
fn file_names(students: &[String]) -> Vec<String> {
    let mut used = std::collections::BTreeSet::new();
    students
        .iter()
        .map(|k| {
            let base: String = normalise_key(k)
                .chars()
                .map(|c| {
                    if c.is_ascii_alphanumeric() || "._-@".contains(c) {
                        c
                    } else {
                        '_'
                    }
                })
                .take(80)
                .collect();
            let base = match base.trim_start_matches('.') {
                "" => "student".to_string(),
                b => b.to_string(),
            };
            let mut name = base.clone();
            let mut n = 1;
            while !used.insert(name.clone()) {
                n += 1;
                name = format!("{base}-{n}");
            }
            name
        })
        .collect()
}

/// `s` as one CSV field (quoted when it holds a comma, a quote or a line break).
fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn students_come_from_a_list_or_a_class_csv() {
        assert_eq!(students_of("ada\n\n Ben \nADA\n"), ["ada", "Ben"]);
        let csv = "problem,Student,answer\np,ada@x,\"a, b\"\np,\"ben@x\",c\np,ada@x,d\n";
        assert_eq!(students_of(csv), ["ada@x", "ben@x"]);
        assert_eq!(
            file_names(&["A b".into(), "a_b".into(), "../x".into()]),
            ["a_b", "a_b-2", "_x"]
        );
    }
}

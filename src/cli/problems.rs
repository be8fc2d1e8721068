//! `lagrange problems list|show|verify`: the bank, for students and instructors.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Subcommand;

use crate::face::{Terminal, load_bank, load_bank_with_findings};
use lagrange::bank::FindingCode;
use lagrange::bank::load::read_file;
use lagrange::bank::{Bank, load_dir, load_str};
use lagrange::report::{problem_list, problem_sheet, verification};

#[derive(Subcommand, Debug)]
pub enum ProblemsCommand {
    /// One line per problem: id, title and part ids.
    List,
    /// A problem's statement and parts, for the terminal.
    Show {
        /// The problem id.
        id: String,
        /// Also print the reference answers (for instructors).
        #[arg(long)]
        answers: bool,
        #[command(flatten)]
        student: super::sheets::StudentArgs,
    },
    /// Every student's sheets of the given problems, as Markdown and LaTeX files (one pair per
    /// student, each with that student's numbers).
    ExportSheets(super::sheets::ExportArgs),
    /// Prove every stated answer against the physics. With no PATH, the bank in use.
    Verify {
        /// Problem files or folders of them.
        paths: Vec<PathBuf>,
    },
    /// Draft a proved problem file from a system: a Lagrangian, or bodies (as for `derive`).
    New(Box<super::problem_new::NewArgs>),
    /// Write the built-in problems as TOML files into DIR, to start your own from.
    Export {
        /// The folder to write into (created if needed).
        dir: PathBuf,
        /// Also replace files there that lagrange did not export, or that were edited since.
        #[arg(long)]
        force: bool,
    },
}

pub fn run(
    cmd: &ProblemsCommand,
    dir: Option<&Path>,
    out: &mut String,
) -> anyhow::Result<ExitCode> {
    match cmd {
        ProblemsCommand::List => {
            let bank = load_bank(dir).map_err(anyhow::Error::msg)?;
            out.push_str(&problem_list(&bank).render(&Terminal));
            Ok(ExitCode::SUCCESS)
        }
        ProblemsCommand::ExportSheets(args) => super::sheets::export(args, dir),
        ProblemsCommand::Show {
            id,
            answers,
            student,
        } => {
            let found = crate::face::find_problem(dir, id).map_err(anyhow::Error::msg)?;
            let Some(p) = found.as_ref() else {
                eprintln!(
                    "error: no problem `{id}`\n  help: `lagrange problems list` shows the ids"
                );
                return Ok(ExitCode::from(2));
            };
            let sheet = match &student.student {
                Some(key) => {
                    lagrange::report::sheets::student_sheet(p, *answers, key, student.seed)
                }
                None => problem_sheet(p, *answers),
            };
            out.push_str(&sheet.render(&Terminal));
            Ok(ExitCode::SUCCESS)
        }
        ProblemsCommand::Verify { paths } => {
            let bank = if paths.is_empty() {
                load_bank_with_findings(dir).map_err(anyhow::Error::msg)?
            } else {
                match load_paths(paths)? {
                    Ok(b) => b,
                    Err(message) => {
                        eprintln!("error: {message}");
                        return Ok(ExitCode::from(2));
                    }
                }
            };
            let v = verification(&bank);
            out.push_str(&v.render(&Terminal));
            Ok(if v.failing() > 0 {
                ExitCode::from(1)
            } else {
                ExitCode::SUCCESS
            })
        }
        ProblemsCommand::Export { dir, force } => export(dir, *force, out),
        ProblemsCommand::New(args) => super::problem_new::run(
            args,
            colored::control::SHOULD_COLORIZE.should_colorize(),
            out,
        ),
    }
}

/// `problems export DIR`: every built-in problem as a file, all or none. A file already at a
/// name is replaced only when it is what lagrange exported and nobody has edited it since
/// (its first line's fingerprint still matches), or with `--force`: an instructor's edits are
/// never lost to a second export. Files are written whole and renamed into place
/// (`outfile`), so a reader never sees half a file.
fn export(dir: &Path, force: bool, out: &mut String) -> anyhow::Result<ExitCode> {
    use lagrange::bank::export::{Existing, classify, exported};
    let files = exported();
    let mut kept = Vec::new();
    let mut same = 0;
    let mut todo = Vec::new();
    for f in &files {
        let path = dir.join(f.name);
        let existing = match std::fs::symlink_metadata(&path) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => None,
            // A link, a folder or a device at the name: `outfile` refuses it with the reason.
            Ok(m) if !m.is_file() => Some(Existing::Other),
            _ => Some(match read_file(&path) {
                Ok(text) => classify(&text, f),
                Err(_) => Existing::Other,
            }),
        };
        match existing {
            Some(Existing::Same) => same += 1,
            Some(Existing::Other) if !force => kept.push(path.display().to_string()),
            _ => todo.push(f),
        }
    }
    if !kept.is_empty() {
        eprintln!(
            "error: nothing exported: {} would replace a file that lagrange did not export, or that was edited since\n  help: export into another folder, or give --force to replace {}",
            kept.join(", "),
            if kept.len() == 1 { "it" } else { "them" }
        );
        return Ok(ExitCode::from(2));
    }
    let names: Vec<&str> = todo.iter().map(|f| f.name).collect();
    let folder = crate::face::outfile::Folder::open(dir, &names).map_err(anyhow::Error::msg)?;
    let staged = todo
        .iter()
        .map(|f| folder.stage(f.name, f.text.as_bytes()))
        .collect::<Result<Vec<_>, _>>()
        .map_err(anyhow::Error::msg)?;
    crate::face::outfile::commit(staged).map_err(anyhow::Error::msg)?;
    out.push_str(&format!(
        "{} problems exported to {} ({} written, {} unchanged)\n  next: `lagrange problems verify {}` proves them; `--add-problems {}` uses them beside the built-in ones\n",
        files.len(),
        dir.display(),
        todo.len(),
        same,
        dir.display(),
        dir.display()
    ));
    Ok(ExitCode::SUCCESS)
}

/// A bank of the given files and folders; a file that cannot be opened is an error of its
/// own (the inner `Err`), while a file that does not load — including one that is not a
/// regular file, is too large or is not UTF-8, refused before it is read — is one of the
/// bank's failures.
fn load_paths(paths: &[PathBuf]) -> anyhow::Result<Result<Bank, String>> {
    let mut b = Bank::default();
    for path in paths {
        if path.is_dir() {
            let sub = load_dir(path).map_err(anyhow::Error::msg)?;
            b.failures.extend(sub.failures);
            for p in sub.problems {
                let file = p.file.clone();
                b.add(p, file);
            }
            continue;
        }
        let name = path.display().to_string();
        match read_file(path) {
            Ok(text) => match load_str(&name, &text) {
                Ok(p) => b.add(p, name),
                Err(f) => b.failures.push(f),
            },
            Err(f) if f.code == FindingCode::UnreadableFile => {
                return Ok(Err(format!("cannot read {name}: {}", f.message)));
            }
            Err(f) => b.failures.push(f),
        }
    }
    Ok(Ok(b))
}

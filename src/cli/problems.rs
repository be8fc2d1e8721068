//! `lagrange problems list|show|verify`: the bank, for students and instructors.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Subcommand;

use super::system_args::Terminal;
use lagrange::bank::load::{DUPLICATE_ID, Replaced, load_one, merge, read_file};
use lagrange::bank::{Bank, Problem, embedded, load_dir, load_str};
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
    },
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

/// The bank from `dir`, or the embedded one, refused whole when two files define one
/// problem id (a grade and a check would otherwise judge by different files).
pub fn load_bank(dir: Option<&Path>) -> Result<Bank, String> {
    let bank = load_bank_with_findings(dir)?;
    match bank.failures.iter().find(|f| f.code == DUPLICATE_ID) {
        Some(f) => Err(f.message.clone()),
        None => Ok(bank),
    }
}

/// The folder `--add-problems` adds to the built-in bank, set once from the command line.
/// Every face reaches the bank through [`load_bank`] and [`find_problem`] (the commands, the
/// grader, the REPL), so the folder is kept here rather than threaded through each command's
/// arguments beside `--problems`.
static ADDED: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();

/// Records the `--add-problems` folder (the first call wins; `run` makes the only one).
pub fn set_added(dir: PathBuf) {
    let _ = ADDED.set(dir);
}

/// The bank from `dir`, or the embedded one, with every file that failed to load (a
/// duplicate id among them) as a finding: what `problems verify` reports.
fn load_bank_with_findings(dir: Option<&Path>) -> Result<Bank, String> {
    match (dir, ADDED.get()) {
        (Some(d), _) => load_dir(d),
        (None, Some(added)) => {
            let (bank, replaced) = merge(embedded::bank(), load_dir(added)?);
            for r in &replaced {
                eprintln!("{}", r.note());
            }
            Ok(bank)
        }
        (None, None) => Ok(embedded::bank()),
    }
}

/// The one problem a command is about, from `dir` or the embedded bank, building only that
/// problem (a folder of 30,000 files is not loaded whole to check one answer).
pub fn find_problem(dir: Option<&Path>, id: &str) -> Result<Option<Problem>, String> {
    match (dir, ADDED.get()) {
        (Some(d), _) => load_one(d, id),
        (None, Some(added)) => match load_one(added, id)? {
            Some(p) => {
                if embedded::is_built_in(id) {
                    let note = Replaced {
                        id: id.to_string(),
                        file: p.file.clone(),
                    };
                    eprintln!("{}", note.note());
                }
                Ok(Some(p))
            }
            None => Ok(embedded::problem(id)),
        },
        (None, None) => Ok(embedded::problem(id)),
    }
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
        ProblemsCommand::Show { id, answers } => {
            let found = find_problem(dir, id).map_err(anyhow::Error::msg)?;
            let Some(p) = found.as_ref() else {
                eprintln!(
                    "error: no problem `{id}`\n  help: `lagrange problems list` shows the ids"
                );
                return Ok(ExitCode::from(2));
            };
            out.push_str(&problem_sheet(p, *answers).render(&Terminal));
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
    let folder = crate::outfile::Folder::open(dir, &names).map_err(anyhow::Error::msg)?;
    let staged = todo
        .iter()
        .map(|f| folder.stage(f.name, f.text.as_bytes()))
        .collect::<Result<Vec<_>, _>>()
        .map_err(anyhow::Error::msg)?;
    crate::outfile::commit(staged).map_err(anyhow::Error::msg)?;
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
            Err(f) if f.code == "unreadable-file" => {
                return Ok(Err(format!("cannot read {name}: {}", f.message)));
            }
            Err(f) => b.failures.push(f),
        }
    }
    Ok(Ok(b))
}

//! `lagrange problems list|show|verify`: the bank, for students and instructors.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Subcommand;

use super::system_args::Terminal;
use lagrange::bank::load::{DUPLICATE_ID, load_one, read_file};
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

/// The bank from `dir`, or the embedded one, with every file that failed to load (a
/// duplicate id among them) as a finding: what `problems verify` reports.
fn load_bank_with_findings(dir: Option<&Path>) -> Result<Bank, String> {
    match dir {
        Some(d) => load_dir(d),
        None => Ok(embedded::bank()),
    }
}

/// The one problem a command is about, from `dir` or the embedded bank, building only that
/// problem (a folder of 30,000 files is not loaded whole to check one answer).
pub fn find_problem(dir: Option<&Path>, id: &str) -> Result<Option<Problem>, String> {
    match dir {
        Some(d) => load_one(d, id),
        None => Ok(embedded::problem(id)),
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
        ProblemsCommand::ExportSheets(args) => super::sheets::export(args, dir),
        ProblemsCommand::Show {
            id,
            answers,
            student,
        } => {
            let found = find_problem(dir, id).map_err(anyhow::Error::msg)?;
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
    }
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

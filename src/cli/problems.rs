//! `lagrange problems list|show|verify`: the bank, for students and instructors.

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Subcommand;

use super::system_args::Terminal;
use lagrange::bank::{Bank, embedded, load_dir, load_str};
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
}

/// The bank from `dir`, or the embedded one.
pub fn load_bank(dir: Option<&Path>) -> Result<Bank, String> {
    match dir {
        Some(d) => load_dir(d),
        None => Ok(embedded::bank()),
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
            let bank = load_bank(dir).map_err(anyhow::Error::msg)?;
            let Some(p) = bank.problem(id) else {
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
                load_bank(dir).map_err(anyhow::Error::msg)?
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

/// A bank of the given files and folders; a file that cannot be read is an error of its own
/// (the inner `Err`), while a file that does not load is one of the bank's failures.
fn load_paths(paths: &[PathBuf]) -> anyhow::Result<Result<Bank, String>> {
    let mut b = Bank::default();
    for path in paths {
        if path.is_dir() {
            let sub = load_dir(path).map_err(anyhow::Error::msg)?;
            b.problems.extend(sub.problems);
            b.failures.extend(sub.failures);
            continue;
        }
        let name = path.display().to_string();
        match std::fs::read_to_string(path) {
            Ok(text) => match load_str(&name, &text) {
                Ok(p) => b.problems.push(p),
                Err(f) => b.failures.push(f),
            },
            Err(e) => return Ok(Err(format!("cannot read {name}: {e}"))),
        }
    }
    Ok(Ok(b))
}

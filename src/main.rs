//! The `lagrange` command line: a thin clap layer over the library. It parses the top-level
//! arguments and hands the command to its face — the command line's own commands ([`cli`]),
//! the class grader ([`grade`]) or the REPL ([`repl`]) — which calls the library and prints;
//! no face holds mathematics. The faces share only [`face`] (output files, the progress bar,
//! pictures, the terminal) and never import each other; this file is the one place that
//! sees them all.
//!
//! Exit codes: 0 success, 1 "no" (the input could not be read or is inconsistent),
//! 2 usage or other error.

mod cli;
mod face;
mod grade;
mod repl;

use std::io::IsTerminal;
use std::process::ExitCode;

use clap::{CommandFactory, Parser, Subcommand, ValueEnum};

/// Check, derive and explain analytical mechanics.
#[derive(Parser, Debug)]
#[command(name = "lagrange", version, about)]
struct Cli {
    /// When to use colour: auto (a terminal, unless NO_COLOR is set), always or never.
    #[arg(long, global = true, value_enum, default_value_t = ColorChoice::Auto)]
    color: ColorChoice,
    /// Load the problem bank from this folder of TOML files instead of the built-in one.
    #[arg(long, global = true, value_name = "DIR")]
    problems: Option<std::path::PathBuf>,
    /// Add this folder of TOML files to the built-in problems; a file with a built-in id
    /// replaces that problem (a note says so).
    #[arg(long, global = true, value_name = "DIR", conflicts_with = "problems")]
    add_problems: Option<std::path::PathBuf>,
    /// With no command, the REPL opens when stdin is a terminal (help is printed otherwise).
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum ColorChoice {
    Auto,
    Always,
    Never,
}

/// Every command: the command line's own, then the grader's and the REPL's.
#[derive(Subcommand, Debug)]
enum Command {
    #[command(flatten)]
    Cli(Box<cli::Command>),
    /// Grade a class from a CSV file: results, a gradebook, a summary of the mistakes.
    Grade(grade::GradeArgs),
    /// Practise the problems: answers checked as you type them, hints, progress kept.
    Repl(repl::ReplArgs),
}

fn main() -> ExitCode {
    match run() {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

/// Parses arguments and runs the command.
fn run() -> anyhow::Result<ExitCode> {
    let args = Cli::parse();
    let color = match args.color {
        ColorChoice::Always => true,
        ColorChoice::Never => false,
        ColorChoice::Auto => {
            std::io::stdout().is_terminal() && std::env::var_os("NO_COLOR").is_none()
        }
    };
    colored::control::set_override(color);
    let command = match args.command {
        Some(c) => c,
        None if std::io::stdin().is_terminal() => Command::Repl(repl::ReplArgs::default()),
        None => {
            eprint!("{}", Cli::command().render_help());
            return Ok(ExitCode::from(2));
        }
    };
    if let Some(dir) = args.add_problems {
        face::set_added(dir);
    }
    match command {
        Command::Cli(c) => cli::run(*c, args.problems.as_deref(), color),
        Command::Grade(g) => grade::run(&g.options(args.problems.as_deref())),
        Command::Repl(r) => repl::run(&repl::Options {
            problem: r.problem,
            json: r.json,
            no_save: r.no_save,
            problems: args.problems,
            color,
        }),
    }
}

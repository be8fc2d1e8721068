//! Argument definitions (clap) and dispatch. Clap types stay in the binary; the library
//! never sees them.

mod body_args;
mod chaos;
mod check;
mod derive;
mod grade;
mod grid;
mod modes;
pub(crate) mod problems;
mod read;
mod sheets;
mod simulate;
pub(crate) mod system_args;

use std::io::IsTerminal;
use std::process::ExitCode;

use clap::{Args, CommandFactory, Parser, Subcommand, ValueEnum};

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

#[derive(Subcommand, Debug)]
enum Command {
    /// Show how an input is read: plain, Unicode and LaTeX forms, symbols, dimension, and
    /// optionally a derivative.
    Read(read::ReadArgs),
    /// Derive the Euler–Lagrange equations of a Lagrangian, with every step, the mass matrix,
    /// the energy function, conserved momenta and constraint multipliers.
    Derive(derive::DeriveArgs),
    /// Find equilibria, their stability, normal-mode frequencies and shapes.
    Modes(modes::ModesArgs),
    /// Check an answer to a part of a problem: the verdict and, if wrong, why.
    Check(check::CheckArgs),
    /// List, show and verify the problems of the bank.
    #[command(subcommand)]
    Problems(problems::ProblemsCommand),
    /// Integrate a system's motion: a summary, states at asked times, JSON or a CSV grid.
    Simulate(simulate::SimulateArgs),
    /// Sensitivity to initial conditions: the largest Lyapunov exponent, the separation of
    /// nearby motions, a Poincaré section.
    Chaos(chaos::ChaosArgs),
    /// Grade a class from a CSV file: results, a gradebook, a summary of the mistakes.
    Grade(grade::GradeArgs),
    /// Practise the problems: answers checked as you type them, hints, progress kept.
    Repl(ReplArgs),
}

/// `lagrange repl [PROBLEM] [--json] [--no-save]`.
#[derive(Args, Debug, Default)]
struct ReplArgs {
    /// A problem id to open first.
    problem: Option<String>,
    /// One JSON object per input line (JSON lines; see docs/repl-protocol.md).
    #[arg(long)]
    json: bool,
    /// Keep no progress file.
    #[arg(long)]
    no_save: bool,
}

/// Parses arguments and runs the command.
pub fn run() -> anyhow::Result<ExitCode> {
    let cli = Cli::parse();
    let color = match cli.color {
        ColorChoice::Always => true,
        ColorChoice::Never => false,
        ColorChoice::Auto => {
            std::io::stdout().is_terminal() && std::env::var_os("NO_COLOR").is_none()
        }
    };
    colored::control::set_override(color);
    let command = match cli.command {
        Some(c) => c,
        None if std::io::stdin().is_terminal() => Command::Repl(ReplArgs::default()),
        None => {
            eprint!("{}", Cli::command().render_help());
            return Ok(ExitCode::from(2));
        }
    };
    let mut out = String::new();
    let code = match command {
        Command::Read(args) => read::run(&args, color, &mut out),
        Command::Derive(args) => derive::run(&args, cli.problems.as_deref(), color, &mut out),
        Command::Modes(args) => modes::run(&args, cli.problems.as_deref(), color, &mut out),
        Command::Check(args) => check::run(&args, cli.problems.as_deref(), color, &mut out),
        Command::Simulate(args) => simulate::run(&args, cli.problems.as_deref(), color, &mut out),
        Command::Chaos(args) => chaos::run(&args, cli.problems.as_deref(), color, &mut out),
        Command::Problems(cmd) => problems::run(&cmd, cli.problems.as_deref(), &mut out),
        Command::Grade(args) => return grade::run(&args, cli.problems.as_deref()),
        Command::Repl(args) => {
            return crate::repl::run(&crate::repl::Options {
                problem: args.problem,
                json: args.json,
                no_save: args.no_save,
                problems: cli.problems,
                color,
            });
        }
    };
    emit(&out)?;
    code
}

/// Writes a command's output; a closed pipe (`lagrange … | head`) is not an error.
pub(crate) fn emit(text: &str) -> std::io::Result<()> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
    {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => other,
    }
}

//! The command line's own commands: their clap arguments and dispatch (`read`, `derive`,
//! `modes`, `check`, `problems`, `simulate`, `chaos`). `src/main.rs` parses the top level and
//! hands these here, `grade` and `repl` to their own faces. Clap types stay in the binary; the
//! library never sees them.

mod chaos;
mod check;
mod derive;
mod modes;
mod problem_new;
mod problems;
mod read;
mod sheets;
mod simulate;
pub(crate) mod system_args;

use std::path::Path;
use std::process::ExitCode;

use clap::Subcommand;

use crate::face::emit;

/// The commands of the command-line face.
#[derive(Subcommand, Debug)]
pub enum Command {
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
}

/// Runs one command with the bank folder of `--problems` and the resolved colour choice.
pub fn run(command: Command, problems: Option<&Path>, color: bool) -> anyhow::Result<ExitCode> {
    let mut out = String::new();
    let code = match command {
        Command::Read(args) => read::run(&args, color, &mut out),
        Command::Derive(args) => derive::run(&args, problems, color, &mut out),
        Command::Modes(args) => modes::run(&args, problems, color, &mut out),
        Command::Check(args) => check::run(&args, problems, color, &mut out),
        Command::Simulate(args) => simulate::run(&args, problems, color, &mut out),
        Command::Chaos(args) => chaos::run(&args, problems, color, &mut out),
        Command::Problems(cmd) => problems::run(&cmd, problems, &mut out),
    };
    emit(&out)?;
    code
}

//! `lagrange derive`: the Euler–Lagrange equations with every step, M and f, the energy
//! function and the conserved quantities, and the multipliers of constraints.

use std::process::ExitCode;

use clap::{Args, ValueEnum};

use super::system_args::{CliError, SystemArgs, Terminal, report};
use lagrange::expr::Style;
use lagrange::report::modes::assignments;

#[derive(Clone, Copy, Debug, ValueEnum, PartialEq, Eq)]
pub enum Format {
    Text,
    Latex,
    Json,
}

#[derive(Args, Debug)]
pub struct DeriveArgs {
    #[command(flatten)]
    system: SystemArgs,
    /// Output format.
    #[arg(long, value_enum, default_value_t = Format::Text)]
    format: Format,
    /// Same as --format json.
    #[arg(long)]
    json: bool,
    /// Also the accelerations and the multipliers at this state, e.g.
    /// "x=0.6, y=-0.8, x'=0.8, y'=0.6" (velocities default to 0; values may be expressions).
    #[arg(long, allow_hyphen_values = true)]
    at: Option<String>,
    /// Parameter values for --at, e.g. "m=1, g=9.81".
    #[arg(long, default_value = "", allow_hyphen_values = true)]
    params: String,
}

pub fn run(
    args: &DeriveArgs,
    problems: Option<&std::path::Path>,
    color: bool,
    out: &mut String,
) -> anyhow::Result<ExitCode> {
    if args.at.is_none() && !args.params.trim().is_empty() {
        let e = CliError::usage("--params gives values for --at: give the state with --at too");
        return Ok(report(&e, color));
    }
    let derived = args.system.build(problems).and_then(|sys| match &args.at {
        None => {
            // The derivation first: its validation names a malformed constraint (`1 = 0`).
            let d = lagrange::report::derivation(&sys)?;
            lagrange::report::derivation_at::check_real(&sys).map_err(coded)?;
            Ok(d)
        }
        Some(at) => at_state(&sys, at, &args.params),
    });
    let report_ = match derived {
        Ok(r) => r,
        Err(e) => return Ok(report(&e, color)),
    };
    let format = if args.json { Format::Json } else { args.format };
    match format {
        Format::Json => {
            out.push_str(&serde_json::to_string_pretty(&report_)?);
            out.push('\n');
        }
        Format::Latex => out.push_str(&report_.render(Style::Latex, &Terminal)),
        Format::Text => out.push_str(&report_.render(Style::Unicode, &Terminal)),
    }
    Ok(ExitCode::SUCCESS)
}

/// The derivation with the accelerations and multipliers at the state `at`.
fn at_state(
    sys: &lagrange::mechanics::System,
    at: &str,
    params: &str,
) -> Result<lagrange::report::DerivationReport, CliError> {
    use lagrange::report::derivation_at::derivation_at;
    let usage = |e: lagrange::report::modes::BadAssignment| CliError::Usage(e.to_string());
    let at = assignments(at).map_err(usage)?;
    let params = assignments(params).map_err(usage)?;
    derivation_at(sys, &params, &at).map_err(coded)
}

/// The CLI's error for a state error: a mechanics error as such, the others with their code.
fn coded(e: lagrange::report::derivation_at::StateError) -> CliError {
    use lagrange::report::derivation_at::StateError;
    match e {
        StateError::Mech(e) => CliError::Mech(e),
        e @ StateError::NoRealState { .. } => CliError::Coded {
            code: e.code(),
            message: e.to_string(),
            help: e.help(),
        },
        e => CliError::Coded {
            code: e.code(),
            message: format!("--at: {e}"),
            help: e.help(),
        },
    }
}

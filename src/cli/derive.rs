//! `lagrange derive`: the Euler–Lagrange equations with every step, M and f, the energy
//! function and the conserved quantities, and the multipliers of constraints.

use std::process::ExitCode;

use clap::{Args, ValueEnum};

use super::system_args::{SystemArgs, Terminal, report};
use lagrange::expr::Style;

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
}

pub fn run(
    args: &DeriveArgs,
    problems: Option<&std::path::Path>,
    color: bool,
    out: &mut String,
) -> anyhow::Result<ExitCode> {
    let derived = args
        .system
        .build(problems)
        .and_then(|sys| Ok(lagrange::report::derivation(&sys)?));
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

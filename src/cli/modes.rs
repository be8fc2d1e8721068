//! `lagrange modes`: equilibria, their stability, frequencies and mode shapes; with
//! `--symbolic`, the characteristic polynomial and ω² in closed form.

use std::process::ExitCode;

use clap::Args;

use super::system_args::{CliError, SystemArgs, Terminal, report};
use lagrange::expr::Style;
use lagrange::mechanics::MechError;
use lagrange::report::modes::assignments;
use lagrange::report::{ModesError, ModesOptions, ModesReport};

#[derive(Args, Debug)]
pub struct ModesArgs {
    #[command(flatten)]
    system: SystemArgs,
    /// Parameter values, e.g. "m=1, l=2, g=9.81"; a value may be an expression in other
    /// parameters ("m1=m, l2=l"), which then stay symbolic.
    #[arg(long, default_value = "", allow_hyphen_values = true)]
    params: String,
    /// Only this equilibrium, e.g. "theta1=0, theta2=0" (values may be expressions).
    #[arg(long, allow_hyphen_values = true)]
    at: Option<String>,
    /// Search range of non-periodic coordinates, e.g. "x=-50:50" (default −10:10).
    #[arg(long, allow_hyphen_values = true)]
    range: Vec<String>,
    /// Also the characteristic polynomial and ω² in closed form (needs --at).
    #[arg(long)]
    symbolic: bool,
    /// Steady motions: fix the momenta of cyclic coordinates, e.g. "p_phi=2" (a bare "p_phi"
    /// keeps it symbolic, taken as positive in closed forms); the equilibria and modes are then
    /// those of the Routhian (circular orbits, the conical pendulum, steady precession).
    #[arg(long, allow_hyphen_values = true)]
    steady: Option<String>,
    /// JSON output.
    #[arg(long)]
    json: bool,
}

pub fn run(
    args: &ModesArgs,
    problems: Option<&std::path::Path>,
    color: bool,
    out: &mut String,
) -> anyhow::Result<ExitCode> {
    let report_ = match modes_report(args, problems) {
        Ok(r) => r,
        Err(e) => return Ok(report(&e, color)),
    };
    if args.json {
        out.push_str(&serde_json::to_string_pretty(&report_)?);
        out.push('\n');
    } else {
        out.push_str(&report_.render(Style::Unicode, &Terminal));
    }
    Ok(ExitCode::SUCCESS)
}

fn modes_report(
    args: &ModesArgs,
    problems: Option<&std::path::Path>,
) -> Result<ModesReport, CliError> {
    let sys = args.system.build(problems)?;
    let opts = options(args)?;
    lagrange::report::modes(&sys, &opts).map_err(|e| match e {
        ModesError::Mech(e) => CliError::Mech(e),
        ModesError::MissingPointValue { name } => {
            CliError::Usage(format!("--at gives no value for `{name}`"))
        }
        ModesError::PointValue {
            coordinate,
            source_text,
            error,
        } => CliError::Mech(MechError::Parse {
            what: format!("--at {coordinate}"),
            source_text,
            error,
        }),
        ModesError::UndefinedValue { .. } => CliError::Usage(format!(
            "{e}: give --params a number (or an expression in other parameters)"
        )),
        ModesError::PointNotNumeric => CliError::usage("--at values must be numbers here"),
        ModesError::SymbolicNeedsPoint => {
            CliError::usage("--symbolic needs the equilibrium, given with --at")
        }
        ModesError::Steady(lagrange::mechanics::steady::SteadyError::Mech(e)) => CliError::Mech(e),
        ModesError::Steady(e) => CliError::Usage(format!("--steady: {e}; {}", e.help())),
        ModesError::ConstrainedNeedsPoint => CliError::Usage(format!(
            "{e}: give the equilibrium with --at, e.g. --at \"x=0, y=-L\""
        )),
        ModesError::SymbolicConstrained => CliError::Usage(format!("{e}: drop --symbolic")),
    })
}

/// The library's options from the flags.
fn options(args: &ModesArgs) -> Result<ModesOptions, CliError> {
    let usage = |e: lagrange::report::modes::BadAssignment| CliError::Usage(e.to_string());
    Ok(ModesOptions {
        // A typed Lagrangian has no ranges of its own; a problem's are kept.
        default_range: args.system.problem.is_none().then_some((-10.0, 10.0)),
        ranges: args
            .range
            .iter()
            .map(|r| range(r))
            .collect::<Result<_, _>>()?,
        params: assignments(&args.params).map_err(usage)?,
        at: args
            .at
            .as_deref()
            .map(assignments)
            .transpose()
            .map_err(usage)?,
        symbolic: args.symbolic,
        steady: args.steady.as_deref().map_or_else(Vec::new, steady),
    })
}

/// `p_phi=2, p_psi` as momenta and values; a bare name stands for itself (symbolic).
fn steady(text: &str) -> Vec<(String, String)> {
    text.split(',')
        .map(str::trim)
        .filter(|x| !x.is_empty())
        .map(|item| match item.split_once('=') {
            Some((a, b)) => (lagrange::expr::spelled(a), b.trim().to_string()),
            None => (lagrange::expr::spelled(item), lagrange::expr::spelled(item)),
        })
        .collect()
}

/// `x=-5:5` as a name and a nonempty interval.
fn range(r: &str) -> Result<(String, f64, f64), CliError> {
    let bad = || CliError::Usage(format!("--range `{r}` should look like x=-5:5"));
    let (name, span) = r.split_once('=').ok_or_else(bad)?;
    let (lo, hi) = span
        .split_once(':')
        .and_then(|(a, b)| Some((a.trim().parse::<f64>().ok()?, b.trim().parse::<f64>().ok()?)))
        .filter(|(a, b)| a < b)
        .ok_or_else(bad)?;
    Ok((name.trim().to_string(), lo, hi))
}

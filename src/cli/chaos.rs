//! `lagrange chaos`: the largest Lyapunov exponent (Benettin) with its convergence, the
//! separation of two trajectories started delta apart, and a Poincaré section; the summary or
//! JSON, and the pictures (`--plot`, `--poincare`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Args;
use lagrange::problem::SimulationDefaults;

use super::system_args::{CliError, SystemArgs, Terminal, report};
use lagrange::diagnostic::{Diagnostic, render_plain};
use lagrange::report::chaos::{ChaosError, ChaosOptions, ChaosReport, DEFAULT_T_END, SectionSpec};

#[derive(Args, Debug)]
pub struct ChaosArgs {
    #[command(flatten)]
    system: SystemArgs,
    /// Parameter values, e.g. "m1=1, m2=1, l1=1, l2=1, g=9.81".
    #[arg(long, default_value = "", allow_hyphen_values = true)]
    params: String,
    /// Initial values, e.g. "theta1=2, theta2=2"; velocities not given start at 0.
    #[arg(long, default_value = "", allow_hyphen_values = true)]
    init: String,
    /// The initial separation of the two trajectories, in (0, 1).
    #[arg(long, default_value_t = 1e-9, allow_hyphen_values = true)]
    delta: f64,
    /// The end time of the exponent's estimate (4000: shorter runs of the double pendulum
    /// scatter by more than ±0.05 across delta and tolerance).
    #[arg(long, default_value_t = DEFAULT_T_END, allow_hyphen_values = true)]
    t_end: f64,
    /// The renormalisation interval τ.
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true)]
    tau: f64,
    /// Relative tolerance of dop853.
    #[arg(long, default_value_t = 1e-10, allow_hyphen_values = true)]
    rtol: f64,
    /// Absolute tolerance of dop853.
    #[arg(long, default_value_t = 1e-10, allow_hyphen_values = true)]
    atol: f64,
    /// The separation (never renormalised) is followed until this time (or --t-end).
    #[arg(long, default_value_t = 40.0, allow_hyphen_values = true)]
    separation_t_end: f64,
    /// Even samples of the separation.
    #[arg(long, default_value_t = 1000)]
    samples: usize,
    /// Draw the separation (log scale) and the running estimate to this SVG file.
    #[arg(long)]
    plot: Option<PathBuf>,
    /// Draw the Poincaré section (first coordinate = 0, its velocity > 0) at the initial
    /// energy to this SVG file.
    #[arg(long)]
    poincare: Option<PathBuf>,
    /// Orbits of the section: starting values of the second coordinate evenly in the range.
    #[arg(long, default_value_t = 20)]
    orbits: usize,
    /// The range of the second coordinate at the orbits' starts, "lo:hi".
    #[arg(long, default_value = "-3.14159:3.14159", allow_hyphen_values = true)]
    section_range: String,
    /// Crossings collected per orbit.
    #[arg(long, default_value_t = 200)]
    crossings: usize,
    /// The longest time an orbit of the section is followed.
    #[arg(long, default_value_t = 1000.0, allow_hyphen_values = true)]
    section_t_end: f64,
    /// JSON output.
    #[arg(long)]
    json: bool,
}

pub fn run(
    args: &ChaosArgs,
    problems: Option<&Path>,
    color: bool,
    out: &mut String,
) -> anyhow::Result<ExitCode> {
    for (flag, path) in [("--plot", &args.plot), ("--poincare", &args.poincare)] {
        if let Some(e) = path
            .as_deref()
            .and_then(|p| crate::face::plot::check_picture_path(flag, p, false).err())
        {
            return Ok(report(&CliError::Usage(e), color));
        }
    }
    let (mut sys, defaults, units) = match args.system.build_with_defaults(problems) {
        Ok(s) => s,
        Err(e) => return Ok(report(&e, color)),
    };
    let opts = match options(args, &defaults) {
        Ok(o) => o,
        Err(e) => return Ok(report(&e, color)),
    };
    let mut bar = crate::face::bar::Bar::percent(!args.json);
    let run = lagrange::report::chaos::chaos_with(&mut sys, &opts, &mut bar);
    bar.finish();
    let mut r = match run {
        Ok(r) => r,
        Err(ChaosError::Simulation(e)) => return Ok(super::simulate::failure(&e)),
        Err(e) => return Ok(refuse(&e)),
    };
    r.time_unit = units.time.clone();
    if let Err(e) = pictures(args, &r, &units) {
        return Ok(report(&CliError::Usage(e), color));
    }
    if args.json {
        out.push_str(&serde_json::to_string_pretty(&r)?);
        out.push('\n');
    } else {
        out.push_str(&r.render(&Terminal));
    }
    Ok(ExitCode::SUCCESS)
}

/// Writes the asked pictures; the error names the flag and the file.
fn pictures(
    args: &ChaosArgs,
    r: &ChaosReport,
    units: &lagrange::report::units::AxisUnits,
) -> Result<(), String> {
    if let Some(path) = &args.plot {
        crate::face::plot::chaos_svg(r, path)
            .map_err(|e| format!("--plot {}: cannot draw: {e}", path.display()))?;
    }
    if let Some(path) = &args.poincare {
        crate::face::plot::poincare_svg(r, units, path)
            .map_err(|e| format!("--poincare {}: cannot draw: {e}", path.display()))?;
    }
    Ok(())
}

/// The library's options from the flags, over a bank problem's suggested parameter values
/// and start (not its end time: a Lyapunov estimate needs a much longer run).
fn options(args: &ChaosArgs, defaults: &SimulationDefaults) -> Result<ChaosOptions, CliError> {
    let chosen = super::system_args::chosen(defaults, &args.params, &args.init, None)?;
    let section = match &args.poincare {
        None => None,
        Some(_) => Some(SectionSpec {
            orbits: args.orbits,
            range: range(&args.section_range)?,
            crossings: args.crossings,
            t_max: args.section_t_end,
        }),
    };
    Ok(ChaosOptions {
        params: chosen.params,
        init: chosen.init,
        delta: args.delta,
        t_end: args.t_end,
        tau: args.tau,
        rtol: args.rtol,
        atol: args.atol,
        separation_t_end: args.separation_t_end,
        samples: args.samples,
        section,
    })
}

/// "lo:hi" as two numbers.
fn range(text: &str) -> Result<(f64, f64), CliError> {
    let bad = || CliError::Usage(format!("--section-range: `{text}` is not `lo:hi`"));
    let (lo, hi) = text.split_once(':').ok_or_else(bad)?;
    let lo: f64 = lo.trim().parse().map_err(|_| bad())?;
    let hi: f64 = hi.trim().parse().map_err(|_| bad())?;
    Ok((lo, hi))
}

/// Prints a refusal of the settings (exit 2).
fn refuse(e: &ChaosError) -> ExitCode {
    let help = match e {
        ChaosError::NoSectionState { .. } => "choose another --section-range or --init",
        ChaosError::SectionDimension(_) => "drop --poincare",
        ChaosError::Invalid(_) => "shorten --tau or lengthen --t-end",
        ChaosError::Constraints(_) => {
            "eliminate the constraints by choosing coordinates that satisfy them"
        }
        _ => "check the values given",
    };
    eprint!(
        "{}",
        render_plain(&Diagnostic::new("usage", e.to_string(), help))
    );
    ExitCode::from(2)
}

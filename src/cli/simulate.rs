//! `lagrange simulate`: integrates a system's motion from given initial values and prints a
//! summary (work, energy drift, states at asked times and at the end) or JSON; `--out`
//! writes the even grid as CSV (atomically: a temporary file, then a rename).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, ValueEnum};

mod grid;

use super::system_args::{CliError, SystemArgs, Terminal, report};
use lagrange::diagnostic::{Diagnostic, render_plain};
use lagrange::problem::SimulationDefaults;
use lagrange::report::{SimulationError, SimulationOptions, SimulationReport};
use lagrange::simulate::{Method, SimError};

#[derive(Args, Debug)]
pub struct SimulateArgs {
    #[command(flatten)]
    pub(super) system: SystemArgs,
    /// Parameter values, e.g. "m1=1, m2=1, l1=1, l2=1, g=9.81" (a bank problem suggests
    /// values; these override them).
    #[arg(long, default_value = "", allow_hyphen_values = true)]
    pub(super) params: String,
    /// Initial values, e.g. "theta1=2, theta2=2, theta1'=0"; values not given start at 0
    /// (without --init, a bank problem's suggested start).
    #[arg(long, default_value = "", allow_hyphen_values = true)]
    pub(super) init: String,
    /// The end time (the motion starts at t = 0); a bank problem may suggest one.
    #[arg(long, allow_hyphen_values = true)]
    pub(super) t_end: Option<f64>,
    /// Relative tolerance of dop853.
    #[arg(long, default_value_t = 1e-10, allow_hyphen_values = true)]
    pub(super) rtol: f64,
    /// Absolute tolerance of dop853.
    #[arg(long, default_value_t = 1e-10, allow_hyphen_values = true)]
    pub(super) atol: f64,
    /// The integrator: dop853 (adaptive, the default), rk4 or gauss (fixed step --dt).
    #[arg(long, value_enum)]
    pub(super) method: Option<MethodArg>,
    /// The fixed step of rk4 and gauss.
    #[arg(long, allow_hyphen_values = true)]
    pub(super) dt: Option<f64>,
    /// Times at which to print the state, e.g. "10, 20".
    #[arg(long, default_value = "", allow_hyphen_values = true)]
    pub(super) report_at: String,
    /// Write t, every q, every q' and h on an even grid to this CSV file.
    #[arg(long)]
    pub(super) out: Option<PathBuf>,
    /// Points of the even grid (energy drift, --out and the pictures).
    #[arg(long, default_value_t = 1000)]
    pub(super) samples: usize,
    /// JSON output.
    #[arg(long)]
    pub(super) json: bool,
    /// Draw q(t) for every coordinate to this SVG file (PNG when it ends in .png); `-` draws a
    /// terminal chart on stdout. With --grid: the flip-time map.
    #[arg(long)]
    pub(super) plot: Option<PathBuf>,
    /// Draw the phase portrait (q against q') of every coordinate to this SVG file.
    #[arg(long)]
    pub(super) phase: Option<PathBuf>,
    /// Draw the relative energy error over time to this SVG file.
    #[arg(long)]
    pub(super) energy: Option<PathBuf>,
    /// Draw into --phase a family of trajectories at N energies (1 to 200) instead of the one
    /// from --init: one degree of freedom and a conserved h only (more are refused). All start
    /// at the minimum of V(q) = h(q, 0) on the coordinate's range, with energies evenly below
    /// the highest barrier, at it (the separatrix) and above it up to 1.8 × its height; the
    /// separatrix and rotations go both ways. Each is integrated for one period (at most
    /// --t-end) and drawn with --samples points (at most 2000). Colour shows the energy.
    #[arg(long, value_name = "N")]
    pub(super) portrait: Option<usize>,
    /// A grid over one or two initial values, "theta1=-3:3:200, theta2=-3:3:200"
    /// (start:end:count, ends included; the rest from --init): one trajectory per cell, by
    /// RK4 at --dt (default 1e-3). With --until-flip: the flip-time map (--plot FILE draws
    /// it, --out writes a CSV, --json a summary).
    #[arg(long, allow_hyphen_values = true)]
    pub(super) grid: Option<String>,
    /// With --grid: run each trajectory until an angle goes over the top (the continuous
    /// angle leaves (−π, π)), or to --t-end.
    #[arg(long)]
    pub(super) until_flip: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(super) enum MethodArg {
    Dop853,
    Rk4,
    Gauss,
}

pub fn run(
    args: &SimulateArgs,
    problems: Option<&Path>,
    color: bool,
    out: &mut String,
) -> anyhow::Result<ExitCode> {
    if args.json && args.plot.as_deref() == Some(Path::new("-")) {
        let message = "--plot - and --json both write to stdout; give --plot a file".into();
        return Ok(report(&CliError::Usage(message), color));
    }
    if let Err(e) = check_portrait(args).and_then(|()| check_pictures(args)) {
        return Ok(report(&e, color));
    }
    let (mut sys, defaults, units) = match args.system.build_with_defaults(problems) {
        Ok(s) => s,
        Err(e) => return Ok(report(&e, color)),
    };
    let opts = match options(args, &defaults) {
        Ok(o) => o,
        Err(e) => return Ok(report(&e, color)),
    };
    if let Some(spec) = &args.grid {
        return grid::run(args, &opts, &units, spec, &mut sys, color, out);
    }
    if args.until_flip {
        let message = "--until-flip goes with --grid (the flip-time map)".into();
        return Ok(report(&CliError::Usage(message), color));
    }
    let mut bar = crate::face::bar::Bar::percent(!args.json);
    let run = lagrange::report::simulation_with(&mut sys, &opts, &mut bar);
    bar.finish();
    let mut report_ = match run {
        Ok(r) => r,
        Err(e) => return Ok(failure(&e)),
    };
    report_.units = units;
    if let Some(path) = &args.out
        && let Err(e) = write_atomic(path, report_.csv().as_bytes())
    {
        let message = format!("--out {}: cannot write the file: {e}", path.display());
        return Ok(report(&CliError::Usage(message), color));
    }
    if let Err(e) = pictures(args, &report_) {
        return Ok(report(&CliError::Usage(e), color));
    }
    if let (Some(count), Some(path)) = (args.portrait, &args.phase) {
        let family = match lagrange::report::portrait::portrait_family(&mut sys, &opts, count) {
            Ok(f) => f,
            Err(e) => return Ok(failure(&e)),
        };
        if let Err(e) = crate::face::plot::portrait_svg(&family, &report_.units, path) {
            let message = format!("--phase {}: cannot draw: {e}", path.display());
            return Ok(report(&CliError::Usage(message), color));
        }
    }
    if args.json {
        out.push_str(&serde_json::to_string_pretty(&report_)?);
        out.push('\n');
    } else {
        out.push_str(&report_.render(&Terminal));
    }
    if args.plot.as_deref() == Some(Path::new("-")) {
        out.push_str(&crate::face::plot::terminal_chart(&report_));
    }
    Ok(ExitCode::SUCCESS)
}

/// Writes the asked SVG pictures; the error names the flag and the file.
fn pictures(args: &SimulateArgs, r: &SimulationReport) -> Result<(), String> {
    type Draw = fn(&SimulationReport, &Path) -> Result<(), String>;
    let asked: [(&str, Option<&PathBuf>, Draw); 3] = [
        ("--plot", args.plot.as_ref(), crate::face::plot::qt_svg),
        (
            "--phase",
            args.phase.as_ref().filter(|_| args.portrait.is_none()),
            crate::face::plot::phase_svg,
        ),
        (
            "--energy",
            args.energy.as_ref(),
            crate::face::plot::energy_svg,
        ),
    ];
    for (flag, path, draw) in asked {
        if let Some(path) = path.filter(|p| p.as_path() != Path::new("-")) {
            draw(r, path).map_err(|e| format!("{flag} {}: cannot draw: {e}", path.display()))?;
        }
    }
    Ok(())
}

/// The picture paths, checked before any work.
fn check_pictures(args: &SimulateArgs) -> Result<(), CliError> {
    let asked = [
        ("--plot", args.plot.as_ref(), args.grid.is_none()),
        ("--phase", args.phase.as_ref(), false),
        ("--energy", args.energy.as_ref(), false),
    ];
    for (flag, path, terminal) in asked {
        if let Some(path) = path {
            crate::face::plot::check_picture_path(flag, path, terminal).map_err(CliError::Usage)?;
        }
    }
    // The CSV's name too: a link or a folder there is refused before any work.
    if let Some(path) = args.out.as_deref().filter(|p| *p != Path::new("-")) {
        crate::face::outfile::check(path, true)
            .map_err(|e| CliError::Usage(format!("--out: {e}")))?;
    }
    Ok(())
}

/// `--portrait N` needs `--phase FILE` and N in 1 ..= 200.
fn check_portrait(args: &SimulateArgs) -> Result<(), CliError> {
    use lagrange::simulate::portrait::MAX_PORTRAIT;
    let Some(n) = args.portrait else {
        return Ok(());
    };
    if args.phase.is_none() || args.phase.as_deref() == Some(Path::new("-")) {
        return Err(CliError::Usage(
            "--portrait N draws into the phase picture: give --phase FILE.svg".into(),
        ));
    }
    if n == 0 || n > MAX_PORTRAIT {
        return Err(CliError::Usage(format!(
            "--portrait {n}: give 1 to {MAX_PORTRAIT} energies"
        )));
    }
    Ok(())
}

/// The library's options from the flags, over a bank problem's suggestions: given
/// parameters replace suggested ones one by one, a given --init replaces the suggested start.
fn options(
    args: &SimulateArgs,
    defaults: &SimulationDefaults,
) -> Result<SimulationOptions, CliError> {
    let SimulationDefaults {
        params,
        init,
        t_end,
    } = super::system_args::chosen(defaults, &args.params, &args.init, args.t_end)?;
    let t_end = t_end.ok_or_else(|| {
        CliError::usage("give the end time with --t-end (the motion starts at t = 0)")
    })?;
    Ok(SimulationOptions {
        params,
        init,
        t_end,
        method: match args.method.unwrap_or(MethodArg::Dop853) {
            MethodArg::Dop853 => Method::Dop853,
            MethodArg::Rk4 => Method::Rk4,
            MethodArg::Gauss => Method::Gauss,
        },
        rtol: args.rtol,
        atol: args.atol,
        dt: args.dt,
        report_at: args
            .report_at
            .split(',')
            .map(str::trim)
            .filter(|x| !x.is_empty())
            .map(|x| {
                x.parse::<f64>()
                    .map_err(|_| CliError::Usage(format!("--report-at: `{x}` is not a number")))
            })
            .collect::<Result<_, _>>()?,
        samples: args.samples,
    })
}

/// Prints a simulation error; exit 1 when the motion could not be followed, 2 for input.
pub(super) fn failure(e: &SimulationError) -> ExitCode {
    let help = match e {
        SimulationError::Sim(SimError::MissingParameters { names }) => format!(
            "add {} to --params",
            names
                .iter()
                .map(|n| format!("`{n}=<value>`"))
                .collect::<Vec<_>>()
                .join(", ")
        ),
        SimulationError::Portrait(_) if !e.along_the_way() => "--portrait needs one degree of freedom, a conserved h and a potential with a lowest point inside the coordinate's range; without --portrait, --phase draws the motion from --init".into(),
        _ => e.help(),
    };
    let code = e.code();
    eprint!(
        "{}",
        render_plain(&Diagnostic::new(code, e.to_string(), help))
    );
    ExitCode::from(if e.along_the_way() { 1 } else { 2 })
}

/// Writes `bytes` to `path` as [`crate::face::outfile::write_named`] does: a regular file through a
/// temporary file beside it and a rename, a device or FIFO by streaming, never through a link.
pub(super) fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), String> {
    crate::face::outfile::write_named(path, bytes)
}

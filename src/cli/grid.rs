//! `lagrange simulate --grid "theta1=-3:3:200, theta2=-3:3:200" --until-flip`: one
//! trajectory per cell of a grid over one or two initial values (the others from --init),
//! each run with the library's batch RK4 until an angle goes over the top; the flip-time map
//! as a picture (--plot), a CSV (--out), JSON (--json) or a summary. Batches of cells run on
//! every core (rayon); a progress bar shows on a terminal.

use std::process::ExitCode;
use std::time::Instant;

use std::ops::ControlFlow;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::bar::Bar;
use lagrange::progress::Progress;
use rayon::prelude::*;
use serde::Serialize;

use super::simulate::{SimulateArgs, write_atomic};
use super::system_args::{CliError, report};
use lagrange::diagnostic::did_you_mean;
use lagrange::mechanics::System;
use lagrange::report::SimulationOptions;
use lagrange::report::simulation::{initial_state, state_names};
use lagrange::report::units::AxisUnits;
use lagrange::simulate::{
    DEFAULT_FLIP_DT, FlipRun, FlipSettings, Outcome, Rhs, SimError, flip_times_with,
};

/// The most cells a grid may have.
pub const MAX_CELLS: usize = 1_000_000;
/// The most RK4 steps a whole map may take (cells × steps).
pub const MAX_WORK: f64 = 2e10;
/// Trajectories per lockstep batch (the fastest width measured by benches/flip.rs).
const LANES: usize = 16;
/// Cells per parallel job (a multiple of the lanes; small enough to balance two cores).
const CHUNK: usize = 512;

/// One axis of the grid: `name=start:end:count`, ends included.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Axis {
    pub name: String,
    pub start: f64,
    pub end: f64,
    pub count: usize,
}

impl Axis {
    /// The values, evenly spaced from start to end inclusive.
    pub fn values(&self) -> Vec<f64> {
        if self.count == 1 {
            return vec![self.start];
        }
        let step = (self.end - self.start) / (self.count - 1) as f64;
        (0..self.count)
            .map(|k| self.start + step * k as f64)
            .collect()
    }
}

/// Reads `name=start:end:count` items separated by commas; errors name the column.
pub fn parse_grid(spec: &str) -> Result<Vec<Axis>, String> {
    let mut axes = Vec::new();
    let mut column = 1;
    for item in spec.split(',') {
        let at = column + item.len() - item.trim_start().len();
        column += item.chars().count() + 1;
        let item = item.trim();
        if item.is_empty() {
            return Err(format!(
                "--grid: column {at}: an empty item (write name=start:end:count)"
            ));
        }
        axes.push(parse_axis(item, at)?);
    }
    if axes.len() > 2 {
        return Err(format!("--grid: {} axes; a map has one or two", axes.len()));
    }
    if axes.len() == 2 && axes[0].name == axes[1].name {
        return Err(format!("--grid: `{}` is given twice", axes[0].name));
    }
    Ok(axes)
}

fn parse_axis(item: &str, at: usize) -> Result<Axis, String> {
    let Some((name, range)) = item.split_once('=') else {
        return Err(format!(
            "--grid: column {at}: `{item}` has no `=` (write name=start:end:count)"
        ));
    };
    let name = lagrange::expr::spelled(name);
    let name = name.as_str();
    let at_range = at + item.find('=').unwrap_or(0) + 1;
    let parts: Vec<&str> = range.split(':').collect();
    if parts.len() != 3 {
        return Err(format!(
            "--grid: column {at_range}: `{}` should be start:end:count",
            range.trim()
        ));
    }
    let number = |s: &str| s.trim().parse::<f64>().ok().filter(|v| v.is_finite());
    let (Some(start), Some(end)) = (number(parts[0]), number(parts[1])) else {
        return Err(format!(
            "--grid: column {at_range}: the start and end of `{name}` must be finite numbers"
        ));
    };
    let count = parts[2].trim().parse::<usize>().ok().filter(|&c| c >= 1);
    let Some(count) = count else {
        return Err(format!(
            "--grid: column {at_range}: the count of `{name}` must be a whole number ≥ 1, not `{}`",
            parts[2].trim()
        ));
    };
    if count == 1 && start != end {
        return Err(format!(
            "--grid: `{name}` has one point but two different ends"
        ));
    }
    Ok(Axis {
        name: name.to_string(),
        start,
        end,
        count,
    })
}

/// What the map found, as printed and as JSON (no wall time: that is the face's, below).
#[derive(Debug, Serialize)]
struct Summary {
    axes: Vec<Axis>,
    /// The values every cell shares (the coordinates and velocities not on an axis).
    others: Vec<(String, f64)>,
    cells: usize,
    t_end: f64,
    dt: f64,
    watched: Vec<String>,
    flipped: usize,
    starts_over: usize,
    did_not_flip: usize,
    singular: usize,
    diverged: usize,
    flipped_fraction: f64,
    trajectory_steps: u64,
}

/// The grid run of `lagrange simulate`.
pub fn run(
    args: &SimulateArgs,
    opts: &SimulationOptions,
    units: &AxisUnits,
    spec: &str,
    sys: &mut System,
    color: bool,
    out: &mut String,
) -> anyhow::Result<ExitCode> {
    let plan = match plan(args, opts, spec, sys) {
        Ok(p) => p,
        Err(e) => return Ok(report(&e, color)),
    };
    let clock = Instant::now();
    let run = integrate(&plan, args.json);
    let wall = clock.elapsed().as_secs_f64();
    let summary = summarize(&plan, &run);
    if let Err(e) = write_files(args, &plan, &run, units) {
        return Ok(report(&CliError::Usage(e), color));
    }
    if args.json {
        out.push_str(&serde_json::to_string_pretty(&summary)?);
        out.push('\n');
    } else {
        out.push_str(&render(&summary));
        let rate = summary.trajectory_steps as f64 / wall.max(1e-9) / 1e6;
        let threads = rayon::current_num_threads();
        out.push_str(&format!(
            "Wall time: {wall:.2} s on {threads} threads ({rate:.1} M trajectory-steps/s)\n"
        ));
    }
    Ok(ExitCode::SUCCESS)
}

/// Everything the run needs, checked.
struct Plan {
    rhs: Rhs,
    axes: Vec<Axis>,
    /// The axes' indices in y = (q, q') and their values.
    index: Vec<usize>,
    values: Vec<Vec<f64>>,
    /// y at every cell before the grid values are set.
    base: Vec<f64>,
    names: Vec<String>,
    settings: FlipSettings,
    cells: usize,
}

impl Plan {
    /// The start of cell `c` (row-major, the last axis fastest).
    fn start(&self, c: usize, y: &mut [f64]) {
        y.copy_from_slice(&self.base);
        let mut rest = c;
        for (k, values) in self.values.iter().enumerate().rev() {
            y[self.index[k]] = values[rest % values.len()];
            rest /= values.len();
        }
    }
}

/// Reads and checks the flags against the system.
fn plan(
    args: &SimulateArgs,
    opts: &SimulationOptions,
    spec: &str,
    sys: &mut System,
) -> Result<Plan, CliError> {
    let usage = |m: String| CliError::Usage(m);
    check_flags(args)?;
    let axes = parse_grid(spec).map_err(usage)?;
    // A problem's suggested start gives way to the grid's axes; a typed --init does not.
    let init: Vec<(String, f64)> = (opts.init.iter())
        .filter(|(n, _)| !args.init.trim().is_empty() || !axes.iter().any(|a| a.name == *n))
        .cloned()
        .collect();
    let rhs = equations(&opts.params, sys)?;
    let coords = rhs.names().to_vec();
    let names = state_names(&coords);
    let base = initial_state(&names, &init).map_err(|e| usage(e.to_string()))?;
    let find = |name: &str, flag: &str| {
        names.iter().position(|n| n == name).ok_or_else(|| {
            let hint = did_you_mean(name, names.iter().map(String::as_str))
                .map_or(String::new(), |s| format!(" (did you mean `{s}`?)"));
            usage(format!(
                "{flag}: `{name}` is not a coordinate or velocity of the system{hint}"
            ))
        })
    };
    let index = axes
        .iter()
        .map(|a| find(&a.name, "--grid"))
        .collect::<Result<Vec<_>, _>>()?;
    if let Some(a) = axes.iter().find(|a| init.iter().any(|(n, _)| *n == a.name)) {
        return Err(usage(format!(
            "`{}` is given by both --grid and --init",
            a.name
        )));
    }
    let watch: Vec<usize> = (0..coords.len())
        .filter(|&i| sys.coordinates[i].periodic)
        .collect();
    if watch.is_empty() {
        return Err(usage(format!(
            "--until-flip watches angles, and none of the coordinates ({}) is an angle",
            coords.join(", ")
        )));
    }
    let (cells, dt) = limits(args, opts.t_end, &axes)?;
    let settings = FlipSettings {
        t_end: opts.t_end,
        dt,
        watch,
        lanes: LANES,
    };
    let values = axes.iter().map(Axis::values).collect();
    Ok(Plan {
        rhs,
        axes,
        index,
        values,
        base,
        names,
        settings,
        cells,
    })
}

/// The flags that make no sense with a grid.
fn check_flags(args: &SimulateArgs) -> Result<(), CliError> {
    let usage = |m: String| Err(CliError::Usage(m));
    if !args.until_flip {
        return usage(
            "--grid draws the flip-time map: add --until-flip (the time until an angle goes over the top)".into(),
        );
    }
    for (flag, given) in [
        ("--phase", args.phase.is_some()),
        ("--energy", args.energy.is_some()),
        ("--report-at", !args.report_at.trim().is_empty()),
    ] {
        if given {
            return usage(format!(
                "{flag} is for a single trajectory, not with --grid"
            ));
        }
    }
    if let Some(m) = args
        .method
        .filter(|m| *m != super::simulate::MethodArg::Rk4)
    {
        return usage(format!(
            "--grid integrates every cell with rk4 at --dt; --method {m:?} is not available there"
        )
        .to_lowercase());
    }
    Ok(())
}

/// The compiled equations at the given parameter values.
fn equations(params: &[(String, f64)], sys: &mut System) -> Result<Rhs, CliError> {
    // A bank problem declares parameters for all its parts; those the motion does not use
    // take any value, as in a single run.
    let params = lagrange::report::simulation::motion_parameters(sys, params);
    Rhs::new(sys, &params).map_err(|e| match e {
        SimError::MissingParameters { .. } => CliError::Usage(format!("{e}: add them to --params")),
        e => CliError::Usage(e.to_string()),
    })
}

/// The number of cells and the step, within the limits of work.
fn limits(args: &SimulateArgs, t_end: f64, axes: &[Axis]) -> Result<(usize, f64), CliError> {
    let usage = |m: String| Err(CliError::Usage(m));
    let cells = axes
        .iter()
        .try_fold(1usize, |acc, a| acc.checked_mul(a.count))
        .unwrap_or(usize::MAX);
    if cells > MAX_CELLS {
        return usage(format!(
            "--grid asks for {cells} cells, over the limit of {MAX_CELLS}"
        ));
    }
    let dt = args.dt.unwrap_or(DEFAULT_FLIP_DT);
    if !(t_end.is_finite() && t_end > 0.0 && dt > 0.0 && dt.is_finite()) {
        return usage(format!(
            "--t-end {} and --dt {dt} must be positive numbers",
            t_end
        ));
    }
    let steps = (t_end / dt).ceil();
    let work = cells as f64 * steps;
    if work > MAX_WORK {
        return usage(format!(
            "{cells} cells of {steps} steps each is {work:.2e} steps, over the limit of {MAX_WORK:.0e}: coarsen the grid, shorten --t-end or enlarge --dt"
        ));
    }
    Ok((cells, dt))
}

/// Every cell's outcome, batches of cells on every core; the batches' progress callbacks
/// add up into one bar (none with `--json`).
fn integrate(plan: &Plan, json: bool) -> FlipRun {
    let bar = Mutex::new(Bar::new("{bar:40} {pos}/{len} cells, {eta} left", !json));
    let done = AtomicU64::new(0);
    let dim = plan.base.len();
    let chunks: Vec<FlipRun> = (0..plan.cells.div_ceil(CHUNK))
        .into_par_iter()
        .map(|k| {
            let cells = k * CHUNK..((k + 1) * CHUNK).min(plan.cells);
            let mut starts = vec![0.0; cells.len() * dim];
            for (c, y) in cells.clone().zip(starts.chunks_mut(dim)) {
                plan.start(c, y);
            }
            // The settings were checked above, so a refusal here cannot happen; if it did,
            // the cells are marked as not followed rather than invented.
            let mut last = 0;
            let mut tell = |finished: u64, _: u64| {
                let new = finished.saturating_sub(last);
                let all = done.fetch_add(new, Ordering::Relaxed) + new;
                last = last.max(finished);
                match bar.try_lock() {
                    Ok(mut b) => b.report(all, plan.cells as u64),
                    Err(_) => ControlFlow::Continue(()),
                }
            };
            let run = flip_times_with(&plan.rhs, &starts, &plan.settings, &mut tell);
            run.unwrap_or_else(|_| FlipRun {
                outcomes: vec![Outcome::Diverged { t: 0.0 }; cells.len()],
                steps: 0,
            })
        })
        .collect();
    if let Ok(b) = bar.lock() {
        b.finish();
    }
    chunks.into_iter().fold(
        FlipRun {
            outcomes: Vec::with_capacity(plan.cells),
            steps: 0,
        },
        |mut all, r| {
            all.outcomes.extend(r.outcomes);
            all.steps += r.steps;
            all
        },
    )
}

fn summarize(plan: &Plan, run: &FlipRun) -> Summary {
    let count = |f: fn(&Outcome) -> bool| run.outcomes.iter().filter(|o| f(o)).count();
    let flipped = count(|o| o.flip_time().is_some());
    Summary {
        axes: plan.axes.clone(),
        others: (plan.names.iter().zip(&plan.base).enumerate())
            .filter(|(i, _)| !plan.index.contains(i))
            .map(|(_, (n, v))| (n.clone(), *v))
            .collect(),
        cells: plan.cells,
        t_end: plan.settings.t_end,
        dt: plan.settings.dt,
        watched: plan
            .settings
            .watch
            .iter()
            .map(|&i| plan.names[i].clone())
            .collect(),
        flipped,
        starts_over: count(|o| matches!(o, Outcome::StartsOver { .. })),
        did_not_flip: count(|o| matches!(o, Outcome::Stayed)),
        singular: count(|o| matches!(o, Outcome::Singular { .. })),
        diverged: count(|o| matches!(o, Outcome::Diverged { .. })),
        flipped_fraction: flipped as f64 / plan.cells.max(1) as f64,
        trajectory_steps: run.steps,
    }
}

fn render(s: &Summary) -> String {
    let axes: Vec<String> = s
        .axes
        .iter()
        .map(|a| format!("{} = {} … {} ({})", a.name, a.start, a.end, a.count))
        .collect();
    let mut o = format!(
        "Flip-time map: {}; {} cells, RK4 at dt = {} to t = {}\n",
        axes.join(" × "),
        s.cells,
        s.dt,
        s.t_end
    );
    let others: Vec<String> = (s.others.iter())
        .map(|(n, v)| format!("{n} = {v}"))
        .collect();
    o += &format!("Every cell starts with: {}\n", others.join(", "));
    o += &format!(
        "Watched angles: {} (a flip: the continuous angle leaves (−π, π))\n",
        s.watched.join(", ")
    );
    o += &format!(
        "Flipped: {} of {} ({:.1} %)",
        s.flipped,
        s.cells,
        100.0 * s.flipped_fraction
    );
    if s.starts_over > 0 {
        o += &format!(
            ", of which {} start over the top already (flip time 0)",
            s.starts_over
        );
    }
    o += &format!("\nDid not flip by t = {}: {}\n", s.t_end, s.did_not_flip);
    if s.singular + s.diverged > 0 {
        o += &format!(
            "Not followed to the end: {} (mass matrix singular: {}, diverged: {})\n",
            s.singular + s.diverged,
            s.singular,
            s.diverged
        );
    }
    o += &format!("Trajectory-steps: {}\n", s.trajectory_steps);
    o
}

/// The CSV and the picture, if asked.
fn write_files(
    args: &SimulateArgs,
    plan: &Plan,
    run: &FlipRun,
    units: &AxisUnits,
) -> Result<(), String> {
    if let Some(path) = &args.out {
        write_atomic(path, csv(plan, run).as_bytes())
            .map_err(|e| format!("--out {}: cannot write the file: {e}", path.display()))?;
    }
    if let Some(path) = &args.plot {
        // An axis is a coordinate or a velocity: y = (q, q').
        let n = plan.names.len() / 2;
        let label = |k: usize| {
            let i = plan.index[k];
            let unit = if i < n {
                units.coordinates.get(i)
            } else {
                units.velocities.get(i - n)
            };
            let name = crate::plot::unicode(&plan.axes[k].name);
            crate::plot::axis(&name, unit.cloned().flatten().as_deref())
        };
        let map = crate::plot::FlipMap {
            x: (label(0), &plan.values[0]),
            y: plan.values.get(1).map(|v| (label(1), v.as_slice())),
            cells: &run.outcomes,
            t_end: plan.settings.t_end,
            dt: plan.settings.dt,
            time_unit: units.time.clone(),
        };
        crate::plot::flip_map(&map, path)
            .map_err(|e| format!("--plot {}: cannot draw: {e}", path.display()))?;
    }
    Ok(())
}

/// One row per cell: the grid values, the flip time (empty when none) and what happened.
fn csv(plan: &Plan, run: &FlipRun) -> String {
    let mut o: String = plan.axes.iter().map(|a| format!("{},", a.name)).collect();
    o += "flip_time,outcome\n";
    let mut y = vec![0.0; plan.base.len()];
    for (c, outcome) in run.outcomes.iter().enumerate() {
        plan.start(c, &mut y);
        for &i in &plan.index {
            o += &format!("{},", y[i]);
        }
        let time = outcome.flip_time().map_or(String::new(), |t| t.to_string());
        let kind = match outcome {
            Outcome::Flipped { .. } => "flipped",
            Outcome::StartsOver { .. } => "starts_over",
            Outcome::Stayed => "did_not_flip",
            Outcome::Singular { .. } => "singular",
            Outcome::Diverged { .. } => "diverged",
        };
        o += &format!("{time},{kind}\n");
    }
    o
}

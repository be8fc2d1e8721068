//! `lagrange simulate --grid "theta1=-3:3:200, theta2=-3:3:200" --until-flip`: the face of
//! the library's flip-time map ([`lagrange::report::flip_map`]): the flags that make no sense
//! with a grid, the chunks run on every core (rayon) with one progress bar on a terminal, and
//! the picture (--plot), the CSV (--out), JSON (--json) or the summary with the wall time.

use std::process::ExitCode;
use std::time::Instant;

use std::ops::ControlFlow;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

use crate::face::bar::Bar;
use lagrange::progress::Progress;
use rayon::prelude::*;

use super::super::system_args::{CliError, report};
use super::{SimulateArgs, write_atomic};
use lagrange::mechanics::System;
use lagrange::report::SimulationOptions;
use lagrange::report::flip_map::{FlipMap, FlipMapOptions, parse_grid};
use lagrange::report::units::AxisUnits;
use lagrange::simulate::FlipRun;

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
    let map = match plan(args, opts, spec, sys) {
        Ok(p) => p,
        Err(e) => return Ok(report(&e, color)),
    };
    let clock = Instant::now();
    let run = integrate(&map, args.json);
    let wall = clock.elapsed().as_secs_f64();
    let summary = map.summary(&run);
    if let Err(e) = write_files(args, &map, &run, units) {
        return Ok(report(&CliError::Usage(e), color));
    }
    if args.json {
        out.push_str(&serde_json::to_string_pretty(&summary)?);
        out.push('\n');
    } else {
        out.push_str(&summary.render());
        let rate = summary.trajectory_steps as f64 / wall.max(1e-9) / 1e6;
        let threads = rayon::current_num_threads();
        out.push_str(&format!(
            "Wall time: {wall:.2} s on {threads} threads ({rate:.1} M trajectory-steps/s)\n"
        ));
    }
    Ok(ExitCode::SUCCESS)
}

/// Reads the flags and has the library check them against the system.
fn plan(
    args: &SimulateArgs,
    opts: &SimulationOptions,
    spec: &str,
    sys: &mut System,
) -> Result<FlipMap, CliError> {
    let usage = |e: lagrange::report::flip_map::FlipMapError| CliError::Usage(e.to_string());
    check_flags(args)?;
    let axes = parse_grid(spec).map_err(usage)?;
    let options = FlipMapOptions {
        params: opts.params.clone(),
        init: opts.init.clone(),
        init_typed: !args.init.trim().is_empty(),
        t_end: opts.t_end,
        dt: args.dt,
    };
    FlipMap::plan(sys, &options, axes).map_err(usage)
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
    if let Some(m) = args.method.filter(|m| *m != super::MethodArg::Rk4) {
        return usage(format!(
            "--grid integrates every cell with rk4 at --dt; --method {m:?} is not available there"
        )
        .to_lowercase());
    }
    Ok(())
}

/// Every chunk's outcomes, chunks on every core; the chunks' progress callbacks add up into
/// one bar (none with `--json`).
fn integrate(map: &FlipMap, json: bool) -> FlipRun {
    let bar = Mutex::new(Bar::new("{bar:40} {pos}/{len} cells, {eta} left", !json));
    let done = AtomicU64::new(0);
    let cells = map.cells() as u64;
    let chunks: Vec<FlipRun> = (0..map.chunks())
        .into_par_iter()
        .map(|k| {
            let mut last = 0;
            let mut tell = |finished: u64, _: u64| {
                let new = finished.saturating_sub(last);
                let all = done.fetch_add(new, Ordering::Relaxed) + new;
                last = last.max(finished);
                match bar.try_lock() {
                    Ok(mut b) => b.report(all, cells),
                    Err(_) => ControlFlow::Continue(()),
                }
            };
            map.run_chunk(k, &mut tell)
        })
        .collect();
    if let Ok(b) = bar.lock() {
        b.finish();
    }
    map.join(chunks)
}

/// The CSV and the picture, if asked.
fn write_files(
    args: &SimulateArgs,
    map: &FlipMap,
    run: &FlipRun,
    units: &AxisUnits,
) -> Result<(), String> {
    if let Some(path) = &args.out {
        write_atomic(path, map.csv(run).as_bytes())
            .map_err(|e| format!("--out {}: cannot write the file: {e}", path.display()))?;
    }
    if let Some(path) = &args.plot {
        // An axis is a coordinate or a velocity: y = (q, q').
        let n = map.coordinates();
        let axes: Vec<_> = map.axes().collect();
        let label = |k: usize| {
            let i = map.axis_index(k);
            let unit = if i < n {
                units.coordinates.get(i)
            } else {
                units.velocities.get(i - n)
            };
            let name = crate::face::plot::unicode(&axes[k].0.name);
            crate::face::plot::axis(&name, unit.cloned().flatten().as_deref())
        };
        let map = crate::face::plot::FlipMap {
            x: (label(0), axes[0].1),
            y: axes.get(1).map(|a| (label(1), a.1)),
            cells: &run.outcomes,
            t_end: map.settings().t_end,
            dt: map.settings().dt,
            time_unit: units.time.clone(),
        };
        crate::face::plot::flip_map(&map, path)
            .map_err(|e| format!("--plot {}: cannot draw: {e}", path.display()))?;
    }
    Ok(())
}

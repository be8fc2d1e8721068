//! [`SimulationReport`]: what `lagrange simulate` shows — the work done by the integrator, the
//! energy function h at the start and end with its largest relative drift over an even grid,
//! the state at asked times and at the end — and the even grid for a CSV file. The face
//! writes the file; this module only builds the rows.

use std::fmt::Write as _;

use super::constraint_watch::{ConstraintWatch, off_constraint};
use serde::Serialize;
use serde::ser::SerializeMap;

use super::units::AxisUnits;
use super::{Paint, text};
use crate::mechanics::System;

mod error;
use crate::progress::{Ambient, Progress};
use crate::simulate::{Method, Rhs, SimError, Tolerances, Trajectory};
use crate::simulate::{dop853_with, gauss_with, rk4_with};
pub use error::SimulationError;

/// The most grid samples a run may ask for (`--samples`).
pub const MAX_SAMPLES: usize = 1_000_000;
/// The most report times a run may ask for (`--report-at`).
pub const MAX_REPORTS: usize = 10_000;

/// A drift of a conserved h above this makes the summary warn that the run is not to be
/// trusted (a step far too long, a tolerance far too loose).
pub const UNTRUSTED_DRIFT: f64 = 1e-3;

/// What to simulate and how.
#[derive(Clone, Debug)]
pub struct SimulationOptions {
    /// Every parameter's value.
    pub params: Vec<(String, f64)>,
    /// Initial values by name: `theta1` or `theta1'`; the rest start at 0.
    pub init: Vec<(String, f64)>,
    /// The end time (the start is 0).
    pub t_end: f64,
    /// The integrator.
    pub method: Method,
    /// DOP853's tolerances.
    pub rtol: f64,
    pub atol: f64,
    /// The fixed step of RK4 and Gauss.
    pub dt: Option<f64>,
    /// Times at which to report the state.
    pub report_at: Vec<f64>,
    /// Points of the even grid (energy error and CSV rows).
    pub samples: usize,
}

/// A state as a map from names (`theta1`, `theta1'`) to values, in the order of y.
#[derive(Clone, Debug, PartialEq)]
pub struct State(pub Vec<(String, f64)>);

impl Serialize for State {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut m = s.serialize_map(Some(self.0.len()))?;
        for (k, v) in &self.0 {
            m.serialize_entry(k, v)?;
        }
        m.end()
    }
}

/// The state at one asked time.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TimedState {
    pub(crate) t: f64,
    pub(crate) state: State,
}

/// Everything `simulate` shows.
#[derive(Clone, Debug, Serialize)]
#[non_exhaustive]
pub struct SimulationReport {
    /// The initial state (given values, zeros elsewhere).
    pub start: State,
    /// The parameter values the motion used (those of its equations, in the system's order).
    pub params: State,
    pub(crate) method: Method,
    /// Accepted steps.
    pub(crate) steps: usize,
    pub(crate) rejected: usize,
    pub(crate) rhs_evals: usize,
    pub(crate) h_start: f64,
    pub(crate) h_end: f64,
    /// max |h(t) − h(0)| / |h(0)| over the even grid (absolute when h(0) = 0).
    pub(crate) max_rel_energy_error: f64,
    pub(crate) reports: Vec<TimedState>,
    #[serde(rename = "final")]
    pub(crate) final_state: State,
    /// Whether h is expected to be constant (no explicit t, no forces doing work): a JSON
    /// reader judges `max_rel_energy_error` by it.
    #[serde(rename = "h_expected_constant")]
    pub(crate) h_conserved: bool,
    /// The largest |f(q, t)| of the holonomic constraints over the grid (None without any).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) constraint_drift: Option<f64>,
    /// The end time.
    #[serde(skip)]
    pub t_end: f64,
    /// The even grid: t, y and h per row.
    #[serde(skip)]
    pub grid: Vec<(f64, Vec<f64>, f64)>,
    /// The names of y's entries.
    #[serde(skip)]
    pub names: Vec<String>,
    /// The axes' units, when the face knows them (a bank problem's dimensions).
    #[serde(skip)]
    pub units: AxisUnits,
}

/// Why a list of `name=number` values (`--params`, `--init`) cannot be read; each names its
/// flag.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum NumbersError {
    /// An item that is not `name=value`.
    #[error("{flag}: {bad}")]
    NotAnAssignment {
        /// The flag the list was given to.
        flag: String,
        /// The item.
        bad: super::modes::BadAssignment,
    },
    /// One name given two values.
    #[error("{flag}: `{name}` is given twice")]
    GivenTwice {
        /// The flag the list was given to.
        flag: String,
        /// The name.
        name: String,
    },
    /// A value that is not a finite number.
    #[error("{flag}: the value of `{name}` must be a finite number, not `{value}`")]
    NotFinite {
        /// The flag the list was given to.
        flag: String,
        /// The name.
        name: String,
        /// The value as written.
        value: String,
    },
}

/// "a=1, b=2" as names and finite numbers (`--params`, `--init`); the error names `flag`.
pub fn numbers(flag: &str, text: &str) -> Result<Vec<(String, f64)>, NumbersError> {
    let pairs = super::modes::assignments(text).map_err(|bad| NumbersError::NotAnAssignment {
        flag: flag.to_string(),
        bad,
    })?;
    let mut out: Vec<(String, f64)> = Vec::with_capacity(pairs.len());
    for (name, value) in pairs {
        if out.iter().any(|(n, _)| *n == name) {
            return Err(NumbersError::GivenTwice {
                flag: flag.to_string(),
                name,
            });
        }
        match value.parse::<f64>() {
            Ok(v) if v.is_finite() => out.push((name, v)),
            _ => {
                return Err(NumbersError::NotFinite {
                    flag: flag.to_string(),
                    name,
                    value,
                });
            }
        }
    }
    Ok(out)
}

/// Simulates `sys` from rest-or-given initial values to `opts.t_end`. Reports to the
/// callback a face set with [`with_ambient`](crate::progress::with_ambient), if any.
pub fn simulation(
    sys: &mut System,
    opts: &SimulationOptions,
) -> Result<SimulationReport, SimulationError> {
    simulation_with(sys, opts, &mut Ambient)
}

/// [`simulation`] that reports the integration's progress to `progress` (millionths of the
/// interval, or fixed steps); a `Break` ends it with `SimulationError::Sim(SimError::Interrupted)`.
pub fn simulation_with(
    sys: &mut System,
    opts: &SimulationOptions,
    progress: &mut dyn Progress,
) -> Result<SimulationReport, SimulationError> {
    check_options(opts)?;
    let params = motion_parameters(sys, &opts.params);
    let mut rhs = Rhs::new(sys, &params)?;
    let h_conserved = rhs.energy_conserved();
    let names = state_names(rhs.names());
    let y0 = initial_state(&names, &opts.init)?;
    let mech = |e: crate::mechanics::MechError| SimulationError::Sim(e.into());
    let values = crate::simulate::parameter_values(sys, &params)?;
    if let Some(off) = off_constraint(sys, &values, &y0).map_err(mech)? {
        return Err(SimulationError::OffConstraint {
            index: off.index,
            text: off.text,
            level: off.level,
            residual: off.residual,
        });
    }
    let mut watch = ConstraintWatch::new(sys, &values).map_err(mech)?;
    let traj = integrate(&mut rhs, &y0, opts, progress).map_err(|e| match e {
        SimError::Singular { t, y } => SimulationError::Singular {
            t,
            state: line(&state(&names, &y)),
        },
        e => SimulationError::Sim(e),
    })?;
    let grid = traj
        .sample_even(opts.samples)
        .into_iter()
        .map(|(t, y)| rhs.energy(t, &y).map(|h| (t, y, h)))
        .collect::<Result<Vec<_>, _>>()?;
    let constraint_drift = watch.as_mut().map(|w| {
        (grid.iter())
            .map(|(t, y, _)| w.residual(*t, y))
            .fold(0.0, f64::max)
    });
    let h_start = rhs.energy(0.0, &traj.y0)?;
    let h_end = rhs.energy(traj.t_end, &traj.y_final)?;
    let max_rel_energy_error = largest_drift(&grid, h_start);
    let reports = reports_at(&traj, &names, &opts.report_at)?;
    // Those of the motion only: a bank problem's other parts may have more.
    let idle = unused_parameters(sys, &[]);
    let given: Vec<(String, f64)> = (sys.parameters.iter())
        .filter(|p| !idle.contains(&p.name))
        .filter_map(|p| opts.params.iter().find(|(n, _)| *n == p.name).cloned())
        .collect();
    Ok(SimulationReport {
        start: state(&names, &traj.y0),
        params: State(given),
        method: traj.method,
        steps: traj.stats.accepted,
        rejected: traj.stats.rejected,
        rhs_evals: traj.stats.rhs_evals,
        h_start,
        h_end,
        max_rel_energy_error,
        reports,
        final_state: state(&names, &traj.y_final),
        h_conserved,
        constraint_drift,
        t_end: traj.t_end,
        grid,
        names,
        units: AxisUnits::default(),
    })
}

/// max |h − h(0)| / |h(0)| over the grid (absolute when h(0) = 0).
fn largest_drift(grid: &[(f64, Vec<f64>, f64)], h_start: f64) -> f64 {
    let scale = if h_start == 0.0 { 1.0 } else { h_start.abs() };
    grid.iter()
        .map(|(_, _, h)| (h - h_start).abs() / scale)
        .fold(0.0, f64::max)
}

/// The states at the asked times, in time order, each time once (from dense output).
fn reports_at(
    traj: &Trajectory,
    names: &[String],
    asked: &[f64],
) -> Result<Vec<TimedState>, SimError> {
    let mut times = asked.to_vec();
    crate::sort::sort_by(&mut times, f64::total_cmp);
    times.dedup();
    times
        .iter()
        .map(|&t| {
            Ok(TimedState {
                t,
                state: state(names, &traj.at(t)?),
            })
        })
        .collect()
}

/// The parameters of `sys` that occur neither in L nor in a force and have no value (a bank
/// problem declares parameters for all its parts): any value does for them.
fn unused_parameters(sys: &System, given: &[(String, f64)]) -> Vec<String> {
    let mut used = sys.pool.variables(sys.lagrangian);
    for &f in &sys.forces {
        used.extend(sys.pool.variables(f));
    }
    sys.parameters
        .iter()
        .filter(|p| !used.iter().any(|(s, _)| *s == p.sym))
        .filter(|p| !given.iter().any(|(n, _)| *n == p.name))
        .map(|p| p.name.clone())
        .collect()
}

/// `given` and any value (1) for the parameters of `sys` that its motion does not involve (a
/// bank problem declares parameters for all its parts): what [`Rhs::new`] needs.
pub fn motion_parameters(sys: &System, given: &[(String, f64)]) -> Vec<(String, f64)> {
    let unused = unused_parameters(sys, given);
    (given.iter().cloned())
        .chain(unused.into_iter().map(|n| (n, 1.0)))
        .collect()
}

/// The parameters of the motion of `sys` (in L or a force) that `given` has no value for.
pub fn missing_parameters(sys: &System, given: &[(String, f64)]) -> Vec<String> {
    let unused = unused_parameters(sys, given);
    sys.parameters
        .iter()
        .filter(|p| !unused.contains(&p.name) && !given.iter().any(|(n, _)| *n == p.name))
        .map(|p| p.name.clone())
        .collect()
}

/// The checks that need no system.
pub(super) fn check_options(opts: &SimulationOptions) -> Result<(), SimulationError> {
    if !(opts.t_end.is_finite() && opts.t_end > 0.0) {
        return Err(SimulationError::TEnd(opts.t_end));
    }
    for (what, got, max) in [
        ("--samples", opts.samples, MAX_SAMPLES),
        ("--report-at", opts.report_at.len(), MAX_REPORTS),
    ] {
        if got > max {
            return Err(SimulationError::TooMany { what, got, max });
        }
    }
    if let Some(&t) = opts
        .report_at
        .iter()
        .find(|&&t| !(0.0..=opts.t_end).contains(&t))
    {
        return Err(SimulationError::ReportTime {
            t,
            t_end: opts.t_end,
        });
    }
    if opts.samples < 2 {
        return Err(SimulationError::Invalid(format!(
            "--samples {} is too few: the grid needs its two ends at least",
            opts.samples
        )));
    }
    match (opts.method, opts.dt) {
        (Method::Rk4, None) => Err(SimulationError::MissingDt("rk4")),
        (Method::Gauss, None) => Err(SimulationError::MissingDt("gauss")),
        (Method::Dop853, Some(_)) => Err(SimulationError::Invalid(
            "--dt is the step of rk4 and gauss; dop853 chooses its own steps from --rtol and --atol"
                .into(),
        )),
        (_, Some(dt)) if !(dt > 0.0 && dt.is_finite()) => Err(SimulationError::Invalid(format!(
            "--dt must be a positive number, not {dt}"
        ))),
        (_, Some(dt)) if dt > opts.t_end => Err(SimulationError::Invalid(format!(
            "--dt {dt} is longer than the run (t = 0 … {}): a single step says nothing",
            opts.t_end
        ))),
        _ => Ok(()),
    }
}

/// Runs the chosen integrator from t = 0.
fn integrate(
    rhs: &mut Rhs,
    y0: &[f64],
    opts: &SimulationOptions,
    progress: &mut dyn Progress,
) -> Result<Trajectory, SimError> {
    let span = (0.0, y0, opts.t_end);
    match (opts.method, opts.dt) {
        (Method::Dop853, _) => {
            let tol = Tolerances::new(opts.rtol, opts.atol);
            dop853_with(rhs, span, &tol, progress)
        }
        (Method::Rk4, Some(dt)) => rk4_with(rhs, span, dt, progress),
        (Method::Gauss, Some(dt)) => gauss_with(rhs, span, dt, progress),
        (_, None) => Err(SimError::Invalid("a fixed-step method needs a step".into())),
    }
}

/// `q…` then `q'…`.
pub fn state_names(coords: &[String]) -> Vec<String> {
    let mut names = coords.to_vec();
    names.extend(coords.iter().map(|c| format!("{c}'")));
    names
}

pub(super) fn state(names: &[String], y: &[f64]) -> State {
    State(names.iter().cloned().zip(y.iter().copied()).collect())
}

/// y0 from the given values, zero elsewhere.
pub fn initial_state(
    names: &[String],
    init: &[(String, f64)],
) -> Result<Vec<f64>, SimulationError> {
    let mut y0 = vec![0.0; names.len()];
    let mut seen = vec![false; names.len()];
    for (name, value) in init {
        let Some(i) = names.iter().position(|n| n == name) else {
            return Err(SimulationError::UnknownCoordinate {
                name: name.clone(),
                suggestion: crate::diagnostic::did_you_mean(name, names.iter().map(String::as_str)),
            });
        };
        if std::mem::replace(&mut seen[i], true) {
            return Err(SimulationError::Repeated { name: name.clone() });
        }
        y0[i] = *value;
    }
    Ok(y0)
}

impl SimulationReport {
    /// The summary as text, names as typed (`theta1'`): what the command line prints.
    pub fn render(&self, paint: &dyn Paint) -> String {
        self.render_named(paint, &|n: &str| n.to_string())
    }

    /// The summary with names in Unicode (`θ̇₁`), as the REPL shows everything else.
    pub fn render_unicode(&self, paint: &dyn Paint) -> String {
        self.render_named(paint, &crate::expr::names::unicode_state_name)
    }

    fn render_named(&self, paint: &dyn Paint, name: &dyn Fn(&str) -> String) -> String {
        let named = |s: &State| State(s.0.iter().map(|(n, v)| (name(n), *v)).collect());
        let given_line = |s: &State| given_line(&named(s));
        let line = |s: &State| line(&named(s));
        text(|o| {
            let method = match self.method {
                Method::Dop853 => "dop853",
                Method::Rk4 => "rk4",
                Method::Gauss => "gauss",
            };
            writeln!(
                o,
                "{} {method}, t = 0 … {}",
                paint.heading("Method:"),
                self.t_end
            )?;
            writeln!(o, "{} {}", paint.heading("Start:"), given_line(&self.start))?;
            if !self.params.0.is_empty() {
                let params = given_line(&self.params);
                writeln!(o, "{} {params}", paint.heading("Parameters:"))?;
            }
            writeln!(
                o,
                "{} {} accepted, {} rejected, {} right-hand-side evaluations",
                paint.heading("Steps:"),
                self.steps,
                self.rejected,
                self.rhs_evals
            )?;
            let drift = if self.h_start == 0.0 {
                "largest drift |h − h(0)| (absolute: h(0) = 0)"
            } else {
                "largest relative drift"
            };
            writeln!(
                o,
                "{} h(0) = {:.12e}, h(end) = {:.12e}, {drift} {:.3e}",
                paint.heading("Energy:"),
                self.h_start,
                self.h_end,
                self.max_rel_energy_error
            )?;
            if !self.h_conserved {
                let note =
                    "h is not expected to be constant here (explicit time or forces doing work)";
                writeln!(o, "  {}", paint.warn(note))?;
            } else if self.max_rel_energy_error > UNTRUSTED_DRIFT {
                let note = "h should be constant but drifts this much: the numbers below are not to be trusted; take a smaller step or tighter tolerances";
                writeln!(o, "  {}", paint.warn(note))?;
            }
            if let Some(d) = self.constraint_drift {
                writeln!(
                    o,
                    "{} largest residual |f(q, t)| over the run {d:.3e}",
                    paint.heading("Constraints:")
                )?;
            }
            for r in &self.reports {
                writeln!(
                    o,
                    "{} {}",
                    paint.heading(&format!("t = {}:", r.t)),
                    line(&r.state)
                )?;
            }
            writeln!(o, "{} {}", paint.heading("Final:"), line(&self.final_state))
        })
    }

    /// The even grid as CSV: `t, q…, q'…, h`.
    pub fn csv(&self) -> String {
        text(|o| {
            writeln!(o, "t,{},h", self.names.join(","))?;
            for (t, y, h) in &self.grid {
                write!(o, "{t}")?;
                for v in y {
                    write!(o, ",{v}")?;
                }
                writeln!(o, ",{h}")?;
            }
            Ok(())
        })
    }
}

/// `theta1 = 1.0, theta1' = 0.0`.
pub(super) fn line(s: &State) -> String {
    s.0.iter()
        .map(|(n, v)| format!("{n} = {v:.10}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// "a = 1, b = 9.81": numbers as given (shortest form), for inputs rather than results.
fn given_line(s: &State) -> String {
    s.0.iter()
        .map(|(n, v)| format!("{n} = {v}"))
        .collect::<Vec<_>>()
        .join(", ")
}

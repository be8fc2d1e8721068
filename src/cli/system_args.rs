//! Arguments shared by `derive` and `modes`: how to describe a system on the command line,
//! how its errors are shown, and the terminal's colours for every report.

use std::process::ExitCode;

use clap::Args;

pub(crate) mod body_args;

use lagrange::diagnostic::{Diagnostic, render, render_plain};
use lagrange::mechanics::system::NameError;
use lagrange::mechanics::{MechError, System};

/// A system given on the command line, or a problem of the bank by id.
#[derive(Args, Debug)]
pub struct SystemArgs {
    /// A problem id from the bank (`lagrange problems list`), instead of --lagrangian.
    pub problem: Option<String>,
    /// The Lagrangian, e.g. "1/2 m l^2 theta'^2 + m g l cos(theta)", or @FILE to read it
    /// from a file (as every expression flag here accepts).
    #[arg(long, short = 'L', allow_hyphen_values = true)]
    pub lagrangian: Option<String>,
    /// The kinetic energy (instead of --lagrangian; without --potential, V = 0).
    #[arg(
        long,
        short = 'T',
        allow_hyphen_values = true,
        conflicts_with = "lagrangian"
    )]
    pub kinetic: Option<String>,
    /// The potential energy (with --kinetic, or added to the bodies' potentials).
    #[arg(long, short = 'V', allow_hyphen_values = true)]
    pub potential: Option<String>,
    /// A point body, "mass=m; position=x, y" (its position in the coordinates); repeat for several.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["lagrangian", "kinetic"])]
    pub point: Vec<String>,
    /// A rigid body, "mass=M; position=xc, yc; inertia=I; angle=theta" (planar: centre of mass,
    /// moment about it, orientation angle) or in 3-D "mass=M; position=x, y, z; moments=I1, I2, I3"
    /// (or tensor=nine entries row by row) with "euler=phi, theta, psi" (z-x-z) or
    /// "omega_body=w1, w2, w3" (body-frame angular velocity); repeat for several.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["lagrangian", "kinetic"])]
    pub rigid: Vec<String>,
    /// Uniform gravity on the bodies, "g" (down the y axis) or "g, z" (down the z axis).
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["lagrangian", "kinetic"])]
    pub gravity: Option<String>,
    /// A spring between bodies or fixed points, "k=k; from=1; to=0, 0; natural=l0" (ends:
    /// a body number, 1-based in the order --point then --rigid, or a point); repeat.
    #[arg(long, allow_hyphen_values = true, conflicts_with_all = ["lagrangian", "kinetic"])]
    pub spring: Vec<String>,
    /// The generalized coordinates, comma-separated, e.g. "theta1,theta2".
    #[arg(long, short = 'q', default_value = "")]
    pub coords: String,
    /// Generalized non-conservative forces, one per coordinate, separated by `;`.
    #[arg(long, allow_hyphen_values = true)]
    pub force: Option<String>,
    /// A force vector at a point, "x, y: Fx, Fy" (or 3-D): Qᵢ = F·∂r/∂qᵢ is added to the
    /// generalized forces; repeat for several.
    #[arg(long, allow_hyphen_values = true)]
    pub force_at: Vec<String>,
    /// A constraint f = 0 (or lhs = rhs); repeat for several. Velocity-linear constraints
    /// are nonholonomic.
    #[arg(long, allow_hyphen_values = true)]
    pub constraint: Vec<String>,
}

impl SystemArgs {
    /// Builds the system (from the bank when a problem id is given).
    pub fn build(&self, problems: Option<&std::path::Path>) -> Result<System, CliError> {
        self.build_with_defaults(problems).map(|(sys, ..)| sys)
    }

    /// The system and, for a bank problem, its suggested simulation numbers and the units of
    /// its axes (none for a typed system: it declares no dimensions).
    pub fn build_with_defaults(
        &self,
        problems: Option<&std::path::Path>,
    ) -> Result<Built, CliError> {
        match &self.problem {
            Some(id) => self.build_problem(id, problems),
            None => Ok((self.build_typed()?, Default::default(), Default::default())),
        }
    }

    /// A bank problem's system, suggestions and units.
    fn build_problem(
        &self,
        id: &str,
        problems: Option<&std::path::Path>,
    ) -> Result<Built, CliError> {
        if self.lagrangian.is_some() || self.kinetic.is_some() {
            return Err(CliError::usage(
                "give a problem id or --lagrangian, not both",
            ));
        }
        let p = crate::face::find_problem(problems, id)
            .map_err(CliError::Usage)?
            .ok_or_else(|| {
                let ids = lagrange::bank::embedded::FILES
                    .iter()
                    .map(|(f, _)| f.trim_end_matches(".toml"));
                let hint = lagrange::diagnostic::did_you_mean(id, ids)
                    .filter(|_| problems.is_none())
                    .map_or(String::new(), |s| format!("; did you mean `{s}`?"));
                CliError::Usage(format!(
                    "no problem `{id}` (see `lagrange problems list`){hint}"
                ))
            })?;
        let units = lagrange::report::units::AxisUnits::of(&p);
        Ok((p.system, p.simulation, units))
    }

    /// The system typed with flags: a Lagrangian, T and V, or bodies; forces; constraints.
    fn build_typed(&self) -> Result<System, CliError> {
        // Names as in expressions: `θ₁` is `theta1`.
        let spelled: Vec<String> = self
            .coords
            .split(',')
            .filter(|c| !c.trim().is_empty())
            .map(lagrange::expr::spelled)
            .collect();
        let coords: Vec<&str> = spelled.iter().map(String::as_str).collect();
        let no_system = self.lagrangian.is_none()
            && self.kinetic.is_none()
            && self.potential.is_none()
            && self.point.is_empty()
            && self.rigid.is_empty();
        if no_system && coords.is_empty() {
            return Err(CliError::usage(
                "give a problem id (see `lagrange problems list`) or a system: --lagrangian L --coords q1,q2",
            ));
        }
        if coords.is_empty() {
            return Err(CliError::usage("--coords names no coordinate"));
        }
        lagrange::mechanics::system::check_coordinate_names(&coords).map_err(CliError::Name)?;
        let text =
            |flag: &str, v: &Option<String>| v.as_deref().map(|v| expression(flag, v)).transpose();
        let lagrangian = text("--lagrangian", &self.lagrangian)?;
        let kinetic = text("--kinetic", &self.kinetic)?;
        let potential = text("--potential", &self.potential)?;
        let bodies = body_args::BodyFlags {
            points: &self.point,
            rigids: &self.rigid,
            gravity: self.gravity.as_deref(),
            springs: &self.spring,
            potential: potential.as_deref(),
        };
        if (self.gravity.is_some() || !self.spring.is_empty()) && !bodies.any() {
            return Err(CliError::usage(
                "--gravity and --spring act on bodies: give --point or --rigid",
            ));
        }
        let mut sys = match (lagrangian, kinetic, potential.as_deref()) {
            _ if bodies.any() => bodies.build(System::from_lagrangian("0", &coords)?)?,
            (Some(_), _, Some(_)) => {
                return Err(CliError::usage(
                    "--potential goes with --kinetic or bodies, not --lagrangian",
                ));
            }
            (Some(l), _, _) => System::from_lagrangian(&l, &coords)?,
            // A kinetic energy alone is a free system: V = 0.
            (None, Some(t), v) => System::from_energies(&t, v.unwrap_or("0"), &coords)?,
            _ => {
                return Err(CliError::usage(
                    "give --lagrangian, --kinetic (and --potential), or bodies (--point, --rigid)",
                ));
            }
        };
        if let Some(f) = text("--force", &self.force)? {
            sys.set_forces(&f)?;
        }
        for f in &self.force_at {
            body_args::force_at(&mut sys, &expression("--force-at", f)?)?;
        }
        for c in &self.constraint {
            sys.add_constraint(&expression("--constraint", c)?)?;
        }
        Ok(sys)
    }
}

/// A system with, for a bank problem, its suggested simulation numbers and its axes' units.
pub type Built = (
    System,
    lagrange::problem::SimulationDefaults,
    lagrange::report::units::AxisUnits,
);

/// The largest file an expression flag reads with `@FILE` (a derivation's input may be
/// large, a bicycle's T is 24 kB, but stays bounded).
const MAX_EXPRESSION_FILE: u64 = 1_000_000;

/// The text of an expression flag: the value itself, or the contents of FILE for `@FILE`.
fn expression(flag: &str, value: &str) -> Result<String, CliError> {
    let Some(path) = value.strip_prefix('@') else {
        return Ok(value.to_string());
    };
    let too_big = |n: u64| {
        CliError::Usage(format!(
            "{flag} @{path}: the file is {n} bytes, over the limit of {MAX_EXPRESSION_FILE}"
        ))
    };
    let unreadable =
        |e: std::io::Error| CliError::Usage(format!("{flag} @{path}: cannot read the file: {e}"));
    let meta = std::fs::metadata(path).map_err(unreadable)?;
    if meta.len() > MAX_EXPRESSION_FILE {
        return Err(too_big(meta.len()));
    }
    let mut text = String::new();
    use std::io::Read as _;
    std::fs::File::open(path)
        .map_err(unreadable)?
        .take(MAX_EXPRESSION_FILE + 1)
        .read_to_string(&mut text)
        .map_err(unreadable)?;
    if text.len() as u64 > MAX_EXPRESSION_FILE {
        return Err(too_big(text.len() as u64));
    }
    Ok(text.trim().to_string())
}

/// What `derive` and `modes` can fail with: the face's own argument errors, or the
/// library's.
#[derive(Debug)]
pub enum CliError {
    /// An argument is malformed or arguments do not fit together.
    Usage(String),
    /// The mechanics could not be done.
    Mech(MechError),
    /// A name given to --coords cannot be a coordinate.
    Name(NameError),
    /// A library error with its own code and help (`derive --at`).
    Coded {
        code: &'static str,
        message: String,
        help: String,
    },
}

impl CliError {
    pub fn usage(message: &str) -> CliError {
        CliError::Usage(message.to_string())
    }
}

impl From<MechError> for CliError {
    fn from(e: MechError) -> Self {
        CliError::Mech(e)
    }
}

/// Prints an error through the one diagnostic renderer (with the input and a caret for a
/// parse error) and returns exit code 2.
pub fn report(e: &CliError, color: bool) -> ExitCode {
    let text = match e {
        CliError::Usage(message) => render_plain(&Diagnostic::new(
            "usage",
            message.as_str(),
            "the message names what to change; `--help` after the command lists its flags",
        )),
        CliError::Mech(
            m @ MechError::Parse {
                what, source_text, ..
            },
        ) => render(what, source_text, &Diagnostic::from(m), color),
        CliError::Mech(m) => render_plain(&Diagnostic::from(m).with_help(help(m))),
        CliError::Name(n) => render_plain(&Diagnostic::new(
            n.code(),
            format!("--coords: {n}"),
            n.help(),
        )),
        CliError::Coded {
            code,
            message,
            help,
        } => render_plain(&Diagnostic::new(*code, message.as_str(), help.as_str())),
    };
    eprint!("{text}");
    ExitCode::from(2)
}

/// The help for a mechanics error, phrased with this face's flags.
fn help(e: &MechError) -> String {
    match e {
        MechError::UnknownCoordinate { .. } => "list it in --coords".into(),
        MechError::MissingValue { name } => format!("add `{name}=<value>` to --params"),
        MechError::NoEquilibrium => "widen the ranges, or give --at".into(),
        MechError::ValueForCoordinate { .. } => "give a coordinate's value with --at".into(),
        MechError::ClosedFormTooLarge { .. } => "drop --symbolic for the numeric modes".into(),
        other => other.help(),
    }
}

/// `--params`, `--init` and an end time over a bank problem's suggestions: a given parameter
/// replaces the suggested one by name, a non-empty `--init` replaces the suggested start.
pub fn chosen(
    defaults: &lagrange::problem::SimulationDefaults,
    params: &str,
    init: &str,
    t_end: Option<f64>,
) -> Result<lagrange::problem::SimulationDefaults, CliError> {
    let given_init = if init.trim().is_empty() {
        None
    } else {
        Some(numbers("--init", init)?)
    };
    Ok(defaults.complete(numbers("--params", params)?, given_init, t_end))
}

/// "a=1, b=2" as names and numbers (`--params`, `--init` of `simulate` and `chaos`).
pub fn numbers(flag: &str, text: &str) -> Result<Vec<(String, f64)>, CliError> {
    lagrange::report::simulation::numbers(flag, text).map_err(|e| CliError::Usage(e.to_string()))
}

/// The terminal's colours, shared with the other faces.
pub use crate::face::Terminal;

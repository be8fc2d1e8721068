//! Arguments shared by `derive` and `modes`: how to describe a system on the command line,
//! and how its errors are shown.

use std::process::ExitCode;

use clap::Args;

use lagrange::diagnostic::render_parse_error;
use lagrange::mechanics::{MechError, System};

/// A system given on the command line, or a problem of the bank by id.
#[derive(Args, Debug)]
pub struct SystemArgs {
    /// A problem id from the bank (`lagrange problems list`), instead of --lagrangian.
    pub problem: Option<String>,
    /// The Lagrangian, e.g. "1/2 m l^2 theta'^2 + m g l cos(theta)".
    #[arg(long, short = 'L')]
    pub lagrangian: Option<String>,
    /// The kinetic energy (with --potential, instead of --lagrangian).
    #[arg(
        long,
        short = 'T',
        requires = "potential",
        conflicts_with = "lagrangian"
    )]
    pub kinetic: Option<String>,
    /// The potential energy (with --kinetic).
    #[arg(long, short = 'V', requires = "kinetic")]
    pub potential: Option<String>,
    /// The generalized coordinates, comma-separated, e.g. "theta1,theta2".
    #[arg(long, short = 'q', default_value = "")]
    pub coords: String,
    /// Generalized non-conservative forces, one per coordinate, separated by `;`.
    #[arg(long)]
    pub force: Option<String>,
    /// A constraint f = 0 (or lhs = rhs); repeat for several. Velocity-linear constraints
    /// are nonholonomic.
    #[arg(long)]
    pub constraint: Vec<String>,
}

impl SystemArgs {
    /// Builds the system (from the bank when a problem id is given).
    pub fn build(&self, problems: Option<&std::path::Path>) -> Result<System, MechError> {
        if let Some(id) = &self.problem {
            if self.lagrangian.is_some() || self.kinetic.is_some() {
                return Err(MechError::Invalid(
                    "give a problem id or --lagrangian, not both".into(),
                ));
            }
            let bank = super::problems::load_bank(problems).map_err(MechError::Invalid)?;
            let p = bank.problem(id).ok_or_else(|| {
                MechError::Invalid(format!("no problem `{id}` (see `lagrange problems list`)"))
            })?;
            return Ok(p.system.clone());
        }
        let coords: Vec<&str> = self
            .coords
            .split(',')
            .map(str::trim)
            .filter(|c| !c.is_empty())
            .collect();
        if coords.is_empty() {
            return Err(MechError::Invalid("--coords names no coordinate".into()));
        }
        let mut sys = match (&self.lagrangian, &self.kinetic, &self.potential) {
            (Some(l), _, _) => System::from_lagrangian(l, &coords)?,
            (None, Some(t), Some(v)) => System::from_energies(t, v, &coords)?,
            _ => {
                return Err(MechError::Invalid(
                    "give --lagrangian, or --kinetic and --potential".into(),
                ));
            }
        };
        if let Some(f) = &self.force {
            sys.set_forces(f)?;
        }
        for c in &self.constraint {
            sys.add_constraint(c)?;
        }
        Ok(sys)
    }
}

/// Prints a mechanics error (with the input and a caret for a parse error) and returns
/// exit code 2.
pub fn report(e: &MechError, color: bool) -> ExitCode {
    match e {
        MechError::Parse {
            what,
            source_text,
            error,
        } => {
            eprint!("{}", render_parse_error(what, source_text, error, color));
        }
        other => eprintln!("error: {other}\n  help: {}", other.help()),
    }
    ExitCode::from(2)
}

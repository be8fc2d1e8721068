//! Errors of the mechanics layer: data, with a one-line help each.

use crate::expr::ParseError;

/// What can go wrong building or analysing a system.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MechError {
    #[error("cannot read {what}: {error}")]
    Parse {
        what: String,
        source_text: String,
        error: Box<ParseError>,
    },
    #[error("`{name}` is not a coordinate of this system")]
    UnknownCoordinate { name: String },
    #[error("L does not depend on {name}' quadratically: the system is degenerate")]
    NoKineticTerm { name: String },
    #[error("the mass matrix is singular: the velocities {names} enter L only in a combination")]
    SingularMass { names: String },
    #[error("parameter `{name}` has no value")]
    MissingValue { name: String },
    #[error("no equilibrium was found in the coordinate ranges")]
    NoEquilibrium,
    #[error("{what} is undefined at this state")]
    Undefined { what: String },
    #[error("{0}")]
    Invalid(String),
}

impl MechError {
    /// One line telling the user what to do.
    pub fn help(&self) -> String {
        match self {
            MechError::Parse { error, .. } => error.help(),
            MechError::UnknownCoordinate { .. } => "list it in --coords".into(),
            MechError::NoKineticTerm { name } => {
                format!(
                    "give {name} a kinetic term such as 1/2*m*{name}'^2, or drop it from the coordinates"
                )
            }
            MechError::SingularMass { .. } => {
                "choose independent coordinates, or add the missing kinetic terms".into()
            }
            MechError::MissingValue { name } => format!("add `{name}=<value>` to --params"),
            MechError::NoEquilibrium => "widen the ranges, or give --at".into(),
            MechError::Undefined { .. } => "choose another state".into(),
            MechError::Invalid(_) => "check the input".into(),
        }
    }
}

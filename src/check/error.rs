//! Why the checker could not check: usage errors (no such part) and parts or reference answers
//! that cannot be prepared or read. Never a judgement of a student's answer — that is a
//! [`Diagnosis`](super::Diagnosis) in a verdict.

use crate::diagnostic::Diagnostic;
use crate::expr::{ParseError, ParseErrorKind};
use crate::mechanics::error::MechError;

/// An error of the checker, with a stable [`code`](CheckError::code) and a one-line
/// [`help`](CheckError::help).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CheckError {
    /// The problem has no part with this id.
    #[error("problem `{problem}` has no part `{part}`")]
    UnknownPart { problem: String, part: String },
    /// The part's `substitute` values cannot be applied to the system.
    #[error("{error}")]
    Substitution { error: MechError },
    /// The equations of motion of the (substituted) system cannot be derived.
    #[error("{error}")]
    Derivation { error: MechError },
    /// Expressions of the part cannot be compiled for evaluation.
    #[error("{error}")]
    Compile { error: MechError },
    /// The accelerations cannot be solved for (the dynamics is unusable).
    #[error("{error}")]
    Dynamics { error: MechError },
    /// The assumptions reject (nearly) every sample point.
    #[error("the assumptions ({assumptions}) hold almost nowhere in the parameter ranges")]
    Unsatisfiable { assumptions: String },
    /// An expression names a symbol that is not the problem's.
    #[error("`{name}` is not a symbol of this problem")]
    UnknownSymbol { name: String },
    /// The reference cannot be evaluated at any sample point.
    #[error("the reference is undefined at every sample point")]
    ReferenceUndefined,
    /// An answer item (expression) cannot be read.
    #[error("`{src}`: {error} ({help})", help = .error.help())]
    UnreadableItem { src: String, error: Box<ParseError> },
    /// An equation cannot be read.
    #[error("`{src}`: {error}")]
    UnreadableEquation { src: String, error: Box<ParseError> },
    /// An equilibrium point cannot be read.
    #[error("`{src}`: {error}")]
    UnreadablePoint { src: String, error: Box<ParseError> },
    /// An equilibrium assigns to something that is not a coordinate.
    #[error("`{src}`: the left side must be a coordinate")]
    NotACoordinate { src: String },
    /// An equilibrium equation whose left side is not a name.
    #[error("`{src}`: write coordinate = value")]
    NotAnAssignment { src: String },
    /// A list in an equilibrium holds something other than assignments.
    #[error("`{src}`: write coordinate = value for each coordinate")]
    NotAssignments { src: String },
    /// An equilibrium that is neither an assignment nor a list of them.
    #[error("`{src}`: an equilibrium is coordinate = value")]
    NotAnEquilibrium { src: String },
    /// An equilibrium that leaves a coordinate out.
    #[error("`{src}` gives no value for {coordinate}")]
    MissingCoordinate { src: String, coordinate: String },
    /// The part's `at` names something that is not a coordinate.
    #[error("`at` names `{name}`, which is not a coordinate")]
    BadAt { name: String },
}

impl CheckError {
    /// The stable code, e.g. `unreadable`.
    pub fn code(&self) -> &'static str {
        match self {
            CheckError::UnknownPart { .. } => "unknown-part",
            CheckError::Substitution { .. }
            | CheckError::Derivation { .. }
            | CheckError::Compile { .. }
            | CheckError::Dynamics { .. } => "unusable",
            CheckError::Unsatisfiable { .. }
            | CheckError::UnknownSymbol { .. }
            | CheckError::ReferenceUndefined => "sampling",
            CheckError::UnreadableItem { error, .. }
                if matches!(error.kind, ParseErrorKind::UnknownName { .. }) =>
            {
                "undeclared-symbol"
            }
            CheckError::UnreadableItem { .. }
            | CheckError::UnreadableEquation { .. }
            | CheckError::UnreadablePoint { .. }
            | CheckError::NotACoordinate { .. }
            | CheckError::NotAnAssignment { .. }
            | CheckError::NotAssignments { .. }
            | CheckError::NotAnEquilibrium { .. }
            | CheckError::MissingCoordinate { .. } => "unreadable",
            CheckError::BadAt { .. } => "bad-at",
        }
    }

    /// One line telling the author or user what to do (names no command-line flag).
    pub fn help(&self) -> String {
        match self {
            CheckError::UnknownPart { .. } => "use one of the problem's part ids".into(),
            CheckError::Substitution { .. } => {
                "give each substituted parameter a value readable in the problem's symbols".into()
            }
            CheckError::Derivation { .. } => {
                "check the problem's Lagrangian (or bodies) and coordinates".into()
            }
            CheckError::Compile { .. } | CheckError::UnknownSymbol { .. } => {
                "use only the problem's coordinates and parameters".into()
            }
            CheckError::Dynamics { .. } => {
                "the equations of motion must determine every acceleration".into()
            }
            CheckError::Unsatisfiable { .. } => {
                "loosen the assumptions or widen the parameter ranges".into()
            }
            CheckError::ReferenceUndefined => {
                "check the reference answer against the parameter ranges".into()
            }
            CheckError::UnreadableItem { error, .. }
            | CheckError::UnreadableEquation { error, .. }
            | CheckError::UnreadablePoint { error, .. } => error.help(),
            CheckError::NotACoordinate { .. }
            | CheckError::NotAnAssignment { .. }
            | CheckError::NotAssignments { .. }
            | CheckError::NotAnEquilibrium { .. }
            | CheckError::MissingCoordinate { .. } => {
                "write an equilibrium as coordinate = value, one per coordinate".into()
            }
            CheckError::BadAt { .. } => "name a coordinate of the problem in `at`".into(),
        }
    }
}

impl From<&CheckError> for Diagnostic {
    fn from(e: &CheckError) -> Self {
        Diagnostic::new(e.code(), e.to_string(), e.help())
    }
}

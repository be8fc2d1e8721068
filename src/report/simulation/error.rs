//! [`SimulationError`]: why a simulation could not be set up (input), could not be finished
//! (numerics) or was stopped by its progress callback, with a code and a line of help.

use crate::simulate::SimError;
use crate::simulate::portrait::PortraitError;

/// Why a simulation could not be set up (input) or could not be finished (numerics).
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SimulationError {
    /// An initial value names no coordinate or velocity.
    #[error("`{name}` in --init is not a coordinate or velocity of the system{}", suggestion.as_ref().map_or(String::new(), |s| format!(" (did you mean `{s}`?)")))]
    UnknownCoordinate {
        name: String,
        suggestion: Option<String>,
    },
    /// The same value given twice.
    #[error("`{name}` is given twice in --init")]
    Repeated { name: String },
    /// The end time is not positive.
    #[error("--t-end must be a positive number of seconds, not {0}")]
    TEnd(f64),
    /// A fixed-step method without its step.
    #[error("--method {0} is a fixed-step method: give its step with --dt")]
    MissingDt(&'static str),
    /// Too many samples or report times.
    #[error("{what} asks for {got} points, over the limit of {max}")]
    TooMany {
        what: &'static str,
        got: usize,
        max: usize,
    },
    /// A report time outside (0, t_end].
    #[error("--report-at {t} is outside the simulated interval [0, {t_end}]")]
    ReportTime { t: f64, t_end: f64 },
    /// The initial state is off a constraint.
    #[error(
        "the initial state is off constraint {index} ({text} = 0): its {level} miss it by {residual:.3e}; give initial values on it"
    )]
    OffConstraint {
        index: usize,
        text: String,
        level: &'static str,
        residual: f64,
    },
    /// A setting that cannot give a meaningful run.
    #[error("{0}")]
    Invalid(String),
    /// M became singular along the motion.
    #[error("the mass matrix became singular at t = {t}, where {state}")]
    Singular { t: f64, state: String },
    /// The library's error (setup or along the motion).
    #[error(transparent)]
    Sim(#[from] SimError),
    /// A phase-portrait family that cannot be drawn.
    #[error(transparent)]
    Portrait(#[from] PortraitError),
}

impl SimulationError {
    /// Whether the progress callback stopped the run.
    pub fn interrupted(&self) -> bool {
        matches!(self, SimulationError::Sim(SimError::Interrupted))
    }

    /// A short stable code for the diagnostic.
    pub fn code(&self) -> &'static str {
        match self {
            SimulationError::Sim(SimError::Interrupted) => "interrupted",
            SimulationError::Singular { .. } => "singular",
            SimulationError::OffConstraint { .. } => "off-constraint",
            _ if self.along_the_way() => "numerics",
            _ => "usage",
        }
    }

    /// What to do about it, in one line (no flag of any face: the faces add theirs).
    pub fn help(&self) -> String {
        match self {
            SimulationError::Sim(SimError::MissingParameters { names }) => format!(
                "give {} a value",
                names
                    .iter()
                    .map(|n| format!("`{n}=<value>`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            SimulationError::UnknownCoordinate { .. } | SimulationError::Repeated { .. } => {
                "name each coordinate (q) or velocity (q') once".into()
            }
            SimulationError::OffConstraint { .. } => {
                "choose positions and velocities that satisfy every constraint".into()
            }
            SimulationError::Singular { .. } => {
                "the coordinates degenerate there; choose other coordinates or start elsewhere"
                    .into()
            }
            SimulationError::Sim(SimError::Interrupted) => {
                "the run was stopped before its end; run it again to finish".into()
            }
            SimulationError::Sim(SimError::StepUnderflow { .. }) => {
                "if the motion really blows up there, end the run before that time".into()
            }
            _ if self.along_the_way() => {
                "shorten the time, or tighten the step (smaller tolerances or step)".into()
            }
            SimulationError::Sim(SimError::UnknownParameter { .. }) => {
                "give values only to the system's parameters".into()
            }
            SimulationError::Sim(SimError::Mechanics(m)) => m.help(),
            SimulationError::TEnd(_) => "give a positive end time".into(),
            SimulationError::MissingDt(_) => "give the step, or use the adaptive dop853".into(),
            SimulationError::TooMany { .. } => "ask for fewer points".into(),
            SimulationError::ReportTime { .. } => {
                "report times lie between 0 and the end time".into()
            }
            SimulationError::Invalid(_) => "change the setting named above".into(),
            _ => "check the values given".into(),
        }
    }

    /// Whether the input was fine but the motion could not be followed (singular M,
    /// divergence, step underflow): a "no" rather than a usage error.
    pub fn along_the_way(&self) -> bool {
        matches!(
            self,
            SimulationError::Singular { .. }
                | SimulationError::Sim(
                    SimError::Singular { .. }
                        | SimError::Diverges { .. }
                        | SimError::StepUnderflow { .. }
                        | SimError::TooManySteps { .. }
                        | SimError::NoConvergence { .. }
                )
                | SimulationError::Portrait(PortraitError::Sim(
                    SimError::Singular { .. }
                        | SimError::Diverges { .. }
                        | SimError::StepUnderflow { .. }
                        | SimError::TooManySteps { .. }
                ))
        )
    }
}

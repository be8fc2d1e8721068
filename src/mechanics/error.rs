//! Errors of the mechanics layer (names a user typed are shown with invisible and control
//! characters made visible): one variant per situation, with the data a face needs to
//! phrase it, a one-line help that names no face's flags, and a stable code each (through
//! [`Diagnostic`]).

use crate::diagnostic::Diagnostic;
use crate::expr::ParseError;

/// What can go wrong building or analysing a system.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum MechError {
    /// Some text (a Lagrangian, a force, a constraint, a value) did not read.
    #[error("cannot read {what}: {error}")]
    Parse {
        what: String,
        source_text: String,
        error: Box<ParseError>,
    },
    /// A name used as a coordinate is not one.
    #[error("`{}` is not a coordinate of this system", crate::expr::error::visible(.name))]
    UnknownCoordinate { name: String },
    /// A coordinate's velocity does not enter L quadratically.
    #[error("L does not depend on {name}' quadratically: the system is degenerate")]
    NoKineticTerm { name: String },
    /// The mass matrix is singular everywhere (`names`: the velocities, comma-separated).
    #[error("the mass matrix is singular: the velocities {names} enter L only in a combination")]
    SingularMass { names: String },
    /// A numeric analysis needs a value for this parameter.
    #[error("parameter `{}` has no value", crate::expr::error::visible(.name))]
    MissingValue { name: String },
    /// The equilibrium search found nothing.
    #[error("no equilibrium was found in the coordinate ranges")]
    NoEquilibrium,
    /// Something cannot be evaluated at the state asked for.
    #[error("{what} cannot be evaluated at this state")]
    Undefined { what: String },
    /// More generalized forces than coordinates.
    #[error("{given} generalized forces given for {coordinates} coordinates")]
    TooManyForces { given: usize, coordinates: usize },
    /// A constraint involves accelerations.
    #[error("a constraint may involve positions and velocities, not accelerations")]
    AccelerationInConstraint,
    /// A velocity constraint is not linear in the velocities.
    #[error("a velocity constraint must be linear in the velocities")]
    NonlinearVelocityConstraint,
    /// An expression uses a symbol that is neither a coordinate nor a parameter.
    #[error("`{}` is not a symbol of this system", crate::expr::error::visible(.name))]
    UnknownSymbol { name: String },
    /// A value was given for a coordinate where parameter values were expected.
    #[error("`{}` is a coordinate, not a parameter", crate::expr::error::visible(.name))]
    ValueForCoordinate { name: String },
    /// A value was given for a name that is not a parameter.
    #[error("`{}` is not a parameter of this system", crate::expr::error::visible(.name))]
    UnknownParameter { name: String },
    /// Numeric parameter values do not match the system's parameters.
    #[error("wrong number of parameter values")]
    ParameterCount { expected: usize, given: usize },
    /// The mass matrix is not positive definite at the state asked for.
    #[error("the mass matrix is not positive definite here")]
    MassNotPositiveDefinite,
    /// The mass matrix is singular at the state asked for.
    #[error("the mass matrix is singular here")]
    SingularMassHere,
    /// Closed forms of small oscillations are for small systems only.
    #[error(
        "the characteristic polynomial is given in closed form for up to {max} coordinates, not {n}"
    )]
    ClosedFormTooLarge { n: usize, max: usize },
    /// Velocity terms that are not gyroscopic, or circulatory forces: ω² is not the root of
    /// a real polynomial, so no closed form is given.
    #[error("no closed form for ω²: {reason}")]
    ClosedFormNotGyroscopic { reason: String },
    /// The constraint rows are dependent at the state asked for.
    #[error("the constraints are not independent at this state")]
    DependentConstraints,
    /// A constraint involves no coordinate and is not identically zero (`1 = 0`).
    #[error("constraint {index} (`{text} = 0`) never holds: it involves no coordinate")]
    ConstraintNeverHolds { index: usize, text: String },
    /// A constraint is identically zero (`x = x`).
    #[error("constraint {index} (`{text} = 0`) holds identically: it constrains nothing")]
    EmptyConstraint { index: usize, text: String },
    /// More independent constraints than coordinates.
    #[error("{constraints} constraints on {coordinates} coordinates: at most one per coordinate")]
    TooManyConstraints {
        constraints: usize,
        coordinates: usize,
    },
    /// A constraint's row is a combination of the earlier ones everywhere: it repeats them
    /// (`contradicts` is `Some(false)`), contradicts them (`x = 0` with `x = 1`: `Some(true)`),
    /// or which could not be told (`None`; `x = 1` with `x² = 1` picks a solution).
    #[error(
        "constraint {index} (`{text} = 0`) is not independent of the constraints before it: {}",
        match .contradicts {
            Some(true) => "it contradicts them (no state found satisfies them all)",
            Some(false) => "it repeats what they say",
            None => "it repeats them, contradicts them or picks some of their solutions",
        }
    )]
    DependentConstraint {
        index: usize,
        text: String,
        contradicts: Option<bool>,
    },
    /// A generalized force depends on accelerations (it belongs in the mass matrix).
    #[error("the force on {coordinate} depends on accelerations ({acceleration})")]
    ForceWithAcceleration {
        coordinate: String,
        acceleration: String,
    },
    /// The Lagrangian depends on an acceleration: the Euler–Lagrange equations of a first-order
    /// L do not apply to it (the terms with q'' would be silently dropped).
    #[error(
        "the Lagrangian contains the acceleration {acceleration}: the Euler–Lagrange equations d/dt ∂L/∂q' − ∂L/∂q = 0 hold for an L of positions, velocities and time only"
    )]
    AccelerationInLagrangian { acceleration: String },
    /// A name of the system collides with a Lagrange multiplier's name.
    #[error(
        "`{}` is the name of a Lagrange multiplier here, and cannot also name a parameter or coordinate",
        crate::expr::error::visible(.name)
    )]
    MultiplierName { name: String },
    /// Small oscillations with a rolling (velocity) constraint are not linearized: the
    /// reachable positions are not a manifold of fewer coordinates.
    #[error(
        "small oscillations with a rolling (velocity) constraint are not analysed: the constraint restricts velocities, not positions, so the modes of the unconstrained system would be wrong"
    )]
    ModesRolling,
    /// The point asked for is not on a holonomic constraint.
    #[error("the point does not satisfy constraint {index}")]
    OffConstraint { index: usize },
    /// The point is on the constraints but the forces there have a part along the manifold.
    #[error(
        "the point is not an equilibrium on the constraint manifold: the force along it is {residual:.3e}"
    )]
    NotConstrainedEquilibrium { residual: f64 },
    /// As many independent constraints as coordinates: nothing can move.
    #[error("the constraints fix every coordinate: there is nothing to oscillate")]
    ModesNoFreedom,
    /// A constant part of an expression overflows: its value is beyond the largest number
    /// lagrange computes with, so nothing that contains it can be evaluated anywhere.
    #[error(
        "`{expr}` overflows: its value is beyond the largest number lagrange computes with (about 1.8e308)"
    )]
    Overflow { expr: String },
    /// A constant part of an expression has no value (`log(-1)`), so nothing that contains
    /// it can be evaluated anywhere.
    #[error("`{expr}` is undefined")]
    UndefinedConstant { expr: String },
    /// The equations depend on time explicitly (a driven support, the Kapitza pendulum):
    /// the system at rest at t = 0 is not a physical equilibrium, and its linearization is
    /// not the motion about one.
    #[error(
        "the equations depend on time explicitly (through {terms}): equilibria and normal modes of the system frozen at t = 0 are not physical"
    )]
    ExplicitTime { terms: String },
    /// The point asked for is not an equilibrium: the generalized forces there
    /// (`forces`: "∂V/∂θ = …"-style items, comma-separated) do not vanish.
    #[error("{point} is not an equilibrium: {forces}")]
    NotAnEquilibrium { point: String, forces: String },
    /// The equations decouple into blocks whose equilibria combine into more points than
    /// are listed (`count`: their number, in decimal).
    #[error("the equilibria number {count}: more than the {max} that are listed")]
    TooManyEquilibria { count: String, max: usize },
    /// A name given as a coordinate cannot be one (time, π, a function, listed twice).
    #[error(transparent)]
    Name(#[from] super::naming::NameError),
    /// A rigid body or a point force is ill-posed.
    #[error(transparent)]
    Rigid(#[from] super::rigid::RigidError),
    /// A derivative grew past the size limit.
    #[error(transparent)]
    TooLarge(#[from] crate::expr::pool::TooLarge),
}

impl MechError {
    /// A stable kebab-case code.
    pub fn code(&self) -> &'static str {
        match self {
            MechError::Parse { .. } => "parse-error",
            MechError::UnknownCoordinate { .. } => "unknown-coordinate",
            MechError::NoKineticTerm { .. } => "no-kinetic-term",
            MechError::SingularMass { .. } => "singular-mass",
            MechError::MissingValue { .. } => "missing-value",
            MechError::NoEquilibrium => "no-equilibrium",
            MechError::Undefined { .. } => "undefined",
            MechError::TooManyForces { .. } => "too-many-forces",
            MechError::AccelerationInConstraint => "acceleration-in-constraint",
            MechError::NonlinearVelocityConstraint => "nonlinear-velocity-constraint",
            MechError::UnknownSymbol { .. } => "unknown-symbol",
            MechError::ValueForCoordinate { .. } => "value-for-coordinate",
            MechError::UnknownParameter { .. } => "unknown-parameter",
            MechError::ParameterCount { .. } => "parameter-count",
            MechError::MassNotPositiveDefinite => "mass-not-positive-definite",
            MechError::SingularMassHere => "singular-mass-here",
            MechError::ClosedFormTooLarge { .. } => "closed-form-too-large",
            MechError::ClosedFormNotGyroscopic { .. } => "closed-form-not-gyroscopic",
            MechError::DependentConstraints => "dependent-constraints",
            MechError::ConstraintNeverHolds { .. } => "constraint-never-holds",
            MechError::EmptyConstraint { .. } => "empty-constraint",
            MechError::TooManyConstraints { .. } => "too-many-constraints",
            MechError::DependentConstraint {
                contradicts: Some(true),
                ..
            } => "contradictory-constraints",
            MechError::DependentConstraint {
                contradicts: Some(false),
                ..
            } => "redundant-constraint",
            MechError::DependentConstraint { .. } => "dependent-constraint",
            MechError::ForceWithAcceleration { .. } => "force-with-acceleration",
            MechError::AccelerationInLagrangian { .. } => "acceleration-in-lagrangian",
            MechError::MultiplierName { .. } => "multiplier-name",
            MechError::ModesRolling => "modes-rolling-constraint",
            MechError::OffConstraint { .. } => "off-constraint",
            MechError::NotConstrainedEquilibrium { .. } => "not-constrained-equilibrium",
            MechError::ModesNoFreedom => "no-freedom",
            MechError::Overflow { .. } => "overflow",
            MechError::UndefinedConstant { .. } => "undefined-constant",
            MechError::ExplicitTime { .. } => "explicit-time",
            MechError::TooManyEquilibria { .. } => "too-many-equilibria",
            MechError::NotAnEquilibrium { .. } => "not-an-equilibrium",
            MechError::TooLarge(_) => "too-large",
            MechError::Name(e) => e.code(),
            MechError::Rigid(e) => e.code(),
        }
    }

    /// One line telling the user what to do, in terms of the system (a face may rephrase
    /// it for its own flags with [`Diagnostic::with_help`]).
    pub fn help(&self) -> String {
        match self {
            MechError::Parse { error, .. } => error.help(),
            MechError::UnknownCoordinate { .. } => "declare it as a coordinate".into(),
            MechError::NoKineticTerm { name } => {
                format!(
                    "give {name} a kinetic term such as 1/2*m*{name}'^2, or drop it from the coordinates"
                )
            }
            MechError::SingularMass { .. } => {
                "choose independent coordinates, or add the missing kinetic terms".into()
            }
            MechError::MissingValue { name } => format!("give a value for `{name}`"),
            MechError::NoEquilibrium => "widen the ranges, or give the equilibrium".into(),
            MechError::Undefined { .. } => "choose another state".into(),
            MechError::TooManyForces { .. } => "give at most one force per coordinate".into(),
            MechError::UnknownSymbol { .. } => {
                "use only the system's coordinates and parameters".into()
            }
            MechError::ValueForCoordinate { .. } => {
                "give coordinate values as the state to analyse, not as parameters".into()
            }
            MechError::UnknownParameter { .. } => "give values only for the parameters".into(),
            MechError::ParameterCount { expected, .. } => {
                format!("give exactly {expected} parameter values, in the system's order")
            }
            MechError::MassNotPositiveDefinite | MechError::SingularMassHere => {
                "choose another state".into()
            }
            MechError::ClosedFormTooLarge { .. } | MechError::ClosedFormNotGyroscopic { .. } => {
                "ask for the numeric modes instead".into()
            }
            MechError::ForceWithAcceleration { .. } => {
                "move the term with the acceleration into the kinetic energy (a mass term), so that M includes it".into()
            }
            MechError::AccelerationInLagrangian { .. } => {
                "remove the acceleration, e.g. by integrating a term such as x·x'' by parts (x·x'' = d/dt(x·x') − x'^2: drop the total derivative)".into()
            }
            MechError::Overflow { .. } => {
                "choose units in which the quantities are moderate numbers".into()
            }
            MechError::UndefinedConstant { .. } => "remove or correct that term".into(),
            MechError::TooManyEquilibria { .. } => {
                "narrow the ranges of the coordinates, or give the equilibrium".into()
            }
            MechError::ExplicitTime { .. } => "simulate the motion instead (a numerical integration follows the driven system); for fast driving, an averaged effective potential is an approximation to derive by hand".into(),
            MechError::NotAnEquilibrium { .. } => {
                "give a point where every generalized force vanishes, or leave the point out to search for the equilibria".into()
            }
            MechError::AccelerationInConstraint
            | MechError::NonlinearVelocityConstraint
            | MechError::DependentConstraints
            | MechError::ConstraintNeverHolds { .. }
            | MechError::EmptyConstraint { .. }
            | MechError::TooManyConstraints { .. }
            | MechError::DependentConstraint { .. }
            | MechError::MultiplierName { .. }
            | MechError::ModesRolling
            | MechError::OffConstraint { .. }
            | MechError::NotConstrainedEquilibrium { .. }
            | MechError::ModesNoFreedom => self.constraint_help(),
            MechError::TooLarge(e) => e.help(),
            MechError::Name(e) => e.help(),
            MechError::Rigid(e) => e.help(),
        }
    }

    /// The help for errors in the constraints or in what they allow, kept together because
    /// their advice is about rewriting or dropping constraints rather than the Lagrangian.
    fn constraint_help(&self) -> String {
        match self {
            MechError::AccelerationInConstraint => {
                "write the constraint on positions, or on velocities".into()
            }
            MechError::NonlinearVelocityConstraint => {
                "write the velocity constraint as a linear combination of the velocities".into()
            }
            MechError::DependentConstraints => {
                "drop a redundant constraint, or choose another state".into()
            }
            MechError::ConstraintNeverHolds { .. } => {
                "write the constraint in terms of the coordinates, or drop it".into()
            }
            MechError::EmptyConstraint { .. } => "drop it".into(),
            MechError::TooManyConstraints { .. } => {
                "drop the constraints that follow from the others, or add coordinates".into()
            }
            MechError::DependentConstraint {
                contradicts: Some(true),
                ..
            } => "correct one of the contradicting constraints".into(),
            MechError::DependentConstraint {
                contradicts: Some(false),
                ..
            } => "drop the repeated constraint".into(),
            MechError::DependentConstraint { .. } => {
                "drop the dependent constraint, or correct it if it contradicts the others".into()
            }
            MechError::MultiplierName { name } => {
                format!("rename `{name}` (the multipliers are lambda1, lambda2, …)")
            }
            MechError::ModesRolling => {
                "simulate the motion, or write the system in coordinates that satisfy the rolling condition".into()
            }
            MechError::OffConstraint { .. } => {
                "choose a point that satisfies every constraint".into()
            }
            MechError::NotConstrainedEquilibrium { .. } => {
                "choose a point where the forces are balanced by the constraint forces".into()
            }
            MechError::ModesNoFreedom => "drop a constraint".into(),
            // `help` sends only the constraint errors here; anything else gets no advice rather
            // than a panic.
            _ => String::new(),
        }
    }
}

impl From<&MechError> for Diagnostic {
    /// A parse error keeps its own code, span and label (the caret points into the text
    /// that failed to read); every other error is a plain message with its help.
    fn from(e: &MechError) -> Self {
        match e {
            MechError::Parse { error, .. } => Diagnostic::from(error.as_ref()),
            other => Diagnostic::new(other.code(), other.to_string(), other.help()),
        }
    }
}

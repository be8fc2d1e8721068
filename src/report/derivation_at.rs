//! `derive --at STATE`: the accelerations and the multipliers of a constrained system at one
//! state, from the augmented equations M q̈ − Aᵀλ = f, A q̈ = −r solved there. A state that
//! violates a constraint (at the position or the velocity level) is refused with its
//! residual: the augmented equations keep a state on the constraints, they do not bring one
//! back to them.

use super::derivation::{DerivationReport, StateSolution, derivation};
use crate::expr::{Id, Program, names::normalize};
use crate::mechanics::constraints::ConstraintLevel;
use crate::mechanics::{MechError, System};

/// Why `derive --at` gives no solution.
#[derive(Debug, thiserror::Error)]
pub enum StateError {
    /// The derivation itself failed.
    #[error(transparent)]
    Mech(#[from] MechError),
    /// A name in the state is neither a coordinate, a velocity nor t.
    #[error("`{name}` is not a coordinate, a velocity (x') or t of this system")]
    UnknownName { name: String },
    /// A coordinate has no value.
    #[error("the state gives no value for `{name}`")]
    MissingCoordinate { name: String },
    /// A value does not reduce to a number.
    #[error("the value of `{name}` ({text}) is not a number once the parameters are given")]
    NotNumeric { name: String, text: String },
    /// The state violates a constraint.
    #[error(
        "the state violates constraint {index} ({text} = 0) at the {level} level: the residual there is {residual:.3e}"
    )]
    Violates {
        index: usize,
        text: String,
        level: &'static str,
        residual: f64,
    },
    /// No real state satisfies a constraint.
    #[error(
        "no real state satisfies constraint {index} ({text} = 0): a Newton search from every sampled start ends at a minimum of its value that is not zero (least |value| {least:.3e})"
    )]
    NoRealState {
        index: usize,
        text: String,
        least: f64,
    },
}

impl StateError {
    /// A stable identifier.
    pub fn code(&self) -> &'static str {
        match self {
            StateError::Mech(e) => e.code(),
            StateError::UnknownName { .. } => "unknown-state-name",
            StateError::MissingCoordinate { .. } => "missing-state-value",
            StateError::NotNumeric { .. } => "state-not-numeric",
            StateError::Violates { .. } => "state-violates-constraint",
            StateError::NoRealState { .. } => "no-real-state",
        }
    }

    /// What to do about it.
    pub fn help(&self) -> String {
        match self {
            StateError::Mech(e) => e.help(),
            StateError::UnknownName { .. } | StateError::MissingCoordinate { .. } => {
                "give every coordinate a value (velocities default to 0), e.g. x=0, y=1, x'=0.5".into()
            }
            StateError::NotNumeric { .. } => {
                "give every parameter the value uses a number".into()
            }
            StateError::Violates { .. } => "choose a state on the constraints, with velocities along them; exact values (sqrt(3)/2) avoid rounding residuals".into(),
            StateError::NoRealState { .. } => "check the constraint's signs: as written it has no real solution".into(),
        }
    }
}

/// The derivation of `sys` with its accelerations and multipliers at the state `at`
/// (`name = value` for coordinates, `name'` for velocities, `t`), the parameters taking the
/// values `params`.
pub fn derivation_at(
    sys: &System,
    params: &[(String, String)],
    at: &[(String, String)],
) -> Result<DerivationReport, StateError> {
    let report = derivation(sys)?;
    check_real(sys)?;
    let mut num = sys.clone();
    let values = num.substitute_parameters(params)?;
    num.drop_unused_parameters();
    if let Some(p) = num.parameters.first() {
        return Err(MechError::MissingValue {
            name: p.name.clone(),
        }
        .into());
    }
    let d = num.derive()?;
    let point = state_point(&mut num, at, &values)?;
    if let Some(v) = num.constraint_violation(&point)? {
        return Err(StateError::Violates {
            index: v.index + 1,
            text: num.pool.plain(sys.constraints[v.index].expr),
            level: match v.level {
                ConstraintLevel::Position => "position",
                ConstraintLevel::Velocity => "velocity",
            },
            residual: v.residual,
        });
    }
    let rows = num.constraint_rows();
    let (accelerations, multipliers) = num.multipliers_at(&d, &rows, &point)?;
    let layout = num.state_layout();
    let n = num.n();
    let mut report = report;
    report.at = Some(StateSolution {
        t: point[layout.time()],
        positions: (0..n).map(|i| point[layout.q(i)]).collect(),
        velocities: (0..n).map(|i| point[layout.qdot(i)]).collect(),
        accelerations,
        multipliers,
        acceleration_labels: num
            .coordinates
            .clone()
            .iter()
            .map(|c| {
                let a = num.pool.var(c.sym, 2);
                super::Formula::new(&num.pool, a)
            })
            .collect(),
    });
    Ok(report)
}

/// Refuses a constraint of the coordinates alone that no real state satisfies (`x² = −1`),
/// where a search can tell (see [`System::unsatisfiable_constraint`]).
pub fn check_real(sys: &System) -> Result<(), StateError> {
    let mut sys = sys.clone();
    match sys.unsatisfiable_constraint()? {
        Some((k, least)) => Err(StateError::NoRealState {
            index: k + 1,
            text: sys.pool.plain(sys.constraints[k].expr),
            least,
        }),
        None => Ok(()),
    }
}

/// The sample point of the state: each value read, the parameters' values put in, evaluated.
fn state_point(
    sys: &mut System,
    at: &[(String, String)],
    values: &rustc_hash::FxHashMap<(crate::expr::Sym, u8), Id>,
) -> Result<Vec<f64>, StateError> {
    let layout = sys.state_layout();
    let mut point = layout.at_rest(&[], &[]);
    let mut given = vec![false; sys.n()];
    let ctx = sys.open_context();
    for (name, text) in at {
        let name = normalize(name.trim());
        let (base, order) = match name.strip_suffix('\'') {
            Some(b) => (b.to_string(), 1),
            None => (name.clone(), 0),
        };
        let slot = match sys.coordinates.iter().position(|c| c.name == base) {
            Some(i) if order == 0 => {
                given[i] = true;
                layout.q(i)
            }
            Some(i) => layout.qdot(i),
            None if name == "t" => layout.time(),
            None => return Err(StateError::UnknownName { name }),
        };
        let e = sys.read(text, &format!("the value of {name}"), &ctx)?;
        let e = sys.pool.substitute(e, values);
        let not_numeric = || StateError::NotNumeric {
            name: name.clone(),
            text: text.clone(),
        };
        if !sys.pool.variables(e).is_empty() {
            return Err(not_numeric());
        }
        let v = Program::compile(&sys.pool, &[e], &[])
            .ok()
            .and_then(|p| p.eval(&[]).ok())
            .map(|v| v[0])
            .filter(|v| v.is_finite())
            .ok_or_else(not_numeric)?;
        point[slot] = v;
    }
    if let Some(i) = given.iter().position(|g| !g) {
        return Err(StateError::MissingCoordinate {
            name: sys.coordinates[i].name.clone(),
        });
    }
    Ok(point)
}

//! What a failed verification is (a finding's code and message) and the dimension check every
//! kind of part shares: the leaf the other verification files build on.

use crate::check::CheckError;
use crate::check::prepare::Prepared;
use crate::expr::{Dimension, Id};
use crate::problem::{Part, Problem, Quantity};

/// A failed verification: the finding's code and message.
pub(super) struct Failed {
    pub(super) code: &'static str,
    pub(super) message: String,
}

impl Failed {
    pub(super) fn new(code: &'static str, message: String) -> Self {
        Failed { code, message }
    }
}

/// A checker error met while verifying keeps its own code (`unreadable`, `bad-at`, …).
impl From<CheckError> for Failed {
    fn from(e: CheckError) -> Self {
        Failed::new(e.code(), e.to_string())
    }
}

pub(super) type Check = Result<(), Failed>;

/// The dimension an answer of this quantity must have.
pub(super) fn expected_dimension(problem: &Problem, part: &Part) -> Option<Dimension> {
    if part.dimension.is_some() {
        return part.dimension;
    }
    let coord_dim = |i: usize| problem.dims.get(&problem.system.coordinates[i].name);
    let t = Dimension::new(0, 0, 1);
    match part.quantity {
        Quantity::Kinetic
        | Quantity::Potential
        | Quantity::Lagrangian
        | Quantity::EnergyFunction => Some(Dimension::energy()),
        Quantity::Momentum(i) => coord_dim(i).map(|d| Dimension::energy() * t / d),
        Quantity::Acceleration(i) => coord_dim(i).map(|d| d / (t * t)),
        _ => None,
    }
}

pub(super) fn check_dimension(
    problem: &Problem,
    p: &Prepared,
    e: Id,
    want: Option<Dimension>,
) -> Check {
    match p.system.pool.dimension(e, &problem.dims) {
        Err(err) => Err(Failed::new(
            "dimension",
            format!("{}: {err}", p.system.pool.unicode(e)),
        )),
        Ok(Some(d)) if want.is_some_and(|w| w != d) && !p.system.pool.is_zero(e) => {
            Err(Failed::new(
                "dimension",
                format!(
                    "{} has dimension {d}, but this part asks for {}",
                    p.system.pool.unicode(e),
                    want.unwrap_or(Dimension::NONE)
                ),
            ))
        }
        _ => Ok(()),
    }
}

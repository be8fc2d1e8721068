//! What a failed verification is (a finding's code and message) and the dimension check every
//! kind of part shares: the leaf the other verification files build on.

use super::FindingCode;
use crate::check::CheckError;
use crate::check::prepare::Prepared;
use crate::expr::{Dimension, Id};
use crate::problem::{Part, Problem, Quantity};

/// A failed verification: the finding's code and message.
pub(super) struct Failed {
    pub(super) code: FindingCode,
    pub(super) message: String,
}

impl Failed {
    pub(super) fn new(code: FindingCode, message: String) -> Self {
        Failed { code, message }
    }
}

/// A checker error met while verifying keeps its own code (`unreadable`, `bad-at`, …).
impl From<CheckError> for Failed {
    fn from(e: CheckError) -> Self {
        Failed::new(FindingCode::Engine(e.code()), e.to_string())
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
            FindingCode::Dimension,
            format!("{}: {err}", p.system.pool.unicode(e)),
        )),
        Ok(Some(d)) if want.is_some_and(|w| w != d) && !p.system.pool.is_zero(e) => {
            Err(Failed::new(
                FindingCode::Dimension,
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

/// Where a stated equilibrium fails, for the finding: the parameter values of the first
/// sample at which a generalized force at `point` (velocities and accelerations zero) does
/// not vanish, and that force (`for m = 1.3, g = 9.8: the force on θ is 0.53`).
pub(super) fn equilibrium_failure(p: &mut Prepared, point: &[Id]) -> Option<String> {
    use rustc_hash::FxHashMap;
    let zero = p.system.pool.zero();
    let mut map: FxHashMap<_, _> = FxHashMap::default();
    for (c, &v) in p.system.coordinates.iter().zip(point) {
        map.insert((c.sym, 0), v);
        map.insert((c.sym, 1), zero);
        map.insert((c.sym, 2), zero);
    }
    let forces: Vec<Id> = p
        .derivation
        .forcing
        .iter()
        .map(|&f| p.system.pool.substitute(f, &map))
        .collect();
    let vals = crate::check::compare::values(&p.system, &forces, &p.points).ok()?;
    // (sample, coordinate, force) for every finite force; the first sample (the samples in
    // the ranges come first) with a force that is not round-off of the largest.
    let all: Vec<(usize, usize, f64)> = vals
        .iter()
        .enumerate()
        .filter_map(|(k, v)| v.as_ref().map(|v| (k, v)))
        .flat_map(|(k, v)| v.iter().enumerate().map(move |(i, x)| (k, i, *x)))
        .filter(|(_, _, x)| x.is_finite())
        .collect();
    let largest = all.iter().fold(0.0f64, |m, x| m.max(x.2.abs()));
    let &(k, i, v) = all.iter().find(|x| x.2.abs() > 1e-6 * largest)?;
    let params = p.points.params(&p.system, k).to_vec();
    let at = crate::check::compare::parameter_text(&p.system, &params);
    Some(format!(
        "for {at}, the generalized force on {} there is {}",
        p.system.coordinates[i].name,
        crate::check::compare::fmt_value(v)
    ))
}

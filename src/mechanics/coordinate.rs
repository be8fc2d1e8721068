//! Coordinates and parameters of a system: the names an expression of the system may use,
//! with the ranges where they are sampled. A leaf module, so that bodies and systems can both
//! use it without importing each other.

use crate::expr::{Dimension, Id, Sym};

/// A generalized coordinate.
#[derive(Clone, Debug)]
pub struct Coordinate {
    /// The name as typed (normalized), e.g. `theta1`.
    pub name: String,
    /// Its symbol in the system's pool.
    pub sym: Sym,
    /// An angle: values are compared modulo 2π.
    pub periodic: bool,
    /// Where equilibria are searched and values are sampled.
    pub range: (f64, f64),
    /// Where the coordinate can physically be (r > 0): no sample or probe leaves it.
    pub domain: Domain,
}

/// Where a coordinate or parameter can physically be: an open interval whose ends are
/// expressions of the parameters, each end absent when unbounded. Separate from a sampling
/// range, which is only where values are drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Domain {
    /// The value is greater than this.
    pub(crate) lower: Option<Id>,
    /// The value is less than this.
    pub(crate) upper: Option<Id>,
}

impl Domain {
    /// No restriction.
    pub const ANY: Domain = Domain {
        lower: None,
        upper: None,
    };
}

/// A parameter (a constant of the system).
#[derive(Clone, Debug)]
pub struct Parameter {
    /// The name as typed (normalized), e.g. `m1`.
    pub name: String,
    /// Its symbol in the system's pool.
    pub(crate) sym: Sym,
    /// Its physical dimension, when declared (the bank declares them).
    pub dimension: Option<Dimension>,
    /// Sampling range (positive).
    pub range: (f64, f64),
    /// Where the parameter can physically be: positive for a declared physical dimension,
    /// unless the problem says otherwise.
    pub(crate) domain: Domain,
}

/// Default sampling range of a non-periodic coordinate.
pub const DEFAULT_COORDINATE_RANGE: (f64, f64) = (-2.0, 2.0);
/// Default sampling range of a parameter.
pub const DEFAULT_PARAMETER_RANGE: (f64, f64) = (0.5, 2.0);

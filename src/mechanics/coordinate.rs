//! Coordinates and parameters of a system: the names an expression of the system may use,
//! with the ranges where they are sampled. A leaf module, so that bodies and systems can both
//! use it without importing each other.

use crate::expr::{Dimension, Sym};

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
}

/// A parameter (a constant of the system).
#[derive(Clone, Debug)]
pub struct Parameter {
    /// The name as typed (normalized), e.g. `m1`.
    pub name: String,
    /// Its symbol in the system's pool.
    pub sym: Sym,
    /// Its physical dimension, when declared (the bank declares them).
    pub dimension: Option<Dimension>,
    /// Sampling range (positive).
    pub range: (f64, f64),
}

/// Default sampling range of a non-periodic coordinate.
pub const DEFAULT_COORDINATE_RANGE: (f64, f64) = (-2.0, 2.0);
/// Default sampling range of a parameter.
pub const DEFAULT_PARAMETER_RANGE: (f64, f64) = (0.5, 2.0);

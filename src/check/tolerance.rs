//! Every numeric tolerance of the checker and of problem verification, one per purpose, so that
//! a test's looseness is chosen once and named where it is used.

/// The one documented relative tolerance of a part's comparison with its reference, for every
/// kind of part (expressions, equations through their residuals at the true accelerations,
/// list items, equilibrium angles modulo 2π); a part may set its own `tolerance`.
pub const TOLERANCE: f64 = 1e-9;

/// Relative tolerance when the checker itself decides that two expressions are the same: a
/// repaired candidate against the reference, Euler–Lagrange expressions, proportional
/// conditions, a stated Lagrangian against the bodies'.
pub const SAME: f64 = 1e-9;

/// Closeness of two plain numbers relative to their size: a factor to ±1, a factor to a
/// simple fraction, two factors to each other.
pub const NUMBER: f64 = 1e-9;

/// A value at most this in magnitude is treated as zero when it would be divided by.
pub const ZERO: f64 = 1e-9;

/// A singular value below this fraction of the largest entry counts as zero (rank tests).
pub const RANK: f64 = 1e-9;

/// Two angles (or an angle and a named multiple of π) this close in radians are the same.
pub const ANGLE: f64 = 1e-9;

/// Slack at the ends of a coordinate's range, so an equilibrium on the edge is inside.
pub const RANGE_SLACK: f64 = 1e-9;

/// Keeps a zero scale from turning a relative test into an exact one (or a division by 0).
pub const TINY: f64 = 1e-300;

/// A reference value below this fraction of the scale is not used to estimate a factor.
pub const FACTOR_FLOOR: f64 = 1e-12;

/// Equilibrium coordinates agree to this, relative to their size.
pub const COORDINATE: f64 = 1e-6;

/// How far a power-of-two exponent may be from a half-integer, or from another, and still
/// count as the same (monomial ratios of parameters).
pub const EXPONENT: f64 = 1e-6;

/// The least relative tolerance for frequencies from the eigen-solver.
pub const EIGEN: f64 = 1e-8;

/// Agreement to about two digits only: the mark of a rounded constant.
pub const ROUNDED: f64 = 1e-2;

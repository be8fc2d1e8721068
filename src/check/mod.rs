//! Checking answers numerically: seeded sampling that respects a problem's assumptions,
//! equivalence of expressions (exactly, up to a constant, up to a factor), equations compared
//! through the accelerations they imply, and unordered lists matched item by item.
//!
//! Verdicts never depend on the simplifier: everything here evaluates.

pub mod compare;
pub mod equations;
pub mod points;
pub mod prepare;

pub use compare::{Relation, relate};
pub use points::{Assumption, PointSet};

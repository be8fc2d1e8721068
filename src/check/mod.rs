//! Checking answers numerically: seeded sampling that respects a problem's assumptions,
//! equivalence of expressions (exactly, up to a constant, up to a factor), equations compared
//! through the accelerations they imply, and unordered lists matched item by item.
//!
//! Verdicts never depend on the simplifier: everything here evaluates.

pub mod answer;
mod common;
pub mod compare;
pub mod diagnose;
pub mod equations;
pub mod error;
pub mod lists;
pub mod points;
pub mod prepare;
pub mod tolerance;
pub mod verdict;

pub use crate::problem::Assumption;
pub use answer::{Checker, check};
pub use compare::{Relation, relate};
pub use error::CheckError;
pub use points::PointSet;
pub use verdict::{Code, Diagnosis, Status, Verdict};

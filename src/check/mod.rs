//! Checking answers numerically: seeded sampling that respects a problem's assumptions,
//! equivalence of expressions (exactly, up to a constant, up to a factor), equations compared
//! through the accelerations they imply, and unordered lists matched item by item.
//!
//! Verdicts never depend on the simplifier: everything here evaluates.

// The public face of the checker is the re-exports below; the modules are its internals
// (the bank's verifier and the reports use some of them inside the crate).
pub(crate) mod answer;
mod common;
pub(crate) mod compare;
mod degenerate;
mod diagnose;
mod equation_diagnosis;
pub(crate) mod equations;
pub(crate) mod error;
mod expression_diagnosis;
mod fingerprint;
mod freq_label;
mod generated;
mod item_reading;
mod items;
mod lagrangian;
mod limits;
mod linearize;
mod lists;
mod misconception;
mod modes_lists;
mod named;
pub(crate) mod points;
pub(crate) mod prepare;
mod quote;
mod residual;
mod stability;
pub(crate) mod taylor;
mod terms;
pub(crate) mod tolerance;
pub(crate) mod units;
pub mod verdict;

pub use crate::problem::Assumption;
pub use answer::{Checker, check};
pub use error::CheckError;
pub use item_reading::states_another_frequency;
pub use named::unlabelled;
pub use verdict::{Code, Diagnosis, ReadAs, Status, Verdict};

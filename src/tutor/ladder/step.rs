//! What a rung of the derivation ladder is: a [`Step`] (its question, the part that checks it,
//! and the system it is judged against), and why a ladder cannot be built ([`LadderError`]).

use crate::mechanics::{MechError, System};
use crate::problem::Part;

/// One rung of the ladder: what is asked, and the part that checks it.
#[derive(Clone, Debug)]
pub struct Step {
    /// Stable id: `position:1`, `kinetic`, `momentum:theta`, `eom:theta`, `frequencies`, …
    pub id: String,
    /// The question, a plain sentence.
    pub prompt: String,
    /// The part the checker judges the answer against; its `answers` are the reference.
    pub part: Part,
    /// The system an equation step is judged against when it is not the problem's own (the
    /// checker compares an equation with the motion of a system): the linearized system for
    /// `linearized`, the system without its constraints for the `eom:Q` steps of a
    /// constrained problem (whose Euler–Lagrange equations lack the constraint forces).
    pub against: Option<Box<System>>,
}

impl Step {
    /// The reference answer as a student would type it in one line.
    pub fn reference_text(&self, coordinates: usize) -> String {
        self.part.reference_text(coordinates)
    }
}

/// Why a ladder cannot be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LadderError {
    /// The engine could not derive the equations of motion.
    #[error("cannot derive the equations of motion: {0}")]
    Mechanics(#[from] MechError),
    /// A point named by the problem (a `frequencies` part's `at`) cannot be read.
    #[error("cannot read the equilibrium `{text}` of part `{part}`")]
    BadPoint { part: String, text: String },
}

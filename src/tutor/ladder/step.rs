//! What a rung of the derivation ladder is: a [`Step`] (its question, the part that checks it,
//! and the system it is judged against), and why a ladder cannot be built ([`LadderError`]).

use crate::check::Code;
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
    /// Common wrong answers to this step, generated from its physics, each with the reason a
    /// teacher gives for it (checked in order when the answer is wrong).
    pub(crate) pitfalls: Vec<Pitfall>,
}

/// A known wrong answer to a step and its reason: an answer equal to `answers` (an
/// expression; for an equation step, equations up to a constant factor each) gets
/// `code` and `message` in place of the generic diagnoses.
#[derive(Clone, Debug)]
pub struct Pitfall {
    /// The wrong answer, one plain-syntax expression or equation per item.
    pub(crate) answers: Vec<String>,
    /// The diagnosis code it gets.
    pub(crate) code: Code,
    /// The sentence that names the mistake.
    pub(crate) message: String,
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

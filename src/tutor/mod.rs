//! The tutor: what a practice session knows and does, as data — the derivation ladder
//! generated from a problem's physics, follow-through from a student's own earlier answers,
//! the session state (current problem and part, attempts, hints, revealed answers) and the
//! student's progress. It returns data and never prints; the REPL, the grader and a future
//! browser face share it.

pub mod command;
pub mod follow;
pub mod ladder;
pub mod progress;
pub mod response;
pub(crate) mod session;

pub use command::{Command, CommandError, parse};
pub use progress::{PartProgress, Progress, ProgressError};
pub use response::Response;
pub use session::{Session, first_hint};

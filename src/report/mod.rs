//! Reports: what each command shows, as data, built by the library and rendered once.
//!
//! A face (the command line today; a REPL, a batch grader or a browser later) parses its own
//! arguments into the plain option types here, calls one builder — [`reading`],
//! [`derivation()`], [`modes()`], [`problem_list`], [`problem_sheet`], [`verification`] — and
//! either renders the report as text (each report has exactly one text rendering) or
//! serializes it. The builders do all the mathematics; the faces do none.
//!
//! Colour is a face concern: renderers call a [`Paint`], and [`Plain`] paints nothing, so the
//! library does not depend on a terminal crate.
//!
//! - `formula`: [`Formula`], an expression shown in every notation, serialized as plain syntax;
//! - [`read`]: [`ReadReport`], how an input is understood (`lagrange read`);
//! - [`derivation`](mod@derivation): [`DerivationReport`], the Euler–Lagrange derivation (`lagrange derive`);
//! - [`modes`](mod@modes): [`ModesReport`], equilibria and normal modes (`lagrange modes`);
//! - `problems`: the bank's list ([`ProblemList`]), one problem's sheet ([`ProblemSheet`]) and
//!   the verification of answers ([`Verification`]);
//! - [`simulation`](mod@simulation): [`SimulationReport`], an integrated motion (`lagrange simulate`), and a
//!   phase-portrait family ([`portrait::portrait_family`]);
//! - [`units`]: the SI units of the pictures' axes, from a bank problem's dimensions;
//! - [`chaos`]: [`ChaosReport`](chaos::ChaosReport), Lyapunov exponent, separation and
//!   Poincaré section (`lagrange chaos`).

pub mod chaos;
mod constraint_watch;
pub mod derivation;
pub mod derivation_at;
pub mod flip_map;
pub(crate) mod formula;
pub mod modes;
pub mod portrait;
pub(crate) mod problems;
pub mod read;
pub mod sheets;
pub mod simulation;
pub(crate) mod steady;
pub mod units;

pub use derivation::{DerivationReport, derivation};
pub use formula::Formula;
pub use modes::{ModesError, ModesOptions, ModesReport, modes};
pub use problems::{
    ProblemList, ProblemSheet, Verification, problem_list, problem_sheet, terminal_math,
    verification,
};
pub use read::{ReadOptions, ReadReport, reading};
pub use simulation::{
    SimulationError, SimulationOptions, SimulationReport, simulation, simulation_with,
};

/// Runs a renderer that writes into a `String`, and returns the text: the one place where a
/// renderer's [`std::fmt::Result`] is turned into text. Writing into a `String` never fails, and
/// the renderers format only strings and numbers, whose `Display` never fails either; an error
/// here would be a bug in a renderer, not something about the input.
fn text(render: impl FnOnce(&mut String) -> std::fmt::Result) -> String {
    let mut o = String::new();
    render(&mut o).expect("writing a report into a String cannot fail");
    o
}

/// How a renderer marks up text for a face. Every method defaults to no markup; a terminal
/// face overrides them with colours, a browser face could emit HTML.
pub trait Paint {
    /// A heading or a field label (bold on a terminal).
    fn heading(&self, text: &str) -> String {
        text.to_string()
    }
    /// A result that is good news: correct, stable, proved (green).
    fn good(&self, text: &str) -> String {
        text.to_string()
    }
    /// A result that is bad news: unstable, failing, inconsistent (red).
    fn bad(&self, text: &str) -> String {
        text.to_string()
    }
    /// A result that is neither: marginal, undecided (yellow).
    fn warn(&self, text: &str) -> String {
        text.to_string()
    }
    /// Secondary text: sources, reference answers (dimmed).
    fn dim(&self, text: &str) -> String {
        text.to_string()
    }
}

/// No markup at all.
#[derive(Clone, Copy, Debug, Default)]
pub struct Plain;

impl Paint for Plain {}

//! lagrange: check, derive and explain analytical mechanics.
//!
//! The engine behind every face — the command line, the REPL, the class grader and the
//! browser page: it reads expressions, derives the Euler–Lagrange equations, checks a
//! student's answer against a problem's physics, runs practice sessions and integrates the
//! motion. It prints nothing and returns data; each face renders it.
//!
//! # Check an answer
//!
//! A [`Checker`] judges answers to the parts of a [`Problem`] (from the [`embedded`] bank, a
//! folder with [`load_dir`], or TOML text with [`load_str`]). A [`Verdict`] says whether the
//! answer is right and, if not, why, with stable [`Code`]s:
//!
//! ```
//! use lagrange::{Checker, Code, Status};
//!
//! let problem = lagrange::embedded::problem("simple-pendulum").expect("in the bank");
//! let mut checker = Checker::new(&problem);
//! let right = checker.check("kinetic", "1/2 m l^2 theta'^2").expect("a part of the problem");
//! assert_eq!(right.status, Status::Correct);
//! let wrong = checker.check("kinetic", "m l^2 theta'^2").expect("a part of the problem");
//! assert_eq!(wrong.status, Status::Incorrect);
//! assert!(wrong.diagnoses.iter().any(|d| d.code == Code::ConstantFactor));
//! ```
//!
//! # Derive the equations of motion
//!
//! A [`System`] is a Lagrangian and its coordinates; [`report::derivation()`] derives its
//! equations of motion with every step, as data each face renders:
//!
//! ```
//! use lagrange::System;
//!
//! let sys = System::from_lagrangian("1/2 m l^2 theta'^2 + m g l cos(theta)", &["theta"])
//!     .expect("a Lagrangian");
//! let report = lagrange::report::derivation(&sys).expect("derivable");
//! // m l² θ̈ = −m g l sin θ: the acceleration term and the force, as plain syntax.
//! assert_eq!(report.equations.len(), 1);
//! let text = report.render(lagrange::Style::Plain, &lagrange::report::Plain);
//! assert!(text.contains("sin(theta)"), "{text}");
//! ```
//!
//! # A practice session
//!
//! A [`tutor::Session`] takes the lines a student types — answers and `:` commands — and
//! returns [`tutor::Response`]s; its [`tutor::Progress`] is saved and restored as JSON, and two
//! sessions' records merge with [`tutor::Progress::merged`]:
//!
//! ```
//! use lagrange::Status;
//! use lagrange::tutor::{Progress, Response, Session};
//!
//! let mut session = Session::new(lagrange::embedded::bank(), Progress::new());
//! session.handle(":open simple-pendulum");
//! let replies = session.handle("1/2 m l^2 theta'^2");
//! let correct = |r: &Response| matches!(r, Response::Verdict(v) if v.verdict.status == Status::Correct);
//! assert!(replies.iter().any(correct));
//! assert!(session.progress().is_solved("simple-pendulum", "kinetic"));
//! let saved = session.progress().to_json();
//! assert_eq!(Progress::from_json(&saved).expect("its own format"), *session.progress());
//! ```
//!
//! # The layers
//!
//! Lowest first (a layer never imports a higher one):
//! - [`expr`]: the expression language — parse, canonical arena, evaluate, differentiate,
//!   simplify, print, dimensions;
//! - [`mechanics`]: Euler–Lagrange equations, accelerations, conserved quantities,
//!   constraint forces, equilibria and normal modes;
//! - [`simulate`]: numerical integration of the equations of motion (DOP853, RK4, Gauss);
//! - [`problem`]: problems and parts as data (what the bank builds and the checker reads);
//! - [`check`]: numeric equivalence of answers (sampling, relations, accelerations);
//! - [`bank`]: the problem format, loading, verification and the embedded bank;
//! - [`report`]: what each command shows, as data built here and rendered once, for every
//!   face;
//! - [`tutor`]: practice sessions — the derivation ladder, follow-through, progress;
//! - [`policy`]: the grading policy and the assignment file (credit per code, attempts);
//! - [`diagnostic`]: rendering of positioned errors, shared by every face;
//! - [`progress`]: the one cancellable progress callback that long calls take.
//!
//! `src/main.rs` and its faces (`src/cli/`, `src/repl/`, `src/grade/`, sharing `src/face/`)
//! are the command line over this library; `web/` is the browser page.

/// The layers, lowest first: a module may import only modules of its own layer or lower ones,
/// and the files of one module never import each other in a loop (checked by a test that reads
/// the sources). The faces (`src/main.rs`, `src/cli/`, `src/repl/`, `src/grade/`) sit above
/// all of them.
#[cfg_attr(not(test), allow(dead_code))]
const LAYERS: &[&str] = &[
    "progress",
    "expr",
    "diagnostic",
    "mechanics",
    "simulate",
    "problem",
    "check",
    "bank",
    "report",
    "tutor",
    "policy",
];

#[cfg(test)]
mod layers;

pub mod bank;
pub mod check;
pub mod diagnostic;
pub mod expr;
pub mod mechanics;
pub mod policy;
pub mod problem;
pub mod progress;
pub mod report;
pub mod simulate;
pub mod tutor;

// What a library user needs, in one place (the modules hold the rest).
pub use bank::{Bank, Finding, embedded, load_dir, load_str};
pub use check::{CheckError, Checker, Code, Diagnosis, Status, Verdict};
pub use diagnostic::{Diagnostic, render, render_plain};
pub use expr::{Context, Dimension, Id, ParseError, Pool, Reading, Style, read, read_expr};
pub use mechanics::{Body, Layout, MechError, Potential, System};
pub use problem::{Part, PartKind, Problem};

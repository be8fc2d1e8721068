//! lagrange: check, derive and explain analytical mechanics.
//!
//! Layers, lowest first (a layer never imports a higher one):
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
//! `src/main.rs` is a thin command-line face over this library.

/// The layers, lowest first: a module may import only modules of its own layer or lower ones,
/// and the files of one module never import each other in a loop (checked by a test that reads
/// the sources). The faces (`src/main.rs`, `src/cli/`) sit above all of them.
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
pub use check::{CheckError, Checker, Code, Diagnosis, Status, Verdict, check};
pub use diagnostic::{Diagnostic, render, render_plain};
pub use expr::{Context, Dimension, Id, ParseError, Pool, Reading, Style, read, read_expr};
pub use mechanics::{Body, Layout, MechError, Potential, System};
pub use problem::{Part, PartKind, Problem};

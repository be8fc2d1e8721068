//! The derivation ladder: the guided Euler–Lagrange derivation of a problem, generated from its
//! system by the mechanics engine (never written in the problem file). Each rung is a [`Step`]
//! whose [`Part`](crate::problem::Part) carries the engine's result as its reference answer, so the ordinary checker
//! judges a step with all its diagnoses.
//!
//! Order: for a system built from bodies, each body's position and speed squared, then T, V
//! and L (a system given by L alone starts at L); for each coordinate q, p = ∂L/∂q', d/dt p,
//! ∂L/∂q and the equation of motion; then, when the problem asks for them, the equilibria, the
//! linearized equations at the stable equilibrium its `frequencies` part names, the roots ω² of
//! det(K − ω² M) = 0 and the frequencies.
//!
//! [`check_step`] checks one answer; a session keeps a [`StepChecker`], which prepares each
//! step once. A step judged against another system than the problem's (the linearized one, or
//! the unconstrained one for a constrained problem's `eom:Q`) carries it in [`Step::against`].
//!
//! Choices:
//! - A position is a `values` part, one item per Cartesian component. The list checker matches
//!   items unordered, so [`check_step`] also checks the components in order (an exchanged x
//!   and y is `swapped-symbols`). The student types `x, y` (no brackets).
//! - The momentum-rate and generalized-force (∂L/∂q) steps are `expression` parts containing
//!   accelerations and velocities; the checker samples those as independent variables (over
//!   [−2, 2]) with the coordinates, so they are compared numerically like any expression, with
//!   the usual diagnoses (`velocity-term` for a missing θ̇₁θ̇₂ term, `sign-error`, …).
//! - Equilibria, ω² and ω are not solved symbolically by the engine (it finds them
//!   numerically); their steps take the problem's own verified answers (`lagrange problems
//!   verify` proves them against the engine's search and eigen-solver). The `characteristic`
//!   step asks for the roots ω² of det(K − ω² M) = 0 (a `frequencies` part with `squared`).
//!   The equilibria step checks the points only: the checker does not read a stability.
//!
//! Files: [`step`] holds what a rung is ([`Step`], [`LadderError`]); [`build`] derives the
//! rungs from the system ([`ladder`]); [`checker`] judges an answer to a rung ([`StepChecker`],
//! [`check_step`]).

pub mod build;
pub mod checker;
mod reasons;
pub mod step;

pub use build::ladder;
pub use checker::{StepChecker, check_step};
pub use step::{LadderError, Pitfall, Step};

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bank::load_str;
    use crate::check::Status;

    const ONLY_L: &str = r#"
id = "oscillator"
title = "Harmonic oscillator"
coordinates = [{ name = "x" }]
lagrangian = "1/2*m*x'^2 - 1/2*k*x^2"

[parameters]
m = { dimension = "M", range = [0.5, 2.0] }
k = { dimension = "M T^-2", range = [0.5, 2.0] }

[[parts]]
id = "eom"
kind = "equation"
prompt = "EOM?"
answer = "m*x'' + k*x = 0"
"#;

    #[test]
    fn a_problem_with_only_l_starts_at_l() {
        let p = load_str("oscillator.toml", ONLY_L).unwrap();
        let steps = ladder(&p).unwrap();
        let ids: Vec<&str> = steps.iter().map(|s| s.id.as_str()).collect();
        assert_eq!(
            ids,
            [
                "lagrangian",
                "momentum:x",
                "momentum-rate:x",
                "generalized-force:x",
                "eom:x"
            ]
        );
        assert_eq!(steps[1].part.answers, ["m*x'"]);
        assert_eq!(steps[3].part.answers, ["-k*x"]);
        let v = check_step(&p, &steps[4], "x'' = -k/m*x").unwrap();
        assert_eq!(v.status, Status::Correct);
    }

    #[test]
    fn a_degenerate_system_is_an_error_not_a_panic() {
        let text = ONLY_L.replace("1/2*m*x'^2 - 1/2*k*x^2", "m*x'*x - 1/2*k*x^2");
        // The bank loads it (verification, not loading, would reject it).
        let p = load_str("degenerate.toml", &text).unwrap();
        assert!(matches!(ladder(&p), Err(LadderError::Mechanics(_))));
    }
}

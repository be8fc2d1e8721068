//! Issue 12, section 1, in lists: points of several coordinates as tuples, `±` giving two
//! items, and stability stated in equilibrium answers (judged by the part's data or, where
//! it has none, by the engine).

use lagrange::bank::embedded;
use lagrange::check::{Checker, Status};

use crate::notation::verdicts;

/// The double pendulum with an equilibria part (the bank's has none), for tuples.
fn double_pendulum_with_equilibria() -> lagrange::problem::Problem {
    let text = include_str!("../../problems/double-pendulum.toml").to_string()
        + r#"
[[parts]]
id = "equilibria"
kind = "equilibria"
prompt = "List every equilibrium (θ₁, θ₂), with its stability."
answer = ["theta1 = 0, theta2 = 0", "theta1 = 0, theta2 = pi", "theta1 = pi, theta2 = 0", "theta1 = pi, theta2 = pi"]
stability = ["stable", "unstable", "unstable", "unstable"]
"#;
    lagrange::bank::load_str("double-pendulum.toml", &text).unwrap_or_else(|f| panic!("{f}"))
}

#[test]
fn tuples_are_points_in_the_coordinates_order() {
    let problem = double_pendulum_with_equilibria();
    let mut c = Checker::new(&problem);
    let cases: &[(&str, Status, &[&str])] = &[
        ("(0, 0), (0, π), (π, 0), (π, π)", Status::Correct, &[]),
        ("(0,0), (0,pi), (pi,0), (pi,pi)", Status::Correct, &[]),
        ("[0, 0], [π, π], [0, π], [π, 0]", Status::Correct, &[]),
        (
            "(0, 0) stable, (0, π) unstable, (π, 0) unstable, (π, π) unstable",
            Status::Correct,
            &[],
        ),
        (
            "(0, 0) (unstable), (0, π), (π, 0), (π, π)",
            Status::Incorrect,
            &["wrong-stability"],
        ),
        ("(0, 0), (π, π)", Status::Incorrect, &["missing-item"]),
        (
            "θ₁ = 0, θ₂ = 0; θ₁ = 0, θ₂ = π; θ₁ = π, θ₂ = 0; θ₁ = π, θ₂ = π",
            Status::Correct,
            &[],
        ),
        ("(0, 0, 0), (π, π)", Status::Invalid, &["syntax"]),
    ];
    for (answer, status, codes) in cases {
        let v = c.check("equilibria", answer).expect("a part");
        let got: Vec<&str> = v.diagnoses.iter().map(|d| d.code.as_str()).collect();
        assert_eq!(v.status, *status, "{answer:?}: {got:?} {:?}", v.diagnoses);
        for code in *codes {
            assert!(got.contains(code), "{answer:?}: {got:?}");
        }
    }
    let v = c.check("equilibria", "(0, 0, 0), (π, π)").expect("a part");
    let e = v.parse_error.expect("a parse error");
    assert_eq!(e.kind.code(), "point-size");
    assert_eq!(e.span, 0..9);
}

#[test]
fn plus_minus_and_stated_stability() {
    use Status::*;
    // `±` gives both points (else `missing-item`); the hoop's part asks for stability, so
    // without it the answer is `missing-stability` (issue 19 §3).
    verdicts(&[
        (
            "rotating-hoop",
            "equilibria",
            "0, π, ±arccos(g/(R ω²))",
            Incorrect,
            &["missing-stability"],
        ),
        (
            "rotating-hoop",
            "equilibria",
            "θ = 0, θ = π, θ = ±acos(g/(R ω^2))",
            Incorrect,
            &["missing-stability"],
        ),
        (
            "rotating-hoop",
            "equilibria",
            "0, π, ∓acos(g/(R ω^2))",
            Incorrect,
            &["missing-stability"],
        ),
        (
            "rotating-hoop",
            "equilibria",
            "θ = 0 (unstable), θ = π (unstable), θ = ±arccos(g/(R ω^2)) (stable)",
            Correct,
            &[],
        ),
        (
            "rotating-hoop",
            "equilibria",
            "0 stable, π unstable, ±acos(g/(R ω^2)) stable",
            Incorrect,
            &["wrong-stability"],
        ),
        ("bead-wire", "equilibria", "r = 0 (unstable)", Correct, &[]),
        (
            "bead-wire",
            "equilibria",
            "r = 0 (stable)",
            Incorrect,
            &["wrong-stability"],
        ),
        (
            "simple-pendulum",
            "equilibria",
            "θ = 0 stable, θ = π unstable",
            Correct,
            &[],
        ),
        (
            "simple-pendulum",
            "equilibria",
            "0 (stable), π (unstable)",
            Correct,
            &[],
        ),
        (
            "simple-pendulum",
            "equilibria",
            "0 (Stable), π (marginally stable)",
            Incorrect,
            &["wrong-stability"],
        ),
        (
            "simple-pendulum",
            "equilibria",
            "0 (stabel), π",
            Invalid,
            &["unknown-symbol"],
        ),
        (
            "simple-pendulum",
            "frequencies",
            "ω = sqrt(g/l)",
            Correct,
            &[],
        ),
        (
            "spring-incline",
            "equilibria",
            "x = m g sin α / k (stable)",
            Correct,
            &[],
        ),
    ]);
}

#[test]
fn stability_messages() {
    let bank = embedded::bank();
    let mut shown = String::new();
    for (problem, answer) in [
        ("bead-wire", "r = 0 (stable)"),
        ("simple-pendulum", "θ = 0 stable, θ = π unstable"),
        ("simple-pendulum", "0 (stabel), π"),
    ] {
        let p = bank.problem(problem).expect("bank problem");
        let v = Checker::new(p).check("equilibria", answer).expect("a part");
        shown.push_str(&format!("{problem}: {answer}\n"));
        if let Some(n) = &v.reading.note {
            shown.push_str(&format!("  ({n})\n"));
        }
        for d in &v.diagnoses {
            shown.push_str(&format!("  [{}] {}\n", d.code, d.message));
        }
    }
    insta::assert_snapshot!("notation_stability", shown);
}

#[test]
fn stability_stated_where_the_part_does_not_ask_is_checked_by_the_engine() {
    let text = include_str!("../../problems/simple-pendulum.toml")
        .replace("stability = [\"stable\", \"unstable\"]\n", "");
    let problem =
        lagrange::bank::load_str("simple-pendulum.toml", &text).unwrap_or_else(|f| panic!("{f}"));
    assert!(
        problem
            .part("equilibria")
            .is_some_and(|p| p.stability.is_empty())
    );
    let mut c = Checker::new(&problem);
    let cases: &[(&str, Status)] = &[
        ("0, π", Status::Correct),
        ("0 (stable), π (unstable)", Status::Correct),
        ("θ = 0 stable, θ = π", Status::Correct),
        ("0 (unstable), π", Status::Incorrect),
        ("0, π (stable)", Status::Incorrect),
    ];
    for (answer, status) in cases {
        let v = c.check("equilibria", answer).expect("a part");
        assert_eq!(v.status, *status, "{answer:?}: {:?}", v.diagnoses);
        if *status == Status::Incorrect {
            assert_eq!(
                v.diagnoses[0].code.as_str(),
                "wrong-stability",
                "{answer:?}"
            );
        }
    }
    // The double pendulum (no stability data): only the bottom is stable.
    let text = include_str!("../../problems/double-pendulum.toml").to_string()
        + r#"
[[parts]]
id = "equilibria"
kind = "equilibria"
prompt = "List every equilibrium (θ₁, θ₂)."
answer = ["theta1 = 0, theta2 = 0", "theta1 = 0, theta2 = pi", "theta1 = pi, theta2 = 0", "theta1 = pi, theta2 = pi"]
"#;
    let problem =
        lagrange::bank::load_str("double-pendulum.toml", &text).unwrap_or_else(|f| panic!("{f}"));
    let mut c = Checker::new(&problem);
    let v = c
        .check(
            "equilibria",
            "(0, 0) stable, (0, π) unstable, (π, 0) unstable, (π, π) unstable",
        )
        .expect("a part");
    assert_eq!(v.status, Status::Correct, "{:?}", v.diagnoses);
    let v = c
        .check("equilibria", "(0, 0), (0, π), (π, 0), (π, π) (stable)")
        .expect("a part");
    assert_eq!(v.status, Status::Incorrect, "{:?}", v.diagnoses);
}

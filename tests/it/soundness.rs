//! Soundness of the checker (issue 9, sections 1 and 2): answers that are wrong must never be
//! called correct — an equation multiplied by a factor that vanishes somewhere, a dimensionally
//! inconsistent answer, a constant off by more than the documented tolerance, a difference
//! hidden outside the sampled box, 0 times an undefined value — and scale must not fool a zero
//! test. Each case is the exact input that was wrongly accepted (or rejected) before.

use lagrange::{Checker, Code, Status, Verdict, embedded};

fn verdict(problem: &str, part: &str, answer: &str) -> Verdict {
    let p = embedded::problem(problem).unwrap_or_else(|| panic!("no problem {problem}"));
    Checker::new(&p)
        .check(part, answer)
        .unwrap_or_else(|e| panic!("{problem}/{part}: {e}"))
}

/// The answer is incorrect (never correct, never merely unreadable), and one of its
/// diagnoses has `code`.
fn wrong_with(problem: &str, part: &str, answer: &str, code: Code) -> Verdict {
    let v = verdict(problem, part, answer);
    assert_eq!(v.status, Status::Incorrect, "{answer}: {v:#?}");
    assert!(
        v.diagnoses.iter().any(|d| d.code == code),
        "{answer}: expected {code}, got {:#?}",
        v.diagnoses
    );
    v
}

fn right(problem: &str, part: &str, answer: &str) {
    let v = verdict(problem, part, answer);
    assert_eq!(v.status, Status::Correct, "{answer}: {v:#?}");
}

const PENDULUM: &str = "(θ'' + g/l*sin(θ))";
const ATWOOD: &str = "((m1 + m2)*x'' - (m1 - m2)*g)";

#[test]
fn pendulum_equation_times_velocity_is_the_energy_law() {
    let v = wrong_with(
        "simple-pendulum",
        "eom",
        &format!("θ'*{PENDULUM} = 0"),
        Code::VanishingFactor,
    );
    let text: String = v.diagnoses.iter().map(|d| d.message.as_str()).collect();
    assert!(text.contains("energy"), "{text}");
}

#[test]
fn pendulum_equation_times_vanishing_factors() {
    for factor in ["sin(θ)", "θ", "cos(θ)", "θ'^2", "(θ - 1)^2", "1/θ'"] {
        let answer = format!("{factor}*{PENDULUM} = 0");
        let v = verdict("simple-pendulum", "eom", &answer);
        assert_ne!(v.status, Status::Correct, "{answer}: {v:#?}");
    }
}

#[test]
fn pendulum_equation_times_a_factor_that_never_vanishes_is_right() {
    for factor in ["(2 + sin(θ))", "(1 + l*θ'^2/g)", "exp(θ)", "m*l^2", "-3"] {
        right(
            "simple-pendulum",
            "eom",
            &format!("{factor}*{PENDULUM} = 0"),
        );
    }
}

#[test]
fn atwood_equation_times_vanishing_factors() {
    for factor in ["x", "x'", "(m1 - m2)"] {
        let answer = format!("{factor}*{ATWOOD} = 0");
        wrong_with("atwood", "eom", &answer, Code::VanishingFactor);
    }
}

const DP1: &str =
    "((m1+m2)*l1*θ1'' + m2*l2*θ2''*cos(θ1-θ2) + m2*l2*θ2'^2*sin(θ1-θ2) + (m1+m2)*g*sin(θ1))";
const DP2: &str = "(l2*θ2'' + l1*θ1''*cos(θ1-θ2) - l1*θ1'^2*sin(θ1-θ2) + g*sin(θ2))";

#[test]
fn double_pendulum_equation_replaced_by_the_energy_law() {
    // dE/dt = θ1'·(l1·E1) + θ2'·(m2·l2·E2) with E1, E2 the reference equations.
    let energy = format!("θ1'*l1*{DP1} + θ2'*m2*l2*{DP2} = 0");
    wrong_with(
        "double-pendulum",
        "eom",
        &format!("{energy}; {DP2} = 0"),
        Code::VanishingFactor,
    );
    wrong_with(
        "double-pendulum",
        "eom",
        &format!("{DP1} = 0; θ1*{DP2} = 0"),
        Code::VanishingFactor,
    );
}

#[test]
fn double_pendulum_invertible_combinations_stay_right() {
    right(
        "double-pendulum",
        "eom",
        &format!("{DP1} + 3*m2*cos(θ1)*{DP2} = 0; {DP2} = 0"),
    );
    right(
        "double-pendulum",
        "eom",
        &format!("(2 + cos(θ1))*{DP1} = 0; {DP2} = 0"),
    );
}

#[test]
fn double_pendulum_scaled_equations_are_independent() {
    for s in ["1e-9", "1e9"] {
        right(
            "double-pendulum",
            "eom",
            &format!("{s}*{DP1} = 0; {DP2} = 0"),
        );
    }
}

#[test]
fn dimensionally_inconsistent_answers_are_never_correct() {
    wrong_with(
        "simple-pendulum",
        "eom",
        &format!("(m + 1)*{PENDULUM} = 0"),
        Code::Dimension,
    );
    wrong_with(
        "simple-pendulum",
        "kinetic",
        "1/2 m l^2 θ'^2 (m + 1) - 1/2 m^2 l^2 θ'^2",
        Code::Dimension,
    );
}

#[test]
fn constants_off_by_more_than_the_tolerance_are_rounded_constants() {
    wrong_with(
        "simple-pendulum",
        "eom",
        "θ'' + 1.0000001*g/l*sin(θ) = 0",
        Code::RoundedConstant,
    );
    for pi in ["355/113", "3.14159", "pi + 1e-6"] {
        wrong_with(
            "simple-pendulum",
            "equilibria",
            &format!("0, {pi}"),
            Code::RoundedConstant,
        );
    }
    wrong_with(
        "simple-pendulum",
        "frequencies",
        "1.00000001*sqrt(g/l)",
        Code::RoundedConstant,
    );
    // Within the documented relative tolerance (1e-9) the value is the same number.
    right("simple-pendulum", "equilibria", "0, 3.14159265358979");
}

#[test]
fn differences_outside_the_sampled_box_are_found() {
    wrong_with(
        "simple-pendulum",
        "eom",
        &format!("{PENDULUM} + g/l*(abs(θ - pi) + abs(θ + pi) - 2 pi) = 0"),
        Code::NotEqual,
    );
    let v = verdict(
        "atwood",
        "potential",
        "-(m1 - m2)*g*x + m1*g*(abs(x - 2) + abs(x + 2) - 4)",
    );
    assert_eq!(v.status, Status::Incorrect, "{v:#?}");
    let v = verdict(
        "atwood",
        "eom",
        &format!("{ATWOOD} + g*(abs(m1 - 3) - 3 + m1) = 0"),
    );
    assert_eq!(v.status, Status::Incorrect, "{v:#?}");
}

#[test]
fn zero_times_undefined_is_undefined() {
    let v = verdict("simple-pendulum", "eom", &format!("{PENDULUM} = 0*log(-1)"));
    assert_ne!(v.status, Status::Correct, "{v:#?}");
}

#[test]
fn verification_refuses_a_reference_multiplied_by_a_vanishing_factor() {
    let text = include_str!("../../problems/simple-pendulum.toml").replace(
        r#"answer = "m*l^2*theta'' + m*g*l*sin(theta) = 0""#,
        r#"answer = "theta'*(m*l^2*theta'' + m*g*l*sin(theta)) = 0""#,
    );
    assert!(
        text.contains("theta'*(m*l^2"),
        "the fixture no longer has that answer"
    );
    let problem = lagrange::load_str("energy-law.toml", &text).expect("it loads");
    let findings = lagrange::bank::verify::verify(&problem);
    let eom: Vec<_> = findings
        .iter()
        .filter(|f| f.part.as_deref() == Some("eom"))
        .collect();
    assert!(
        eom.iter().any(|f| f.message.contains("energy law")),
        "{findings:#?}"
    );
}

#[test]
fn huge_and_tiny_factors_are_named_by_their_size() {
    let reference = "(1/2*m*l^2*theta'^2 + m*g*l*cos(theta))";
    for (factor, shown) in [("1e300", "1e300"), ("1e-12", "1e-12")] {
        let v = verdict(
            "simple-pendulum",
            "lagrangian",
            &format!("{factor}*{reference}"),
        );
        assert_eq!(v.status, Status::Correct, "{v:#?}");
        let text = &v.diagnoses[0].message;
        assert!(text.contains(&format!("your L is {shown} times")), "{text}");
        let v = verdict(
            "simple-pendulum",
            "kinetic",
            &format!("{factor}*1/2*m*l^2*theta'^2"),
        );
        assert_eq!(v.status, Status::Incorrect, "{v:#?}");
        assert!(v.diagnoses[0].message.contains(shown), "{:#?}", v.diagnoses);
    }
}

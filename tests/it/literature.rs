//! The mistakes the physics-education literature documents (issue 12): each detector fires on
//! the wrong answer its mistake generates, stays silent on right answers and on other wrong
//! ones, and never reveals the answer; one snapshot holds every message.

use lagrange::bank::embedded;
use lagrange::check::{Checker, Code, Status, Verdict};

/// The literature's codes.
const LITERATURE: [Code; 8] = [
    Code::Convention,
    Code::PeGeometry,
    Code::DerivativeRule,
    Code::PrematureSubstitution,
    Code::HVsE,
    Code::EffectiveMass,
    Code::ExpansionPoint,
    Code::LostRoot,
];

fn check(problem: &str, part: &str, input: &str) -> Verdict {
    let p = embedded::problem(problem).unwrap_or_else(|| panic!("no problem {problem}"));
    Checker::new(&p)
        .check(part, input)
        .unwrap_or_else(|e| panic!("{problem}/{part}: {e}"))
}

/// (problem, part, answer) => the literature code it must get.
const FIRES: &[(&str, &str, &str, Code)] = &[
    (
        "cart-pendulum",
        "eom",
        "(M+m)*x'' + m*l*theta''*cos(theta) = 0; l*theta'' + x''*cos(theta) + g*sin(theta) = 0",
        Code::DerivativeRule,
    ),
    (
        "double-pendulum",
        "eom",
        "(m1+m2)*l1*theta1'' + m2*l2*theta2''*cos(theta1-theta2) + m2*l2*theta1'*theta2'*sin(theta1-theta2) + (m1+m2)*g*sin(theta1) = 0; l2*theta2'' + l1*theta1''*cos(theta1-theta2) - l1*theta1'*theta2'*sin(theta1-theta2) + g*sin(theta2) = 0",
        Code::DerivativeRule,
    ),
    (
        "central-force",
        "eom",
        "m*r'' + m*r*phi'^2 + k/r^2 = 0",
        Code::PrematureSubstitution,
    ),
    (
        "rotating-hoop",
        "energy-function",
        "1/2*m*R^2*(theta'^2 + omega^2*sin(theta)^2) - m*g*R*cos(theta)",
        Code::HVsE,
    ),
    (
        "bead-wire",
        "energy-function",
        "1/2*m*(r'^2 + omega^2*r^2)",
        Code::HVsE,
    ),
    (
        "double-pendulum",
        "potential",
        "-m1*g*l1*cos(theta1) - m2*g*l2*cos(theta2)",
        Code::PeGeometry,
    ),
    (
        "double-pendulum",
        "potential",
        "-m1*g*l1*cos(theta1) - m2*g*l1*l2*cos(theta1)*cos(theta2)",
        Code::PeGeometry,
    ),
    ("atwood", "potential", "(m1+m2)*g*x", Code::PeGeometry),
    (
        "simple-pendulum",
        "potential",
        "-m*g*l*sin(theta)",
        Code::Convention,
    ),
    (
        "simple-pendulum",
        "eom",
        "theta'' = g/l*cos(theta)",
        Code::Convention,
    ),
    (
        "spring-incline",
        "potential",
        "1/2*k*x^2 + m*g*x*sin(alpha)",
        Code::Convention,
    ),
    (
        "simple-pendulum",
        "frequencies",
        "sqrt(g*l)",
        Code::EffectiveMass,
    ),
    (
        "cart-pendulum",
        "frequencies",
        "sqrt(g/l)",
        Code::EffectiveMass,
    ),
    (
        "rotating-hoop",
        "frequencies",
        "sqrt(g/R - omega^2)",
        Code::ExpansionPoint,
    ),
    (
        "rotating-hoop",
        "equilibria",
        "theta = acos(g/(R*omega^2)), theta = -acos(g/(R*omega^2))",
        Code::LostRoot,
    ),
    // The uncoupled value in place of a right frequency.
    (
        "double-pendulum",
        "frequencies",
        "sqrt(g/l), sqrt((2 + sqrt(2))*g/l)",
        Code::EffectiveMass,
    ),
    // The equilibrium condition divided by r (the factor m is harmless).
    (
        "bead-parabola",
        "equilibrium-condition",
        "m*(2*g*a - omega^2) = 0",
        Code::LostRoot,
    ),
    (
        "bead-parabola",
        "equilibrium-condition",
        "2*g*a = omega^2",
        Code::LostRoot,
    ),
];

#[test]
fn each_mistake_gets_its_code_and_stays_incorrect() {
    let mut shown = String::new();
    for &(problem, part, input, code) in FIRES {
        let v = check(problem, part, input);
        assert_eq!(
            v.status,
            Status::Incorrect,
            "{problem}/{part} {input}: {v:?}"
        );
        let d = v
            .diagnoses
            .iter()
            .find(|d| d.code == code)
            .unwrap_or_else(|| panic!("{problem}/{part} {input}: no {code:?} in {v:?}"));
        // The generic diagnosis is dropped once the mistake is named.
        assert!(
            v.diagnoses.iter().all(|d| d.code != Code::NotEqual),
            "{v:?}"
        );
        shown.push_str(&format!(
            "{problem}/{part}: {input}\n  [{}] {}\n",
            code.as_str(),
            d.message
        ));
    }
    insta::assert_snapshot!("literature_messages", shown);
}

/// Right answers (in several forms) and wrong answers of other kinds: no literature code.
const SILENT: &[(&str, &str, &str)] = &[
    (
        "cart-pendulum",
        "eom",
        "(M+m)*x'' + m*l*theta''*cos(theta) - m*l*theta'^2*sin(theta) = 0; l*theta'' + x''*cos(theta) + g*sin(theta) = 0",
    ),
    (
        "cart-pendulum",
        "eom",
        "(M+m)*x'' + m*l*theta''*cos(theta) - m*l*theta'^2*sin(theta) = 0; l*theta'' + x''*cos(theta) - g*sin(theta) = 0",
    ),
    ("central-force", "eom", "m*r'' - m*r*phi'^2 + k/r^2 = 0"),
    ("central-force", "eom", "m*r'' + k/r^2 = 0"),
    ("simple-pendulum", "potential", "m*g*l*cos(theta)"),
    ("simple-pendulum", "eom", "theta'' + g/l*theta = 0"),
    ("simple-pendulum", "equilibria", "theta = 0"),
    (
        "simple-pendulum",
        "energy-function",
        "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)",
    ),
    (
        "rotating-hoop",
        "energy-function",
        "1/2*m*R^2*theta'^2 - 1/2*m*R^2*omega^2*sin(theta)^2 - m*g*R*cos(theta)",
    ),
    ("rotating-hoop", "equilibria", "theta = acos(g/(R*omega^2))"),
    ("rotating-hoop", "equilibria", "theta = 0, theta = pi"),
    (
        "rotating-hoop",
        "frequencies",
        "sqrt(omega^2 - g^2/(R^2*omega^2))",
    ),
    ("atwood", "potential", "(m1-m2)*g*x"),
    (
        "double-pendulum",
        "potential",
        "-(m1+m2)*g*l1*cos(theta1) - m2*g*l2*cos(theta2)",
    ),
    (
        "double-pendulum",
        "frequencies",
        "sqrt((2 - sqrt(2))*g/l), sqrt((2 + sqrt(2))*g/l)",
    ),
    ("spring-incline", "frequencies", "sqrt(k/m)"),
    // Nobody divides sin θ = 0 by θ: an angle is no divisor, and dividing by sin θ would lose
    // both 0 and π, not one of them.
    ("simple-pendulum", "equilibria", "theta = pi"),
    (
        "rotating-hoop",
        "equilibria",
        "theta = pi, theta = acos(g/(R*omega^2)), theta = -acos(g/(R*omega^2))",
    ),
    (
        "rotating-hoop",
        "equilibria",
        "theta = 0, theta = acos(g/(R*omega^2)), theta = -acos(g/(R*omega^2))",
    ),
    // Every right frequency and an extra one: not the wrong inertia.
    (
        "double-pendulum",
        "frequencies",
        "sqrt(g/l), sqrt((2 - sqrt(2))*g/l), sqrt((2 + sqrt(2))*g/l)",
    ),
    // The condition right (up to a factor), or wrong in another way.
    (
        "bead-parabola",
        "equilibrium-condition",
        "r*(2*g*a - omega^2) = 0",
    ),
    (
        "bead-parabola",
        "equilibrium-condition",
        "m*r*(omega^2 - 2*g*a) = 0",
    ),
    (
        "bead-parabola",
        "equilibrium-condition",
        "r*(2*g*a + omega^2) = 0",
    ),
    (
        "bead-parabola",
        "equilibrium-condition",
        "m*(2*g*a + omega^2) = 0",
    ),
];

#[test]
fn right_answers_and_other_mistakes_get_no_literature_code() {
    for &(problem, part, input) in SILENT {
        let v = check(problem, part, input);
        assert!(
            v.diagnoses.iter().all(|d| !LITERATURE.contains(&d.code)),
            "{problem}/{part} {input}: {v:?}"
        );
    }
}

#[test]
fn the_messages_never_reveal_the_answer() {
    for &(problem, part, input, _) in FIRES {
        let p = embedded::problem(problem).unwrap();
        let v = check(problem, part, input);
        // A free mode's `0` is no secret: every message may say "… = 0".
        let answers = &p.part(part).unwrap().answers;
        let first = answers
            .iter()
            .find(|a| a.trim() != "0")
            .unwrap_or(&answers[0]);
        let answer = check(problem, part, first);
        for d in v.diagnoses.iter().filter(|d| LITERATURE.contains(&d.code)) {
            assert!(
                answer.reading.unicode.is_empty() || !d.message.contains(&answer.reading.unicode),
                "{problem}/{part}: {}",
                d.message
            );
        }
    }
}

//! Issue 21 §2, the last item: a diagnosis quotes the student's own term as they built it,
//! also when the term is inside a sum — their sign, grouping and order, on the side of `=`
//! where they wrote it — never the canonical form the checker keeps (`(m₁ − m₂)·g` for
//! `−(m₂ − m₁) g`). Each row: an answer with one mistake in one of several terms, the code
//! that names it, the phrase the message must contain and a form it must not.

use lagrange::bank::embedded;
use lagrange::check::{Checker, Code, Status};
use lagrange::tutor::ladder::{StepChecker, ladder};

/// The verdict of `answer` to `problem`/`part` on the built-in bank.
fn verdict(problem: &str, part: &str, answer: &str) -> lagrange::Verdict {
    let bank = embedded::bank();
    let p = bank.problem(problem).expect("a bank problem");
    Checker::new(p).check(part, answer).expect("a part")
}

/// (problem, part, answer, code, the quote the message contains, a form it must not contain)
type Row = (
    &'static str,
    &'static str,
    &'static str,
    Code,
    &'static str,
    &'static str,
);

const ROWS: &[Row] = &[
    // Atwood: the issue's own example, the second term subtracted as typed.
    (
        "atwood",
        "eom",
        "(m1+m2) x'' - (m2 - m1) g = 0",
        Code::SignError,
        "sign error: your term −(m₂ − m₁) g should have the opposite sign",
        "(m₁ − m₂)",
    ),
    // The same term moved across `=`: quoted as written there, and said to be there.
    (
        "atwood",
        "eom",
        "(m1+m2) x'' = (m2 - m1) g",
        Code::SignError,
        "your term (m₂ − m₁) g on the right should have the opposite sign",
        "(m₁ − m₂)",
    ),
    (
        "atwood",
        "eom",
        "(m₂ − m₁) g = (m1 + m2) x''",
        Code::SignError,
        "your term (m₂ − m₁) g on the left should have the opposite sign",
        "(m₁ − m₂)",
    ),
    // A pendulum on a rotating hoop, three terms, the sign of the middle one wrong.
    (
        "rotating-hoop",
        "eom",
        "R theta'' + R omega^2 sin(theta) cos(theta) + g sin(theta) = 0",
        Code::SignError,
        "your term R ω² sin(θ) cos(θ) should have the opposite sign",
        "R·ω²",
    ),
    // The last of three terms subtracted where it should be added; typed with `*`.
    (
        "rotating-hoop",
        "eom",
        "R*theta'' - R*omega^2*sin(theta)*cos(theta) - g*sin(theta) = 0",
        Code::SignError,
        "your term −g sin(θ) should have the opposite sign",
        "g·sin",
    ),
    // Across `=`: the student's middle term on the right, with the wrong sign there.
    (
        "rotating-hoop",
        "eom",
        "R theta'' + g sin(theta) = -R omega^2 sin(theta) cos(theta)",
        Code::SignError,
        "your term −R ω² sin(θ) cos(θ) on the right should have the opposite sign",
        "R·ω²",
    ),
    // A Lagrangian of three terms with a wrong coefficient in the second.
    (
        "cart-pendulum",
        "lagrangian",
        "1/2 (M+m) x'^2 + 2 m l x' theta' cos(theta) + 1/2 m l^2 theta'^2 + m g l cos(theta)",
        Code::ConstantFactor,
        "your term 2 m l x\u{307} θ\u{307} cos(θ) is off by a constant factor: it should be ½ times what you wrote",
        "m·l·",
    ),
    (
        "rotating-hoop",
        "energy-function",
        "1/2 m R^2 theta'^2 - m R^2 omega^2 sin(theta)^2 - m g R cos(theta)",
        Code::ConstantFactor,
        "your term −m R² ω² sin(θ)² is off by a constant factor: it should be ½ times what you wrote",
        "m·R²",
    ),
    // A term too many, typed on the right.
    (
        "spring-incline",
        "eom",
        "m x'' = -k x + m g sin(alpha) - m g cos(alpha)",
        Code::ExtraTerm,
        "your term −m g cos(α) on the right should not be there",
        "m·g",
    ),
    // A term expanding splits: the part is named as a part of the student's term.
    (
        "atwood",
        "kinetic",
        "1/2 (m1 - m2) x'^2",
        Code::SignError,
        "of your term 1/2 (m₁ − m₂) x\u{307}² should have the opposite sign",
        "your term −",
    ),
];

#[test]
fn diagnoses_quote_the_students_own_terms() {
    for &(problem, part, answer, code, quote, not) in ROWS {
        let v = verdict(problem, part, answer);
        assert_eq!(v.status, Status::Incorrect, "{answer}: {v:#?}");
        let d = v
            .diagnoses
            .iter()
            .find(|d| d.code == code)
            .unwrap_or_else(|| panic!("{answer}: no {code:?} in {:#?}", v.diagnoses));
        assert!(d.message.contains(quote), "{answer}: {}", d.message);
        assert!(!d.message.contains(not), "{answer}: {}", d.message);
    }
}

#[test]
fn a_quote_does_not_depend_on_spacing_or_spelling() {
    // `grade` gives every answer of one canonical form one verdict: its words too.
    let a = verdict("atwood", "eom", "(m1+m2)*x''-(m2-m1)*g=0");
    let b = verdict("atwood", "eom", "(m₁ + m₂) ẍ − (m_2 − m_1) g = 0");
    assert_eq!(a.diagnoses, b.diagnoses);
    let bank = embedded::bank();
    let p = bank.problem("atwood").expect("atwood");
    let mut c = Checker::new(p);
    let form = |c: &mut Checker, a: &str| c.canonical("eom", a).expect("part");
    assert_eq!(
        form(&mut c, "(m1+m2)*x''-(m2-m1)*g=0"),
        form(&mut c, "(m₁ + m₂) ẍ − (m_2 − m_1) g = 0")
    );
    // Read the same, built otherwise: quoted otherwise, so kept apart.
    assert_ne!(
        form(&mut c, "(m1+m2) x'' - (m2 - m1) g = 0"),
        form(&mut c, "(m1+m2) x'' + (m1 - m2) g = 0")
    );
    let v = verdict("atwood", "eom", "(m1+m2) x'' + (m1 - m2) g = 0");
    assert!(
        v.diagnoses[0].message.contains("your term (m₁ − m₂) g "),
        "{:?}",
        v.diagnoses
    );
}

#[test]
fn the_tutor_quotes_the_students_own_terms() {
    // The tutor's equation step (the hoop's, three terms, the middle one's sign wrong) is
    // checked by the same code: its message quotes the term as typed too.
    let p = embedded::problem("rotating-hoop").expect("rotating-hoop");
    let steps = ladder(&p).expect("a ladder");
    let step = steps
        .iter()
        .find(|s| s.id.starts_with("eom"))
        .expect("the equation step");
    let mut checker = StepChecker::new(&p);
    let v = checker
        .check(
            step,
            "R theta'' + R omega^2 sin(theta) cos(theta) + g sin(theta) = 0",
        )
        .expect("checked");
    assert_eq!(v.status, Status::Incorrect);
    let text = format!("{:?}", v.diagnoses);
    assert!(text.contains("your term R ω² sin(θ) cos(θ)"), "{text}");
    assert!(!text.contains("R·ω²"), "{text}");
}

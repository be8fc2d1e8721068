//! Answers in their natural form (issue 21 §2) and the reasons the tutor and the parts give
//! (issue 21 §1's leftovers): an equation naming the asked φ̇², `x arbitrary`, defined names
//! (`θ₀` on rotating-hoop), Leibniz notation, independent `±` signs, an angle outside the
//! stated (−π, π], ordinary words (units, `and`, `const`) answered with what to write, terms
//! quoted as the student wrote them, T + V told once, a sign error up to a free constant, the
//! stability of a gyroscopically stabilised maximum explained by the linearised equations,
//! and no cross-term explanation about T for ∂L/∂θ.

use lagrange::bank::{embedded, load_str};
use lagrange::check::{Checker, Code, Status};
use lagrange::tutor::ladder::{StepChecker, ladder};

use crate::helpers::verdict_table;

/// The verdict of `answer` to `problem`/`part` on the built-in bank.
fn verdict(problem: &str, part: &str, answer: &str) -> lagrange::Verdict {
    let bank = embedded::bank();
    let p = bank.problem(problem).expect("a bank problem");
    Checker::new(p).check(part, answer).expect("a part")
}

/// `answer → status: [code] message` per diagnosis, for the snapshot.
fn shown(problem: &str, part: &str, answer: &str) -> String {
    let v = verdict(problem, part, answer);
    let mut out = format!(
        "{problem}/{part} `{answer}`\n  read as: {}\n  {:?}\n",
        v.reading.unicode, v.status
    );
    for d in &v.diagnoses {
        out.push_str(&format!("  [{}] {}\n", kebab(d.code), d.message));
    }
    out
}

fn kebab(c: Code) -> String {
    serde_json::to_value(c)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

#[test]
fn natural_forms_are_read_as_meant() {
    use Status::{Correct, Incorrect};
    verdict_table(&[
        // An equation whose left side is the quantity asked for (φ̇²) states the answer.
        (
            "conical-pendulum",
            "steady",
            "φ̇² = g/(l cos α)",
            Correct,
            None,
        ),
        (
            "conical-pendulum",
            "steady",
            "phi'^2 = g/(l*cos(alpha))",
            Correct,
            None,
        ),
        // `modes` words a continuum `x arbitrary`; so may the student.
        (
            "spring-cart",
            "equilibria",
            "x arbitrary, s = 0 (stable)",
            Correct,
            None,
        ),
        (
            "spring-cart",
            "equilibria",
            "x is arbitrary, s = 0 (stable)",
            Correct,
            None,
        ),
        (
            "spring-cart",
            "equilibria",
            "x = arbitrary, s = 0 (stable)",
            Correct,
            None,
        ),
        // θ₀ is defined by the problem (cos θ₀ = g/(R ω²)): ω sin θ₀ is the frequency.
        ("rotating-hoop", "frequencies", "ω sin θ₀", Correct, None),
        (
            "rotating-hoop",
            "frequencies",
            "omega*sin(theta0)",
            Correct,
            None,
        ),
        (
            "rotating-hoop",
            "frequencies",
            "ω cos θ₀",
            Incorrect,
            Some(Code::WrongItem),
        ),
        (
            "rotating-trap",
            "frequencies",
            "ω₀ − Ω, ω₀ + Ω",
            Correct,
            None,
        ),
        // Leibniz notation for the coordinate's derivatives.
        (
            "simple-pendulum",
            "eom",
            "d²θ/dt² + g/l sin θ = 0",
            Correct,
            None,
        ),
        (
            "simple-pendulum",
            "eom",
            "d^2theta/dt^2 + g/l*sin(theta) = 0",
            Correct,
            None,
        ),
        (
            "simple-pendulum",
            "eom",
            "l d²θ/dt² + g sin θ = 0",
            Correct,
            None,
        ),
        // Both signs of (2 ± √2) are values.
        (
            "double-pendulum",
            "frequencies",
            "√((2 ± √2) g/l)",
            Correct,
            None,
        ),
        // r = 0 is r (2ga − ω²) = 0 where the problem assumes 2ga > ω²; a factor the
        // reference lacks is still the sign slip.
        (
            "bead-parabola",
            "equilibrium-condition",
            "r = 0",
            Correct,
            None,
        ),
        (
            "bead-parabola",
            "equilibrium-condition",
            "r*(2*g*a + omega^2) = 0",
            Incorrect,
            Some(Code::SignError),
        ),
        // 3π is the position π, outside the range the part asks for.
        (
            "simple-pendulum",
            "equilibria",
            "θ = 0, θ = π",
            Correct,
            None,
        ),
        (
            "simple-pendulum",
            "equilibria",
            "θ = 0, θ = 3π",
            Incorrect,
            Some(Code::WrongItem),
        ),
        (
            "simple-pendulum",
            "equilibria",
            "θ = -2π, θ = π",
            Incorrect,
            Some(Code::WrongItem),
        ),
    ]);
}

#[test]
fn every_sign_choice_is_an_item() {
    // ±√((2 ± √2) g/l): four values, never the two with the signs paired.
    let v = verdict("double-pendulum", "frequencies", "ω = ±√((2 ± √2) g/l)");
    assert_eq!(
        v.reading.unicode,
        "ω = √((2 + √2)·g/l), ω = −√((2 + √2)·g/l), ω = √((2 − √2)·g/l), ω = −√((2 − √2)·g/l)"
    );
    assert_eq!(v.status, Status::Incorrect);
    assert!(v.diagnoses.iter().all(|d| d.code == Code::ExtraItem));
    // A ∓ beside two ±: which signs go together is not said; refused with the reason.
    let v = verdict("double-pendulum", "frequencies", "±√((2 ∓ √2) g/l)");
    assert_eq!(v.status, Status::Invalid);
    let e = v.parse_error.expect("a reading error");
    assert_eq!(e.kind.code(), "ambiguous-signs");
}

#[test]
fn the_echo_shows_the_students_names() {
    // `any`, never the marker value it is compared as; θ₀ by name, not its value.
    let v = verdict("spring-cart", "equilibria", "x arbitrary, s = 0 (unstable)");
    let text = format!("{:?} {:?}", v.reading, v.diagnoses);
    assert!(!text.contains('√') && !text.contains("sqrt"), "{text}");
    assert_eq!(v.reading.unicode, "x = any, s = 0");
    let v = verdict("rotating-hoop", "frequencies", "ω sin θ₀");
    assert_eq!(v.reading.unicode, "ω·sin(θ₀)");
    // The student's own difference is quoted: (m₂ − m₁) g, m g l (1 − cos θ).
    let v = verdict("atwood", "eom", "(m₂ − m₁) g = (m1 + m2) x''");
    assert_eq!(v.reading.unicode, "(m₂ − m₁)·g = (m₁ + m₂)·x\u{308}");
    assert!(
        v.diagnoses[0]
            .message
            .contains("your term (m₂ − m₁) g on the left "),
        "{:?}",
        v.diagnoses
    );
}

#[test]
fn messages_of_natural_answers() {
    let cases = [
        ("conical-pendulum", "steady", "φ̇ = √(g/(l cos α))"),
        ("rotating-hoop", "frequencies", "5 rad/s"),
        ("rotating-hoop", "equilibria", "θ = 0 and θ = π"),
        ("conical-pendulum", "momentum", "p = const"),
        ("simple-pendulum", "eom", "d θ + g = 0"),
        (
            "rotating-hoop",
            "equilibria",
            "θ = 0 (unstable), θ = 3π (unstable), θ = ±θ₀ (stable)",
        ),
        (
            "simple-pendulum",
            "lagrangian",
            "1/2 m l² θ̇² + m g l (1 − cos θ)",
        ),
        ("simple-pendulum", "potential", "-m g l (1 − cos θ)"),
        ("atwood", "eom", "(m₂ − m₁) g = (m1 + m2) x''"),
        (
            "rotating-trap-fast",
            "equilibria",
            "x = 0, y = 0 (unstable)",
        ),
        (
            "simple-pendulum",
            "equilibria",
            "θ = 0 (stable), θ = π (stable)",
        ),
        ("central-force", "eom", "m*r'' + m*r*phi'^2 + k/r^2 = 0"),
    ];
    let out: String = cases
        .iter()
        .map(|(p, part, a)| shown(p, part, a))
        .collect::<Vec<_>>()
        .join("\n");
    insta::assert_snapshot!("natural_answer_messages", out);
}

#[test]
fn the_fast_trap_is_not_sent_to_the_potential() {
    let v = verdict(
        "rotating-trap-fast",
        "equilibria",
        "x = 0, y = 0 (unstable)",
    );
    let m = &v.diagnoses[0].message;
    assert_eq!(v.diagnoses[0].code, Code::WrongStability);
    assert!(!m.contains("has a minimum"), "{m}");
    assert!(m.contains("linearise the equations of motion"), "{m}");
    // Without velocity terms the potential's minimum is still the reason.
    let v = verdict(
        "simple-pendulum",
        "equilibria",
        "θ = 0 (unstable), θ = π (unstable)",
    );
    assert!(
        v.diagnoses[0].message.contains("has a minimum"),
        "{:?}",
        v.diagnoses
    );
}

#[test]
fn t_plus_v_is_told_once() {
    let v = verdict(
        "simple-pendulum",
        "lagrangian",
        "1/2 m l² θ̇² + m g l (1 − cos θ)",
    );
    let codes: Vec<Code> = v.diagnoses.iter().map(|d| d.code).collect();
    assert_eq!(codes, [Code::TPlusV]);
    // V with the wrong sign, up to the free constant: a sign error, no factor called wrong.
    let v = verdict("simple-pendulum", "potential", "-m g l (1 − cos θ)");
    let codes: Vec<Code> = v.diagnoses.iter().map(|d| d.code).collect();
    assert_eq!(codes, [Code::SignError]);
}

#[test]
fn premature_substitution_is_said_as_a_possibility() {
    let v = verdict("central-force", "eom", "m*r'' + m*r*phi'^2 + k/r^2 = 0");
    let d = v
        .diagnoses
        .iter()
        .find(|d| d.code == Code::PrematureSubstitution)
        .expect("premature-substitution");
    assert!(
        d.message.contains("if that is what you did"),
        "{}",
        d.message
    );
    assert!(
        d.message.starts_with("the term that comes from"),
        "{}",
        d.message
    );
}

#[test]
fn no_cross_term_lesson_for_a_generalized_force() {
    // ∂L/∂θ₁ without its θ̇₁θ̇₂ term: no word about squaring a sum of velocities (that is T's).
    let p = embedded::problem("double-pendulum").expect("double-pendulum");
    let steps = ladder(&p).expect("a ladder");
    let step = steps
        .iter()
        .find(|s| s.id == "generalized-force:theta1")
        .expect("the step");
    let mut checker = StepChecker::new(&p);
    let v = checker
        .check(step, "-(m1 + m2)*g*l1*sin(theta1)")
        .expect("checked");
    assert_eq!(v.status, Status::Incorrect);
    let text = format!("{:?}", v.diagnoses);
    assert!(!text.contains("velocities add as vectors"), "{text}");
    // The kinetic energy without it still gets the lesson.
    let step = steps.iter().find(|s| s.id == "kinetic").expect("kinetic");
    let v = checker
        .check(step, "1/2*(m1 + m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2")
        .expect("checked");
    let text = format!("{:?}", v.diagnoses);
    assert!(text.contains("cross term"), "{text}");
}

/// A problem file with a `[definitions]` table around a pendulum.
fn with_definitions(defs: &str) -> String {
    format!(
        r#"id = "defined"
title = "Defined"
coordinates = [{{ name = "theta", periodic = true }}]
lagrangian = "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)"

[parameters]
m = {{ dimension = "M", range = [0.5, 2.0] }}
l = {{ dimension = "L", range = [0.5, 2.0] }}
g = {{ dimension = "L T^-2", range = [5.0, 15.0] }}

[definitions]
{defs}

[[parts]]
id = "frequencies"
kind = "frequencies"
prompt = "Find the angular frequency of small oscillations about θ = 0."
answer = ["w0"]
at = {{ theta = "0" }}
"#
    )
}

#[test]
fn definitions_are_read_and_checked_when_loaded() {
    let p = load_str("defined.toml", &with_definitions(r#"w0 = "sqrt(g/l)""#))
        .expect("a good definitions table loads");
    let mut c = Checker::new(&p);
    assert_eq!(
        c.check("frequencies", "sqrt(g/l)").unwrap().status,
        Status::Correct
    );
    assert_eq!(
        c.check("frequencies", "w0").unwrap().status,
        Status::Correct
    );
    assert_eq!(
        c.check("frequencies", "2*w0").unwrap().status,
        Status::Incorrect
    );
    for (defs, why) in [
        (r#"w0 = "sqrt(g/L)""#, "unknown name"),
        (r#"w0 = "sqrt(g/l)*theta""#, "uses `theta`"),
        (r#"w0 = "sqrt(g/l)*t""#, "uses `t`"),
        (r#"w0 = "g + l""#, "dimension"),
        (r#"g = "l""#, "name of a coordinate or parameter"),
        (r#""w 0" = "l""#, "one name"),
        (r#"sin = "l""#, "sin"),
        (
            r#"w0 = "sqrt(g/l)"
w1 = "2*w0""#,
            "unknown name",
        ),
    ] {
        let f = load_str("defined.toml", &with_definitions(defs))
            .expect_err(&format!("{defs} must be refused"));
        assert_eq!(f.code, "bad-definition", "{defs}: {f:?}");
        assert!(f.message.contains(why), "{defs}: {}", f.message);
    }
}

//! The parts instructors ask for (issue 24 §2), on the bank's `cart-pendulum-small`: a
//! linearized V, T and linearized equations (`about`), frequencies without the zero mode
//! (`omit_zero_modes`), the growth rate at the inverted position (`growth`) and a numeric
//! frequency with units (`values`). Right answers are accepted, each typical wrong answer gets
//! its diagnosis, and verification refuses a file whose reference is wrong.

use lagrange::bank::verify::verify;
use lagrange::bank::{Problem, embedded, load_str};
use lagrange::check::{Checker, Code, Status};

const FILE: &str = include_str!("../../problems/cart-pendulum-small.toml");

fn problem() -> Problem {
    embedded::bank()
        .problems
        .into_iter()
        .find(|p| p.id == "cart-pendulum-small")
        .expect("cart-pendulum-small is in the bank")
}

/// The status and codes of `answer` to `part`.
fn judge(part: &str, answer: &str) -> (Status, Vec<Code>, String) {
    let p = problem();
    let mut c = Checker::new(&p);
    let v = c.check(part, answer).unwrap();
    let codes = v.diagnoses.iter().map(|d| d.code).collect();
    let text = v
        .diagnoses
        .iter()
        .map(|d| d.message.clone())
        .collect::<Vec<_>>()
        .join(" | ");
    (v.status, codes, text)
}

fn assert_correct(part: &str, answer: &str) {
    let (s, _, text) = judge(part, answer);
    assert_eq!(s, Status::Correct, "{part}: `{answer}` rejected: {text}");
}

fn assert_diagnosed(part: &str, answer: &str, code: Code, words: &str) -> String {
    let (s, codes, text) = judge(part, answer);
    assert_ne!(s, Status::Correct, "{part}: `{answer}` accepted");
    assert!(
        codes.contains(&code),
        "{part}: `{answer}`: {codes:?} {text}"
    );
    assert!(text.contains(words), "{part}: `{answer}`: {text}");
    text
}

/// The bank file with `from` replaced by `to` (which must occur), loaded and verified: the
/// codes of the findings.
fn findings_with(from: &str, to: &str) -> Vec<String> {
    assert!(FILE.contains(from), "the file has no `{from}`");
    let text = FILE.replacen(from, to, 1);
    match load_str("cart-pendulum-small.toml", &text) {
        Err(f) => vec![format!("{}: {}", f.code, f.message)],
        Ok(p) => verify(&p)
            .iter()
            .map(|f| format!("{}: {}", f.code, f.message))
            .collect(),
    }
}

#[test]
fn the_problem_with_every_new_part_is_proved() {
    let p = problem();
    let findings: Vec<String> = verify(&p).iter().map(|f| f.to_string()).collect();
    assert!(findings.is_empty(), "{findings:#?}");
    for id in [
        "potential",
        "kinetic",
        "eom",
        "frequencies",
        "growth",
        "frequency-number",
    ] {
        assert!(p.part(id).is_some(), "no part {id}");
    }
}

#[test]
fn a_linearized_potential_is_the_second_order_taylor_polynomial() {
    // V = −m g l cos θ = −m g l + ½ m g l θ² + O(θ⁴); any constant is allowed.
    assert_correct("potential", "1/2*m*g*l*theta^2");
    assert_correct("potential", "-m*g*l + m*g*l*theta^2/2");
    assert_correct("potential", "½ m g l θ²");
    assert_diagnosed(
        "potential",
        "-m*g*l*cos(theta)",
        Code::NotExpanded,
        "not expanded",
    );
    // The second-order term dropped: what is left is a constant.
    let t = assert_diagnosed("potential", "0", Code::ExpansionOrder, "second-order term");
    assert!(t.contains("½·m·g·l·θ²"), "{t}");
    assert_diagnosed(
        "potential",
        "1/2*m*g*l*theta^2 - m*g*l*theta^4/24",
        Code::ExpansionOrder,
        "beyond second order",
    );
    // A wrong coefficient is no expansion slip.
    let (s, codes, _) = judge("potential", "m*g*l*theta^2");
    assert_eq!(s, Status::Incorrect);
    assert!(!codes.contains(&Code::NotExpanded) && !codes.contains(&Code::ExpansionOrder));
}

#[test]
fn a_linearized_kinetic_energy_takes_its_coefficients_at_the_point() {
    assert_correct(
        "kinetic",
        "1/2*(M+m)*x'^2 + m*l*x'*theta' + 1/2*m*l^2*theta'^2",
    );
    assert_diagnosed(
        "kinetic",
        "1/2*(M+m)*x'^2 + m*l*x'*theta'*cos(theta) + 1/2*m*l^2*theta'^2",
        Code::NotExpanded,
        "not expanded",
    );
    // No constant is free in T.
    let (s, _, _) = judge(
        "kinetic",
        "1 + 1/2*(M+m)*x'^2 + m*l*x'*theta' + 1/2*m*l^2*theta'^2",
    );
    assert_ne!(s, Status::Correct);
}

#[test]
fn linearized_equations_are_those_of_the_quadratic_lagrangian() {
    assert_correct(
        "eom",
        "(M+m)*x'' + m*l*theta'' = 0; l*theta'' + x'' + g*theta = 0",
    );
    // Any combination that determines the same accelerations.
    assert_correct(
        "eom",
        "M*x'' - m*g*theta = 0; M*l*theta'' + (M+m)*g*theta = 0",
    );
    assert_diagnosed(
        "eom",
        "(M+m)*x'' + m*l*theta''*cos(theta) - m*l*theta'^2*sin(theta) = 0; l*theta'' + x''*cos(theta) + g*sin(theta) = 0",
        Code::NotExpanded,
        "not linearized",
    );
    // Half linearized: sin θ kept in one equation.
    assert_diagnosed(
        "eom",
        "(M+m)*x'' + m*l*theta'' = 0; l*theta'' + x'' + g*sin(theta) = 0",
        Code::NotExpanded,
        "not linearized",
    );
    // The cart's recoil left out is a physics mistake, not an expansion one.
    let (s, codes, _) = judge(
        "eom",
        "(M+m)*x'' + m*l*theta'' = 0; l*theta'' + g*theta = 0",
    );
    assert_ne!(s, Status::Correct);
    assert!(!codes.contains(&Code::NotExpanded));
}

#[test]
fn frequencies_without_the_zero_mode() {
    // ω² = (M + m) g/(M l) about θ = 0; the free motion along the rail is omitted.
    assert_correct("frequencies", "sqrt((M+m)*g/(M*l))");
    assert_diagnosed(
        "frequencies",
        "0, sqrt((M+m)*g/(M*l))",
        Code::ExtraItem,
        "zero mode of a free motion",
    );
    // The fixed-pivot frequency is wrong, whatever the list.
    let (s, _, _) = judge("frequencies", "sqrt(g/l)");
    assert_eq!(s, Status::Incorrect);
}

#[test]
fn a_part_that_lists_the_zero_mode_names_it_when_it_is_missing() {
    let p = embedded::bank()
        .problems
        .into_iter()
        .find(|p| p.id == "cart-pendulum")
        .unwrap();
    let mut c = Checker::new(&p);
    let v = c.check("frequencies", "sqrt((M+m)*g/(M*l))").unwrap();
    assert_eq!(v.status, Status::Incorrect);
    assert!(
        v.diagnoses
            .iter()
            .any(|d| d.code == Code::MissingItem
                && d.message.contains("missing one is the zero mode")),
        "{:?}",
        v.diagnoses
    );
    let v = c.check("frequencies", "0, sqrt((M+m)*g/(M*l))").unwrap();
    assert_eq!(v.status, Status::Correct);
}

#[test]
fn growth_rates_at_the_inverted_position() {
    // θ = π + φ: φ'' = (M + m) g/(M l) φ, so λ = √((M + m) g/(M l)).
    assert_correct("growth", "sqrt((M+m)*g/(M*l))");
    assert_correct("growth", "lambda = sqrt((M+m)*g/(M*l))");
    assert_diagnosed(
        "growth",
        "0, sqrt((M+m)*g/(M*l))",
        Code::ExtraItem,
        "not a growth rate",
    );
    assert_diagnosed(
        "growth",
        "(M+m)*g/(M*l)",
        Code::OmegaSquared,
        "square of a growth rate",
    );
}

#[test]
fn numbers_with_units_are_converted_and_checked_dimensionally() {
    // ω = √((M + m) g/(M l)) = √(3·9.81/(2·0.5)) = 5.4249 rad/s; tolerance 2e-3.
    let omega = (3.0f64 * 9.81 / (2.0 * 0.5)).sqrt();
    assert!((omega - 5.4249).abs() < 1e-4);
    assert_correct("frequency-number", "5.42 [rad/s]");
    assert_correct("frequency-number", "5.425 [1/s]");
    assert_correct("frequency-number", "omega = 5.42 [rad/s]");
    // 5.4249 rad/s · 60 s/min = 325.5 per minute: convertible units are converted.
    assert_correct("frequency-number", "325.5 [1/min]");
    // No unit: read in SI.
    assert_correct("frequency-number", "5.4249");
    assert_diagnosed("frequency-number", "5.42 [m/s]", Code::Dimension, "L T⁻¹");
    // f = ω/2π = 0.8634 Hz given for ω.
    assert_diagnosed(
        "frequency-number",
        "0.8634 [Hz]",
        Code::OrdinaryFrequency,
        "2π",
    );
    // Off by 0.5 %: outside the instructor's 0.2 %.
    assert_diagnosed(
        "frequency-number",
        "5.4 [rad/s]",
        Code::RoundedConstant,
        "accepted relative error",
    );
    let (s, codes, text) = judge("frequency-number", "5.42 [furlong/s]");
    assert_eq!(s, Status::Invalid);
    assert_eq!(codes, vec![Code::Syntax]);
    assert!(text.contains("unknown unit `furlong`"), "{text}");
    let (s, _, _) = judge("frequency-number", "5.42 [rad/s");
    assert_eq!(s, Status::Invalid);
}

#[test]
fn verification_refuses_a_wrong_reference_in_each_new_part() {
    let wrong = |from: &str, to: &str, code: &str| {
        let f = findings_with(from, to);
        assert!(
            f.iter().any(|x| x.starts_with(code)),
            "`{to}`: expected {code}, got {f:#?}"
        );
    };
    // V to second order with the wrong coefficient.
    wrong(
        "answer = \"1/2*m*g*l*theta^2\"",
        "answer = \"m*g*l*theta^2\"",
        "wrong-answer",
    );
    // The full T where the expansion is asked.
    wrong(
        "answer = \"1/2*(M+m)*x'^2 + m*l*x'*theta' + 1/2*m*l^2*theta'^2\"",
        "answer = \"1/2*(M+m)*x'^2 + m*l*x'*theta'*cos(theta) + 1/2*m*l^2*theta'^2\"",
        "wrong-answer",
    );
    // Linearized equations without the cart's recoil.
    wrong(
        "\"l*theta'' + x'' + g*theta = 0\",",
        "\"l*theta'' + g*theta = 0\",",
        "wrong-eom",
    );
    // A zero mode listed where the part omits them.
    wrong(
        "answer = [\"sqrt((M+m)*g/(M*l))\"]\nat = { x = \"0\", theta = \"0\" }",
        "answer = [\"0\", \"sqrt((M+m)*g/(M*l))\"]\nat = { x = \"0\", theta = \"0\" }",
        "wrong-frequency",
    );
    // The fixed-pivot rate for the cart's.
    wrong(
        "answer = [\"sqrt((M+m)*g/(M*l))\"]\nat = { x = \"0\", theta = \"pi\" }",
        "answer = [\"sqrt(g/l)\"]\nat = { x = \"0\", theta = \"pi\" }",
        "wrong-frequency",
    );
    // Growth rates asked where nothing grows.
    wrong(
        "at = { x = \"0\", theta = \"pi\" }",
        "at = { x = \"0\", theta = \"0\" }",
        "wrong-frequency",
    );
    // The number off by 1 %, and a reference in a unit of another dimension.
    wrong(
        "answer = [\"5.42 [rad/s]\"]",
        "answer = [\"5.37 [rad/s]\"]",
        "wrong-frequency",
    );
    wrong(
        "answer = [\"5.42 [rad/s]\"]",
        "answer = [\"5.42 [m/s]\"]",
        "bad-values",
    );
}

#[test]
fn the_new_fields_are_refused_where_they_mean_nothing() {
    let refused = |from: &str, to: &str, code: &str, words: &str| {
        let f = findings_with(from, to);
        assert!(
            f.iter().any(|x| x.starts_with(code) && x.contains(words)),
            "`{to}`: expected {code} ({words}), got {f:#?}"
        );
    };
    refused(
        "about = { theta = 0 }",
        "about = { phi = 0 }",
        "bad-about",
        "not a coordinate",
    );
    refused(
        "omit_zero_modes = true\nhints",
        "omit_zero_modes = true\ngrowth = true\nhints",
        "bad-frequency-option",
        "growth",
    );
    refused(
        "up_to = \"constant\"",
        "up_to = \"constant\"\ngrowth = true",
        "bad-frequency-option",
        "frequencies part only",
    );
    refused(
        "l = \"50 [cm]\"",
        "l = \"50 [s]\"",
        "bad-values",
        "dimension T",
    );
    refused("l = \"50 [cm]\", ", "", "bad-values", "l has none");
    refused("tolerance = 2e-3\n", "", "bad-values", "tolerance");
    refused(
        "M = \"2 [kg]\"",
        "M = \"2 [kg]\", q = \"1\"",
        "bad-values",
        "not a parameter",
    );
}

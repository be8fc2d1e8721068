//! Issue 19 §3: what the student wrote is what is judged. A label on a frequency states a
//! quantity — `ω² = X` the square, `f = X` an ordinary frequency, `T = X` a period — and an
//! item that states another quantity than the part asks for is not the answer, whether the
//! statement is true (`ω² = g/l` for ω) or the right value is misnamed (`ω² = √(g/l)`). A label
//! names the quantity asked about even where ω is also a parameter (the spin rate). And a part
//! whose prompt asks for stability requires it: a point without one gets half its credit.

use lagrange::bank::{embedded, load_str};
use lagrange::check::{Checker, Code, Status};

use crate::helpers::verdict_table as table;

#[test]
fn a_label_states_a_quantity_and_is_judged_as_written() {
    use Code::*;
    use Status::*;
    table(&[
        // The simple pendulum asks for ω.
        ("simple-pendulum", "frequencies", "sqrt(g/l)", Correct, None),
        (
            "simple-pendulum",
            "frequencies",
            "ω = √(g/l)",
            Correct,
            None,
        ),
        (
            "simple-pendulum",
            "frequencies",
            "omega_1 = sqrt(g/l)",
            Correct,
            None,
        ),
        (
            "simple-pendulum",
            "frequencies",
            "ω² = √(g/l)",
            Incorrect,
            Some(OmegaRoot),
        ),
        (
            "simple-pendulum",
            "frequencies",
            "omega^2 = sqrt(g/l)",
            Incorrect,
            Some(OmegaRoot),
        ),
        (
            "simple-pendulum",
            "frequencies",
            "f = √(g/l)",
            Incorrect,
            Some(OrdinaryFrequency),
        ),
        (
            "simple-pendulum",
            "frequencies",
            "ω² = g/l",
            Incorrect,
            Some(OmegaSquared),
        ),
        (
            "simple-pendulum",
            "frequencies",
            "omega^2 = g/l",
            Incorrect,
            Some(OmegaSquared),
        ),
        (
            "simple-pendulum",
            "frequencies",
            "f = √(g/l)/(2π)",
            Incorrect,
            Some(OrdinaryFrequency),
        ),
        (
            "simple-pendulum",
            "frequencies",
            "T = 2π √(l/g)",
            Incorrect,
            Some(Period),
        ),
        (
            "simple-pendulum",
            "frequencies",
            "T = √(g/l)",
            Incorrect,
            Some(Period),
        ),
        (
            "simple-pendulum",
            "frequencies",
            "ω = g/l",
            Incorrect,
            Some(OmegaSquared),
        ),
        // The double pendulum's `omega-squared` part asks for ω².
        (
            "double-pendulum",
            "omega-squared",
            "ω² = (2 ± √2) g/l",
            Correct,
            None,
        ),
        (
            "double-pendulum",
            "omega-squared",
            "(2 ± √2) g/l",
            Correct,
            None,
        ),
        (
            "double-pendulum",
            "omega-squared",
            "omega1^2 = (2 - sqrt(2))*g/l, omega2^2 = (2 + sqrt(2))*g/l",
            Correct,
            None,
        ),
        (
            "double-pendulum",
            "omega-squared",
            "ω = (2 ± √2) g/l",
            Incorrect,
            Some(OmegaSquared),
        ),
        (
            "double-pendulum",
            "omega-squared",
            "ω = √((2 ± √2) g/l)",
            Incorrect,
            Some(OmegaRoot),
        ),
        // The double pendulum's `frequencies` part asks for ω.
        (
            "double-pendulum",
            "frequencies",
            "ω = √((2 ± √2) g/l)",
            Correct,
            None,
        ),
        (
            "double-pendulum",
            "frequencies",
            "ω² = (2 ± √2) g/l",
            Incorrect,
            Some(OmegaSquared),
        ),
        // Where ω is the spin rate, the label is still the frequency asked about.
        (
            "bead-parabola",
            "frequencies",
            "ω = √(2 g a − ω²)",
            Correct,
            None,
        ),
        (
            "bead-parabola",
            "frequencies",
            "√(2 g a − ω²)",
            Correct,
            None,
        ),
        (
            "bead-parabola",
            "frequencies",
            "ω² = 2 g a − ω²",
            Incorrect,
            Some(OmegaSquared),
        ),
        (
            "bead-parabola",
            "frequencies",
            "f = √(2 g a − ω²)/(2π)",
            Incorrect,
            Some(OrdinaryFrequency),
        ),
        (
            "bead-parabola",
            "frequencies",
            "f = √(2 g a − ω²)",
            Incorrect,
            Some(OrdinaryFrequency),
        ),
        (
            "rotating-hoop",
            "frequencies",
            "ω = ω sin(acos(g/(R ω²)))",
            Correct,
            None,
        ),
        (
            "rotating-hoop",
            "frequencies",
            "ω² = ω² − g²/(R² ω²)",
            Incorrect,
            Some(OmegaSquared),
        ),
    ]);
}

#[test]
fn a_label_message_says_what_the_statement_is() {
    let p = embedded::problem("simple-pendulum").expect("bank");
    let mut c = Checker::new(&p);
    let true_square = c.check("frequencies", "ω² = g/l").expect("part");
    let m = &true_square.diagnoses[0].message;
    assert!(
        m.contains("is true") && m.contains("asks for the angular frequency ω"),
        "{m}"
    );
    assert_eq!(true_square.reading.unicode, "ω² = g/l");
    let misnamed = c.check("frequencies", "ω² = √(g/l)").expect("part");
    let m = &misnamed.diagnoses[0].message;
    assert!(m.contains("your label says"), "{m}");
    // The reference item it names is not also reported missing.
    assert_eq!(misnamed.diagnoses.len(), 1, "{:?}", misnamed.diagnoses);
}

#[test]
fn grading_keeps_labelled_and_bare_answers_apart() {
    // Answers with one canonical form share one verdict in `grade`: a label that changes the
    // verdict must change the form (and the fingerprint of the summary's groups).
    let p = embedded::problem("simple-pendulum").expect("bank");
    let mut c = Checker::new(&p);
    let bare = c.canonical("frequencies", "sqrt(g/l)").expect("part");
    let named = c.canonical("frequencies", "ω = sqrt(g/l)").expect("part");
    let squared = c.canonical("frequencies", "ω² = sqrt(g/l)").expect("part");
    let ordinary = c.canonical("frequencies", "f = sqrt(g/l)").expect("part");
    assert_eq!(bare, named);
    assert_ne!(bare, squared);
    assert_ne!(bare, ordinary);
    assert_ne!(squared, ordinary);
    let fp = |c: &mut Checker, a: &str| c.fingerprint("frequencies", a).expect("part");
    assert_ne!(fp(&mut c, "sqrt(g/l)"), fp(&mut c, "ω² = sqrt(g/l)"));
    assert_eq!(fp(&mut c, "sqrt(g/l)"), fp(&mut c, "omega = sqrt(g/l)"));
}

#[test]
fn stability_a_part_asks_for_is_required() {
    use Status::*;
    table(&[
        (
            "bead-wire",
            "equilibria",
            "r = 0",
            Incorrect,
            Some(Code::MissingStability),
        ),
        ("bead-wire", "equilibria", "r = 0 (unstable)", Correct, None),
        ("bead-wire", "equilibria", "r = 0, unstable", Correct, None),
        (
            "bead-wire",
            "equilibria",
            "r = 0 (stable)",
            Incorrect,
            Some(Code::WrongStability),
        ),
        (
            "spring-incline",
            "equilibria",
            "x = m g sin(α)/k",
            Incorrect,
            Some(Code::MissingStability),
        ),
        (
            "spring-incline",
            "equilibria",
            "x = m g sin(α)/k (stable)",
            Correct,
            None,
        ),
        (
            "rotating-hoop",
            "equilibria",
            "0, π, ±acos(g/(R ω²))",
            Incorrect,
            Some(Code::MissingStability),
        ),
        (
            "rotating-hoop",
            "equilibria",
            "0 (unstable), π (unstable), ±acos(g/(R ω²)) (stable)",
            Correct,
            None,
        ),
        (
            "bead-parabola",
            "equilibria",
            "r = 0",
            Incorrect,
            Some(Code::MissingStability),
        ),
        (
            "bead-parabola",
            "equilibria",
            "r = 0 (stable)",
            Correct,
            None,
        ),
        (
            "spring-cart",
            "equilibria",
            "x = any, s = 0 (stable)",
            Correct,
            None,
        ),
        (
            "rotating-trap",
            "equilibria",
            "x = 0, y = 0 (stable)",
            Correct,
            None,
        ),
        // A wrong point is the mistake first: no stability is asked of it.
        (
            "bead-wire",
            "equilibria",
            "r = 1",
            Incorrect,
            Some(Code::WrongItem),
        ),
        // A prompt that does not ask for it does not require it.
        (
            "simple-pendulum",
            "equilibria",
            "θ = 0, θ = π",
            Correct,
            None,
        ),
    ]);
}

#[test]
fn a_missing_statement_gets_half_credit_and_says_it_was_asked() {
    let p = embedded::problem("rotating-hoop").expect("bank");
    let mut c = Checker::new(&p);
    let none = c
        .check("equilibria", "0, π, ±acos(g/(R ω²))")
        .expect("part");
    assert_eq!(none.score, 0.5);
    let m = &none.diagnoses[0].message;
    assert!(m.contains("asks for the stability"), "{m}");
    // Nothing of the reference leaks into the message.
    assert!(!m.contains("unstable)"), "{m}");
    let half = c
        .check("equilibria", "0 (unstable), π (unstable), ±acos(g/(R ω²))")
        .expect("part");
    assert_eq!(half.score, 0.75);
}

#[test]
fn every_bank_part_whose_prompt_asks_for_stability_requires_it() {
    let bank = embedded::bank();
    let mut asked = 0;
    for p in &bank.problems {
        for part in &p.parts {
            if part.kind == lagrange::PartKind::Equilibria && part.prompt_asks_stability() {
                asked += 1;
                assert!(part.require_stability, "{}/{}", p.id, part.id);
            }
        }
    }
    assert!(asked >= 7, "{asked}");
}

/// The bead on a wire with `require_stability` taken out of its equilibria part.
fn without_requirement() -> String {
    let text = embedded::FILES
        .iter()
        .find(|(n, _)| *n == "bead-wire.toml")
        .map(|(_, t)| *t)
        .expect("the bead on a wire");
    let out = text.replacen("require_stability = true\n", "", 1);
    assert_ne!(out, text);
    out
}

#[test]
fn verify_finds_a_prompt_asking_stability_that_is_not_required() {
    let p = load_str("bead-wire.toml", &without_requirement()).expect("loads");
    let found = lagrange::bank::verify::verify(&p);
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].code, "stability-not-required");
    assert_eq!(found[0].part.as_deref(), Some("equilibria"));
    // Required without a stability per point, or on another kind: refused at load.
    let text =
        without_requirement().replacen("stability = [\"unstable\"]", "require_stability = true", 1);
    assert_eq!(
        load_str("b.toml", &text).unwrap_err().code,
        "bad-require-stability"
    );
    let text =
        without_requirement().replacen("id = \"eom\"", "id = \"eom\"\nrequire_stability = true", 1);
    assert_eq!(
        load_str("b.toml", &text).unwrap_err().code,
        "bad-require-stability"
    );
}

#[test]
fn follow_through_sees_the_frequency_the_label_states() {
    use lagrange::tutor::follow::{Earlier, check_with_history};
    let p = embedded::problem("simple-pendulum").expect("bank");
    let part = p.part("frequencies").expect("part");
    // A doubled potential in L gives ω = √(2g/l).
    let history = [Earlier::new(
        "lagrangian",
        "L = 1/2*m*l^2*theta'^2 + 2*m*g*l*cos(theta)",
    )];
    for (answer, follows) in [
        ("sqrt(2*g/l)", true),
        ("ω = √(2g/l)", true),
        // Labelled as ω², it states another quantity: that is its mistake.
        ("ω² = 2g/l", false),
        ("ω² = √(2g/l)", false),
    ] {
        let v = check_with_history(&p, part, answer, &history).expect("checks");
        assert_eq!(v.status, Status::Incorrect, "{answer}");
        assert_eq!(
            v.diagnoses[0].code == Code::FollowsFromEarlier,
            follows,
            "{answer}: {:#?}",
            v.diagnoses
        );
    }
}

#[test]
fn the_reading_shows_the_label_in_each_style() {
    let p = embedded::problem("double-pendulum").expect("bank");
    let v = Checker::new(&p)
        .check("omega-squared", "ω² = (2 ± √2) g/l")
        .expect("part");
    assert_eq!(
        v.reading.plain,
        "omega^2 = (2 + sqrt(2))*g/l, omega^2 = (2 - sqrt(2))*g/l"
    );
    assert_eq!(v.reading.unicode, "ω² = (2 + √2)·g/l, ω² = (2 − √2)·g/l");
}

/// The answer sheet shows what a right answer is: a part that requires stability shows the
/// points with it, and that text, checked, is correct (it showed `r = 0`, which scores 50%).
#[test]
fn the_answer_sheet_shows_the_required_stability() {
    let (code, out, _) = crate::helpers::lagrange(&["problems", "show", "bead-wire", "--answers"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("answer: r = 0 (unstable)"), "{out}");
    let (code, out, _) =
        crate::helpers::lagrange(&["check", "bead-wire", "equilibria", "r = 0 (unstable)"]);
    assert_eq!(code, 0, "{out}");
}

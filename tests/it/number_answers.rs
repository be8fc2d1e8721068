//! Diagnoses of answers with numbers and of list items (an instructor's report, t25): a sign
//! error in an equilibrium is told as one; bare numbers get no constant-factor diagnosis (any
//! two numbers have a ratio); a near miss on a part that takes the student's numbers is told
//! by how much and against which tolerance; equations one a line are separate equations; a
//! part in symbols answered with numbers is told to use the symbols.

use lagrange::bank::{embedded, load_str};
use lagrange::check::{Code, Status, Verdict, check};
use lagrange::problem::Problem;
use lagrange::problem::variant::pick;

/// The example problem with variants (ada: m = 1.5 kg, l = 1.65 m; ben: m = 0.5 kg,
/// l = 0.45 m; g = 9.81 m/s², seed 2026), with `from` replaced by `to` when given.
fn example(edit: Option<(&str, &str)>) -> Problem {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/variants/pendulum-numbers.toml"),
    )
    .expect("the example problem");
    let text = match edit {
        Some((from, to)) => {
            assert!(text.contains(from), "the example has no `{from}`");
            text.replacen(from, to, 1)
        }
        None => text,
    };
    load_str("pendulum-numbers.toml", &text).expect("the example loads")
}

/// The problem pinned to a student's numbers.
fn student(p: &Problem, key: &str) -> Problem {
    p.pinned(&pick(p, 2026, key).expect("variants"))
}

fn judge(p: &Problem, part: &str, answer: &str) -> Verdict {
    check(p, p.part(part).expect("the part"), answer).expect("checkable")
}

fn codes(v: &Verdict) -> Vec<Code> {
    v.diagnoses.iter().map(|d| d.code).collect()
}

fn builtin(id: &str) -> Problem {
    embedded::problem(id).expect("a bank problem")
}

/// A bob on a spring in a vertical plane (the report's spring pendulum): equilibria at
/// r = l₀ + m g/k, θ = 0 (stable) and r = l₀ − m g/k, θ = π (unstable).
const SPRING_PENDULUM: &str = r#"
id = "spring-pendulum-test"
title = "Spring pendulum"
statement = "A bob on a spring in a vertical plane."
axes = "x horizontal, y up, origin at the fixed end of the spring"
coordinates = [
  { name = "r", domain = "positive", range = [0.3, 3.0], description = "length of the spring" },
  { name = "theta", periodic = true, description = "angle from the downward vertical" },
]
assume = ["k*l0 > m*g"]

[parameters]
g = { dimension = "L T^-2", range = [5.0, 15.0], value = 9.81, description = "gravity" }
k = { dimension = "M T^-2", range = [5.0, 100.0], value = 50.0, description = "stiffness" }
l0 = { dimension = "L", range = [0.5, 1.5], value = 1.0, description = "natural length" }
m = { dimension = "M", range = [0.5, 4.0], value = 1.0, description = "mass" }

[[bodies]]
kind = "point"
mass = "m"
position = ["r*sin(theta)", "-r*cos(theta)"]

[[potentials]]
kind = "gravity"
g = "g"
axis = "y"

[[potentials]]
kind = "spring"
k = "k"
from = 1
to = ["0", "0"]
natural = "l0"

[[parts]]
id = "equilibria"
kind = "equilibria"
prompt = "Find every equilibrium (r, θ) and say whether it is stable."
answer = ["r = l0 + m*g/k, theta = 0", "r = l0 - m*g/k, theta = pi"]
stability = ["stable", "unstable"]
require_stability = true
"#;

#[test]
fn an_equilibrium_of_the_wrong_sign_is_a_sign_error() {
    // The mass on the incline rests at x = m g sin α / k below the natural length.
    let p = builtin("spring-incline");
    let right = judge(&p, "equilibria", "x = m*g*sin(alpha)/k (stable)");
    assert_eq!(right.status, Status::Correct);
    let v = judge(&p, "equilibria", "x = -m*g*sin(alpha)/k (stable)");
    assert_eq!(v.status, Status::Incorrect);
    assert_eq!(codes(&v), vec![Code::SignError], "{v:?}");
    assert!(v.diagnoses[0].message.contains("opposite sign"), "{v:?}");
    assert!(v.diagnoses[0].message.contains("m g sin(α)/k"), "{v:?}");
    // Another wrong value is still only wrong (no sign to blame): twice the extension.
    let twice = judge(&p, "equilibria", "x = 2*m*g*sin(alpha)/k (stable)");
    assert_eq!(twice.status, Status::Incorrect);
    assert!(!codes(&twice).contains(&Code::SignError), "{twice:?}");
    // A frequency's sign error is told as before.
    let f = judge(&p, "frequencies", "-sqrt(k/m)");
    assert_eq!(codes(&f), vec![Code::SignError]);
}

#[test]
fn a_coordinate_with_one_term_of_the_wrong_sign_names_that_term() {
    let p = load_str("spring-pendulum-test.toml", SPRING_PENDULUM).expect("loads");
    let right = "r = l0 + m*g/k, theta = 0 (stable); r = l0 - m*g/k, theta = pi (unstable)";
    assert_eq!(judge(&p, "equilibria", right).status, Status::Correct);
    // The static stretch m g/k with the wrong sign, at the stable point only.
    let v = judge(
        &p,
        "equilibria",
        "r = l0 - m*g/k, theta = 0 (stable); r = l0 - m*g/k, theta = pi (unstable)",
    );
    assert_eq!(v.status, Status::Incorrect);
    assert_eq!(v.score, 0.5);
    assert_eq!(codes(&v), vec![Code::SignError], "{v:?}");
    let m = &v.diagnoses[0].message;
    assert!(m.starts_with("item 1 "), "{m}");
    assert!(m.contains("in r: sign error: your term"), "{m}");
    // A missing stretch is no sign error: still a wrong item.
    let w = judge(
        &p,
        "equilibria",
        "r = l0, theta = 0 (stable); r = l0 - m*g/k, theta = pi (unstable)",
    );
    assert_eq!(codes(&w), vec![Code::WrongItem], "{w:?}");
}

#[test]
fn another_students_numbers_are_a_wrong_value_not_a_constant_factor() {
    let p = example(None);
    let ada = student(&p, "ada@uni.example");
    // V = −m g l cos θ = −24.27975 cos θ for ada; another student's numbers, −2.207475 cos θ.
    assert_eq!(
        judge(&ada, "potential", "-24.27975*cos(theta)").status,
        Status::Correct
    );
    let v = judge(&ada, "potential", "-2.207475*cos(theta)");
    assert_eq!(v.status, Status::Incorrect);
    assert_eq!(codes(&v), vec![Code::NotEqual], "{v:?}");
    // 2.207475 / 24.27975 = 0.0909…: about 91% too small.
    assert!(v.diagnoses[0].message.contains("91% too small"), "{v:?}");
    // A symbolic slip keeps its factor diagnosis, with the student's numbers pinned too.
    let half = judge(&ada, "potential", "-m*g*l*cos(theta)/2");
    assert_eq!(codes(&half), vec![Code::ConstantFactor], "{half:?}");
    // The sign of bare numbers is still a sign error (the exact negative).
    let neg = judge(&ada, "potential", "24.27975*cos(theta)");
    assert_eq!(codes(&neg), vec![Code::SignError], "{neg:?}");
    // A frequency: ω = √(g/l) = 2.4383… for ada; ben's numbers √(9.81/0.45) are wrong,
    // not "√(11/3) times" right; the symbolic √(2g/l) is √2 times right.
    assert_eq!(
        judge(&ada, "frequencies", "sqrt(9.81/1.65)").status,
        Status::Correct
    );
    let f = judge(&ada, "frequencies", "sqrt(9.81/0.45)");
    assert_eq!(codes(&f), vec![Code::WrongItem], "{f:?}");
    let root2 = judge(&ada, "frequencies", "sqrt(2*g/l)");
    assert_eq!(codes(&root2), vec![Code::ConstantFactor], "{root2:?}");
    // An equation of motion with ben's g/l = 21.8 for ada's 5.945…: the term's value is
    // wrong, said without a factor code.
    let e = judge(&ada, "eom", "theta'' + 21.8*sin(theta) = 0");
    assert_eq!(e.status, Status::Incorrect);
    assert!(
        !codes(&e).contains(&Code::ConstantFactor) && !codes(&e).contains(&Code::WrongFactor),
        "{e:?}"
    );
    assert_eq!(
        judge(&ada, "eom", "theta'' + 5.945454545454545*sin(theta) = 0").status,
        Status::Correct
    );
}

#[test]
fn a_near_miss_with_numbers_says_how_far_and_the_tolerance() {
    // cleo (l = 1.35 m): ω = √(9.81/1.35) = 2.695676…; to three significant figures 2.70,
    // 0.160% off: beyond 1e-3, within 5e-3 (the rule for 3 s.f.).
    let omega = "answer = [\"sqrt(g/l)\"]";
    let with = |tol: &str| example(Some((omega, &format!("{omega}\ntolerance = {tol}"))));
    let cleo = student(&with("1e-3"), "cleo@uni.example");
    let v = judge(&cleo, "frequencies", "2.70");
    assert_eq!(codes(&v), vec![Code::RoundedConstant], "{v:?}");
    let m = &v.diagnoses[0].message;
    assert!(m.contains("off by 0.160%"), "{m}");
    assert!(m.contains("tolerance of 1e-3 (0.1%)"), "{m}");
    assert!(!m.contains("exact constants"), "{m}");
    let cleo = student(&with("5e-3"), "cleo@uni.example");
    assert_eq!(judge(&cleo, "frequencies", "2.70").status, Status::Correct);
    // 2.72 is 0.9% off: beyond 5e-3.
    assert_eq!(
        judge(&cleo, "frequencies", "2.72").status,
        Status::Incorrect
    );
    // An expression: ben's V = −m g l cos θ = −2.20725 cos θ, written −2.21 cos θ (0.124%
    // off, beyond a tolerance of 1e-4); −2.23 cos θ, 1.03% off, is past the near-miss
    // window: a wrong value, with how far off, and no factor.
    let potential = "answer = \"-m*g*l*cos(theta)\"\nnumbers = true";
    let tight = example(Some((potential, &format!("{potential}\ntolerance = 1e-4"))));
    let ben = student(&tight, "ben@uni.example");
    let v = judge(&ben, "potential", "-2.21*cos(theta)");
    assert_eq!(codes(&v), vec![Code::RoundedConstant], "{v:?}");
    let m = &v.diagnoses[0].message;
    assert!(m.contains("off by 0.124%"), "{m}");
    assert!(m.contains("tolerance of 1e-4"), "{m}");
    assert!(!m.contains("exact constants"), "{m}");
    let far = judge(&ben, "potential", "-2.23*cos(theta)");
    assert_eq!(codes(&far), vec![Code::NotEqual], "{far:?}");
    assert!(
        far.diagnoses[0].message.contains("1.03% too large"),
        "{far:?}"
    );
    // In symbols a decimal for an exact constant is still told to be written exactly.
    let s = judge(
        &builtin("simple-pendulum"),
        "potential",
        "-3.14*m*g*l*cos(theta)/pi",
    );
    assert_eq!(codes(&s), vec![Code::RoundedConstant], "{s:?}");
    assert!(s.diagnoses[0].message.contains("exact constants"), "{s:?}");
}

#[test]
fn the_documented_tolerance_rule_and_default() {
    // The documented default is the checker's; n significant figures need 5·10⁻ⁿ.
    let p = example(None);
    let part = p.part("potential").expect("part");
    assert_eq!(part.tolerance, 1e-9);
    let doc = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/problem-format.md"),
    )
    .expect("docs");
    assert!(
        doc.contains("(default 1e-9"),
        "the default tolerance is documented"
    );
    assert!(
        doc.contains("tolerance = 5e-3"),
        "the 3 s.f. rule is documented"
    );
    assert!(
        !doc.contains("`tolerance = 1e-3` on a part that accepts three significant figures"),
        "the old advice is gone"
    );
}

#[test]
fn equations_on_separate_lines_are_separate_equations() {
    let p = builtin("double-pendulum");
    let one = "(m1+m2)*l1*theta1'' + m2*l2*theta2''*cos(theta1-theta2) + m2*l2*theta2'^2*sin(theta1-theta2) + (m1+m2)*g*sin(theta1) = 0";
    let two = "l2*theta2'' + l1*theta1''*cos(theta1-theta2) - l1*theta1'^2*sin(theta1-theta2) + g*sin(theta2) = 0";
    for sep in ["; ", "\n", "\r\n", " \n  "] {
        let v = judge(&p, "eom", &format!("{one}{sep}{two}"));
        assert_eq!(v.status, Status::Correct, "{sep:?}: {v:?}");
    }
    // A wrong second line is still diagnosed as before.
    let wrong = two.replace("+ g*sin(theta2)", "- g*sin(theta2)");
    let v = judge(&p, "eom", &format!("{one}\n{wrong}"));
    assert_eq!(v.status, Status::Incorrect);
    assert!(codes(&v).contains(&Code::SignError), "{v:?}");
    // A line break inside one equation is whitespace.
    let s = builtin("simple-pendulum");
    let v = judge(&s, "eom", "m*l^2*theta'' +\n m*g*l*sin(theta) = 0");
    assert_eq!(v.status, Status::Correct);
}

#[test]
fn a_part_in_symbols_answered_with_numbers_asks_for_the_symbols() {
    // The example's kinetic energy does not accept numbers: ½ m l² θ̇².
    let p = example(None);
    let ada = student(&p, "ada@uni.example");
    // Judged in symbols, as for every student: the part does not take numbers.
    let v = judge(&p, "kinetic", "0.5*1.5*1.65^2*theta'^2");
    assert_eq!(v.status, Status::Invalid, "{v:?}");
    assert_eq!(codes(&v), vec![Code::NumbersForSymbols]);
    assert!(
        v.diagnoses[0].message.contains("problem's symbols"),
        "{v:?}"
    );
    // Symbols are judged as before, right or wrong.
    assert_eq!(
        judge(&p, "kinetic", "m*l^2*theta'^2/2").status,
        Status::Correct
    );
    assert_eq!(
        codes(&judge(&p, "kinetic", "m*l^2*theta'^2")),
        vec![Code::ConstantFactor]
    );
    // A part that accepts numbers takes them (here judged for ada).
    assert_eq!(
        judge(&ada, "potential", "-1.5*9.81*1.65*cos(theta)").status,
        Status::Correct
    );
    // A bank equation in symbols answered with numbers.
    let s = builtin("simple-pendulum");
    let e = judge(&s, "eom", "theta'' + 9.81*sin(theta) = 0");
    assert_eq!(codes(&e), vec![Code::NumbersForSymbols], "{e:?}");
}

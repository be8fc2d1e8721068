//! Equations of motion near the places where the physics itself is singular (issue 19 §1):
//! an answer may stop determining an acceleration only where the mass matrix does too (r = 0,
//! sin θ = 0 for φ), where the true equations are not finite (k/r² at r = 0), or outside the
//! problem's domain; a sampling range is not a domain. Both directions are tested on the
//! systems in `tests/singular/`: the forms textbooks print are accepted, factors that vanish
//! where the physics is regular are refused.

use std::path::Path;

use lagrange::bank::verify::verify;
use lagrange::{Checker, Code, Status, Verdict};

fn bank() -> lagrange::bank::Bank {
    lagrange::bank::load_dir(Path::new("tests/singular")).expect("the fixtures load")
}

fn verdict(bank: &lagrange::bank::Bank, problem: &str, part: &str, answer: &str) -> Verdict {
    let p = bank
        .problems
        .iter()
        .find(|p| p.id == problem)
        .unwrap_or_else(|| panic!("no problem {problem}"));
    Checker::new(p)
        .check(part, answer)
        .unwrap_or_else(|e| panic!("{problem}/{part}: {e}"))
}

const SPHERICAL_THETA: &str = "theta'' - sin(theta)*cos(theta)*phi'^2 + g/l*sin(theta)";
const KEPLER_RADIAL: &str = "m*r'' - m*r*phi'^2 + k/r^2";

#[test]
fn textbook_forms_at_singular_sets_are_accepted() {
    let b = bank();
    let th = SPHERICAL_THETA;
    let kr = KEPLER_RADIAL;
    let cases: Vec<(&str, &str, String)> = vec![
        // The spherical pendulum's φ equation divided by sin θ or sin²θ (undefined or
        // singular only where sin θ = 0, where M loses rank in the φ direction).
        (
            "spherical-pendulum",
            "eom",
            format!("phi'' + 2*theta'*phi'*cot(theta) = 0; {th} = 0"),
        ),
        (
            "spherical-pendulum",
            "eom",
            format!("{th} = 0; sin(theta)*phi'' + 2*cos(theta)*theta'*phi' = 0"),
        ),
        (
            "spherical-pendulum",
            "eom",
            format!("{th} = 0; 1/sin(theta)*d/dt(sin(theta)^2*phi') = 0"),
        ),
        (
            "spherical-pendulum",
            "eom",
            format!("{th} = 0; phi'' = -2*theta'*phi'*cos(theta)/sin(theta)"),
        ),
        (
            "spherical-pendulum",
            "eom",
            "θ̈ = sin θ cos θ φ̇² − g/l sin θ; d/dt(m l^2 sin(θ)^2 φ̇) = 0".to_string(),
        ),
        // Kepler: the angular equation in every printed form, the radial one with its
        // denominator cleared (the force k/r² is not finite at r = 0).
        (
            "kepler",
            "eom",
            format!("{kr} = 0; r*phi'' + 2*r'*phi' = 0"),
        ),
        (
            "kepler",
            "eom",
            format!("{kr} = 0; phi'' + 2*r'*phi'/r = 0"),
        ),
        ("kepler", "eom", format!("{kr} = 0; 1/r*d/dt(r^2*phi') = 0")),
        (
            "kepler",
            "eom",
            "r^2*r'' - r^3*phi'^2 + k/m = 0; r*phi'' + 2*r'*phi' = 0".to_string(),
        ),
        (
            "kepler",
            "radial",
            "r^2*r'' - r^3*phi'^2 + k/m = 0".to_string(),
        ),
        ("kepler", "radial", format!("r*({kr}) = 0")),
        ("kepler", "radial", "r'' = r*phi'^2 - k/(m*r^2)".to_string()),
        ("kepler", "angular", "r*phi'' + 2*r'*phi' = 0".to_string()),
        ("kepler", "angular", "phi'' + 2*r'*phi'/r = 0".to_string()),
        ("kepler", "angular", "1/r*d/dt(r^2*phi') = 0".to_string()),
        // The cone: α = π (where sin α = 0) is outside what the physics defines.
        (
            "cone",
            "radial",
            "r'' = r*phi'^2*sin(alpha)^2 - g*sin(alpha)*cos(alpha)".to_string(),
        ),
        (
            "cone",
            "radial",
            "r''/sin(alpha)^2 - r*phi'^2 + g*cot(alpha) = 0".to_string(),
        ),
        (
            "cone",
            "radial",
            "m*r'' - m*r*phi'^2*sin(alpha)^2 + m*g*sin(alpha)*cos(alpha) = 0".to_string(),
        ),
    ];
    let mut wrong = Vec::new();
    for (problem, part, answer) in &cases {
        let v = verdict(&b, problem, part, answer);
        if v.status != Status::Correct {
            wrong.push(format!("{problem}/{part}: {answer}\n    {:?}", v.diagnoses));
        }
    }
    assert!(wrong.is_empty(), "rejected:\n{}", wrong.join("\n"));
}

#[test]
fn factors_vanishing_where_the_physics_is_regular_are_refused() {
    let b = bank();
    let th = SPHERICAL_THETA;
    let kr = KEPLER_RADIAL;
    let phi = "d/dt(sin(theta)^2*phi')";
    let cases: Vec<(&str, &str, String)> = vec![
        // At θ = 0 the θ direction is regular although M loses rank in φ: per direction.
        (
            "spherical-pendulum",
            "eom",
            format!("sin(theta)*({th}) = 0; {phi} = 0"),
        ),
        (
            "spherical-pendulum",
            "eom",
            format!("cos(theta)*({th}) = 0; {phi} = 0"),
        ),
        (
            "spherical-pendulum",
            "eom",
            format!("theta'*({th}) = 0; {phi} = 0"),
        ),
        (
            "spherical-pendulum",
            "eom",
            format!("{th} = 0; phi'*{phi} = 0"),
        ),
        (
            "spherical-pendulum",
            "eom",
            format!("{th} = 0; (phi''*sin(theta) + 2*theta'*phi'*cos(theta))*cos(theta) = 0"),
        ),
        ("kepler", "radial", format!("r'*({kr}) = 0")),
        ("kepler", "radial", format!("(m*r^3*phi'^2 - k)*({kr}) = 0")),
        ("kepler", "radial", format!("phi'*({kr}) = 0")),
        (
            "kepler",
            "eom",
            format!("{kr} = 0; r'*(r*phi'' + 2*r'*phi') = 0"),
        ),
        (
            "kepler",
            "angular",
            "phi'*(r*phi'' + 2*r'*phi') = 0".to_string(),
        ),
        (
            "kepler",
            "angular",
            "(r*phi'' + 2*r'*phi')/phi' = 0".to_string(),
        ),
        // α = π/2 is outside the sampled [0.3, 1.2] but inside the domain, and regular.
        (
            "cone",
            "radial",
            "cos(alpha)*(r'' - r*phi'^2*sin(alpha)^2 + g*sin(alpha)*cos(alpha)) = 0".to_string(),
        ),
    ];
    let mut missed = Vec::new();
    for (problem, part, answer) in &cases {
        let v = verdict(&b, problem, part, answer);
        let named = v.diagnoses.iter().any(|d| d.code == Code::VanishingFactor);
        if v.status != Status::Incorrect || !named {
            missed.push(format!(
                "{problem}/{part}: {answer}\n    {:?} {:?}",
                v.status, v.diagnoses
            ));
        }
    }
    assert!(
        missed.is_empty(),
        "not refused as vanishing-factor:\n{}",
        missed.join("\n")
    );
}

/// The message names where the physics is regular, never a place where it is singular.
#[test]
fn the_place_named_is_regular() {
    let b = bank();
    let v = verdict(
        &b,
        "spherical-pendulum",
        "eom",
        &format!("sin(theta)*({SPHERICAL_THETA}) = 0; d/dt(sin(theta)^2*phi') = 0"),
    );
    let text: String = v.diagnoses.iter().map(|d| d.message.as_str()).collect();
    assert!(text.contains("sin(θ)") && text.contains("θ = 0"), "{text}");
}

/// `domain = "positive"` keeps every sample at r > 0: √(r²) is r there. Without the domain
/// the same answer is wrong (r < 0 is sampled), so the domain is what decides.
#[test]
fn a_declared_domain_is_never_left() {
    let b = bank();
    let answer = "m*r'' - m*sqrt(r^2)*phi'^2 + k/r^2 = 0";
    assert_eq!(
        verdict(&b, "kepler", "radial", answer).status,
        Status::Correct
    );
    let text = std::fs::read_to_string("tests/singular/kepler.toml").expect("reads");
    let open = text.replace(", domain = \"positive\"", "");
    assert_ne!(open, text);
    let p = lagrange::bank::load_str("kepler.toml", &open).expect("loads");
    let v = Checker::new(&p).check("radial", answer).expect("checks");
    assert_eq!(v.status, Status::Incorrect, "{v:?}");
}

/// A spring's length from a body's position is √(r²): with r declared positive it is r, and
/// the file's own Lagrangian, equations and h verify (they did not: `k·l₀·abs(r)`).
#[test]
fn a_spring_on_a_positive_coordinate_has_no_abs() {
    let b = bank();
    let p = b
        .problems
        .iter()
        .find(|p| p.id == "elastic-pendulum")
        .expect("fixture");
    let findings: Vec<String> = verify(p).iter().map(|f| f.to_string()).collect();
    assert!(findings.is_empty(), "{findings:?}");
    let text = std::fs::read_to_string("tests/singular/elastic-pendulum.toml").expect("reads");
    let open = text.replace(", domain = \"positive\"", "");
    let p = lagrange::bank::load_str("elastic.toml", &open).expect("loads");
    assert!(
        !verify(&p).is_empty(),
        "without the domain the length is |r|"
    );
}

/// A domain word is read whatever its ASCII case.
#[test]
fn a_domain_word_is_read_in_any_case() {
    let text = std::fs::read_to_string("tests/singular/kepler.toml").expect("reads");
    for word in ["Positive", "POSITIVE", " positive "] {
        let file = text.replace("domain = \"positive\"", &format!("domain = \"{word}\""));
        assert_ne!(file, text);
        let p = lagrange::bank::load_str("kepler.toml", &file)
            .unwrap_or_else(|e| panic!("{word}: {e}"));
        assert!(verify(&p).is_empty(), "{word}");
    }
}

#[test]
fn a_bad_domain_is_a_finding() {
    let text = std::fs::read_to_string("tests/singular/kepler.toml").expect("reads");
    for (domain, why) in [
        ("\"sideways\"", "write \"positive\""),
        // The word is quoted as written; only ASCII capitals are read as small letters
        // (`POSİTİVE`'s dotted İ lowercases to i and a combining dot, not to `i`).
        ("\" Sideways \"", "is `Sideways`; write"),
        ("\"POSİTİVE\"", "is `POSİTİVE`; write"),
        ("[\"1\"]", "an interval is [low, high]"),
        ("[\"2\", \"1\"]", "is empty"),
        ("[\"0\", \"1\"]", "outside its domain"),
        ("[\"0\", \"q\"]", "an expression of the parameters"),
        ("\"negative\"", "outside its domain"),
        ("[\"0\", \"k/m\"]", "of dimension"),
    ] {
        let file = text.replace("domain = \"positive\"", &format!("domain = {domain}"));
        let err = lagrange::bank::load_str("kepler.toml", &file)
            .err()
            .unwrap_or_else(|| panic!("{domain} loads"));
        let shown = err.to_string();
        assert!(
            shown.contains("bad-domain") && shown.contains(why),
            "{domain}: {shown}"
        );
        // Reported at the coordinate's own line, not the id's.
        let line = file
            .lines()
            .position(|l| l.contains("name = \"r\""))
            .expect("r")
            + 1;
        assert!(
            shown.contains(&format!("kepler.toml:{line}:")),
            "{domain}: {shown}"
        );
    }
}

/// One rule for a periodic coordinate with a range (issue 19 §5): its range says where
/// states are sampled; its equilibria are searched over the whole period. A pendulum sampled
/// on [0.5, 2.5] still has its equilibria at 0 and π, and stating only one is missing one.
#[test]
fn a_periodic_range_does_not_narrow_the_equilibrium_search() {
    let text = r#"
id = "pendulum-ranged"
title = "Pendulum sampled on part of its circle"
coordinates = [{ name = "theta", periodic = true, range = [0.5, 2.5] }]
lagrangian = "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)"
[parameters]
m = { dimension = "M", range = [0.5, 2.0] }
l = { dimension = "L", range = [0.5, 2.0] }
g = { dimension = "L T^-2", range = [5.0, 15.0] }
[[parts]]
id = "equilibria"
kind = "equilibria"
prompt = "Where can the bob rest?"
answer = ["theta = 0", "theta = pi"]
stability = ["stable", "unstable"]
"#;
    let p = lagrange::bank::load_str("ranged.toml", text).expect("loads");
    let findings: Vec<String> = verify(&p).iter().map(|f| f.to_string()).collect();
    assert!(findings.is_empty(), "{findings:?}");
    let one = text.replace(
        "answer = [\"theta = 0\", \"theta = pi\"]\nstability = [\"stable\", \"unstable\"]",
        "answer = [\"theta = pi\"]\nstability = [\"unstable\"]",
    );
    assert_ne!(one, text);
    let p = lagrange::bank::load_str("ranged.toml", &one).expect("loads");
    let findings: Vec<String> = verify(&p).iter().map(|f| f.to_string()).collect();
    assert!(
        findings.iter().any(|f| f.contains("missing")),
        "{findings:?}"
    );
}

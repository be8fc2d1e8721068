//! Follow-through (issue 10, item 5): an answer that is wrong for the reference but exactly
//! what follows from the student's own earlier wrong answer stays incorrect and gets
//! `follows-from-earlier`, naming the part where the real mistake is.

use lagrange::bank::embedded;
use lagrange::check::{Code, Status, Verdict};
use lagrange::problem::{PartKind, Problem};
use lagrange::tutor::follow::{Earlier, check_with_history, follow_through};

/// Per bank problem with a `lagrangian` and an `eom` part: a wrong L (a flipped potential
/// sign, or for the bead on a wire, where V = 0, the centrifugal term's, and for the cart-pendulum,
/// whose x equation a flipped V leaves right, the cross term's), the EOM that follows
/// from it, and an unrelated wrong EOM.
const WRONG_L: &[(&str, &str, &str, &str)] = &[
    (
        "atwood",
        "1/2*(m1+m2)*x'^2 - (m1-m2)*g*x",
        "(m1+m2)*x'' = -(m1-m2)*g",
        "(m1+m2)*x'' = (m1+m2)*g",
    ),
    (
        "bead-parabola",
        "1/2*m*(1 + 4*a^2*r^2)*r'^2 + 1/2*m*omega^2*r^2 + m*g*a*r^2",
        "m*(1 + 4*a^2*r^2)*r'' + 4*m*a^2*r*r'^2 - m*omega^2*r - 2*m*g*a*r = 0",
        "m*(1 + 4*a^2*r^2)*r'' - m*omega^2*r + 2*m*g*a*r = 0",
    ),
    (
        "bead-wire",
        "1/2*m*(r'^2 - omega^2*r^2)",
        "r'' = -omega^2*r",
        "r'' = 2*omega^2*r",
    ),
    (
        "cart-pendulum",
        "1/2*(M+m)*x'^2 - m*l*x'*theta'*cos(theta) + 1/2*m*l^2*theta'^2 + m*g*l*cos(theta)",
        "(M+m)*x'' - m*l*theta''*cos(theta) + m*l*theta'^2*sin(theta) = 0; l*theta'' - x''*cos(theta) + g*sin(theta) = 0",
        "(M+m)*x'' = 0; l*theta'' + g*sin(theta) = 0",
    ),
    (
        "central-force",
        "1/2*m*(r'^2 + r^2*phi'^2) - k/r",
        "m*r'' - m*r*phi'^2 - k/r^2 = 0",
        "m*r'' + 2*k/r^2 = 0",
    ),
    (
        "double-pendulum",
        "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + m2*l1*l2*theta1'*theta2'*cos(theta1-theta2) - (m1+m2)*g*l1*cos(theta1) - m2*g*l2*cos(theta2)",
        "(m1+m2)*l1*theta1'' + m2*l2*theta2''*cos(theta1-theta2) + m2*l2*theta2'^2*sin(theta1-theta2) - (m1+m2)*g*sin(theta1) = 0; \
         l2*theta2'' + l1*theta1''*cos(theta1-theta2) - l1*theta1'^2*sin(theta1-theta2) - g*sin(theta2) = 0",
        "(m1+m2)*l1*theta1'' + (m1+m2)*g*sin(theta1) = 0; l2*theta2'' + g*sin(theta2) = 0",
    ),
    (
        "simple-pendulum",
        "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)",
        "m*l^2*theta'' - m*g*l*sin(theta) = 0",
        "m*l^2*theta'' + 2*m*g*l*sin(theta) = 0",
    ),
    (
        "spring-incline",
        "1/2*m*x'^2 + 1/2*k*x^2 - m*g*x*sin(alpha)",
        "m*x'' = k*x - m*g*sin(alpha)",
        "m*x'' = -k*x",
    ),
];

fn problem(id: &str) -> Problem {
    embedded::problem(id).unwrap_or_else(|| panic!("no bank problem `{id}`"))
}

fn verdict(p: &Problem, part: &str, input: &str, earlier: &[Earlier]) -> Verdict {
    let part = p
        .part(part)
        .unwrap_or_else(|| panic!("{}: no part {part}", p.id));
    check_with_history(p, part, input, earlier).unwrap_or_else(|e| panic!("{}: {e}", p.id))
}

fn follows(v: &Verdict) -> bool {
    v.diagnoses
        .iter()
        .any(|d| d.code == Code::FollowsFromEarlier)
}

/// Asserts `input` to `part` stays incorrect and gets `follows-from-earlier` naming `place`.
fn assert_follows(p: &Problem, part: &str, input: &str, earlier: &[Earlier], place: &str) {
    let v = verdict(p, part, input, earlier);
    assert_eq!(v.status, Status::Incorrect, "{}/{part}: {v:?}", p.id);
    assert_eq!(v.score, 0.0, "{}/{part}", p.id);
    let d = v
        .diagnoses
        .iter()
        .find(|d| d.code == Code::FollowsFromEarlier)
        .unwrap_or_else(|| panic!("{}/{part}: no follows-from-earlier in {v:?}", p.id));
    assert!(
        d.message.contains(&format!("the mistake is in {place}")),
        "{}/{part}: {}",
        p.id,
        d.message
    );
}

#[test]
fn the_table_covers_every_bank_problem_with_a_lagrangian_and_an_eom() {
    let has = |p: &Problem, kind: PartKind| p.parts.iter().any(|x| x.kind == kind);
    let mut want: Vec<String> = embedded::bank()
        .problems
        .iter()
        .filter(|p| has(p, PartKind::Lagrangian) && p.part("eom").is_some())
        .map(|p| p.id.clone())
        .collect();
    want.sort();
    let got: Vec<String> = WRONG_L.iter().map(|r| r.0.to_string()).collect();
    assert_eq!(got, want);
}

#[test]
fn the_eom_of_a_wrong_lagrangian_follows_from_it() {
    for &(id, wrong_l, its_eom, _) in WRONG_L {
        let p = problem(id);
        // The wrong L is wrong on its own.
        let l = verdict(&p, "lagrangian", wrong_l, &[]);
        assert_eq!(l.status, Status::Incorrect, "{id}: {l:?}");
        let earlier = [Earlier::new("lagrangian", wrong_l)];
        assert_follows(&p, "eom", its_eom, &earlier, "L (part `lagrangian`)");
        // Without the history it is just wrong.
        assert!(!follows(&verdict(&p, "eom", its_eom, &[])), "{id}");
    }
}

#[test]
fn the_right_eom_after_a_wrong_lagrangian_is_simply_correct() {
    for &(id, wrong_l, _, _) in WRONG_L {
        let p = problem(id);
        let part = p.part("eom").unwrap();
        let right = part.reference_text(p.system.n());
        let earlier = [Earlier::new("lagrangian", wrong_l)];
        let v = verdict(&p, "eom", &right, &earlier);
        assert_eq!(v.status, Status::Correct, "{id}: {v:?}");
        assert!(!follows(&v), "{id}");
        assert!(follow_through(&p, part, &right, &earlier).is_none(), "{id}");
    }
}

#[test]
fn an_unrelated_wrong_eom_gets_no_follow_through() {
    for &(id, wrong_l, _, unrelated) in WRONG_L {
        let p = problem(id);
        let v = verdict(&p, "eom", unrelated, &[Earlier::new("lagrangian", wrong_l)]);
        assert_eq!(v.status, Status::Incorrect, "{id}: {v:?}");
        assert!(!follows(&v), "{id}: {v:?}");
    }
}

#[test]
fn the_message_carries_the_earlier_diagnosis() {
    let p = problem("simple-pendulum");
    let (_, wrong_l, its_eom, _) = WRONG_L[6];
    let l = verdict(&p, "lagrangian", wrong_l, &[]);
    let first = &l.diagnoses[0].message;
    let v = verdict(&p, "eom", its_eom, &[Earlier::new("lagrangian", wrong_l)]);
    let d = v
        .diagnoses
        .iter()
        .find(|d| d.code == Code::FollowsFromEarlier)
        .unwrap();
    assert!(
        d.message.starts_with(
            "your equation of motion follows correctly from your Lagrangian; the mistake is in L"
        ),
        "{}",
        d.message
    );
    assert!(
        d.message.ends_with(first.as_str()),
        "{} / {first}",
        d.message
    );
    // Most specific first: the follow-through leads the sign error against the reference.
    assert_eq!(v.diagnoses[0].code, Code::FollowsFromEarlier);
}

#[test]
fn kinetic_and_potential_carry_into_the_lagrangian_and_the_eom() {
    let p = problem("simple-pendulum");
    // T without the ½: L = m·l²·θ̇² + m·g·l·cos θ, so 2·m·l²·θ̈ + m·g·l·sin θ = 0.
    let t = [Earlier::new("kinetic", "m*l^2*theta'^2")];
    assert_follows(
        &p,
        "lagrangian",
        "m*l^2*theta'^2 + m*g*l*cos(theta)",
        &t,
        "T",
    );
    assert_follows(&p, "eom", "2*m*l^2*theta'' + m*g*l*sin(theta) = 0", &t, "T");
    // The right L after a wrong T is correct.
    let right = verdict(
        &p,
        "lagrangian",
        "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)",
        &t,
    );
    assert_eq!(right.status, Status::Correct);
    assert!(!follows(&right));
    // V with the wrong sign: L = ½·m·l²·θ̇² − m·g·l·cos θ.
    let v = [Earlier::new("potential", "m*g*l*cos(theta)")];
    assert_follows(
        &p,
        "lagrangian",
        "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)",
        &v,
        "V",
    );
    // An L unrelated to either is not blamed on them.
    let other = verdict(&p, "lagrangian", "1/2*m*l^2*theta'^2", &t);
    assert!(!follows(&other), "{other:?}");
}

#[test]
fn a_wrong_lagrangian_carries_into_the_equilibria() {
    // (problem, wrong L with other equilibria than the true ones, those equilibria)
    let cases = [
        (
            "simple-pendulum",
            "1/2*m*l^2*theta'^2 + m*g*l*sin(theta)",
            "theta = pi/2, theta = -pi/2",
        ),
        (
            "spring-incline",
            "1/2*m*x'^2 - 1/2*k*x^2 - m*g*x*sin(alpha)",
            "x = -m*g*sin(alpha)/k",
        ),
        ("bead-wire", "1/2*m*(r'^2 + omega^2*(r - a)^2)", "r = a"),
    ];
    for (id, wrong_l, equilibria) in cases {
        let p = problem(id);
        let Some(_) = p.part("equilibria") else {
            panic!("{id} has no equilibria part")
        };
        let earlier = [Earlier::new("lagrangian", wrong_l)];
        if id == "bead-wire" {
            // `a` is not a parameter of the bead on a wire: the L is unreadable, and ignored.
            assert!(!follows(&verdict(&p, "equilibria", equilibria, &earlier)));
            continue;
        }
        assert_follows(&p, "equilibria", equilibria, &earlier, "L");
        // The true equilibria after that L are correct, with no follow-through.
        let right = p.part("equilibria").unwrap().reference_text(p.system.n());
        let v = verdict(&p, "equilibria", &right, &earlier);
        assert_eq!(v.status, Status::Correct, "{id}: {v:?}");
        assert!(!follows(&v));
        // Half of the wrong L's equilibria do not follow from it.
        if let Some((first, _)) = equilibria.split_once(',') {
            assert!(
                !follows(&verdict(&p, "equilibria", first, &earlier)),
                "{id}"
            );
        }
    }
}

#[test]
fn a_wrong_eom_carries_into_the_equilibria() {
    let p = problem("simple-pendulum");
    let earlier = [Earlier::new("eom", "m*l^2*theta'' + m*g*l*cos(theta) = 0")];
    assert_follows(
        &p,
        "equilibria",
        "pi/2, -pi/2",
        &earlier,
        "your equation of motion",
    );
    assert!(!follows(&verdict(&p, "equilibria", "pi/3", &earlier)));
}

#[test]
fn a_wrong_lagrangian_carries_into_the_frequencies() {
    // Twice the gravity term: ω = √(2g/l) about θ = 0.
    let p = problem("simple-pendulum");
    let earlier = [Earlier::new(
        "lagrangian",
        "1/2*m*l^2*theta'^2 + 2*m*g*l*cos(theta)",
    )];
    assert_follows(&p, "frequencies", "sqrt(2*g/l)", &earlier, "L");
    let right = verdict(&p, "frequencies", "sqrt(g/l)", &earlier);
    assert_eq!(right.status, Status::Correct);
    assert!(!follows(&right));
    assert!(!follows(&verdict(
        &p,
        "frequencies",
        "sqrt(3*g/l)",
        &earlier
    )));
}

#[test]
fn the_most_recent_relevant_earlier_answer_is_blamed() {
    let p = problem("simple-pendulum");
    let earlier = [
        Earlier::new("kinetic", "m*l^2*theta'^2"),
        Earlier::new("lagrangian", "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)"),
        Earlier::new("momentum", "m*l*theta'"),
    ];
    assert_follows(
        &p,
        "eom",
        "m*l^2*theta'' - m*g*l*sin(theta) = 0",
        &earlier,
        "L",
    );
    assert_follows(
        &p,
        "eom",
        "2*m*l^2*theta'' + m*g*l*sin(theta) = 0",
        &earlier,
        "T",
    );
}

#[test]
fn only_the_latest_answer_to_a_part_counts() {
    let p = problem("simple-pendulum");
    let wrong_l = "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)";
    let its_eom = "m*l^2*theta'' - m*g*l*sin(theta) = 0";
    // L put right since: the old wrong L no longer explains the EOM.
    let fixed = [
        Earlier::new("lagrangian", wrong_l),
        Earlier::new("lagrangian", "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)"),
    ];
    assert!(!follows(&verdict(&p, "eom", its_eom, &fixed)));
    // L got wrong since: the latest answer is the one blamed.
    let broke = [
        Earlier::new("lagrangian", "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)"),
        Earlier::new("lagrangian", wrong_l),
    ];
    assert_follows(&p, "eom", its_eom, &broke, "L");
    // Earlier answers to the same part never explain it.
    let same = [Earlier::new("eom", its_eom)];
    assert!(!follows(&verdict(&p, "eom", its_eom, &same)));
}

#[test]
fn verdict_with_follow_through_snapshot() {
    let mut shown = String::new();
    let cases: [(&str, &str, &str, &str, &str); 4] = [
        (
            "simple-pendulum",
            "lagrangian",
            "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)",
            "eom",
            "m*l^2*theta'' - m*g*l*sin(theta) = 0",
        ),
        (
            "simple-pendulum",
            "kinetic",
            "m*l^2*theta'^2",
            "lagrangian",
            "m*l^2*theta'^2 + m*g*l*cos(theta)",
        ),
        (
            "simple-pendulum",
            "eom",
            "m*l^2*theta'' + m*g*l*cos(theta) = 0",
            "equilibria",
            "pi/2, -pi/2",
        ),
        (
            "double-pendulum",
            "lagrangian",
            WRONG_L[5].1,
            "eom",
            WRONG_L[5].2,
        ),
    ];
    for (id, before, wrong, part, input) in cases {
        let p = problem(id);
        let v = verdict(&p, part, input, &[Earlier::new(before, wrong)]);
        shown.push_str(&format!(
            "{id}/{part} after a wrong {before}: {}\n",
            v.status.name()
        ));
        for d in &v.diagnoses {
            shown.push_str(&format!("  {}: {}\n", d.code, d.message));
        }
    }
    insta::assert_snapshot!("follow_through_verdicts", shown);
}

#[test]
fn a_wrong_eom_carries_into_the_frequencies() {
    // Twice the gravity term: ω = √(2g/l).
    let p = problem("simple-pendulum");
    let earlier = [Earlier::new(
        "eom",
        "m*l^2*theta'' + 2*m*g*l*sin(theta) = 0",
    )];
    assert_follows(
        &p,
        "frequencies",
        "sqrt(2*g/l)",
        &earlier,
        "your equation of motion",
    );
    assert!(!follows(&verdict(
        &p,
        "frequencies",
        "sqrt(3*g/l)",
        &earlier
    )));
    // The double pendulum (equal masses and lengths) with g doubled in both equations: both
    // frequencies grow by √2, but follow-through from equations of several coordinates to
    // frequencies is not attempted (the engine's modes want a symmetric stiffness): no claim.
    let p = problem("double-pendulum");
    let eom = "(m1+m2)*l1*theta1'' + m2*l2*theta2''*cos(theta1-theta2) + m2*l2*theta2'^2*sin(theta1-theta2) + 2*(m1+m2)*g*sin(theta1) = 0; \
               l2*theta2'' + l1*theta1''*cos(theta1-theta2) - l1*theta1'^2*sin(theta1-theta2) + 2*g*sin(theta2) = 0";
    let earlier = [Earlier::new("eom", eom)];
    let doubled = "sqrt(2*(2 - sqrt(2))*g/l), sqrt(2*(2 + sqrt(2))*g/l)";
    let v = verdict(&p, "frequencies", doubled, &earlier);
    assert_eq!(v.status, Status::Incorrect);
    assert!(!follows(&v), "{v:?}");
}

#[test]
fn an_equation_without_accelerations_explains_equilibria_only() {
    // The bead on the parabola's equilibrium condition, with the wrong sign of g: its rest
    // points are the equilibria; it says nothing about frequencies.
    let p = problem("bead-parabola");
    let earlier = [Earlier::new(
        "equilibrium-condition",
        "r*(2*g*a + omega^2) = 0",
    )];
    let v = verdict(&p, "frequencies", "sqrt(2*g*a + omega^2)", &earlier);
    assert_eq!(v.status, Status::Incorrect);
    assert!(!follows(&v), "{v:?}");
}

#[test]
fn hostile_histories_neither_panic_nor_claim() {
    let p = problem("simple-pendulum");
    let wrong_l = "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)";
    let its_eom = "m*l^2*theta'' - m*g*l*sin(theta) = 0";
    // Many answers to parts that do not exist, and garbage, around the real wrong L.
    let mut earlier: Vec<Earlier> = (0..20_000)
        .map(|i| Earlier::new(format!("no-part-{i}"), "x"))
        .collect();
    earlier.push(Earlier::new("lagrangian", wrong_l));
    for junk in [
        "",
        ";;;",
        "((((",
        "theta'' = ",
        "1/0",
        "{",
        "}",
        "[]",
        "θ̈ = sin(θ",
    ] {
        earlier.push(Earlier::new("kinetic", junk));
        earlier.push(Earlier::new("eom", junk));
        for part in ["lagrangian", "eom", "equilibria", "frequencies"] {
            let v = verdict(&p, part, junk, &earlier);
            assert!(!follows(&v), "{part} `{junk}`: {v:?}");
        }
    }
    // The wrong L is still the latest answer to `lagrangian`.
    assert_follows(&p, "eom", its_eom, &earlier, "L");
}

#[test]
fn a_wrong_equilibrium_condition_carries_into_the_equilibria() {
    // The bead on the parabola: a condition with a spurious root r = g/ω².
    let p = problem("bead-parabola");
    let earlier = [Earlier::new(
        "equilibrium-condition",
        "(r - g/omega^2)*(2*g*a - omega^2) = 0",
    )];
    assert_follows(
        &p,
        "equilibria",
        "r = g/omega^2",
        &earlier,
        "your equation (part `equilibrium-condition`)",
    );
    // The true equilibrium is just correct (with the stability the part asks for).
    let v = verdict(&p, "equilibria", "r = 0 (stable)", &earlier);
    assert_eq!(v.status, Status::Correct);
    assert!(!follows(&v));
}

#[test]
fn a_wrong_t_or_l_carries_into_the_momentum_and_the_energy_function() {
    let p = problem("simple-pendulum");
    // T without the ½: p = 2·m·l²·θ̇, h = m·l²·θ̇² − m·g·l·cos θ.
    let t = [Earlier::new("kinetic", "m*l^2*theta'^2")];
    assert_follows(&p, "momentum", "2*m*l^2*theta'", &t, "T");
    assert_follows(
        &p,
        "energy-function",
        "m*l^2*theta'^2 - m*g*l*cos(theta)",
        &t,
        "T",
    );
    // The right momentum p = m·l²·θ̇ after it is correct.
    let v = verdict(&p, "momentum", "m*l^2*theta'", &t);
    assert_eq!(v.status, Status::Correct);
    assert!(!follows(&v));
    // A flipped V leaves p alone but flips the potential part of h.
    let l = [Earlier::new("lagrangian", WRONG_L[6].1)];
    assert_follows(
        &p,
        "energy-function",
        "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)",
        &l,
        "L",
    );
    assert!(!follows(&verdict(&p, "momentum", "2*m*l^2*theta'", &l)));
}

#[test]
fn a_wrong_lagrangian_carries_into_substituted_frequencies() {
    // The double pendulum's frequencies part sets m1 = m2 = m, l1 = l2 = l; an L with g
    // doubled gives frequencies √2 times the true √((2 ∓ √2)·g/l).
    let p = problem("double-pendulum");
    let l = "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + m2*l1*l2*theta1'*theta2'*cos(theta1-theta2) + 2*(m1+m2)*g*l1*cos(theta1) + 2*m2*g*l2*cos(theta2)";
    let earlier = [Earlier::new("lagrangian", l)];
    assert_follows(
        &p,
        "frequencies",
        "sqrt(2*(2 - sqrt(2))*g/l), sqrt(2*(2 + sqrt(2))*g/l)",
        &earlier,
        "L",
    );
    assert_follows(
        &p,
        "omega-squared",
        "2*(2 - sqrt(2))*g/l, 2*(2 + sqrt(2))*g/l",
        &earlier,
        "L",
    );
    let v = verdict(&p, "frequencies", "sqrt(2*(2 - sqrt(2))*g/l)", &earlier);
    assert!(
        !follows(&v),
        "one of two frequencies does not follow: {v:?}"
    );
}

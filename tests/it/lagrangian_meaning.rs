//! Issue 19 §2: the Lagrangian and the energy function mean what the part asks. L = T − V is
//! defined up to an added constant and a total time derivative, not up to a factor (V − T and
//! 2L give the same motion, but other momenta and another h); h is defined up to a constant,
//! as V and L are, and "the frame moves" is said only where it does. Follow-through (§3)
//! reads an earlier `L = …` or `T = …` as the quantity, and accepts the momenta of an L
//! accepted with a total derivative added.

use lagrange::bank::{embedded, load_str};
use lagrange::check::{Checker, Code, Status, Verdict};
use lagrange::problem::{Part, Problem};
use lagrange::tutor::follow::{Earlier, check_with_history};

fn bank(id: &str) -> Problem {
    embedded::problem(id).unwrap_or_else(|| panic!("no problem {id}"))
}

fn verdict(p: &Problem, part: &str, answer: &str) -> Verdict {
    Checker::new(p)
        .check(part, answer)
        .unwrap_or_else(|e| panic!("{}/{part}: {e}", p.id))
}

use crate::helpers::verdict_table as table;

const PENDULUM_L: &str = "(1/2*m*l^2*theta'^2 + m*g*l*cos(theta))";

#[test]
fn a_lagrangian_is_t_minus_v_up_to_a_constant_and_a_total_derivative() {
    use Status::*;
    let twice = format!("2*{PENDULUM_L}");
    let half = format!("{PENDULUM_L}/2");
    let gauge = format!("{PENDULUM_L} + m*sqrt(g*l^3)*cos(theta)*theta'");
    // d/dt (m g l θ t) = m g l (θ' t + θ): F depends on t too.
    let gauge_t = format!("{PENDULUM_L} + m*g*l*(theta'*t + theta)");
    let twice_gauge = format!("2*{PENDULUM_L} + m*sqrt(g*l^3)*cos(theta)*theta'");
    let rows: Vec<(&str, &str, &str, Status, Option<Code>)> = vec![
        ("simple-pendulum", "lagrangian", PENDULUM_L, Correct, None),
        (
            "simple-pendulum",
            "lagrangian",
            "-m*g*l*cos(theta) - 1/2*m*l^2*theta'^2",
            Incorrect,
            Some(Code::SignError),
        ),
        (
            "simple-pendulum",
            "lagrangian",
            "m*l^2*theta'^2 + 2*m*g*l*cos(theta)",
            Incorrect,
            Some(Code::ConstantFactor),
        ),
        (
            "simple-pendulum",
            "lagrangian",
            &twice,
            Incorrect,
            Some(Code::ConstantFactor),
        ),
        (
            "simple-pendulum",
            "lagrangian",
            &half,
            Incorrect,
            Some(Code::ConstantFactor),
        ),
        (
            "simple-pendulum",
            "lagrangian",
            &twice_gauge,
            Incorrect,
            Some(Code::ConstantFactor),
        ),
        (
            "simple-pendulum",
            "lagrangian",
            "1/2*m*l^2*theta'^2 + m*g*l*cos(theta) + 7*m*g*l",
            Correct,
            Some(Code::UpToConstant),
        ),
        (
            "simple-pendulum",
            "lagrangian",
            &gauge,
            Correct,
            Some(Code::TotalDerivative),
        ),
        (
            "simple-pendulum",
            "lagrangian",
            &gauge_t,
            Correct,
            Some(Code::TotalDerivative),
        ),
        (
            "double-pendulum",
            "lagrangian",
            "-(1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + m2*l1*l2*theta1'*theta2'*cos(theta1-theta2) + (m1+m2)*g*l1*cos(theta1) + m2*g*l2*cos(theta2))",
            Incorrect,
            Some(Code::SignError),
        ),
        (
            "central-force",
            "lagrangian",
            "m*(r'^2 + r^2*phi'^2) + 2*k/r",
            Incorrect,
            Some(Code::ConstantFactor),
        ),
        (
            "bead-parabola",
            "lagrangian",
            "-(1/2*m*(1 + 4*a^2*r^2)*r'^2 + 1/2*m*omega^2*r^2 - m*g*a*r^2)",
            Incorrect,
            Some(Code::SignError),
        ),
    ];
    table(&rows);
    // Not a total derivative: a velocity term that changes the motion stays wrong.
    let other = format!("{PENDULUM_L} + m*sqrt(g*l^3)*theta*theta'^2");
    let v = verdict(&bank("simple-pendulum"), "lagrangian", &other);
    assert_eq!(v.status, Status::Incorrect, "{v:#?}");
}

#[test]
fn a_scaled_lagrangian_says_it_gives_the_same_motion_but_other_momenta() {
    let p = bank("simple-pendulum");
    let v = verdict(&p, "lagrangian", "-m*g*l*cos(theta) - 1/2*m*l^2*theta'^2");
    assert_eq!(v.score, 0.0);
    let m = &v.diagnoses[0].message;
    assert!(m.contains("same equations of motion"), "{m}");
    assert!(m.contains("not the Lagrangian asked for"), "{m}");
    assert!(
        m.contains("momenta") && m.contains("energy function h"),
        "{m}"
    );
    let v = verdict(&p, "lagrangian", "m*l^2*theta'^2 + 2*m*g*l*cos(theta)");
    assert!(
        v.diagnoses[0].message.contains("your L is 2 times T − V"),
        "{v:?}"
    );
}

/// The simple pendulum with `accept = "same-motion"` on its Lagrangian part.
fn same_motion_pendulum() -> Problem {
    let text = embedded::FILES
        .iter()
        .find(|(n, _)| *n == "simple-pendulum.toml")
        .map(|(_, t)| *t)
        .expect("the simple pendulum");
    let marked = text.replacen(
        "kind = \"lagrangian\"",
        "kind = \"lagrangian\"\naccept = \"same-motion\"",
        1,
    );
    assert_ne!(marked, text);
    load_str("same-motion.toml", &marked).expect("loads")
}

#[test]
fn a_part_can_accept_any_lagrangian_with_the_right_motion() {
    let p = same_motion_pendulum();
    assert!(lagrange::bank::verify::verify(&p).is_empty());
    for (answer, code) in [
        (
            "m*l^2*theta'^2 + 2*m*g*l*cos(theta)",
            Code::EquivalentLagrangian,
        ),
        (
            "-m*g*l*cos(theta) - 1/2*m*l^2*theta'^2",
            Code::EquivalentLagrangian,
        ),
        (
            "1/2*m*l^2*theta'^2 + m*g*l*cos(theta) + m*sqrt(g*l^3)*cos(theta)*theta'",
            Code::TotalDerivative,
        ),
    ] {
        let v = verdict(&p, "lagrangian", answer);
        assert_eq!(v.status, Status::Correct, "{answer}: {v:?}");
        assert_eq!(v.diagnoses[0].code, code, "{answer}");
    }
    // The motion must still be right.
    let v = verdict(&p, "lagrangian", "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)");
    assert_eq!(v.status, Status::Incorrect);
}

#[test]
fn accept_same_motion_is_refused_off_a_lagrangian_part() {
    let text = embedded::FILES
        .iter()
        .find(|(n, _)| *n == "simple-pendulum.toml")
        .map(|(_, t)| *t)
        .expect("the simple pendulum");
    let wrong_part = text.replacen("id = \"eom\"", "id = \"eom\"\naccept = \"same-motion\"", 1);
    let err = load_str("bad.toml", &wrong_part).expect_err("refused");
    assert_eq!(err.code, "bad-accept");
    let misspelt = text.replacen(
        "kind = \"lagrangian\"",
        "kind = \"lagrangian\"\naccept = \"any\"",
        1,
    );
    assert_eq!(
        load_str("bad.toml", &misspelt).unwrap_err().code,
        "bad-accept"
    );
}

#[test]
fn h_is_defined_up_to_a_constant() {
    use Status::*;
    let c = Some(Code::UpToConstant);
    table(&[
        (
            "simple-pendulum",
            "energy-function",
            "1/2*m*l^2*theta'^2 + m*g*l*(1 - cos(theta))",
            Correct,
            c,
        ),
        (
            "simple-pendulum",
            "energy-function",
            "½ m l² θ̇² − m g l cos θ",
            Correct,
            None,
        ),
        (
            "double-pendulum",
            "energy-function",
            "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + m2*l1*l2*theta1'*theta2'*cos(theta1-theta2) + (m1+m2)*g*l1*(1-cos(theta1)) + m2*g*l2*(1-cos(theta2))",
            Correct,
            c,
        ),
        (
            "spring-incline",
            "energy-function",
            "1/2*m*x'^2 + 1/2*k*x^2 - m*g*x*sin(alpha) + m^2*g^2/k",
            Correct,
            c,
        ),
        (
            "rotating-hoop",
            "energy-function",
            "1/2*m*R^2*theta'^2 - 1/2*m*R^2*omega^2*sin(theta)^2 + m*g*R*(1 - cos(theta))",
            Correct,
            c,
        ),
        // Both directions: T + V is still wrong where the frame moves, and so is a term that
        // is not a constant.
        (
            "rotating-hoop",
            "energy-function",
            "1/2*m*R^2*theta'^2 + 1/2*m*R^2*omega^2*sin(theta)^2 + m*g*R*(1 - cos(theta))",
            Incorrect,
            Some(Code::HVsE),
        ),
        (
            "bead-wire",
            "energy-function",
            "1/2*m*r'^2 + 1/2*m*omega^2*r^2 + m*omega",
            Incorrect,
            Some(Code::Dimension),
        ),
    ]);
    let v = verdict(
        &bank("simple-pendulum"),
        "energy-function",
        "1/2*m*l^2*theta'^2 + m*g*l*(1 - cos(theta)) + m*g*l*theta",
    );
    assert_eq!(v.status, Status::Incorrect);
}

#[test]
fn the_frame_moves_only_where_it_does() {
    // Wrong h on fixed-frame problems never blames a moving frame.
    for (problem, answer) in [
        (
            "simple-pendulum",
            "1/2*m*l^2*theta'^2 + m*g*l*(1 - cos(theta)) + m*g*l*theta",
        ),
        ("simple-pendulum", "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)"),
        (
            "spring-incline",
            "1/2*m*x'^2 - 1/2*k*x^2 - m*g*x*sin(alpha)",
        ),
        (
            "double-pendulum",
            "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 - (m1+m2)*g*l1*cos(theta1) - m2*g*l2*cos(theta2)",
        ),
    ] {
        let v = verdict(&bank(problem), "energy-function", answer);
        assert_eq!(v.status, Status::Incorrect, "{answer}");
        assert!(
            v.diagnoses.iter().all(|d| !d.message.contains("frame")),
            "{problem} `{answer}`: {:#?}",
            v.diagnoses
        );
    }
    // The rotating hoop's frame does move: T + V is named as such.
    let v = verdict(
        &bank("bead-wire"),
        "energy-function",
        "1/2*m*r'^2 + 1/2*m*omega^2*r^2",
    );
    assert!(
        v.diagnoses.iter().any(|d| d.message.contains("frame")),
        "{:#?}",
        v.diagnoses
    );
}

#[test]
fn follow_through_reads_a_labelled_earlier_answer_as_the_quantity() {
    let p = bank("simple-pendulum");
    let eom = p.part("eom").expect("eom");
    let lagrangian = p.part("lagrangian").expect("lagrangian");
    let wrong_eom = "m*l^2*theta'' - m*g*l*sin(theta) = 0";
    let wrong_l = "L = 1/2*m*l^2*theta'^2 - m*g*l*cos(theta)";
    let doubled_l = "m*l^2*theta'^2 + m*g*l*cos(theta)";
    let cases: [(&str, &str, &Part, &str); 4] = [
        ("lagrangian", wrong_l, eom, wrong_eom),
        (
            "lagrangian",
            "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)",
            eom,
            wrong_eom,
        ),
        ("kinetic", "T = m*l^2*theta'^2", lagrangian, doubled_l),
        ("kinetic", "m*l^2*theta'^2", lagrangian, doubled_l),
    ];
    for (earlier_part, earlier, part, answer) in cases {
        let history = [Earlier::new(earlier_part, earlier)];
        let v = check_with_history(&p, part, answer, &history).expect("checks");
        assert_eq!(v.status, Status::Incorrect, "{earlier} → {answer}");
        assert_eq!(
            v.diagnoses[0].code,
            Code::FollowsFromEarlier,
            "{earlier} → {answer}: {:#?}",
            v.diagnoses
        );
    }
}

#[test]
fn the_momentum_of_an_accepted_gauge_lagrangian_is_accepted() {
    let p = bank("simple-pendulum");
    let momentum = p.part("momentum").expect("momentum");
    let energy = p.part("energy-function").expect("h");
    let gauge = "L = 1/2*m*l^2*theta'^2 + m*g*l*cos(theta) + m*sqrt(g*l^3)*cos(theta)*theta'";
    let history = [Earlier::new("lagrangian", gauge)];
    // p = ∂L/∂θ' of the student's L: right for it.
    let v = check_with_history(
        &p,
        momentum,
        "m*l^2*theta' + m*sqrt(g*l^3)*cos(theta)",
        &history,
    )
    .expect("checks");
    assert_eq!(v.status, Status::Correct, "{v:#?}");
    assert_eq!(v.diagnoses[0].code, Code::TotalDerivative);
    // h of that L is the same h (F has no t): the reference's h is right, and stays so.
    let v = check_with_history(
        &p,
        energy,
        "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)",
        &history,
    )
    .expect("checks");
    assert_eq!(v.status, Status::Correct);
    // A momentum that follows from neither stays wrong.
    let v = check_with_history(
        &p,
        momentum,
        "m*l^2*theta' + 2*m*sqrt(g*l^3)*cos(theta)",
        &history,
    )
    .expect("checks");
    assert_eq!(v.status, Status::Incorrect);
    // Without that L, the shifted momentum is wrong.
    let v = check_with_history(&p, momentum, "m*l^2*theta' + m*sqrt(g*l^3)*cos(theta)", &[])
        .expect("checks");
    assert_eq!(v.status, Status::Incorrect);
    // A scaled L is not accepted, so its momentum is only follows-from-earlier.
    let history = [Earlier::new(
        "lagrangian",
        "m*l^2*theta'^2 + 2*m*g*l*cos(theta)",
    )];
    let v = check_with_history(&p, momentum, "2*m*l^2*theta'", &history).expect("checks");
    assert_eq!(v.status, Status::Incorrect);
    assert_eq!(v.diagnoses[0].code, Code::FollowsFromEarlier);
}

#[test]
fn the_repl_follows_through_from_a_labelled_lagrangian() {
    let mut s = crate::helpers::session();
    let lines = [
        ":open simple-pendulum",
        ":next",
        ":next",
        "L = 1/2*m*l^2*theta'^2 - m*g*l*cos(theta)",
        ":next",
        ":next",
    ];
    for line in lines {
        s.handle(line);
    }
    let r = crate::helpers::one(&mut s, "m*l^2*theta'' - m*g*l*sin(theta) = 0");
    let lagrange::tutor::Response::Verdict(v) = r else {
        panic!("{r:?}")
    };
    assert_eq!(v.verdict.part, "eom");
    assert_eq!(
        v.verdict.diagnoses[0].code,
        Code::FollowsFromEarlier,
        "{v:?}"
    );
}

#[test]
fn grade_follows_through_from_a_labelled_lagrangian() {
    let dir = crate::helpers::scratch("follow");
    let csv = dir.join("class.csv");
    std::fs::write(
        &csv,
        "student,problem,part,answer\n\
         f,simple-pendulum,lagrangian,L = 1/2*m*l^2*theta'^2 - m*g*l*cos(theta)\n\
         f,simple-pendulum,eom,m*l^2*theta'' - m*g*l*sin(theta) = 0\n\
         g,simple-pendulum,lagrangian,L = 1/2*m*l^2*theta'^2 + m*g*l*cos(theta) + m*sqrt(g*l^3)*cos(theta)*theta'\n\
         g,simple-pendulum,momentum,p = m*l^2*theta' + m*sqrt(g*l^3)*cos(theta)\n",
    )
    .unwrap();
    let out = dir.join("out");
    let (code, _, err) = crate::helpers::lagrange(&[
        "grade",
        &csv.display().to_string(),
        "--out",
        &out.display().to_string(),
        "--follow-through",
    ]);
    let results = std::fs::read_to_string(out.join("results.csv")).unwrap_or_default();
    assert_eq!(code, 0, "{err}");
    let rows: Vec<&str> = results.lines().collect();
    assert!(
        rows[2].contains("follows-from-earlier") && rows[2].contains("incorrect"),
        "{results}"
    );
    assert!(
        rows[4].contains("total-derivative") && rows[4].contains(",correct,"),
        "{results}"
    );
}

#[test]
fn on_every_bank_lagrangian_part_a_constant_factor_is_not_the_lagrangian() {
    let mut checked = 0;
    for p in &embedded::bank().problems {
        for part in p
            .parts
            .iter()
            .filter(|x| x.kind == lagrange::PartKind::Lagrangian)
        {
            let reference = &part.answers[0];
            let mut c = Checker::new(p);
            assert_eq!(
                c.check(&part.id, reference).expect("part").status,
                Status::Correct
            );
            for (factor, code) in [
                ("-1", Code::SignError),
                ("2", Code::ConstantFactor),
                ("1/2", Code::ConstantFactor),
                ("3", Code::ConstantFactor),
                ("-2", Code::ConstantFactor),
            ] {
                let v = c
                    .check(&part.id, &format!("{factor}*({reference})"))
                    .expect("part");
                assert_eq!(v.status, Status::Incorrect, "{}: {factor}·L", p.id);
                assert_eq!(v.score, 0.0, "{}: {factor}·L", p.id);
                assert_eq!(v.diagnoses[0].code, code, "{}: {factor}·L {v:#?}", p.id);
            }
            checked += 1;
        }
    }
    assert!(checked >= 8, "{checked}");
}

//! The tutor in the practice session (issue 10, items 4, 5 and 7, library side): for every
//! bank problem the ladder is climbed through the session with each step's reference and the
//! `next` chain walks every step; wrong steps of the simple pendulum get their diagnoses;
//! follow-through from a wrong L to its EOM through the session; the JSON of a short tutor
//! session pinned.

use lagrange::check::{Code, Status};
use lagrange::embedded;
use lagrange::tutor::Response;
use lagrange::tutor::ladder::ladder;
use lagrange::tutor::response::{StepPrompt, StepVerdictReply};

use crate::helpers::{one, session};

fn step(r: &Response) -> &StepPrompt {
    match r {
        Response::Step(p) => p,
        other => panic!("expected a step, got {other:?}"),
    }
}

fn step_verdict(r: &Response) -> &StepVerdictReply {
    match r {
        Response::StepVerdict(v) => v,
        other => panic!("expected a step verdict, got {other:?}"),
    }
}

#[test]
fn every_bank_problem_is_climbed_through_the_session() {
    let mut failures = Vec::new();
    for p in &embedded::bank().problems {
        let steps = ladder(p).unwrap_or_else(|e| panic!("{}: {e}", p.id));
        let mut s = session();
        s.handle(&format!(":open {}", p.id));
        let first = one(&mut s, ":tutor");
        assert_eq!(step(&first).step, steps[0].id, "{}", p.id);
        assert_eq!(step(&first).total, steps.len(), "{}", p.id);
        for (i, st) in steps.iter().enumerate() {
            assert_eq!(s.current_step(), Some(st.id.as_str()), "{}", p.id);
            let answer = st.reference_text(p.system.n());
            let r = one(&mut s, &answer);
            let v = step_verdict(&r);
            assert_eq!((v.step.as_str(), v.number), (st.id.as_str(), i + 1));
            if v.verdict.status != Status::Correct {
                failures.push(format!("{} {} `{answer}`: {:?}", p.id, st.id, v.verdict));
                break;
            }
            let next = v.next.clone().unwrap_or_else(|| panic!("no next: {v:?}"));
            assert_eq!(
                next.map(|n| n.step),
                steps.get(i + 1).map(|n| n.id.clone()),
                "{} after {}",
                p.id,
                st.id
            );
        }
        assert!(
            !s.in_tutor(),
            "{}: the tutor ends after the last step",
            p.id
        );
    }
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

#[test]
fn show_reveals_each_step_and_its_text_is_accepted() {
    let mut s = session();
    s.handle(":open double-pendulum");
    let mut current = step(&one(&mut s, ":tutor")).clone();
    let mut shown = 0;
    loop {
        let revealed = match one(&mut s, ":show") {
            Response::StepSolution(r) => r,
            other => panic!("{other:?}"),
        };
        assert_eq!(revealed.step, current.step);
        assert!(!revealed.unicode.is_empty(), "{revealed:?}");
        shown += 1;
        // The revealed text is the step's accepted answer: check it again from a fresh tutor.
        let mut again = session();
        again.handle(":open double-pendulum");
        again.handle(":tutor");
        for _ in 1..shown {
            again.handle(":show");
        }
        let v = one(&mut again, &revealed.answer);
        assert_eq!(
            step_verdict(&v).verdict.status,
            Status::Correct,
            "{revealed:?}"
        );
        match revealed.next {
            Some(n) => current = n,
            None => break,
        }
    }
    assert_eq!(shown, current.total);
    assert!(!s.in_tutor());
}

#[test]
fn a_wrong_answer_per_step_of_the_simple_pendulum_is_diagnosed() {
    let cases: &[(&str, &str, Code)] = &[
        (
            "position:1",
            "-l*cos(theta), l*sin(theta)",
            Code::Convention,
        ),
        ("speed-squared:1", "l*theta'^2", Code::Dimension),
        ("kinetic", "m*l^2*theta'^2", Code::ConstantFactor),
        ("potential", "m*g*l*cos(theta)", Code::SignError),
        // T + V: told once, without a sign error on V's term beside it (issue 21 §1).
        (
            "lagrangian",
            "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)",
            Code::TPlusV,
        ),
        ("momentum:theta", "m*l*theta'", Code::Dimension),
        ("momentum-rate:theta", "-m*l^2*theta''", Code::SignError),
        (
            "generalized-force:theta",
            "m*g*l*sin(theta)",
            Code::SignError,
        ),
        ("eom:theta", "l*theta'' + g*theta = 0", Code::SmallAngle),
        ("equilibria", "theta = 0", Code::MissingItem),
        ("linearized", "l*theta'' - g*theta = 0", Code::SignError),
        ("characteristic", "sqrt(g/l)", Code::OmegaRoot),
        ("frequencies", "g/l", Code::OmegaSquared),
    ];
    let mut s = session();
    s.handle(":open simple-pendulum");
    s.handle(":tutor");
    let mut seen = 0;
    while let Some(id) = s.current_step().map(str::to_string) {
        if let Some((_, wrong, code)) = cases.iter().find(|c| c.0 == id) {
            let r = one(&mut s, wrong);
            let v = step_verdict(&r);
            assert_eq!(v.verdict.status, Status::Incorrect, "{id}");
            assert_eq!(v.next, None, "no next on a wrong step");
            assert_eq!(v.attempts, 1);
            let codes: Vec<Code> = v.verdict.diagnoses.iter().map(|d| d.code).collect();
            assert!(codes.contains(code), "{id}: {codes:?}");
            assert_eq!(s.current_step(), Some(id.as_str()), "a wrong step stays");
            seen += 1;
        }
        s.handle(":show");
    }
    assert_eq!(seen, cases.len());
}

#[test]
fn back_hint_and_commands_in_the_tutor() {
    let mut s = session();
    s.handle(":open simple-pendulum");
    assert!(matches!(one(&mut s, ":back"), Response::Error(e) if e.code == "not-in-tutor"));
    assert!(matches!(one(&mut s, ":show"), Response::Error(e) if e.code == "not-in-tutor"));
    s.handle(":tutor");
    s.handle(":show");
    // Every step has hints from its physics (issue 21 §1), then points to `:show`.
    let h = one(&mut s, ":hint");
    let Response::Hint(h) = h else {
        panic!("expected a hint, got {h:?}");
    };
    assert_eq!(h.part, "speed-squared:1");
    assert!(h.hint.as_deref().is_some_and(|t| t.contains("chain rule")));
    s.handle(":hint");
    let Response::Hint(last) = one(&mut s, ":hint") else {
        panic!("expected a hint");
    };
    assert!(last.hint.is_none() && last.reveal == ":show");
    assert!(matches!(one(&mut s, ":solution"), Response::Error(e) if e.code == "in-tutor"));
    // `:back` asks the current part again; answers go to the parts.
    let b = one(&mut s, ":back");
    assert!(matches!(&b, Response::Part(p) if p.part == "kinetic"));
    assert!(!s.in_tutor());
    let r = s.handle("1/2*m*l^2*theta'^2");
    assert!(matches!(&r[0], Response::Verdict(v) if v.verdict.status == Status::Correct));
    // `:tutor` resumes where the student left it; `:part` leaves it.
    assert_eq!(step(&one(&mut s, ":tutor")).step, "speed-squared:1");
    assert!(matches!(one(&mut s, ":part eom"), Response::Part(p) if p.part == "eom"));
    assert!(!s.in_tutor());
    // A step's attempts are counted; an unreadable answer is not one.
    s.handle(":tutor");
    let bad = one(&mut s, "l*(theta'");
    assert_eq!(step_verdict(&bad).verdict.status, Status::Invalid);
    assert_eq!(step_verdict(&bad).attempts, 0);
}

#[test]
fn follow_through_in_the_session_from_a_wrong_lagrangian_to_its_eom() {
    let mut s = session();
    s.handle(":open simple-pendulum");
    s.handle(":part lagrangian");
    let l = one(&mut s, "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)");
    assert!(matches!(&l, Response::Verdict(v) if v.verdict.status == Status::Incorrect));
    s.handle(":part eom");
    let r = one(&mut s, "m*l^2*theta'' - m*g*l*sin(theta) = 0");
    let Response::Verdict(v) = &r else {
        panic!("{r:?}")
    };
    assert_eq!(v.verdict.status, Status::Incorrect);
    let d = v
        .verdict
        .diagnoses
        .iter()
        .find(|d| d.code == Code::FollowsFromEarlier)
        .unwrap_or_else(|| panic!("{v:?}"));
    assert!(d.message.contains("part `lagrangian`"), "{}", d.message);
    // Put right, L no longer carries the mistake: the same EOM is simply wrong.
    s.handle(":part lagrangian");
    s.handle("1/2*m*l^2*theta'^2 + m*g*l*cos(theta)");
    s.handle(":part eom");
    let r = one(&mut s, "m*l^2*theta'' - m*g*l*sin(theta) = 0");
    let Response::Verdict(v) = &r else {
        panic!("{r:?}")
    };
    assert!(
        !v.verdict
            .diagnoses
            .iter()
            .any(|d| d.code == Code::FollowsFromEarlier)
    );
    // The right EOM is correct whatever came before.
    let r = s.handle("m*l^2*theta'' + m*g*l*sin(theta) = 0");
    assert!(matches!(&r[0], Response::Verdict(v) if v.verdict.status == Status::Correct));
}

/// A wrong L and the EOM that follows from it, per bank problem with a `lagrangian` part (as
/// in `follow_through.rs`), answered through the session.
const WRONG_L: &[(&str, &str, &str)] = &[
    (
        "atwood",
        "1/2*(m1+m2)*x'^2 - (m1-m2)*g*x",
        "(m1+m2)*x'' = -(m1-m2)*g",
    ),
    (
        "bead-parabola",
        "1/2*m*(1 + 4*a^2*r^2)*r'^2 + 1/2*m*omega^2*r^2 + m*g*a*r^2",
        "m*(1 + 4*a^2*r^2)*r'' + 4*m*a^2*r*r'^2 - m*omega^2*r - 2*m*g*a*r = 0",
    ),
    (
        "bead-wire",
        "1/2*m*(r'^2 - omega^2*r^2)",
        "r'' = -omega^2*r",
    ),
    (
        "double-pendulum",
        "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + m2*l1*l2*theta1'*theta2'*cos(theta1-theta2) - (m1+m2)*g*l1*cos(theta1) - m2*g*l2*cos(theta2)",
        "(m1+m2)*l1*theta1'' + m2*l2*theta2''*cos(theta1-theta2) + m2*l2*theta2'^2*sin(theta1-theta2) - (m1+m2)*g*sin(theta1) = 0; \
         l2*theta2'' + l1*theta1''*cos(theta1-theta2) - l1*theta1'^2*sin(theta1-theta2) - g*sin(theta2) = 0",
    ),
    (
        "spring-incline",
        "1/2*m*x'^2 + 1/2*k*x^2 - m*g*x*sin(alpha)",
        "m*x'' = k*x - m*g*sin(alpha)",
    ),
];

#[test]
fn follow_through_in_the_session_for_every_wrong_l_of_the_table() {
    for &(id, wrong_l, its_eom) in WRONG_L {
        let mut s = session();
        s.handle(&format!(":open {id}"));
        s.handle(":part lagrangian");
        let l = one(&mut s, wrong_l);
        assert!(
            matches!(&l, Response::Verdict(v) if v.verdict.status == Status::Incorrect),
            "{id}: {l:?}"
        );
        s.handle(":part eom");
        let r = one(&mut s, its_eom);
        let Response::Verdict(v) = &r else {
            panic!("{id}: {r:?}")
        };
        assert_eq!(v.verdict.status, Status::Incorrect, "{id}");
        assert!(
            v.verdict
                .diagnoses
                .iter()
                .any(|d| d.code == Code::FollowsFromEarlier),
            "{id}: {v:?}"
        );
    }
}

#[test]
fn json_of_a_short_tutor_session() {
    let mut s = session();
    let lines = [
        ":open simple-pendulum",
        ":tutor",
        "l*cos(theta), l*sin(theta)",
        "l*sin(theta), -l*cos(theta)",
        ":show",
        ":hint",
        ":back",
    ];
    let mut out = String::new();
    for line in lines {
        for r in s.handle(line) {
            if matches!(r, Response::Statement(_)) {
                continue;
            }
            let json = serde_json::to_string(&r).unwrap_or_default();
            out.push_str(&format!("> {line}\n{json}\n"));
        }
    }
    insta::assert_snapshot!("tutor_session_json", out);
}

/// `:solution` gives the reference answer and its worked derivation: the tutor's steps that
/// lead to the part, with their results.
#[test]
fn a_solution_comes_with_its_worked_derivation() {
    let mut s =
        lagrange::tutor::Session::new(lagrange::embedded::bank(), lagrange::tutor::Progress::new());
    s.handle(":open simple-pendulum");
    s.handle(":part eom");
    let out = s.handle(":solution");
    let v = serde_json::to_value(&out[0]).expect("serialises");
    assert_eq!(v["kind"], "solution");
    let steps: Vec<&str> = v["derivation"]
        .as_array()
        .expect("a derivation")
        .iter()
        .filter_map(|w| w["step"].as_str())
        .collect();
    assert_eq!(steps.first(), Some(&"position:1"));
    assert_eq!(steps.last(), Some(&"eom:theta"));
    let p = v["derivation"]
        .as_array()
        .and_then(|a| a.iter().find(|w| w["step"] == "momentum:theta"))
        .expect("the momentum step");
    assert_eq!(p["answer"], "m*l^2*theta'");
}

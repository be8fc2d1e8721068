//! The practice session (issue 10, items 2 and 6, library side): a scripted session on the
//! simple pendulum, did-you-mean for commands and problems, invalid input that is never an
//! attempt, and the progress file's JSON round trip and typed errors.

use lagrange::check::{Code, Status};
use lagrange::embedded;
use lagrange::tutor::response::VerdictReply;
use lagrange::tutor::{Progress, ProgressError, Response, Session};

use crate::helpers::{one, session};

fn verdict(r: &Response) -> &VerdictReply {
    match r {
        Response::Verdict(v) => v,
        other => panic!("expected a verdict, got {other:?}"),
    }
}

#[test]
fn scripted_pendulum_session() {
    let mut s = session();
    let opened = s.handle(":open simple-pendulum");
    assert!(
        matches!(&opened[0], Response::Statement(st) if st.current.as_deref() == Some("kinetic"))
    );
    assert!(matches!(&opened[1], Response::Part(p) if p.number == 1 && p.part == "kinetic"));
    assert_eq!(s.current_part(), Some("kinetic"));

    // Wrong: T without the l² (the speed is l·θ̇).
    let wrong = one(&mut s, "1/2*m*l*theta'^2");
    let v = verdict(&wrong);
    assert_eq!(v.verdict.status, Status::Incorrect);
    assert_eq!(v.attempts, 1);
    assert!(!v.verdict.diagnoses.is_empty());
    assert!(
        v.verdict
            .diagnoses
            .iter()
            .any(|d| d.code == Code::Dimension),
        "{v:?}"
    );

    // Hints in order, counting down.
    match one(&mut s, "hint") {
        Response::Hint(h) => {
            assert_eq!(
                h.hint.as_deref(),
                Some("The bob moves on a circle of radius l.")
            );
            assert_eq!((h.number, h.remaining), (1, 2));
        }
        other => panic!("{other:?}"),
    }
    s.handle(":hint");
    s.handle(":hint");
    match one(&mut s, ":hint") {
        Response::Hint(h) => assert_eq!((h.hint, h.remaining), (None, 0)),
        other => panic!("{other:?}"),
    }

    // Right → verdict, then the next unsolved part is current.
    let right = s.handle("1/2*m*l^2*theta'^2");
    assert_eq!(verdict(&right[0]).verdict.status, Status::Correct);
    assert_eq!(verdict(&right[0]).attempts, 2);
    assert!(matches!(&right[1], Response::Part(p) if p.part == "potential" && p.number == 2));
    assert_eq!(s.current_part(), Some("potential"));

    // The momentum p = m·l²·θ̇, chosen by id.
    s.handle(":part momentum");
    let p = s.handle("m*l^2*theta'");
    assert_eq!(verdict(&p[0]).verdict.status, Status::Correct);
    // Next unsolved after `momentum` is `eom`.
    assert_eq!(s.current_part(), Some("eom"));

    // The solution of the EOM part marks it revealed (not solved).
    match one(&mut s, ":solution") {
        Response::Solution(sol) => {
            assert_eq!(sol.answer, "m*l^2*theta'' + m*g*l*sin(theta) = 0");
            assert!(
                sol.unicode.contains("θ̈") || sol.unicode.contains("sin θ"),
                "{}",
                sol.unicode
            );
        }
        other => panic!("{other:?}"),
    }
    let rec = s
        .progress()
        .part("simple-pendulum", "eom")
        .cloned()
        .unwrap_or_default();
    assert!(rec.revealed && !rec.solved);

    // Progress counts: 2 of 8 solved, 3 attempts, 3 hints, 1 revealed.
    match one(&mut s, ":progress") {
        Response::Progress(p) => {
            let sp = p.problems.iter().find(|e| e.id == "simple-pendulum");
            let sp = sp.cloned().unwrap_or_else(|| panic!("no entry"));
            assert_eq!(
                (sp.solved, sp.parts, sp.attempts, sp.hints_used, sp.revealed),
                (2, 8, 3, 3, 1)
            );
            assert_eq!(p.solved, 2);
        }
        other => panic!("{other:?}"),
    }
    match one(&mut s, ":problems") {
        Response::Problems(p) => {
            assert_eq!(p.problems.len(), s.bank().problems.len());
            assert!(
                p.problems
                    .iter()
                    .any(|e| e.id == "simple-pendulum" && e.solved == 2)
            );
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn reopening_starts_at_the_first_unsolved_part() {
    let mut progress = Progress::new();
    progress.record_attempt("simple-pendulum", "kinetic", "1/2*m*l^2*theta'^2", true);
    let mut s = Session::new(embedded::bank(), progress);
    s.handle(":open simple-pendulum");
    assert_eq!(s.current_part(), Some("potential"));
    assert!(s.symbol_names().contains(&"theta"));
    assert!(s.part_ids().contains(&"eom"));
    assert!(s.command_names().contains(&":open".to_string()));
    s.handle(":part 8");
    assert_eq!(s.current_part(), Some("energy-function"));
    s.handle(":next");
    assert_eq!(
        s.current_part(),
        Some("potential"),
        "wraps to the first unsolved part"
    );
}

#[test]
fn unknown_names_get_did_you_mean() {
    let mut s = session();
    match one(&mut s, ":opne simple-pendulum") {
        Response::Error(e) => {
            assert_eq!(e.code, "unknown-command");
            assert_eq!(e.suggestion.as_deref(), Some(":open"));
            // Said once, from its own slot (the face prints it under the message).
            assert!(!e.message.contains("did you mean"), "{}", e.message);
        }
        other => panic!("{other:?}"),
    }
    match one(&mut s, ":open simple-pendulm") {
        Response::Error(e) => {
            assert_eq!(e.code, "unknown-problem");
            assert_eq!(e.suggestion.as_deref(), Some("simple-pendulum"));
        }
        other => panic!("{other:?}"),
    }
    // Answering with nothing open is explained, not a crash.
    assert!(matches!(one(&mut s, "m*g*l"), Response::Error(e) if e.code == "no-problem-open"));
    s.handle(":open atwood");
    assert!(
        matches!(one(&mut s, ":part kinetik"), Response::Error(e) if e.suggestion.as_deref() == Some("kinetic"))
    );
    assert!(matches!(one(&mut s, ":show"), Response::Error(e) if e.code == "not-in-tutor"));
}

#[test]
fn invalid_input_is_not_an_attempt() {
    let mut s = session();
    s.handle(":open simple-pendulum");
    for bad in ["1/2*m*(l*theta'^2", "1/2*M*l^2*theta'^2", "theta = 0, 1"] {
        let r = one(&mut s, bad);
        assert_eq!(verdict(&r).verdict.status, Status::Invalid, "{bad}");
        assert_eq!(verdict(&r).attempts, 0, "{bad}");
    }
    assert_eq!(s.progress().part("simple-pendulum", "kinetic"), None);
    assert_eq!(s.current_part(), Some("kinetic"));
}

#[test]
fn progress_round_trips_and_corrupt_json_is_typed() {
    let mut s = session();
    for line in [
        ":open simple-pendulum",
        "1/2*m*l*theta'^2",
        ":hint",
        "1/2*m*l^2*theta'^2",
    ] {
        s.handle(line);
    }
    let json = s.progress().to_json();
    let back = Progress::from_json(&json);
    assert_eq!(back.as_ref(), Ok(s.progress()));
    let rec = s
        .progress()
        .part("simple-pendulum", "kinetic")
        .cloned()
        .unwrap_or_default();
    assert_eq!(rec.answers, ["1/2*m*l*theta'^2", "1/2*m*l^2*theta'^2"]);
    assert!(matches!(
        Progress::from_json("{\"version\": 1,"),
        Err(ProgressError::Malformed { .. })
    ));
    assert!(matches!(
        Progress::from_json("\u{0}garbage"),
        Err(ProgressError::Malformed { .. })
    ));
    assert_eq!(
        Progress::from_json("{\"version\": 2}"),
        Err(ProgressError::Version { found: 2 })
    );
    // A session continues from reloaded progress.
    let mut again = Session::new(embedded::bank(), back.unwrap_or_default());
    again.handle(":open simple-pendulum");
    assert_eq!(again.current_part(), Some("potential"));
}

#[test]
fn short_session_json() {
    let mut s = session();
    let mut lines = Vec::new();
    for line in [
        ":open bead-wire",
        "1/2*m*r'^2",
        "hint",
        "1/2*m*(r'^2 + omega^2*r^2)",
        ":solution",
        ":parts",
        ":help hint",
        ":quit",
    ] {
        for r in s.handle(line) {
            let json = serde_json::to_string(&r).unwrap_or_default();
            lines.push(format!("> {line}\n{json}"));
        }
    }
    insta::assert_snapshot!("session_short_json", lines.join("\n"));
}

#[test]
fn analyses_of_the_open_problem() {
    let mut s = session();
    // Nothing open: `:read` still reads (every name open); `:derive` asks for a problem.
    assert!(matches!(one(&mut s, ":read m*g*l"), Response::Analysis(a) if a.of == "read"));
    assert!(matches!(one(&mut s, ":derive"), Response::Error(e) if e.code == "no-problem-open"));
    s.handle(":open simple-pendulum");
    let json = |r: &Response| serde_json::to_value(r).unwrap_or_default();
    let read = json(&one(&mut s, ":read 1/2*m*l^2*thetadot^2"));
    assert_eq!(read["kind"], "analysis");
    assert_eq!(read["report"]["forms"], "m*l^2*theta'^2/2");
    assert_eq!(read["report"]["dimension"]["known"], "M L² T⁻²");
    let derive = json(&one(&mut s, ":derive"));
    assert_eq!(derive["of"], "derive");
    // p = m·l²·θ̇ and the full EOM.
    assert_eq!(derive["report"]["momenta"][0], "m*l^2*theta'");
    assert_eq!(
        derive["report"]["equations"][0],
        "m*l^2*theta'' + m*g*l*sin(theta)"
    );
    let modes = json(&one(&mut s, ":modes"));
    // ω = √(g/l) at the stated midpoints g = 10, l = 1.25: √8.
    assert!(modes["note"].as_str().is_some_and(|n| n.contains("g = 10")));
    let omega = modes["report"]["equilibria"][0]["frequencies"][0].as_f64();
    assert!(
        omega.is_some_and(|w| (w - 8f64.sqrt()).abs() < 1e-9),
        "{omega:?}"
    );
    assert_eq!(
        modes["report"]["equilibria"].as_array().map(Vec::len),
        Some(2)
    );
    // ω = √(g/l) at the stated midpoints g = 10, l = 1.25: √8.
    assert!(modes["note"].as_str().is_some_and(|n| n.contains("g = 10")));
    let omega = modes["report"]["equilibria"][0]["frequencies"][0].as_f64();
    assert!(
        omega.is_some_and(|w| (w - 8f64.sqrt()).abs() < 1e-9),
        "{omega:?}"
    );
    assert!(matches!(one(&mut s, ":read 1/(m"), Response::Error(e) if e.code == "syntax"));
    // A typed Lagrangian: coordinates are the names written with a prime, or --coords.
    let derived = json(&one(&mut s, ":derive 1/2 m x'^2 - 1/2 k x^2"));
    assert_eq!(derived["report"]["coordinates"][0], "x");
    assert_eq!(derived["report"]["equations"][0], "m*x'' + k*x");
    let modes = json(&one(
        &mut s,
        ":modes 1/2 m x'^2 - 1/2 k x^2 --params m=1,k=4",
    ));
    let omega = modes["report"]["equilibria"][0]["frequencies"][0].as_f64();
    assert!(omega.is_some_and(|w| (w - 2.0).abs() < 1e-12), "{omega:?}");
    assert!(matches!(
        one(&mut s, ":derive 1/2 x'^2 + y --coords x,x"),
        Response::Error(e) if e.code == "repeated-coordinate"
    ));
}

#[test]
fn every_bank_problem_can_be_solved_through_the_session() {
    let bank = embedded::bank();
    let ids: Vec<String> = bank.problems.iter().map(|p| p.id.clone()).collect();
    let mut s = Session::new(bank, Progress::new());
    for id in &ids {
        s.handle(&format!(":open {id}"));
        let problem = s
            .problem()
            .cloned()
            .unwrap_or_else(|| panic!("{id} did not open"));
        let n = problem.system.n();
        let mut last = Vec::new();
        for part in &problem.parts {
            assert_eq!(s.current_part(), Some(part.id.as_str()), "{id}");
            last = s.handle(&part.reference_text(n));
            let v = verdict(&last[0]);
            assert_eq!(v.verdict.status, Status::Correct, "{id}/{}: {v:?}", part.id);
        }
        assert!(matches!(last.last(), Some(Response::Done(d)) if d.parts == problem.parts.len()));
    }
    match one(&mut s, ":progress") {
        Response::Progress(p) => assert_eq!(p.solved, p.parts),
        other => panic!("{other:?}"),
    }
}

#[test]
fn hostile_lines_never_panic() {
    let mut s = session();
    let lines = [
        ":",
        "::",
        ": open",
        ":open",
        ":open \u{1b}[31mred",
        ":part 0",
        ":part 99",
        ":part -1",
        ":hint",
        ":solution",
        ":next",
        ":parts",
        "\u{0}",
        "((((((((((",
        "=",
        ";;;",
        "1/0",
        ":help :nope",
        ":help",
        ":read",
        ":read )",
        ":derive",
        ":modes",
        ":tutor",
        ":show",
        ":back",
    ];
    for round in 0..2 {
        for line in lines {
            let out = s.handle(line);
            // Every response serialises.
            for r in &out {
                assert!(serde_json::to_string(r).is_ok(), "{line}");
            }
        }
        if round == 0 {
            s.handle(":open double-pendulum");
        }
    }
    assert_eq!(s.current_problem(), Some("double-pendulum"));
}

#[test]
fn physics_hints_follow_the_files() {
    let mut s = session();
    s.handle(":open simple-pendulum");
    s.handle(":part eom");
    let hints: Vec<(Option<String>, usize)> = (0..7)
        .flat_map(|_| s.handle(":hint"))
        .filter_map(|r| match r {
            Response::Hint(h) => Some((h.hint, h.remaining)),
            _ => None,
        })
        .collect();
    // Three from the file, then p = ∂L/∂θ̇ = m·l²·θ̇, its rate and ∂L/∂θ, then none.
    assert_eq!(hints[0].1, 5);
    assert_eq!(hints[3], (Some("∂L/∂θ̇ = m·l²·θ̇".to_string()), 2));
    assert_eq!(hints[4].0.as_deref(), Some("d/dt ∂L/∂θ̇ = m·l²·θ̈"));
    let force = hints[5].0.clone().unwrap_or_default();
    assert!(force.starts_with("∂L/∂θ = −m·g·l·sin(θ)"), "{force}");
    assert_eq!(hints[6], (None, 0));
    // A momentum part gets L to differentiate.
    s.handle(":part momentum");
    let last = (0..3).flat_map(|_| s.handle(":hint")).last();
    assert!(
        matches!(last, Some(Response::Hint(h)) if h.hint.as_deref().is_some_and(|t| t.contains("with respect to θ̇")))
    );
}

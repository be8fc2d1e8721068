//! Conventions are stated or all accepted (issue 19 §4): every bank statement and tutor
//! position step states the axes, sense of rotation and phase its reference uses; an answer
//! right in another convention is told `convention`, never `swapped-symbols`; and no tutor
//! step of a problem whose parameter is ω calls a frequency ω.

use lagrange::bank::embedded;
use lagrange::check::{Code, Status, Verdict, check};
use lagrange::problem::Problem;
use lagrange::tutor::ladder::{check_step, ladder};

fn problem(id: &str) -> Problem {
    embedded::problem(id).unwrap()
}

fn codes(v: &Verdict) -> Vec<Code> {
    v.diagnoses.iter().map(|d| d.code).collect()
}

/// The rotating trap's T and L with the frame turning the other way (Ω → −Ω, the same as x
/// and y exchanged): the statements fix the sense (counterclockwise, from x toward y), so these
/// are wrong — as `convention` alone, never `swapped-symbols`. The stated sense is accepted.
#[test]
fn rotating_trap_in_the_other_sense_is_a_convention() {
    let cases: &[(&str, &str, &str, bool)] = &[
        (
            "rotating-trap",
            "kinetic",
            "1/2*m*((x' + Omega*y)^2 + (y' - Omega*x)^2)",
            false,
        ),
        (
            "rotating-trap",
            "kinetic",
            "1/2*m*((x' - Omega*y)^2 + (y' + Omega*x)^2)",
            true,
        ),
        (
            "rotating-trap",
            "kinetic",
            "1/2*m*(x'^2 + y'^2 + Omega^2*(x^2 + y^2)) + m*Omega*(y*x' - x*y')",
            false,
        ),
        (
            "rotating-trap",
            "lagrangian",
            "1/2*m*((x' + Omega*y)^2 + (y' - Omega*x)^2) - 1/2*k*(x^2 + y^2)",
            false,
        ),
        (
            "rotating-trap",
            "lagrangian",
            "1/2*m*((x' - Omega*y)^2 + (y' + Omega*x)^2) - 1/2*k*(x^2 + y^2)",
            true,
        ),
        // The energy function does not depend on the sense: every sense gives it.
        (
            "rotating-trap-fast",
            "energy-function",
            "1/2*m*(x'^2 + y'^2) + 1/2*(k - m*Omega^2)*(x^2 + y^2)",
            true,
        ),
    ];
    for &(id, part_id, answer, right) in cases {
        let p = problem(id);
        assert!(
            p.statement.contains("counterclockwise"),
            "{id}: the statement must fix the sense of rotation"
        );
        let part = p.parts.iter().find(|x| x.id == part_id).unwrap();
        let v = check(&p, part, answer).unwrap();
        if right {
            assert_eq!(
                v.status,
                Status::Correct,
                "{id} {part_id} `{answer}`: {v:?}"
            );
        } else {
            assert_eq!(v.status, Status::Incorrect, "{id} {part_id} `{answer}`");
            assert_eq!(
                codes(&v),
                [Code::Convention],
                "{id} {part_id} `{answer}`: {v:?}"
            );
        }
    }
}

/// The trap's equations of motion (the tutor's `eom:x` step) for the other sense are a
/// `convention` too.
#[test]
fn rotating_trap_equations_in_the_other_sense_are_a_convention() {
    let p = problem("rotating-trap");
    let steps = ladder(&p).unwrap();
    let cases: &[(&str, &str, bool)] = &[
        (
            "eom:x",
            "m*x'' - 2*m*Omega*y' - m*Omega^2*x + k*x = 0",
            true,
        ),
        (
            "eom:x",
            "m*x'' + 2*m*Omega*y' - m*Omega^2*x + k*x = 0",
            false,
        ),
        (
            "eom:y",
            "m*y'' + 2*m*Omega*x' - m*Omega^2*y + k*y = 0",
            true,
        ),
        (
            "eom:y",
            "m*y'' - 2*m*Omega*x' - m*Omega^2*y + k*y = 0",
            false,
        ),
    ];
    for &(id, answer, right) in cases {
        let step = steps.iter().find(|s| s.id == id).unwrap();
        let v = check_step(&p, step, answer).unwrap();
        if right {
            assert_eq!(v.status, Status::Correct, "{id} `{answer}`: {v:?}");
        } else {
            assert_eq!(v.status, Status::Incorrect, "{id} `{answer}`");
            assert!(
                codes(&v).contains(&Code::Convention) && !codes(&v).contains(&Code::SwappedSymbols),
                "{id} `{answer}`: {v:?}"
            );
        }
    }
}

/// The rotating hoop's tutor step 1 (the bead's position): its prompt states the axes, the
/// phase and the sense; the stated axes are accepted, and the same point in other axes (z up,
/// another phase, the other sense, y down) is `convention`, never `swapped-symbols`. A wrong
/// point is neither.
#[test]
fn hoop_positions_in_other_axes_are_a_convention() {
    let p = problem("rotating-hoop");
    let steps = ladder(&p).unwrap();
    let step = steps.iter().find(|s| s.id == "position:1").unwrap();
    for words in ["y up", "at t = 0", "from the x axis toward the z axis"] {
        assert!(
            step.prompt.contains(words),
            "prompt lacks `{words}`: {}",
            step.prompt
        );
    }
    let cases: &[(&str, &str, Option<Code>)] = &[
        (
            "stated axes",
            "R*sin(theta)*cos(omega*t), -R*cos(theta), R*sin(theta)*sin(omega*t)",
            None,
        ),
        (
            "z up",
            "R*sin(theta)*cos(omega*t), R*sin(theta)*sin(omega*t), -R*cos(theta)",
            Some(Code::Convention),
        ),
        (
            "phase a quarter turn",
            "R*sin(theta)*sin(omega*t), -R*cos(theta), R*sin(theta)*cos(omega*t)",
            Some(Code::Convention),
        ),
        (
            "phase a twelfth of a turn",
            "R*sin(theta)*cos(omega*t + pi/6), -R*cos(theta), R*sin(theta)*sin(omega*t + pi/6)",
            Some(Code::Convention),
        ),
        (
            "other sense",
            "R*sin(theta)*cos(omega*t), -R*cos(theta), -R*sin(theta)*sin(omega*t)",
            Some(Code::Convention),
        ),
        (
            "y down",
            "R*sin(theta)*cos(omega*t), R*cos(theta), R*sin(theta)*sin(omega*t)",
            Some(Code::Convention),
        ),
        (
            "spin left out",
            "R*sin(theta), -R*cos(theta), 0",
            Some(Code::NotEqual),
        ),
        (
            "wrong radius",
            "2*R*sin(theta)*cos(omega*t), -R*cos(theta), R*sin(theta)*sin(omega*t)",
            Some(Code::NotEqual),
        ),
    ];
    for &(what, answer, want) in cases {
        let v = check_step(&p, step, answer).unwrap();
        match want {
            None => assert_eq!(v.status, Status::Correct, "{what} `{answer}`: {v:?}"),
            Some(Code::Convention) => {
                assert_eq!(v.status, Status::Incorrect, "{what} `{answer}`");
                assert_eq!(
                    codes(&v)[..1],
                    [Code::Convention],
                    "{what} `{answer}`: {v:?}"
                );
                assert!(!codes(&v).contains(&Code::SwappedSymbols), "{what}: {v:?}");
            }
            Some(_) => {
                assert_eq!(v.status, Status::Incorrect, "{what} `{answer}`");
                assert!(
                    !codes(&v).contains(&Code::Convention)
                        && !codes(&v).contains(&Code::SwappedSymbols),
                    "{what} `{answer}`: {v:?}"
                );
            }
        }
    }
}

/// Every bank problem built from bodies states its axes, and every tutor position step
/// repeats them.
#[test]
fn every_position_step_states_its_axes() {
    for p in &embedded::bank().problems {
        if p.system.bodies.is_empty() {
            continue;
        }
        assert!(!p.axes.is_empty(), "{}: no `axes`", p.id);
        for s in ladder(p).unwrap() {
            if s.id.starts_with("position:") {
                assert!(
                    s.prompt.contains(&p.axes),
                    "{} {}: {}",
                    p.id,
                    s.id,
                    s.prompt
                );
            }
        }
    }
}

/// No tutor prompt of a problem with a parameter ω (the spin of rotating-hoop, bead-wire,
/// bead-parabola) uses ω for a frequency; those problems' frequency steps use another name.
#[test]
fn no_tutor_prompt_reuses_a_parameters_omega() {
    let mut with_omega = Vec::new();
    for p in &embedded::bank().problems {
        if !p.system.parameters.iter().any(|x| x.name == "omega") {
            continue;
        }
        with_omega.push(p.id.clone());
        for s in ladder(p).unwrap() {
            if s.id == "frequencies" || s.id == "characteristic" {
                assert!(
                    !s.prompt.contains('ω') && s.prompt.contains('Ω'),
                    "{} {}: {}",
                    p.id,
                    s.id,
                    s.prompt
                );
            }
        }
    }
    with_omega.sort();
    assert_eq!(with_omega, ["bead-parabola", "bead-wire", "rotating-hoop"]);
    // Where ω is free, the frequency keeps its usual name.
    let p = problem("simple-pendulum");
    let steps = ladder(&p).unwrap();
    let s = steps.iter().find(|s| s.id == "frequencies").unwrap();
    assert!(s.prompt.contains("frequencies ω"), "{}", s.prompt);
}

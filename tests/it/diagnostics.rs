//! Every parse-error kind: a table of `input => code` and one snapshot of all the rendered
//! diagnostics (message, caret under the span, help). And the checker's diagnoses of issue 12
//! (term level, limits, list items): a table of `answer => code`, the regressions of the
//! misleading messages it removed, and one snapshot of the new messages.

use lagrange::diagnostic::render_parse_error;
use lagrange::expr::error::{MAX_DEPTH, MAX_INPUT_BYTES};
use lagrange::expr::{Context, ParseError, Pool, read, read_expr};

use crate::helpers::mech_ctx;

fn closed() -> Context {
    Context::new()
        .with_coordinates(["theta"])
        .with_parameters(["m", "g", "l"])
}

enum Want {
    Any,
    Expr,
}

fn cases() -> Vec<(&'static str, String, Want, Context)> {
    let deep = format!(
        "{}x{}",
        "(".repeat(MAX_DEPTH + 5),
        ")".repeat(MAX_DEPTH + 5)
    );
    let long = "x+".repeat(MAX_INPUT_BYTES / 2 + 10) + "x";
    vec![
        ("empty", String::new(), Want::Any, closed()),
        ("blank", "   ".into(), Want::Any, closed()),
        ("too-long", long, Want::Any, Context::open()),
        ("too-deep", deep, Want::Any, Context::open()),
        (
            "unexpected-character",
            "m*g $ l".into(),
            Want::Any,
            closed(),
        ),
        ("latex-input", r"\frac{1}{2} m".into(), Want::Any, closed()),
        ("unclosed-paren", "m*(g + l".into(), Want::Any, closed()),
        ("unclosed-call", "sin(theta".into(), Want::Any, closed()),
        ("unmatched-paren", "m*g)".into(), Want::Any, closed()),
        ("missing-operand-end", "m*g +".into(), Want::Any, closed()),
        ("missing-operand-start", "* m".into(), Want::Any, closed()),
        ("missing-operand-list", "m,,g".into(), Want::Any, closed()),
        ("missing-operator", "2 3".into(), Want::Any, closed()),
        (
            "unknown-function",
            "m*g*l*sinn(theta)".into(),
            Want::Any,
            closed(),
        ),
        (
            "unknown-function-closed",
            "f(theta)".into(),
            Want::Any,
            closed(),
        ),
        (
            "function-without-argument",
            "sin + m".into(),
            Want::Any,
            closed(),
        ),
        ("function-at-end", "m*g*cos".into(), Want::Any, closed()),
        (
            "unknown-symbol",
            "thta'' + g/l*sin(theta)".into(),
            Want::Any,
            closed(),
        ),
        (
            "unknown-symbol-split",
            "mgl*sin(theta)".into(),
            Want::Any,
            closed(),
        ),
        (
            "unknown-symbol-nothing-close",
            "zzz".into(),
            Want::Any,
            closed(),
        ),
        ("not-a-coordinate", "m' + g".into(), Want::Any, closed()),
        (
            "equation-not-allowed",
            "m*g = l".into(),
            Want::Expr,
            closed(),
        ),
        ("list-not-allowed", "m, g".into(), Want::Expr, closed()),
        ("chained-equals", "m = g = l".into(), Want::Any, closed()),
        ("number-too-large", "1e999*m".into(), Want::Any, closed()),
        ("dot-needs-name", "dot(2)".into(), Want::Any, mech_ctx()),
        ("prime-without-name", "(m + g)'".into(), Want::Any, closed()),
    ]
}

fn error_of(src: &str, want: &Want, ctx: &Context) -> ParseError {
    let mut pool = Pool::new();
    let r = match want {
        Want::Any => read(src, ctx, &mut pool).map(|_| ()),
        Want::Expr => read_expr(src, ctx, &mut pool).map(|_| ()),
    };
    match r {
        Err(e) => e,
        Ok(()) => panic!("{src:?} should not be read"),
    }
}

#[test]
fn every_error_kind_is_reported_with_its_code() {
    for (name, src, want, ctx) in cases() {
        let e = error_of(&src, &want, &ctx);
        let expected_code = match name {
            "blank" => "empty",
            "latex-input" => "unexpected-character",
            "unclosed-call" => "unclosed-paren",
            n if n.starts_with("missing-operand") => "missing-operand",
            "unknown-function-closed" => "unknown-function",
            "function-at-end" => "function-without-argument",
            n if n.starts_with("unknown-symbol") => "unknown-symbol",
            n => n,
        };
        assert_eq!(e.kind.code(), expected_code, "case {name}: {e}");
        assert!(e.span.end <= src.len(), "case {name}: span out of range");
        assert!(!e.help().is_empty());
    }
}

#[test]
fn rendered_diagnostics() {
    let mut all = String::new();
    for (name, src, want, ctx) in cases() {
        if name == "too-long" || name == "too-deep" {
            // Their source lines are huge; the message and code are pinned above.
            continue;
        }
        let e = error_of(&src, &want, &ctx);
        all.push_str(&format!("── {name}: {src:?}\n"));
        all.push_str(&render_parse_error("answer", &src, &e, false));
        all.push('\n');
    }
    insta::assert_snapshot!("parse_diagnostics", all);
}

#[test]
fn suggestions_name_the_fix() {
    let ctx = closed();
    let e = error_of("thta'' + g/l*sin(theta)", &Want::Any, &ctx);
    assert_eq!(e.help(), "did you mean `theta`?");
    let e = error_of("mgl*sin(theta)", &Want::Any, &ctx);
    assert!(e.help().contains("m*g*l"), "{}", e.help());
    let e = error_of("m*g*l*sinn(theta)", &Want::Any, &ctx);
    assert_eq!(e.help(), "did you mean `sin`?");
}

// ── Issue 12: naming the actual mistake ─────────────────────────────────────────────────

use lagrange::check::{Checker, Code, Status, Verdict};
use lagrange::problem::Problem;

/// A puck on a turntable, seen in the turning frame: Coriolis terms ±2Ω·q̇.
const ROTATING_FRAME: &str = r#"
id = "rotating-frame"
title = "A puck in a rotating frame"
source = "issue 12 regression"
statement = "A puck of mass $m$ on a frictionless turntable turning at the rate $\\Omega$."
coordinates = [{ name = "x" }, { name = "y" }]
lagrangian = "1/2*m*((x' - Omega*y)^2 + (y' + Omega*x)^2)"

[parameters]
m = { dimension = "M", range = [0.5, 2.0] }
Omega = { dimension = "T^-1", range = [0.5, 2.0] }

[[parts]]
id = "eom"
kind = "equations"
prompt = "Write the equations of motion."
answer = ["x'' - 2*Omega*y' - Omega^2*x = 0", "y'' + 2*Omega*x' - Omega^2*y = 0"]
hints = ["Differentiate."]
"#;

/// A rotor whose inertia 1 + x² a slider changes: the ψ equation linearizes to ψ'' = 0.
const SLIDING_ROTOR: &str = r#"
id = "sliding-rotor"
title = "A slider that loads a rotor"
source = "issue 12 regression"
statement = "A slider on a spring changes the inertia of a rotor."
coordinates = [{ name = "x" }, { name = "psi", periodic = true }]
lagrangian = "1/2*m*x'^2 + 1/2*m*(1 + x^2)*psi'^2 - 1/2*k*x^2"

[parameters]
m = { dimension = "M", range = [0.5, 2.0] }
k = { dimension = "M T^-2", range = [0.5, 2.0] }

[[parts]]
id = "eom"
kind = "equation"
prompt = "Write the equation of motion for psi."
answer = "(1 + x^2)*psi'' + 2*x*x'*psi' = 0"
hints = ["Differentiate."]
"#;

fn problem_of(id: &str) -> Problem {
    match id {
        "rotating-frame" => lagrange::bank::load_str("rotating-frame.toml", ROTATING_FRAME)
            .unwrap_or_else(|f| panic!("{f}")),
        "sliding-rotor" => lagrange::bank::load_str("sliding-rotor.toml", SLIDING_ROTOR)
            .unwrap_or_else(|f| panic!("{f}")),
        id => lagrange::embedded::problem(id).unwrap_or_else(|| panic!("no problem {id}")),
    }
}

fn checked(problem: &str, part: &str, answer: &str) -> Verdict {
    let p = problem_of(problem);
    Checker::new(&p)
        .check(part, answer)
        .unwrap_or_else(|e| panic!("{problem}/{part}: {e}"))
}

/// `(problem, part, answer) => the code naming the mistake`.
fn mistakes() -> Vec<((&'static str, &'static str, &'static str), Code)> {
    vec![
        (
            ("simple-pendulum", "eom", "θ'' = g/l*sin(θ)"),
            Code::SignError,
        ),
        (
            ("spring-incline", "eom", "m*x'' = -2*k*x + m*g*sin(alpha)"),
            Code::ConstantFactor,
        ),
        (
            ("simple-pendulum", "eom", "θ'' + 1.01*g/l*sin(θ) = 0"),
            Code::RoundedConstant,
        ),
        (
            (
                "double-pendulum",
                "kinetic",
                "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2",
            ),
            Code::MissingTerm,
        ),
        (
            (
                "double-pendulum",
                "eom",
                "(m1+m2)*l1*theta1'' + m2*l2*theta2''*cos(theta1-theta2) + (m1+m2)*g*sin(theta1) = 0; l2*theta2'' + l1*theta1''*cos(theta1-theta2) - l1*theta1'^2*sin(theta1-theta2) + g*sin(theta2) = 0",
            ),
            Code::MissingTerm,
        ),
        (("spring-incline", "eom", "m*x'' = -k*x"), Code::MissingTerm),
        (
            ("simple-pendulum", "eom", "θ'' + g/l*sin(θ) + g/l*θ = 0"),
            Code::ExtraTerm,
        ),
        (
            ("simple-pendulum", "eom", "θ'' + g/l*cos(θ) = 0"),
            Code::WrongFactor,
        ),
        (
            ("spring-incline", "potential", "1/2*k*x^2 - m*g*x"),
            Code::WrongFactor,
        ),
        (
            (
                "double-pendulum",
                "kinetic",
                "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + m2*l1*l2*theta1'*theta2'*cos(theta1 + theta2)",
            ),
            Code::WrongFactor,
        ),
        (
            ("simple-pendulum", "momentum", "m*l^2*theta'*cos(theta)"),
            Code::WrongFactor,
        ),
        (
            ("bead-parabola", "eom", "m*r'' - m*omega^2*r = 0"),
            Code::RightInLimit,
        ),
        (
            (
                "bead-parabola",
                "lagrangian",
                "1/2*m*r'^2 + 1/2*m*omega^2*r^2 + m*g*a*r^2",
            ),
            Code::RightInLimit,
        ),
        (
            (
                "double-pendulum",
                "lagrangian",
                "(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + 2*m2*l1*l2*theta1'*theta2'*cos(theta1-theta2) + (m1+m2)*g*l1*cos(theta1) + m2*g*l2*cos(theta2)",
            ),
            Code::VelocityTerm,
        ),
        (
            ("simple-pendulum", "potential", "1/2*m*g*l*θ^2"),
            Code::SmallAngle,
        ),
        (
            (
                "simple-pendulum",
                "lagrangian",
                "1/2*m*l^2*θ'^2 - 1/2*m*g*l*θ^2",
            ),
            Code::SmallAngle,
        ),
        (
            ("simple-pendulum", "frequencies", "sqrt(g/l)/(2*pi)"),
            Code::OrdinaryFrequency,
        ),
        (
            ("simple-pendulum", "frequencies", "2*pi*sqrt(l/g)"),
            Code::Period,
        ),
        (
            ("simple-pendulum", "frequencies", "sqrt(2*g/l)"),
            Code::ConstantFactor,
        ),
        (
            (
                "double-pendulum",
                "frequencies",
                "sqrt((2 - sqrt(2))*g/l), sqrt((sqrt(2) - 2)*g/l)",
            ),
            Code::SignError,
        ),
        (
            ("simple-pendulum", "equilibria", "0, pi, -pi"),
            Code::ExtraItem,
        ),
        (
            ("simple-pendulum", "equilibria", "0, 3.14"),
            Code::RoundedConstant,
        ),
        (
            ("simple-pendulum", "equilibria", "0, 3.14159"),
            Code::RoundedConstant,
        ),
        (
            (
                "rotating-frame",
                "eom",
                "x'' + 2*Omega*y' - Omega^2*x = 0; y'' + 2*Omega*x' - Omega^2*y = 0",
            ),
            Code::SignError,
        ),
        (("sliding-rotor", "eom", "psi'' = 0"), Code::MissingTerm),
        (("bead-wire", "momentum", "m*omega*r"), Code::NotEqual),
    ]
}

#[test]
fn each_mistake_gets_the_code_that_names_it() {
    for ((problem, part, answer), code) in mistakes() {
        let v = checked(problem, part, answer);
        assert_eq!(v.status, Status::Incorrect, "{answer}: {v:#?}");
        let codes: Vec<Code> = v.diagnoses.iter().map(|d| d.code).collect();
        assert!(
            codes.contains(&code),
            "{answer}: expected {code}, got {v:#?}"
        );
    }
}

#[test]
fn the_misleading_messages_of_issue_12_are_gone() {
    let message = |problem, part, answer| -> String {
        let v = checked(problem, part, answer);
        v.diagnoses
            .iter()
            .map(|d| format!("[{}] {}\n", d.code, d.message))
            .collect()
    };
    // The sign error names the term the student typed (not −g·sin(θ)/l), where they typed it.
    let m = message("simple-pendulum", "eom", "θ'' = g/l*sin(θ)");
    assert!(m.contains("your term g/l sin(θ) on the right "), "{m}");
    // A momentum or T is never "right when nothing moves": every term depends on velocity.
    for (problem, part, answer) in [
        ("atwood", "momentum", "m1*x'"),
        ("bead-parabola", "momentum", "m*r'"),
        ("simple-pendulum", "kinetic", "1/2*m*l*theta'^2"),
    ] {
        let m = message(problem, part, answer);
        assert!(
            !m.contains("velocity-term") && !m.contains("nothing moves"),
            "{m}"
        );
    }
    // ψ'' = 0 holds in every approximation: it is no small-angle slip.
    let m = message("sliding-rotor", "eom", "psi'' = 0");
    assert!(!m.contains("small-angle"), "{m}");
    // A Coriolis sign error is a sign error, not "x and y are swapped".
    let m = message(
        "rotating-frame",
        "eom",
        "x'' + 2*Omega*y' - Omega^2*x = 0; y'' + 2*Omega*x' - Omega^2*y = 0",
    );
    assert!(!m.contains("swapped"), "{m}");
    assert!(
        m.contains("sign error in equation 1: your term 2 Ω "),
        "{m}"
    );
    // not-equal shows the variables the answers use, velocities included, and no others.
    let m = message("double-pendulum", "kinetic", "m1*l1^2*theta1'^2");
    // (a velocity is printed with a combining dot above, U+0307)
    assert!(
        m.contains("θ\u{307}₂ = ") && m.contains("θ\u{307}₁ = "),
        "{m}"
    );
    assert!(
        !m.contains(" m = ") && !m.contains(" l = ") && !m.contains("g = "),
        "{m}"
    );
    // θ = −π after θ = π is π listed twice, not "not an equilibrium".
    let m = message("simple-pendulum", "equilibria", "0, pi, -pi");
    assert!(
        m.contains("listed twice") && !m.contains("not an equilibrium"),
        "{m}"
    );
    // Decimals for π: one rule, whatever the number of digits; exact enough is right.
    assert_eq!(
        checked("simple-pendulum", "equilibria", "0, 3.14159265358979").status,
        Status::Correct
    );
}

#[test]
fn term_level_messages() {
    let mut all = String::new();
    for ((problem, part, answer), _) in mistakes() {
        let v = checked(problem, part, answer);
        all.push_str(&format!("── {problem} / {part}: {answer}\n"));
        for d in &v.diagnoses {
            all.push_str(&format!("  [{}] {}\n", d.code, d.message));
        }
    }
    insta::assert_snapshot!("term_level_messages", all);
}

//! Every parse-error kind: a table of `input => code` and one snapshot of all the rendered
//! diagnostics (message, caret under the span, help).

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

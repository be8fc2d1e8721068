//! Issue 20 §6, "also found by the same attack": each finding with its bound, clear error or
//! fix. A derivative order beyond the bound is a positioned error; `dot(sqrt)` is refused so
//! that whatever reads prints back; a run that ends at t = ∞ says so in words; a huge problem
//! file is refused by name and costs no command that does not need it; a long line in the
//! REPL's editor costs time linear in its length.

use lagrange::expr::error::{MAX_DERIVATIVE_ORDER, ParseErrorKind};
use lagrange::expr::{Context, Pool, read_expr};

fn error_of(src: &str, ctx: &Context) -> lagrange::expr::error::ParseError {
    let mut pool = Pool::new();
    match read_expr(src, ctx, &mut pool) {
        Ok(e) => panic!("{src:?} read as {}", pool.plain(e)),
        Err(e) => e,
    }
}

#[test]
fn derivative_order_256_is_refused_not_read_as_255() {
    let ctx = Context::new().with_coordinates(["x"]);
    for (src, order) in [
        (format!("x{}", "'".repeat(256)), 256),
        (format!("2 + x{}", "'".repeat(300)), 300),
        (format!("dot(x{})", "'".repeat(255)), 256),
        (format!("xddot{}", "'".repeat(254)), 256),
        (format!("x{}", "\u{0308}".repeat(128)), 256),
        (format!("x{}", "'".repeat(MAX_DERIVATIVE_ORDER + 1)), 21),
    ] {
        let e = error_of(&src, &ctx);
        assert_eq!(
            e.kind,
            ParseErrorKind::OrderTooHigh {
                order,
                max: MAX_DERIVATIVE_ORDER
            },
            "{src:?}"
        );
        assert_eq!(e.kind.code(), "order-too-high");
        // Positioned at the name and its marks, not the whole input.
        let start = src.find('x').unwrap_or(0);
        assert_eq!(e.span.start, start, "{src:?}: {:?}", e.span);
    }
    // In an open context the implied coordinate is bounded the same way.
    let e = error_of(&format!("q{}", "'".repeat(256)), &Context::open());
    assert_eq!(e.kind.code(), "order-too-high");
    // The bound itself still reads, as exactly that order.
    let mut pool = Pool::new();
    let src = format!("x{}", "'".repeat(MAX_DERIVATIVE_ORDER));
    let e = read_expr(&src, &ctx, &mut pool).expect("the highest order reads");
    assert_eq!(pool.plain(e), src);
}

#[test]
fn dot_of_a_function_name_is_refused_so_printing_reads_back() {
    for src in [
        "dot(sqrt)",
        "ddot(sin)",
        "dot(log')",
        "dot(dot)",
        "dot(abs)",
    ] {
        let e = error_of(src, &Context::open());
        assert_eq!(e.kind.code(), "dot-needs-name", "{src}");
    }
    // A coordinate still works in both forms.
    let mut pool = Pool::new();
    let e = read_expr("dot(q)", &Context::open(), &mut pool).unwrap();
    assert_eq!(pool.plain(e), "q'");
}

#[test]
fn a_run_that_ends_at_infinity_says_so_in_words() {
    use lagrange::simulate::SimError;
    let at_inf = SimError::Diverges { t: f64::INFINITY }.to_string();
    assert!(!at_inf.contains("inf"), "{at_inf}");
    assert!(at_inf.contains("time itself overflowed"), "{at_inf}");
    let nan = SimError::Diverges { t: f64::NAN }.to_string();
    assert!(!nan.contains("NaN"), "{nan}");
    // A huge finite time is short, not 308 digits.
    let huge = SimError::Diverges { t: 4.5e307 }.to_string();
    assert_eq!(huge, "the solution diverges near t = 4.5e307");
    let steps = SimError::TooManySteps { max: 10, t: 1e300 }.to_string();
    assert!(steps.len() < 80, "{steps}");
    assert_eq!(
        SimError::Diverges { t: 1.25 }.to_string(),
        "the solution diverges near t = 1.25"
    );
    // Through the CLI: a step of 1e308 runs time past every number.
    let (code, _, err) = crate::helpers::lagrange(&[
        "simulate",
        "-L",
        "1/2 x'^2 + t x",
        "-q",
        "x",
        "--init",
        "x=1",
        "--t-end",
        "1.7976931348623157e308",
        "--method",
        "rk4",
        "--dt",
        "1e308",
    ]);
    assert_eq!(code, 1, "{err}");
    assert!(!err.contains("inf") && err.len() < 400, "{err}");
}

#[test]
fn a_huge_problem_file_is_refused_by_name_and_costs_no_other_command() {
    use lagrange::bank::load::MAX_FILE_BYTES;
    let dir = tempfile::tempdir().unwrap();
    let src = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("problems/simple-pendulum.toml"),
    )
    .unwrap();
    std::fs::write(dir.path().join("simple-pendulum.toml"), &src).unwrap();
    // 600 kB: the problem with its parts repeated under new ids, and mentioning the id
    // `simple-pendulum` throughout (so a substring search cannot skip it).
    let (head, parts) = src.split_once("[[parts]]").unwrap();
    let mut huge = head.replace("id = \"simple-pendulum\"", "id = \"huge\"");
    let mut k = 0;
    while huge.len() < 600_000 {
        huge.push_str("# like simple-pendulum\n[[parts]]");
        huge.push_str(&parts.replace("id = \"", &format!("id = \"p{k}-")));
        k += 1;
    }
    let huge_path = dir.path().join("huge.toml");
    std::fs::write(&huge_path, &huge).unwrap();
    let d = dir.path().to_str().unwrap();
    let start = std::time::Instant::now();
    let (code, out, err) = crate::helpers::lagrange(&[
        "--problems",
        d,
        "check",
        "simple-pendulum",
        "kinetic",
        "1/2 m l^2 theta'^2",
    ]);
    let took = start.elapsed();
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("correct"), "{out}");
    assert!(took.as_secs_f64() < 5.0, "check took {took:?}");
    // Asking for the huge problem names the file, its size and the limit.
    let (code, _, err) = crate::helpers::lagrange(&["--problems", d, "check", "huge", "eom", "0"]);
    assert_eq!(code, 2, "{err}");
    for want in [
        huge_path.to_str().unwrap(),
        &huge.len().to_string(),
        &MAX_FILE_BYTES.to_string(),
        "too-large",
    ] {
        assert!(err.contains(want), "{want} missing from: {err}");
    }
    // The listing names it as a finding and lists the rest.
    let (code, out, _) = crate::helpers::lagrange(&["--problems", d, "problems", "list"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("simple-pendulum") && out.contains("[too-large]"),
        "{out}"
    );
}

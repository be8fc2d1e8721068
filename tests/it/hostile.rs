//! Issue 9, sections 4 and 5: what `problems verify` must refuse beyond the `tests/broken`
//! fixtures, and messages that echo hostile text (escape sequences, invisible characters,
//! over-long inputs) or misname a situation. Each test runs the exact input of the issue.

use crate::helpers::lagrange;

use lagrange::diagnostic::render_parse_error;
use lagrange::expr::error::MAX_INPUT_BYTES;
use lagrange::expr::{Context, Pool, read_expr};

use crate::helpers::eval;

fn root() -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// No control character other than a line break reaches the terminal.
fn assert_no_raw_controls(text: &str) {
    for c in text.chars() {
        assert!(
            c == '\n' || !c.is_control(),
            "raw control character {:?} in:\n{text}",
            c
        );
    }
}

/// No invisible (zero-width or bidi) character is printed as itself.
fn assert_no_invisibles(text: &str) {
    for c in ['\u{200B}', '\u{202E}', '\u{FEFF}', '\u{2066}'] {
        assert!(!text.contains(c), "raw {c:?} in:\n{text}");
    }
}

// ── Section 4 ────────────────────────────────────────────────────────────────────────────

#[test]
fn duplicate_problem_ids_across_separately_named_files_are_refused() {
    let tmp = crate::helpers::scratch("hostile");
    let src = root().join("problems/simple-pendulum.toml");
    std::fs::copy(&src, tmp.join("a.toml")).unwrap();
    std::fs::copy(&src, tmp.join("b.toml")).unwrap();
    let a = tmp.join("a.toml").display().to_string();
    let b = tmp.join("b.toml").display().to_string();
    let (code, out, _) = lagrange(&["problems", "verify", &a, &b]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("[duplicate-id]"), "{out}");
    // Issue 19 §5: both files are named, and neither is verified as the problem.
    assert!(
        out.contains("the problem `simple-pendulum` is defined by two files"),
        "{out}"
    );
    assert!(out.contains(&a) && out.contains(&b), "{out}");
    assert!(!out.contains("✓ simple-pendulum"), "{out}");
}

#[test]
fn a_tolerance_of_one_is_refused_so_check_cannot_accept_zero() {
    let path = root().join("tests/broken/bad-tolerance--one.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let err = lagrange::bank::load_str("t.toml", &text).unwrap_err();
    assert_eq!(err.code, "bad-tolerance");
    assert!(err.message.contains("tolerance = 1.0"), "{}", err.message);
}

#[test]
fn a_coordinate_range_of_three_elements_is_refused() {
    let path = root().join("tests/broken/bad-range--three.toml");
    let text = std::fs::read_to_string(path).unwrap();
    let err = lagrange::bank::load_str("t.toml", &text).unwrap_err();
    assert_eq!(err.code, "bad-range");
    assert!(err.message.contains("[-1.0, 0.0, 1.0]"), "{}", err.message);
}

// ── Section 5: hostile text is never echoed raw ──────────────────────────────────────────

#[test]
fn escape_sequences_in_an_answer_are_shown_escaped() {
    let answer = "theta\u{1b}]0;pwned\u{7} = 0";
    let (code, out, err) = lagrange(&["check", "simple-pendulum", "eom", answer]);
    assert_eq!(code, 1);
    assert_no_raw_controls(&out);
    assert_no_raw_controls(&err);
    assert!(
        out.contains("unexpected control character `\\u{1b}`"),
        "{out}"
    );
    // The caret box is printed once, on stdout with the verdict.
    assert!(out.contains("theta\\u{1b}]0;pwned\\u{7} = 0"), "{out}");
}

#[test]
fn a_clear_screen_sequence_in_a_lagrangian_is_shown_escaped() {
    let (code, _, err) = lagrange(&[
        "derive",
        "--lagrangian",
        "\u{1b}[2J\u{1b}[H",
        "--coords",
        "x",
    ]);
    assert_eq!(code, 2);
    assert_no_raw_controls(&err);
    assert!(err.contains("\\u{1b}[2J"), "{err}");
}

#[test]
fn zero_width_and_bidi_characters_are_named() {
    let (_, out, err) = lagrange(&["check", "simple-pendulum", "eom", "theta\u{200b} = 0"]);
    assert_no_invisibles(&out);
    assert_no_invisibles(&err);
    assert!(out.contains("U+200B zero-width space"), "{out}");
    let (_, out, err) = lagrange(&["read", "x\u{202e} + 1"]);
    assert_no_invisibles(&out);
    assert_no_invisibles(&err);
    assert!(err.contains("U+202E right-to-left override"), "{err}");
}

#[test]
fn an_unknown_problem_id_is_echoed_escaped() {
    let (code, _, err) = lagrange(&["check", "pend\u{1b}[2J", "eom", "0"]);
    assert_eq!(code, 2);
    assert_no_raw_controls(&err);
}

#[test]
fn an_input_over_the_length_limit_is_shown_as_a_bounded_excerpt() {
    let long = "x+".repeat(MAX_INPUT_BYTES / 2 + 10) + "x";
    let mut pool = Pool::new();
    let e = read_expr(&long, &Context::open(), &mut pool).unwrap_err();
    assert_eq!(e.kind.code(), "too-long");
    let shown = render_parse_error("answer", &long, &e, false);
    assert!(shown.len() < 2_000, "{} bytes shown", shown.len());
    assert!(shown.lines().all(|l| l.chars().count() < 300), "{shown}");
    assert!(shown.contains('…'), "{shown}");
    // Through the binary, too: the whole input is never echoed.
    let (_, _, err) = lagrange(&["read", &long]);
    assert!(err.len() < 2_000, "{} bytes on stderr", err.len());
}

#[test]
fn an_error_deep_in_a_long_line_is_shown_in_a_window_around_it() {
    let src = format!("{}${}", "x+".repeat(1000), "+x".repeat(1000));
    let mut pool = Pool::new();
    let e = read_expr(&src, &Context::open(), &mut pool).unwrap_err();
    assert_eq!(e.kind.code(), "unexpected-character");
    let shown = render_parse_error("answer", &src, &e, false);
    assert!(shown.len() < 2_000, "{shown}");
    let line = shown
        .lines()
        .find(|l| l.contains('…') && l.contains('$'))
        .expect("the `$` is shown in an excerpt");
    let caret = shown
        .lines()
        .find(|l| l.contains('┬'))
        .expect("a caret line");
    // The caret sits under the `$` (both lines start with the same gutter).
    let col = |l: &str, c: char| l.chars().position(|x| x == c);
    assert_eq!(col(line, '$'), col(caret, '┬'), "\n{line}\n{caret}");
}

// ── Section 5: numbers and their printing ────────────────────────────────────────────────

#[test]
fn zero_over_zero_is_undefined_and_shown_as_such() {
    let mut pool = Pool::new();
    let e = read_expr("0/0", &Context::open(), &mut pool).unwrap();
    assert_eq!(pool.plain(e), "0/0");
    assert_eq!(pool.unicode(e), "0/0");
    assert_eq!(pool.latex(e), "\\frac{0}{0}");
    assert_eq!(eval(&pool, e, &[]), None, "0/0 must not evaluate");
    // And what it prints reads back as the same (undefined) value.
    let again = read_expr(&pool.plain(e), &Context::open(), &mut pool).unwrap();
    assert_eq!(again, e);
    let (code, out, _) = lagrange(&["read", "0/0"]);
    assert_eq!(code, 0);
    assert!(out.contains("read as: 0/0"), "{out}");
    assert!(!out.contains("1/0"), "{out}");
}

#[test]
fn an_exponent_too_large_for_i64_prints_exactly_and_reads_back() {
    let ctx = Context::open();
    let mut pool = Pool::new();
    let e = read_expr("m^99999999999999999999", &ctx, &mut pool).unwrap();
    let shown = pool.unicode(e);
    assert_eq!(shown, "m⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹");
    assert_eq!(read_expr(&shown, &ctx, &mut pool).unwrap(), e);
    let neg = read_expr("m^(-99999999999999999999)", &ctx, &mut pool).unwrap();
    let shown = pool.unicode(neg);
    assert_eq!(shown, "1/m⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹");
    assert_eq!(read_expr(&shown, &ctx, &mut pool).unwrap(), neg);
    let sup = read_expr("m⁻⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹⁹", &ctx, &mut pool).unwrap();
    assert_eq!(sup, neg);
}

#[test]
fn a_number_beyond_1e300_names_the_limit() {
    let mut pool = Pool::new();
    for src in ["1e301", "1e-301"] {
        let e = read_expr(src, &Context::open(), &mut pool).unwrap_err();
        assert_eq!(e.kind.code(), "number-too-large", "{src}");
        let m = e.kind.to_string();
        assert!(m.contains("1e300") && m.contains("1e-300"), "{src}: {m}");
    }
    let (code, _, err) = lagrange(&["read", "1e301"]);
    assert_eq!(code, 1);
    assert!(err.contains("1e300"), "{err}");
    let digits = "1".repeat(1001);
    let e = read_expr(&digits, &Context::open(), &mut pool).unwrap_err();
    assert_eq!(e.kind.code(), "too-many-digits");
    assert!(e.kind.to_string().contains("1000"), "{}", e.kind);
}

// ── Section 5: modes' arguments get their own errors ─────────────────────────────────────

const PENDULUM: &str = "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)";

#[test]
fn modes_an_undefined_parameter_value_is_its_own_error() {
    let (code, _, err) = lagrange(&[
        "modes",
        "--lagrangian",
        PENDULUM,
        "--coords",
        "theta",
        "--params",
        "m=1, l=1, g=0/0",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("the value of `g`, 0/0, is undefined"), "{err}");
    assert!(!err.contains("quadratically"), "{err}");
}

#[test]
fn modes_a_repeated_coordinate_is_its_own_error() {
    let (code, _, err) = lagrange(&[
        "modes",
        "--lagrangian",
        "1/2*m*x'^2 - 1/2*k*x^2",
        "--coords",
        "x,x",
        "--params",
        "m=1,k=1",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("[repeated-coordinate]"), "{err}");
    assert!(err.contains("coordinate `x` is listed twice"), "{err}");
    assert!(!err.contains("singular"), "{err}");
}

#[test]
fn modes_time_and_a_function_are_not_coordinates() {
    for (coord, says) in [
        ("t", "`t` is time, not a coordinate"),
        ("sin", "`sin` is a function, not a coordinate"),
    ] {
        let (code, _, err) = lagrange(&[
            "modes",
            "--lagrangian",
            "1/2*m*x'^2",
            "--coords",
            coord,
            "--params",
            "m=1",
        ]);
        assert_eq!(code, 2, "{coord}");
        assert!(err.contains(says), "{coord}: {err}");
        assert!(!err.contains("degenerate"), "{coord}: {err}");
    }
}

#[test]
fn modes_double_pendulum_asks_only_for_the_parameters_l_uses() {
    let (code, out, err) = lagrange(&[
        "modes",
        "double-pendulum",
        "--params",
        "m1=1,m2=1,l1=1,l2=1,g=9.8",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("equilibrium θ₁ = 0, θ₂ = 0: stable"), "{out}");
    // ω² = (2 ∓ √2)·g/l for equal masses and lengths.
    let w1 = ((2.0 - 2f64.sqrt()) * 9.8f64).sqrt();
    assert!(out.contains(&format!("{w1:.6}")), "{out}");
}

#[test]
fn a_problem_files_title_and_prompt_are_shown_escaped() {
    let tmp = crate::helpers::scratch("hostile");
    let text = std::fs::read_to_string(root().join("problems/simple-pendulum.toml"))
        .unwrap()
        .replace(
            "title = \"Simple pendulum\"",
            "title = \"Pendulum\\u001b]0;pwned\\u0007\"",
        )
        .replace(
            "prompt = \"Write the kinetic energy T of the bob.\"",
            "prompt = \"T?\\u202E evil\"",
        );
    std::fs::write(tmp.join("a.toml"), text).unwrap();
    let dir = tmp.display().to_string();
    let (code, show, _) = lagrange(&["--problems", &dir, "problems", "show", "simple-pendulum"]);
    let (_, list, _) = lagrange(&["--problems", &dir, "problems", "list"]);
    assert_eq!(code, 0);
    for out in [&show, &list] {
        assert_no_raw_controls(out);
        assert_no_invisibles(out);
        assert!(out.contains("Pendulum\\u{1b}]0;pwned\\u{7}"), "{out}");
    }
    assert!(
        show.contains("T?⟨U+202E right-to-left override⟩ evil"),
        "{show}"
    );
}

/// Found by the fuzzer: each reads, prints as shown, and the printed form reads back as the
/// same node (0^k is not undefined; 10^1000 stays a power the reader accepts; a numeric power
/// with a negative exponent is canonical after one reading).
#[test]
fn fuzz_found_readings_print_and_read_back() {
    use lagrange::expr::{Context, Pool, read_expr};
    let cases = [
        ("0^k", "0^k"),
        ("0/0", "0/0"),
        ("10^1000", "10^1000"),
        ("2^5000*x", "2^5000*x"),
        ("log(abs(-pi))", "log(pi)"),
        ("abs(-x)*sin(-pi)", "0"),
        (
            "100000^(-10000001/10000000)",
            "100000^(9999999/10000000)/10000000000",
        ),
        (
            "3.14159^1.0000001",
            "314159*100000^(9999999/10000000)*314159^(1/10000000)/10000000000",
        ),
    ];
    for (input, printed) in cases {
        let mut pool = Pool::new();
        let ctx = Context::open();
        let id = read_expr(input, &ctx, &mut pool).unwrap_or_else(|e| panic!("{input}: {e}"));
        assert_eq!(pool.plain(id), printed, "{input}");
        let back = read_expr(printed, &ctx, &mut pool).unwrap_or_else(|e| panic!("{printed}: {e}"));
        assert_eq!(back, id, "{input} → {printed} read back differently");
    }
}

/// The library itself refuses names that cannot be coordinates, not only the CLI.
#[test]
fn the_library_refuses_repeated_and_reserved_coordinates() {
    use lagrange::mechanics::naming::NameError;
    use lagrange::{MechError, System};
    let l = "1/2*m*x'^2 - 1/2*k*x^2";
    for (coords, want) in [
        (&["x", "x"][..], NameError::Repeated("x".into())),
        (&["t"][..], NameError::Time),
        (&["sin"][..], NameError::Function("sin".into())),
    ] {
        match System::from_lagrangian(l, coords) {
            Err(MechError::Name(e)) => assert_eq!(e, want, "{coords:?}"),
            other => panic!("{coords:?}: {other:?}"),
        }
    }
}

//! Property tests (fixed seed, so every run and machine tests the same cases):
//! - the symbolic derivative agrees with a central finite difference;
//! - simplification preserves the value;
//! - plain and Unicode printing read back to the same node;
//! - the compiled evaluator agrees with an independent tree walker;
//! - no string, and no soup of valid tokens, makes the reader panic;
//! - whatever a soup of derivative forms and function names reads as prints back (issue 20 §6).

use lagrange::expr::eval::eval_tree;
use lagrange::expr::{Context, Id, Pool, Program, Sym, read, read_expr};
use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed};

fn config(cases: u32) -> Config {
    Config {
        cases,
        rng_seed: RngSeed::Fixed(0x1a9_2a96e),
        failure_persistence: None,
        ..Config::default()
    }
}

/// Random expressions over x, y, x' (as text, fully parenthesized where it matters).
fn expr_text() -> impl Strategy<Value = String> {
    let leaf = prop_oneof![
        Just("x".to_string()),
        Just("y".to_string()),
        Just("x'".to_string()),
        Just("pi".to_string()),
        (1i32..9).prop_map(|n| n.to_string()),
        (1i32..9, 1i32..5).prop_map(|(n, d)| format!("{n}/{d}")),
        Just("0.5".to_string()),
    ];
    leaf.prop_recursive(5, 40, 3, |inner| {
        prop_oneof![
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a}) + ({b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a}) - ({b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a})*({b})")),
            (inner.clone(), inner.clone()).prop_map(|(a, b)| format!("({a})/({b})")),
            (inner.clone(), -2i32..4).prop_map(|(a, k)| format!("({a})^{k}")),
            inner.clone().prop_map(|a| format!("-({a})")),
            inner.clone().prop_map(|a| format!("({a})^(1/2)")),
            (
                inner.clone(),
                prop::sample::select(vec![
                    "sin", "cos", "tan", "exp", "log", "sqrt", "atan", "sinh", "cosh", "tanh",
                    "abs", "sec", "asin",
                ])
            )
                .prop_map(|(a, f)| format!("{f}({a})")),
            (inner.clone(), inner).prop_map(|(a, b)| format!("{a} {b}")),
        ]
    })
}

struct Case {
    pool: Pool,
    e: Id,
    x: Sym,
    vars: Vec<(Sym, u8)>,
}

fn build(text: &str) -> Option<Case> {
    let mut pool = Pool::new();
    let ctx = Context::open().with_coordinates(["x"]);
    let e = read_expr(text, &ctx, &mut pool).ok()?;
    let x = pool.symbol("x");
    let y = pool.symbol("y");
    Some(Case {
        pool,
        e,
        x,
        vars: vec![(x, 0), (x, 1), (y, 0)],
    })
}

fn value(pool: &Pool, e: Id, vars: &[(Sym, u8)], point: &[f64]) -> Option<f64> {
    let p = Program::compile(pool, &[e], vars).ok()?;
    p.eval(point).ok().map(|v| v[0])
}

fn close(a: f64, b: f64, rel: f64) -> bool {
    (a - b).abs() <= rel * (1.0 + a.abs().max(b.abs()))
}

proptest! {
    #![proptest_config(config(600))]

    #[test]
    fn derivative_matches_finite_difference(
        text in expr_text(),
        x in -2.0f64..2.0, xd in -2.0f64..2.0, y in 0.1f64..2.0,
    ) {
        let Some(mut c) = build(&text) else { return Ok(()); };
        let d = c.pool.diff(c.e, c.x, 0);
        let h = 1e-6 * (1.0 + x.abs());
        let f = |xx: f64| value(&c.pool, c.e, &c.vars, &[xx, xd, y]);
        let (Some(f0), Some(fp), Some(fm), Some(fp2), Some(fm2)) =
            (f(x), f(x + h), f(x - h), f(x + 2.0 * h), f(x - 2.0 * h))
        else {
            return Ok(());
        };
        let Some(dv) = value(&c.pool, d, &c.vars, &[x, xd, y]) else { return Ok(()); };
        // Skip steep or huge regions, where a finite difference says nothing.
        prop_assume!(f0.abs() < 1e4 && dv.abs() < 1e4);
        let fd = (8.0 * (fp - fm) - (fp2 - fm2)) / (12.0 * h);
        let fd_coarse = (fp - fm) / (2.0 * h);
        prop_assume!(close(fd, fd_coarse, 1e-4));
        prop_assert!(close(dv, fd, 1e-5), "{text}: d = {dv}, finite difference = {fd}");
    }

    #[test]
    fn simplify_preserves_value(
        text in expr_text(),
        x in -2.0f64..2.0, xd in -2.0f64..2.0, y in 0.1f64..2.0,
    ) {
        let Some(mut c) = build(&text) else { return Ok(()); };
        let ysym = c.pool.symbol("y");
        let s = c.pool.simplify(c.e, &[ysym]);
        let point = [x, xd, y];
        let (Some(a), Some(b)) = (value(&c.pool, c.e, &c.vars, &point), value(&c.pool, s, &c.vars, &point))
        else { return Ok(()); };
        prop_assume!(a.abs() < 1e8);
        prop_assert!(close(a, b, 1e-9), "{text}: {a} vs simplified {} = {b}", c.pool.plain(s));
    }

    #[test]
    fn printing_round_trips(text in expr_text()) {
        let Some(mut c) = build(&text) else { return Ok(()); };
        let ctx = Context::open().with_coordinates(["x"]);
        let plain = c.pool.plain(c.e);
        let back = read_expr(&plain, &ctx, &mut c.pool);
        prop_assert_eq!(back.clone().ok(), Some(c.e), "{} printed as {} read back as {:?}", text, plain, back);
        let uni = c.pool.unicode(c.e);
        let back = read_expr(&uni, &ctx, &mut c.pool);
        prop_assert_eq!(back.clone().ok(), Some(c.e), "{} printed as {} read back as {:?}", text, uni, back);
    }

    #[test]
    fn compiled_evaluation_matches_tree_walk(
        text in expr_text(),
        x in -2.0f64..2.0, xd in -2.0f64..2.0, y in 0.1f64..2.0,
    ) {
        let Some(c) = build(&text) else { return Ok(()); };
        let point = [x, xd, y];
        let compiled = value(&c.pool, c.e, &c.vars, &point);
        let walk = eval_tree(&c.pool, c.e, &|s, o| {
            c.vars.iter().position(|v| *v == (s, o)).map_or(f64::NAN, |k| point[k])
        });
        // Where the compiled program reports "undefined", the tree walk may still produce a
        // number (1/inf is 0); where it is defined, the two must agree.
        if let Some(v) = compiled {
            prop_assert!(close(v, walk, 1e-12), "{text}: {v} vs {walk}");
        }
    }
}

proptest! {
    #![proptest_config(config(2000))]

    #[test]
    fn random_strings_never_panic(s in "\\PC{0,200}") {
        let mut pool = Pool::new();
        let _ = read(&s, &Context::open(), &mut pool);
        let _ = read(&s, &crate::helpers::mech_ctx(), &mut pool);
    }

    #[test]
    fn token_soup_never_panics(toks in prop::collection::vec(prop::sample::select(vec![
        "x", "theta", "θ̇", "'", "2", "0.5", "1e-3", "+", "-", "*", "/", "^", "**", "(", ")", "(", ")",
        ",", ";", "=", "sin", "sqrt", "√", "²", "⁻¹", "½", "·", "dot", "ddot", " ", "pi", "e", "_",
    ]), 0..120)) {
        let s: String = toks.concat();
        let mut pool = Pool::new();
        let _ = read(&s, &Context::open(), &mut pool);
        let _ = read(&s, &crate::helpers::mech_ctx(), &mut pool);
    }

    /// Issue 20 §6: whatever reads, printed plain or in Unicode, reads back as the same node —
    /// also soups of derivative forms over function names (`dot(sqrt)` printed `sqrt'`).
    #[test]
    fn whatever_reads_prints_back(toks in prop::collection::vec(prop::sample::select(vec![
        "x", "q", "sqrt", "sin", "log", "abs", "dot(", "ddot(", "'", "''", "θ̇", "(", ")", "(",
        ")", "2", "+", "-", "*", "/", "^", " ", "pi", "t", "xdot", "q_ddot", "√",
    ]), 1..24)) {
        let s: String = toks.concat();
        let mut pool = Pool::new();
        let ctx = Context::open().with_coordinates(["x"]);
        let Ok(e) = read_expr(&s, &ctx, &mut pool) else { return Ok(()); };
        let plain = pool.plain(e);
        let back = read_expr(&plain, &ctx, &mut pool);
        prop_assert_eq!(back.clone().ok(), Some(e), "{} printed as {} read back as {:?}", s, plain, back);
        let uni = pool.unicode(e);
        let back = read_expr(&uni, &ctx, &mut pool);
        prop_assert_eq!(back.clone().ok(), Some(e), "{} printed as {} read back as {:?}", s, uni, back);
    }
}

#[test]
fn hostile_inputs_are_refused_not_crashed() {
    // Too long or too deep: refused with the bound named, in process (a typed error) and by
    // `lagrange read` (exit 1, the documented "could not be read", and the message first).
    let deep = "(".repeat(100_000);
    let powers = "2^".repeat(5000) + "2";
    let negs = "-".repeat(50_000) + "x";
    let refused = [
        (
            deep.as_str(),
            "too-long",
            "the input is 100000 bytes long; at most 20000 are read",
        ),
        (
            powers.as_str(),
            "too-deep",
            "the expression is nested more than 100 levels deep",
        ),
        (
            negs.as_str(),
            "too-long",
            "the input is 50001 bytes long; at most 20000 are read",
        ),
    ];
    for (input, code, message) in refused {
        let mut pool = Pool::new();
        match read(input, &Context::open(), &mut pool) {
            Ok(_) => panic!("{code}: an input of {} bytes was read", input.len()),
            Err(e) => assert_eq!(e.kind.code(), code, "{e}"),
        }
        let (exit, out, err) = crate::helpers::lagrange(&["read", "--", input]);
        assert_eq!(exit, 1, "{code}: {out}{err}");
        let first = err.lines().next().unwrap_or_default();
        assert_eq!(first, format!("[{code}] Error: {message}"), "{err}");
        assert!(out.is_empty(), "{out}");
    }
    // Huge exponents are exact expressions, not overflows: read as written (never evaluated
    // to a number), and printed back.
    let read_as = [
        ("2^2^2^2^2^2^2^2", "2^2^2^2^65536"),
        ("9^9^9^9", "9^9^387420489"),
        ("(x+1)^100000", "(x + 1)^100000"),
    ];
    for (input, plain) in read_as {
        let mut pool = Pool::new();
        assert!(read(input, &Context::open(), &mut pool).is_ok(), "{input}");
        let (exit, out, err) = crate::helpers::lagrange(&["read", "--", input]);
        assert_eq!(exit, 0, "{input}: {err}");
        assert!(out.starts_with(&format!("read as: {plain}\n")), "{out}");
    }
}

proptest! {
    #![proptest_config(config(300))]

    /// Whatever a student types, every kind of part returns a verdict.
    #[test]
    fn the_checker_never_panics(
        soup in prop::collection::vec(prop::sample::select(vec![
            "theta", "theta1", "theta2", "r", "x", "'", "''", "m", "l", "g", "omega", "=", ";", ",",
            "+", "-", "*", "/", "^", "(", ")", "sin", "cos", "sqrt", "pi", "0", "1", "2", "0.5",
            " ", "θ̇", "½", "√", "dot(", "t", "abs", "log", "exp", "/0",
        ]), 0..40),
        which in 0usize..6,
    ) {
        let targets = [
            ("simple-pendulum", "eom"),
            ("simple-pendulum", "equilibria"),
            ("double-pendulum", "eom"),
            ("double-pendulum", "frequencies"),
            ("bead-parabola", "equilibrium-condition"),
            ("atwood-tension", "tension"),
        ];
        let (id, part) = targets[which];
        let problem = lagrange::bank::embedded::problem(id).unwrap();
        let mut checker = lagrange::check::Checker::new(&problem);
        let input: String = soup.concat();
        let v = checker.check(part, &input).unwrap();
        prop_assert!((0.0..=1.0).contains(&v.score));
    }
}

/// Issue 20 §6: every derivative form over every kind of name — a coordinate, an unknown
/// name, a function, π, t — either is refused or prints (plain and Unicode) back to itself.
/// `dot(sqrt)` once read as a coordinate `sqrt` printed `sqrt'`, which does not read.
#[test]
fn every_derivative_form_of_every_name_prints_back() {
    let names = [
        "x", "q", "sqrt", "sin", "log", "abs", "exp", "pi", "t", "dot", "ddot", "d", "e", "theta",
    ];
    let forms = [
        "dot({})",
        "ddot({})",
        "{}'",
        "{}''",
        "dot({}')",
        "{}dot",
        "{}_ddot",
        "{}\u{307}",
        "{}\u{308}",
        "2 {}'",
        "({})'",
        "{}'(t)",
    ];
    for ctx in [Context::open(), Context::open().with_coordinates(["x"])] {
        for n in names {
            for f in forms {
                let s = f.replace("{}", n);
                let mut pool = Pool::new();
                let Ok(e) = read_expr(&s, &ctx, &mut pool) else {
                    continue;
                };
                for printed in [pool.plain(e), pool.unicode(e)] {
                    let back = read_expr(&printed, &ctx, &mut pool);
                    assert_eq!(back, Ok(e), "{s} printed as {printed}");
                }
            }
        }
    }
}

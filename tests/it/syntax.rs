//! Table-driven tests of every syntax form: derivative notations, implicit multiplication,
//! precedence, numbers, Unicode, functions and canonical forms. Each row is
//! `input => how lagrange prints what it read` (plain syntax).

use lagrange::expr::{Context, Pool, Reading, read};

use crate::helpers::{mech_ctx, plain_mech, plain_open};

fn check(rows: &[(&str, &str)], f: fn(&str) -> String) {
    for (input, want) in rows {
        assert_eq!(f(input), *want, "input {input:?}");
    }
}

#[test]
fn derivative_notations() {
    check(
        &[
            ("theta'", "theta'"),
            ("theta''", "theta''"),
            ("thetadot", "theta'"),
            ("theta_dot", "theta'"),
            ("dot(theta)", "theta'"),
            ("thetaddot", "theta''"),
            ("theta_ddot", "theta''"),
            ("ddot(theta)", "theta''"),
            ("θ̇", "theta'"),
            ("θ̈", "theta''"),
            ("θ̇₁", "theta1'"),
            ("θ₁̇", "theta1'"),
            ("theta1_dot", "theta1'"),
            ("theta_1'", "theta1'"),
            ("dot(theta)'", "theta''"),
            ("theta(t)", "theta"),
            ("theta'(t)", "theta'"),
            ("xdot^2", "x'^2"),
            ("ṙ", "r'"),
            ("ẍ", "x''"),
            ("mẍ", "m*x''"),
        ],
        plain_mech,
    );
}

#[test]
fn implicit_multiplication() {
    check(
        &[
            ("2m", "2*m"),
            ("m g l", "m*g*l"),
            ("2(x+1)", "2*x + 2"),
            ("(a)(b)", "a*b"),
            ("2 sin(x)", "2*sin(x)"),
            ("g/l sin(theta)", "g*sin(theta)/l"),
            ("1/2 m x'^2", "m*x'^2/2"),
            ("(a+b)k", "(a + b)*k"),
            ("m(x+1)", "(x + 1)*m"),
            ("2√2", "2*sqrt(2)"),
            ("a b/k", "a*b/k"),
        ],
        plain_mech,
    );
}

#[test]
fn precedence() {
    check(
        &[
            ("-x^2", "-x^2"),
            ("-2^2", "-4"),
            ("(-2)^2", "4"),
            ("2^3^2", "512"),
            ("a^b^c", "a^b^c"),
            ("a-b-c", "a - b - c"),
            ("a/b/c", "a/(b*c)"),
            ("a/b*c", "a*c/b"),
            ("x^-2", "1/x^2"),
            ("2**3", "8"),
            ("a*-b", "-a*b"),
            ("a - -b", "a + b"),
            ("+a", "a"),
            ("x^(1/2)", "sqrt(x)"),
            ("x^0.5", "sqrt(x)"),
            ("x^(-1/2)", "1/sqrt(x)"),
            ("x^(3/2)", "x^(3/2)"),
        ],
        plain_open,
    );
}

#[test]
fn numbers() {
    check(
        &[
            ("0.5", "1/2"),
            ("1e-3", "1/1000"),
            ("2.5e2", "250"),
            (".25", "1/4"),
            ("9.81", "981/100"),
            ("0.1 + 0.2", "3/10"),
        ],
        plain_open,
    );
}

#[test]
fn unicode_input() {
    check(
        &[
            ("l²", "l^2"),
            ("T⁻²", "1/T^2"),
            ("a·b", "a*b"),
            ("a×b", "a*b"),
            ("√2", "sqrt(2)"),
            ("√(g/l)", "sqrt(g/l)"),
            ("½m", "m/2"),
            ("¾", "3/4"),
            ("a − b", "a - b"),
            ("π", "pi"),
            ("θ₁ + ω", "omega + theta1"),
            ("2πr", "2*pi*r"),
        ],
        plain_open,
    );
}

#[test]
fn functions_and_canonical_forms() {
    check(
        &[
            ("sec(x)", "1/cos(x)"),
            ("csc(x)", "1/sin(x)"),
            ("cot(x)", "cos(x)/sin(x)"),
            ("ln(x)", "log(x)"),
            ("abs(-3)", "3"),
            ("x + x", "2*x"),
            ("x*x", "x^2"),
            ("x*x^-1", "1"),
            ("sin(-x)", "-sin(x)"),
            ("cos(-x)", "cos(x)"),
            ("sin(b - a)", "-sin(a - b)"),
            ("cos(b - a)", "cos(a - b)"),
            ("2*(x+1) - 2*x", "2"),
            ("sqrt(8)", "2*sqrt(2)"),
            ("sqrt(2)*sqrt(3)", "sqrt(6)"),
            ("sqrt(2)*sqrt(8)", "4"),
            ("sqrt(2)*sqrt(6)", "2*sqrt(3)"),
            ("2^(1/3)*4^(1/3)", "2"),
            ("sqrt(4)", "2"),
            ("sqrt(1/2)", "sqrt(2)/2"),
            ("8^(1/3)", "2"),
            ("(-8)^(1/3)", "-2"),
            ("cos(pi)", "-1"),
            ("sin(pi/6)", "1/2"),
            ("cos(pi/4)", "sqrt(2)/2"),
            ("sin(3*pi/2)", "-1"),
            ("log(exp(x))", "x"),
            ("exp(x)^2", "exp(2*x)"),
            ("(x*y)^2", "x^2*y^2"),
            ("(x^2)^3", "x^6"),
            ("0*x", "0"),
            ("x^0", "1"),
        ],
        plain_open,
    );
}

#[test]
fn statements() {
    let ctx = mech_ctx();
    let mut pool = Pool::new();
    let kind = |pool: &mut Pool, src: &str| match read(src, &ctx, pool).unwrap() {
        Reading::Expr(..) => "expr".to_string(),
        Reading::Equation { .. } => "equation".to_string(),
        Reading::List(v, _) => format!("list {}", v.len()),
        Reading::System(v, _) => format!("system {}", v.len()),
    };
    for (src, want) in [
        ("m*g", "expr"),
        ("theta'' = -g/l*theta", "equation"),
        ("theta = 0, theta = pi", "list 2"),
        ("x'' = 0; theta'' = 0", "system 2"),
        (
            "theta1 = 0, theta2 = 0; theta1 = pi, theta2 = 0",
            "system 2",
        ),
    ] {
        assert_eq!(kind(&mut pool, src), want, "{src}");
    }
    assert_eq!(
        plain_mech("m*l^2*theta'' + m*g*l*sin(theta) = 0"),
        "m*l^2*theta'' + m*g*l*sin(theta) = 0"
    );
}

#[test]
fn equal_inputs_share_one_node() {
    let ctx = mech_ctx();
    let mut pool = Pool::new();
    let forms = [
        "m*l^2*theta'' + m*g*l*sin(theta)",
        "m g l sin(θ) + m l² θ̈",
        "l*(m*g*sin(theta)) + theta_ddot*l^2*m",
        "m·l²·θ̈ + m·g·l·sin(θ)",
    ];
    let ids: Vec<_> = forms
        .iter()
        .map(|f| crate::helpers::expr(&mut pool, f, &ctx))
        .collect();
    assert!(ids.windows(2).all(|w| w[0] == w[1]), "{ids:?}");
}

#[test]
fn printing_styles() {
    let ctx = mech_ctx();
    let mut pool = Pool::new();
    let rows = [
        (
            "m*l^2*theta'' + m*g*l*sin(theta)",
            "m·l²·θ̈ + m·g·l·sin(θ)",
            r"m l^{2} \ddot{\theta} + m g l \sin{\theta}",
        ),
        (
            "1/2*m*l^2*theta'^2 - m*g*l*(1 - cos(theta))",
            "½·m·l²·θ̇² + m·g·l·(cos(θ) − 1)",
            r"\frac{1}{2} m l^{2} \dot{\theta}^{2} + m g l \left(\cos{\theta} - 1\right)",
        ),
        ("sqrt(g/l)", "√(g/l)", r"\sqrt{\frac{g}{l}}"),
        (
            "(m1 - m2)/(m1 + m2)*g",
            "(m₁ − m₂)·g/(m₁ + m₂)",
            r"\frac{\left(m_{1} - m_{2}\right) g}{m_{1} + m_{2}}",
        ),
        (
            "theta1''*cos(theta1 - theta2)",
            "θ̈₁·cos(θ₁ − θ₂)",
            r"\ddot{\theta}_{1} \cos\left(\theta_{1} - \theta_{2}\right)",
        ),
        ("sin(theta)^2", "sin(θ)²", r"\sin^{2}{\theta}"),
        ("3/7*x", "3·x/7", r"\frac{3}{7} x"),
        ("-omega^2*r", "−ω²·r", r"-\omega^{2} r"),
        ("exp(-b*x)", "exp(−b·x)", r"e^{-b x}"),
    ];
    for (src, uni, tex) in rows {
        let e = crate::helpers::expr(&mut pool, src, &ctx);
        assert_eq!(pool.unicode(e), uni, "unicode of {src}");
        assert_eq!(pool.latex(e), tex, "latex of {src}");
        // What is printed in Unicode reads back as the same expression.
        let uni = pool.unicode(e);
        let back = crate::helpers::expr(&mut pool, &uni, &ctx);
        assert_eq!(back, e, "unicode round trip of {src}");
    }
}

#[test]
fn open_context_makes_primed_names_coordinates() {
    let parsed = lagrange::expr::parser::parse("q'' + k*q", &Context::open()).unwrap();
    assert_eq!(
        parsed.implied_coordinates.into_iter().collect::<Vec<_>>(),
        vec!["q".to_string()]
    );
}

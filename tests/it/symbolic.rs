//! Differentiation and simplification, checked against results derived by hand.
//! Rows compare canonical forms: both sides are read and expanded, then must be one node.

use lagrange::expr::{Context, Id, Pool, Sym};

use crate::helpers::{expr, mech_ctx};

fn same(pool: &mut Pool, got: Id, want: &str, ctx: &Context) {
    let w = expr(pool, want, ctx);
    let (g, w) = (pool.expand(got), pool.expand(w));
    assert_eq!(pool.plain(g), pool.plain(w));
    assert_eq!(g, w);
}

#[test]
fn partial_derivatives() {
    let ctx = mech_ctx();
    let rows = [
        ("sin(x^2)", "x", 0, "2*x*cos(x^2)"),
        (
            "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)",
            "theta",
            1,
            "m*l^2*theta'",
        ),
        (
            "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)",
            "theta",
            0,
            "-m*g*l*sin(theta)",
        ),
        ("x^3/3 - log(x)", "x", 0, "x^2 - 1/x"),
        ("sqrt(x)", "x", 0, "1/(2*sqrt(x))"),
        ("exp(-k*x)", "x", 0, "-k*exp(-k*x)"),
        ("tan(x)", "x", 0, "1/cos(x)^2"),
        ("atan(x)", "x", 0, "1/(1 + x^2)"),
        ("asin(x)", "x", 0, "1/sqrt(1 - x^2)"),
        ("x^x", "x", 0, "x^x*(log(x) + 1)"),
        ("abs(x)", "x", 0, "x/abs(x)"),
        ("cosh(x)", "x", 0, "sinh(x)"),
        ("tanh(x)", "x", 0, "1 - tanh(x)^2"),
        ("m*g*l", "x", 0, "0"),
    ];
    let mut pool = Pool::new();
    for (src, var, order, want) in rows {
        let e = expr(&mut pool, src, &ctx);
        let s = pool.symbol(var);
        let d = pool.diff(e, s, order);
        same(&mut pool, d, want, &ctx);
    }
}

#[test]
fn time_derivatives() {
    let ctx = mech_ctx();
    let rows = [
        ("theta", "theta'"),
        ("theta'", "theta''"),
        ("sin(theta)", "theta'*cos(theta)"),
        ("theta'^2", "2*theta'*theta''"),
        ("t^2", "2*t"),
        ("m*g*l", "0"),
        ("r*omega*t", "r'*omega*t + r*omega"),
        ("m*l^2*theta'", "m*l^2*theta''"),
        (
            "m2*l1*l2*theta2'*cos(theta1 - theta2)",
            "m2*l1*l2*theta2''*cos(theta1 - theta2) - m2*l1*l2*theta2'*(theta1' - theta2')*sin(theta1 - theta2)",
        ),
    ];
    let mut pool = Pool::new();
    let coords: Vec<Sym> = ctx.coordinates().iter().map(|c| pool.symbol(c)).collect();
    for (src, want) in rows {
        let e = expr(&mut pool, src, &ctx);
        let d = pool.dt(e, &coords);
        same(&mut pool, d, want, &ctx);
    }
}

#[test]
fn simplification_for_people() {
    let ctx = mech_ctx();
    let rows = [
        ("sin(x)^2 + cos(x)^2", "1"),
        ("3*sin(x)^2 + 3*cos(x)^2 + m", "m + 3"),
        ("a^2*l^2*sin(theta)^2 + a^2*l^2*cos(theta)^2", "a^2*l^2"),
        ("2*sin(x)^2 + cos(x)^2", "sin(x)^2 + 1"),
        ("(a + b)^2", "a^2 + 2*a*b + b^2"),
        ("(a + b)*(a - b)", "a^2 - b^2"),
        (
            "cos(theta1)*cos(theta2) + sin(theta1)*sin(theta2)",
            "cos(theta1 - theta2)",
        ),
        (
            "cos(theta1)*cos(theta2) - sin(theta1)*sin(theta2)",
            "cos(theta1 + theta2)",
        ),
        (
            "sin(theta1)*cos(theta2) - cos(theta1)*sin(theta2)",
            "sin(theta1 - theta2)",
        ),
        ("sqrt(l^2)", "l"),
        ("sqrt(4*m^2*g^2)", "2*m*g"),
        ("sqrt(x^2)", "abs(x)"),
        ("sqrt(g^2/l^2)", "g/l"),
    ];
    let mut pool = Pool::new();
    let positive: Vec<Sym> = ctx.parameters().iter().map(|p| pool.symbol(p)).collect();
    for (src, want) in rows {
        let e = expr(&mut pool, src, &ctx);
        let s = pool.simplify(e, &positive);
        let w = expr(&mut pool, want, &ctx);
        assert_eq!(pool.plain(s), pool.plain(w), "simplify {src}");
    }
}

/// The double pendulum's kinetic energy from Cartesian positions simplifies to the
/// textbook form, and its equations of motion print at a size comparable to SymPy's
/// simplified ones.
#[test]
fn double_pendulum_from_positions() {
    let ctx = mech_ctx();
    let mut pool = Pool::new();
    let coords: Vec<Sym> = ["theta1", "theta2"]
        .iter()
        .map(|c| pool.symbol(c))
        .collect();
    let positive: Vec<Sym> = ctx.parameters().iter().map(|p| pool.symbol(p)).collect();
    let x1 = expr(&mut pool, "l1*sin(theta1)", &ctx);
    let y1 = expr(&mut pool, "-l1*cos(theta1)", &ctx);
    let x2 = expr(&mut pool, "l1*sin(theta1) + l2*sin(theta2)", &ctx);
    let y2 = expr(&mut pool, "-l1*cos(theta1) - l2*cos(theta2)", &ctx);
    let mut t_terms = Vec::new();
    for (m, x, y) in [("m1", x1, y1), ("m2", x2, y2)] {
        let m = pool.sym(m);
        let vx = pool.dt(x, &coords);
        let vy = pool.dt(y, &coords);
        let vx2 = pool.powi(vx, 2);
        let vy2 = pool.powi(vy, 2);
        let v2 = pool.add(vx2, vy2);
        let h = pool.ratio(1, 2);
        t_terms.push(pool.product([h, m, v2]));
    }
    let t = pool.sum(t_terms);
    let t = pool.simplify(t, &positive);
    let want = expr(
        &mut pool,
        "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + m2*l1*l2*theta1'*theta2'*cos(theta1-theta2)",
        &ctx,
    );
    let want = pool.simplify(want, &positive);
    assert_eq!(pool.unicode(t), pool.unicode(want));
    assert_eq!(t, want);
}

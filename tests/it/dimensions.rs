//! Dimension inference: `expression => dimension` rows, and errors naming the offending
//! terms with their dimensions.

use lagrange::expr::{Context, Dimension, Dimensions, Pool};

use crate::helpers::{expr, mech_ctx};

fn dims() -> Dimensions {
    let d = |s: &str| Dimension::parse(s).unwrap();
    Dimensions::new()
        .with("m", d("M"))
        .with("m1", d("M"))
        .with("m2", d("M"))
        .with("l", d("L"))
        .with("l1", d("L"))
        .with("l2", d("L"))
        .with("g", d("L T^-2"))
        .with("k", d("M T^-2"))
        .with("omega", d("T^-1"))
        .with_coordinate("theta", d("1"))
        .with_coordinate("theta1", d("1"))
        .with_coordinate("theta2", d("1"))
        .with_coordinate("x", d("L"))
        .with_coordinate("r", d("L"))
}

#[test]
fn inferred_dimensions() {
    let ctx = mech_ctx();
    let rows = [
        ("1/2*m*l^2*theta'^2 + m*g*l*cos(theta)", "M L² T⁻²"),
        ("m*l^2*theta''", "M L² T⁻²"),
        ("theta''", "T⁻²"),
        ("x'", "L T⁻¹"),
        ("sqrt(g/l)", "T⁻¹"),
        ("sqrt(k/m)", "T⁻¹"),
        ("omega^2*r", "L T⁻²"),
        ("m*g*sin(theta)/k", "L"),
        ("t*omega", "dimensionless"),
        ("abs(x)", "L"),
        ("pi", "dimensionless"),
    ];
    let mut pool = Pool::new();
    for (src, want) in rows {
        let e = expr(&mut pool, src, &ctx);
        let d = pool.dimension(e, &dims()).unwrap().unwrap();
        assert_eq!(d.to_string(), want, "{src}");
    }
}

#[test]
fn dimension_errors_name_the_terms() {
    let ctx = mech_ctx();
    let rows = [
        (
            "m*g + m*g*l",
            "terms of different dimensions are added: m·g·l is M L² T⁻², m·g is M L T⁻²",
        ),
        (
            "sin(l)",
            "the argument of sin must be dimensionless, but l is L",
        ),
        (
            "exp(t)",
            "the argument of exp must be dimensionless, but t is T",
        ),
        (
            "l^theta",
            "l has dimension L, so its exponent must be a number, not θ",
        ),
        ("theta^l", "an exponent must be dimensionless, but l is L"),
    ];
    let mut pool = Pool::new();
    for (src, want) in rows {
        let e = expr(&mut pool, src, &ctx);
        let err = pool.dimension(e, &dims()).unwrap_err();
        assert_eq!(err.to_string(), want, "{src}");
    }
}

#[test]
fn equations_compare_sides() {
    let ctx = mech_ctx();
    let mut pool = Pool::new();
    let lhs = expr(&mut pool, "m*x''", &ctx);
    let rhs = expr(&mut pool, "-k*x + m*g*sin(alpha)", &ctx);
    let d = dims().with("alpha", Dimension::NONE);
    assert_eq!(
        pool.check_equation_dimension(lhs, rhs, &d).unwrap(),
        Some(Dimension::new(1, 1, -2))
    );
    let bad = expr(&mut pool, "-k*x^2", &ctx);
    let err = pool.check_equation_dimension(lhs, bad, &d).unwrap_err();
    assert_eq!(
        err.to_string(),
        "the two sides differ in dimension: m·x\u{308} is M L T⁻², −k·x² is M L² T⁻²"
    );
}

#[test]
fn unknown_dimensions_are_not_guessed() {
    let mut pool = Pool::new();
    let e = expr(&mut pool, "q + m", &Context::open());
    assert_eq!(pool.dimension(e, &dims()).unwrap(), None);
}

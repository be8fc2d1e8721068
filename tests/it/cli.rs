//! The `lagrange` binary, run as a user would.

use std::process::Command;

fn lagrange(args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_lagrange"))
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("the binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn read_shows_every_form() {
    let (code, out, _) = lagrange(&[
        "read",
        "m*l^2*theta'' + m*g*l*sin(theta) = 0",
        "--coords",
        "theta",
        "--dims",
        "m=M, l=L, g=L T^-2, theta=1",
    ]);
    assert_eq!(code, 0);
    assert!(
        out.contains("read as: m*l^2*theta'' + m*g*l*sin(theta) = 0"),
        "{out}"
    );
    assert!(out.contains("unicode: m·l²·θ̈ + m·g·l·sin(θ) = 0"), "{out}");
    assert!(out.contains(r"\ddot{\theta}"), "{out}");
    assert!(out.contains("dimension:   M L² T⁻²"), "{out}");
}

#[test]
fn read_derivatives() {
    let (code, out, _) = lagrange(&[
        "read",
        "1/2 m l^2 thetadot^2 + m g l cos(theta)",
        "--coords",
        "theta",
        "--diff",
        "theta'",
        "--dt",
    ]);
    assert_eq!(code, 0);
    assert!(out.contains("∂/∂θ̇: m·l²·θ̇"), "{out}");
    assert!(out.contains("d/dt: m·l²·θ̇·θ̈ − m·g·l·θ̇·sin(θ)"), "{out}");
}

#[test]
fn unreadable_input_exits_1_with_a_diagnostic() {
    let (code, out, err) = lagrange(&[
        "read",
        "thta'' + g/l*sin(theta)",
        "--coords",
        "theta",
        "--strict",
        "--dims",
        "g=L T^-2, l=L",
    ]);
    assert_eq!(code, 1);
    assert!(out.is_empty());
    assert!(err.contains("unknown name `thta`"), "{err}");
    assert!(err.contains("did you mean `theta`?"), "{err}");
}

#[test]
fn dimension_error_exits_1() {
    let (code, out, _) = lagrange(&["read", "m*g + m*g*l", "--dims", "m=M, g=L T^-2, l=L"]);
    assert_eq!(code, 1);
    assert!(out.contains("m·g·l is M L² T⁻², m·g is M L T⁻²"), "{out}");
}

#[test]
fn usage_errors_exit_2() {
    let (code, _, err) = lagrange(&["read", "x", "--dims", "m=K"]);
    assert_eq!(code, 2, "{err}");
    let (code, _, _) = lagrange(&["no-such-command"]);
    assert_eq!(code, 2);
}

//! The `lagrange` binary, run as a user would.

use std::process::Command;

use crate::helpers::lagrange;

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

const DOUBLE_PENDULUM: &str = "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + m2*l1*l2*theta1'*theta2'*cos(theta1-theta2) + (m1+m2)*g*l1*cos(theta1) + m2*g*l2*cos(theta2)";

#[test]
fn derive_prints_every_step() {
    let (code, out, err) = lagrange(&[
        "derive",
        "--lagrangian",
        "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)",
        "--coords",
        "theta",
    ]);
    assert_eq!(code, 0, "{err}");
    insta::assert_snapshot!("derive_simple_pendulum", out);
    let (code, out, _) = lagrange(&[
        "derive",
        "--lagrangian",
        DOUBLE_PENDULUM,
        "--coords",
        "theta1,theta2",
    ]);
    assert_eq!(code, 0);
    insta::assert_snapshot!("derive_double_pendulum", out);
}

#[test]
fn derive_json_has_the_documented_fields() {
    let (code, out, _) = lagrange(&[
        "derive",
        "--lagrangian",
        DOUBLE_PENDULUM,
        "--coords",
        "theta1,theta2",
        "--json",
    ]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for key in [
        "coordinates",
        "parameters",
        "equations",
        "mass_matrix",
        "forcing",
        "momenta",
        "energy_function",
        "energy_conserved",
        "energy_is_total",
        "cyclic",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(v["coordinates"], serde_json::json!(["theta1", "theta2"]));
    assert_eq!(v["mass_matrix"].as_array().unwrap().len(), 2);
    assert_eq!(v["energy_conserved"], true);
    // Every expression is plain syntax that lagrange reads back.
    let eq = v["equations"][0].as_str().unwrap();
    let (code, _, _) = lagrange(&["read", eq, "--coords", "theta1,theta2"]);
    assert_eq!(code, 0);
}

#[test]
fn derive_bead_wire_energy_is_not_t_plus_v() {
    let (code, out, _) = lagrange(&[
        "derive",
        "--kinetic",
        "1/2*m*(r'^2 + r^2*omega^2)",
        "--potential",
        "0",
        "--coords",
        "r",
        "--json",
    ]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["energy_conserved"], true);
    assert_eq!(v["energy_is_total"], false);
}

#[test]
fn derive_with_constraint_and_format_latex() {
    let (code, out, err) = lagrange(&[
        "derive",
        "--lagrangian",
        "1/2*m*(x'^2 + y'^2) - m*g*y",
        "--coords",
        "x,y",
        "--constraint",
        "x^2 + y^2 = l^2",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("λ1 = "), "{out}");
    let (code, out, _) = lagrange(&[
        "derive",
        "--lagrangian",
        "1/2*m*x'^2 - 1/2*k*x^2",
        "--coords",
        "x",
        "--format",
        "latex",
    ]);
    assert_eq!(code, 0);
    assert!(out.starts_with("\\begin{align*}"), "{out}");
    assert!(out.contains("\\ddot{x}"), "{out}");
}

#[test]
fn modes_numeric_and_symbolic() {
    let (code, out, err) = lagrange(&[
        "modes",
        "--lagrangian",
        DOUBLE_PENDULUM,
        "--coords",
        "theta1,theta2",
        "--params",
        "m1=m,m2=m,l1=l,l2=l",
        "--at",
        "theta1=0,theta2=0",
        "--symbolic",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("ω² = (2 − √2)·g/l"), "{out}");
    assert!(out.contains("ω² = (2 + √2)·g/l"), "{out}");
    let (code, out, _) = lagrange(&[
        "modes",
        "--lagrangian",
        DOUBLE_PENDULUM,
        "--coords",
        "theta1,theta2",
        "--params",
        "m1=1,m2=1,l1=1,l2=1,g=9.81",
        "--json",
    ]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let eqs = v["equilibria"].as_array().unwrap();
    assert_eq!(eqs.len(), 4, "{out}");
    let bottom = &eqs[0];
    assert_eq!(bottom["stable"], true);
    let f: Vec<f64> = bottom["frequencies"]
        .as_array()
        .unwrap()
        .iter()
        .map(|x| x.as_f64().unwrap())
        .collect();
    assert!((f[0] - ((2.0 - 2f64.sqrt()) * 9.81f64).sqrt()).abs() < 1e-9);
    assert!((f[1] - ((2.0 + 2f64.sqrt()) * 9.81f64).sqrt()).abs() < 1e-9);
}

#[test]
fn bad_mechanics_input_exits_2_with_one_clear_line() {
    let cases: &[(&[&str], &str)] = &[
        (
            &[
                "derive",
                "--lagrangian",
                "1/2*m*x'^2 - k*y^2",
                "--coords",
                "x,y",
            ],
            "L does not depend on y' quadratically",
        ),
        (
            &[
                "derive",
                "--lagrangian",
                "1/2*m*(x' + y')^2",
                "--coords",
                "x,y",
            ],
            "mass matrix is singular",
        ),
        (
            &["derive", "--lagrangian", "1/2*m*x'^2 +* k", "--coords", "x"],
            "expected a value",
        ),
        (
            &[
                "modes",
                "--lagrangian",
                "1/2*m*x'^2 - 1/2*k*x^2",
                "--coords",
                "x",
                "--params",
                "m=1",
            ],
            "parameter `k` has no value",
        ),
        (
            &[
                "modes",
                "--lagrangian",
                "1/2*m*x'^2 - 1/2*k*x^2",
                "--coords",
                "x",
                "--params",
                "m=1, k=abc+",
            ],
            "expected a value",
        ),
        (
            &[
                "modes",
                "--lagrangian",
                "1/2*m*x'^2 - 1/2*k*x^2",
                "--coords",
                "x",
                "--params",
                "m=1, k=1",
                "--at",
                "y=0",
            ],
            "`y` is not a coordinate",
        ),
        (
            &[
                "modes",
                "--lagrangian",
                "1/2*m*x'^2 - F*x",
                "--coords",
                "x",
                "--params",
                "m=1, F=1",
            ],
            "no equilibrium",
        ),
        (
            &[
                "modes",
                "--lagrangian",
                "1/2*m*x'^2",
                "--coords",
                "x",
                "--params",
                "m",
            ],
            "should look like name=value",
        ),
    ];
    for (args, want) in cases {
        let (code, out, err) = lagrange(args);
        assert_eq!(code, 2, "{args:?}: {out}{err}");
        assert!(err.contains(want), "{args:?}: {err}");
    }
}

#[test]
fn problems_list_show_verify() {
    let (code, out, _) = lagrange(&["problems", "list"]);
    assert_eq!(code, 0);
    for id in [
        "simple-pendulum",
        "bead-wire",
        "double-pendulum",
        "atwood",
        "bead-parabola",
        "spring-incline",
    ] {
        assert!(out.contains(id), "{id} missing from\n{out}");
    }
    let (code, out, _) = lagrange(&["problems", "show", "simple-pendulum"]);
    assert_eq!(code, 0);
    assert!(out.contains("coordinates: θ"), "{out}");
    assert!(!out.contains("answer:"), "answers are hidden by default");
    let (code, out, _) = lagrange(&["problems", "show", "simple-pendulum", "--answers"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("answer: m*l^2*theta'' + m*g*l*sin(theta) = 0"),
        "{out}"
    );
    let (code, _, err) = lagrange(&["problems", "show", "no-such-problem"]);
    assert_eq!(code, 2);
    assert!(err.contains("no problem `no-such-problem`"));
    let (code, out, _) = lagrange(&["problems", "verify"]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("0 failing"), "{out}");
    let broken = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/broken/wrong-eom.toml");
    let (code, out, _) = lagrange(&["problems", "verify", broken]);
    assert_eq!(code, 1);
    assert!(out.contains("[wrong-eom]"), "{out}");
}

#[test]
fn problems_folder_and_problem_ids_in_other_commands() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/broken");
    let (code, out, _) = lagrange(&["--problems", dir, "problems", "list"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("wrong-eom") && out.contains("[toml-syntax]"),
        "{out}"
    );
    let (code, out, err) = lagrange(&["derive", "atwood-tension"]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("λ1 = 2·m₁·m₂·g/(m₁ + m₂)"), "{out}");
    let (code, out, _) = lagrange(&[
        "modes",
        "simple-pendulum",
        "--params",
        "m=1, l=1, g=9.81",
        "--json",
    ]);
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["equilibria"].as_array().unwrap().len(), 2);
}

#[test]
fn check_verdicts_exit_codes_and_json() {
    let cases: &[(&str, &str, &str, i32)] = &[
        ("simple-pendulum", "eom", "theta'' = -g/l sin(θ)", 0),
        ("simple-pendulum", "eom", "theta'' + g/l*theta = 0", 1),
        (
            "simple-pendulum",
            "eom",
            "m*l^2*theta'' - m*g*l*sin(theta) = 0",
            1,
        ),
        ("simple-pendulum", "eom", "thta'' + g/l*sin(theta) = 0", 1),
        ("simple-pendulum", "frequencies", "g/l", 1),
        ("simple-pendulum", "equilibria", "theta = 0", 1),
        ("simple-pendulum", "potential", "m*g*l*(1 - cos(theta))", 0),
        (
            "double-pendulum",
            "frequencies",
            "sqrt(0.586*g/l), sqrt(3.414*g/l)",
            1,
        ),
        (
            "bead-wire",
            "energy-function",
            "1/2*m*r'^2 + 1/2*m*omega^2*r^2",
            1,
        ),
        ("simple-pendulum", "eom", "theta'' + g/l sin(theta)", 0),
    ];
    let mut shown = String::new();
    for (problem, part, answer, code) in cases {
        let (c, out, err) = lagrange(&["--color", "never", "check", problem, part, answer]);
        assert_eq!(c, *code, "{problem} {part} {answer}: {out}{err}");
        shown.push_str(&format!(
            "$ lagrange check {problem} {part} {answer:?}\n{out}{err}\n"
        ));
    }
    insta::assert_snapshot!("check_verdicts", shown);
    let (c, out, _) = lagrange(&[
        "check",
        "simple-pendulum",
        "eom",
        "theta'' + g/l*theta = 0",
        "--json",
    ]);
    assert_eq!(c, 1);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for key in [
        "problem",
        "part",
        "status",
        "score",
        "reading",
        "diagnoses",
        "seed",
    ] {
        assert!(v.get(key).is_some(), "missing {key}");
    }
    assert_eq!(v["status"], "incorrect");
    assert_eq!(v["diagnoses"][0]["code"], "small-angle");
    assert_eq!(v["reading"]["plain"], "theta'' + g*theta/l = 0");
    // Usage errors exit 2.
    assert_eq!(lagrange(&["check", "no-such-problem", "eom", "x"]).0, 2);
    let (c, _, err) = lagrange(&["check", "simple-pendulum", "no-such-part", "x"]);
    assert_eq!(c, 2);
    assert!(err.contains("the parts are kinetic"), "{err}");
}

#[test]
fn check_colour_follows_the_flag_and_no_color() {
    let out = Command::new(env!("CARGO_BIN_EXE_lagrange"))
        .args([
            "--color",
            "always",
            "check",
            "simple-pendulum",
            "eom",
            "theta'' + g/l*sin(theta) = 0",
        ])
        .output()
        .unwrap();
    assert!(
        String::from_utf8_lossy(&out.stdout).contains("\u{1b}["),
        "colour was asked for"
    );
    let out = Command::new(env!("CARGO_BIN_EXE_lagrange"))
        .args([
            "check",
            "simple-pendulum",
            "eom",
            "theta'' + g/l*sin(theta) = 0",
        ])
        .env("NO_COLOR", "1")
        .output()
        .unwrap();
    assert!(!String::from_utf8_lossy(&out.stdout).contains("\u{1b}["));
}

#[test]
fn symbolic_modes_of_a_large_system_is_a_clear_error() {
    let l = "1/2*(a'^2 + b'^2 + c'^2 + d'^2) - 1/2*k*(a^2 + b^2 + c^2 + d^2)";
    let (code, _, err) = lagrange(&[
        "modes",
        "--lagrangian",
        l,
        "--coords",
        "a,b,c,d",
        "--params",
        "k=k",
        "--at",
        "a=0,b=0,c=0,d=0",
        "--symbolic",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("up to 3 coordinates"), "{err}");
}

#[test]
fn argument_errors_are_the_faces_own() {
    let base = [
        "modes",
        "--lagrangian",
        "1/2*m*x'^2 - 1/2*k*x^2",
        "--coords",
        "x",
        "--params",
        "m=1, k=1",
    ];
    for (extra, want) in [
        (
            &["--range", "x=5:-5"][..],
            "--range `x=5:-5` should look like x=-5:5",
        ),
        (&["--range", "y=-5:5"][..], "`y` is not a coordinate"),
        (
            &["--symbolic"][..],
            "--symbolic needs the equilibrium, given with --at",
        ),
    ] {
        let args: Vec<&str> = base.iter().chain(extra).copied().collect();
        let (code, _, err) = lagrange(&args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains(want), "{args:?}: {err}");
    }
    // The reading is shown before the face reports a --diff that is not one variable.
    let (code, out, err) = lagrange(&["read", "x^2 + y", "--diff", "x+y", "--dt"]);
    assert_eq!(code, 2);
    assert!(
        out.contains("parameters:  x, y") && !out.contains("d/dt"),
        "{out}"
    );
    assert!(err.contains("--diff takes one variable"), "{err}");
}

#[test]
fn check_a_part_that_cannot_be_prepared_gets_its_own_help() {
    // Assumptions that no parameter values satisfy: the part cannot be prepared.
    let dir = crate::helpers::scratch("unprepared");
    std::fs::write(
        dir.join("nowhere.toml"),
        r#"id = "nowhere"
title = "A pendulum with impossible assumptions"
coordinates = [{ name = "theta", periodic = true }]
lagrangian = "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)"
assume = ["m > 100"]

[parameters]
m = { dimension = "M", range = [0.5, 2.0] }
l = { dimension = "L", range = [0.5, 2.0] }
g = { dimension = "L T^-2", range = [5.0, 15.0] }

[[parts]]
id = "eom"
kind = "equation"
prompt = "p"
answer = "m*l^2*theta'' + m*g*l*sin(theta) = 0"
"#,
    )
    .unwrap();
    let problems = dir.to_string_lossy().into_owned();
    let (c, _, err) = lagrange(&["--problems", &problems, "check", "nowhere", "eom", "x"]);
    let (c2, _, err2) = lagrange(&["--problems", &problems, "check", "nowhere", "no-part", "x"]);
    assert_eq!(c, 2, "{err}");
    assert!(err.contains("hold almost nowhere"), "{err}");
    assert!(!err.contains("the parts are"), "{err}");
    assert_eq!(c2, 2, "{err2}");
    assert!(err2.contains("the parts are eom"), "{err2}");
}

//! Issue 19 §2: a Lagrangian that contains accelerations (`½ẋ² − ½x² + x ẍ`) is refused with
//! the reason — by the mechanics layer (a typed error), and so by `derive`, `modes`,
//! `simulate`, the REPL and problem files. It used to give ẍ = −x silently, where the physics
//! of that L (x ẍ = d/dt(x ẋ) − ẋ²) is ẍ = +x, and `problems verify` proved a wrong reference.

use lagrange::mechanics::{MechError, System};

use crate::helpers::lagrange;

const WITH_ACCELERATION: &str = "1/2*x'^2 - 1/2*x^2 + x*x''";

#[test]
fn the_mechanics_layer_refuses_an_acceleration_in_l() {
    let cases: [(&str, &str, &str); 4] = [
        (WITH_ACCELERATION, "", "x''"),
        ("1/2*x'^2 + x''^2", "", "x''"),
        // In T as well as in L.
        ("1/2*x'^2 + m*x*x''", "x^2/2", "x''"),
        ("1/2*theta'^2 + cos(theta)*theta'''", "", "theta'''"),
    ];
    for (t, v, named) in cases {
        let built = if v.is_empty() {
            System::from_lagrangian(
                t,
                &["x", "theta"][..if t.contains("theta") { 2 } else { 1 }],
            )
        } else {
            System::from_energies(t, v, &["x"])
        };
        match built {
            Err(MechError::AccelerationInLagrangian { acceleration }) => {
                assert_eq!(acceleration, named, "{t}")
            }
            other => panic!("{t}: {other:?}"),
        }
    }
    // A first-order L is untouched, and derive() also guards a system built otherwise.
    let mut ok = System::from_lagrangian("1/2*x'^2 - 1/2*x^2", &["x"]).expect("builds");
    assert!(ok.derive().is_ok());
    let ctx = ok.open_context();
    ok.lagrangian = ok.read(WITH_ACCELERATION, "L", &ctx).expect("reads");
    assert!(matches!(
        ok.derive(),
        Err(MechError::AccelerationInLagrangian { .. })
    ));
    let e = MechError::AccelerationInLagrangian {
        acceleration: "x''".into(),
    };
    assert_eq!(e.code(), "acceleration-in-lagrangian");
    assert!(e.help().contains("by parts"));
}

#[test]
fn every_command_refuses_it_with_the_reason() {
    let runs: [(&str, Vec<&str>); 4] = [
        ("derive", vec!["derive", "-L", WITH_ACCELERATION, "-q", "x"]),
        ("modes", vec!["modes", "-L", WITH_ACCELERATION, "-q", "x"]),
        (
            "simulate",
            vec![
                "simulate",
                "-L",
                WITH_ACCELERATION,
                "-q",
                "x",
                "--init",
                "x=1",
            ],
        ),
        (
            "derive -T",
            vec!["derive", "-T", "1/2*x'^2 + x*x''", "-V", "x^2/2", "-q", "x"],
        ),
    ];
    for (what, args) in runs {
        let (code, out, err) = lagrange(&args);
        assert_eq!(code, 2, "{what}: {out}{err}");
        assert!(
            err.contains("[acceleration-in-lagrangian]") && err.contains("x''"),
            "{what}: {err}"
        );
        // No equation of motion was printed from the dropped term.
        assert!(!out.contains("ẍ"), "{what}: {out}");
    }
}

#[test]
fn the_repl_refuses_it() {
    let mut s = crate::helpers::session();
    let replies = s.handle(&format!(":derive {WITH_ACCELERATION}"));
    let text = format!("{replies:?}");
    assert!(text.contains("acceleration-in-lagrangian"), "{text}");
}

#[test]
fn a_problem_file_with_it_is_a_finding_at_its_line() {
    let text = r#"id = "second-order"
title = "An L with an acceleration"
coordinates = [{ name = "x" }]
lagrangian = "1/2*m*x'^2 - 1/2*k*x^2 + m*x*x''"

[parameters]
m = { dimension = "M", range = [0.5, 2.0] }
k = { dimension = "M T^-2", range = [0.5, 2.0] }

[[parts]]
id = "eom"
kind = "equation"
prompt = "Equation of motion?"
answer = "m*x'' + k*x = 0"
"#;
    let f = lagrange::bank::load_str("second-order.toml", text).expect_err("refused");
    assert_eq!(f.code, "acceleration-in-lagrangian");
    assert_eq!(f.line, 4);
    assert!(f.message.contains("x''"), "{}", f.message);
}

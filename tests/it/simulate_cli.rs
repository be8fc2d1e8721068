//! Issue 14, items 3 and 7: `lagrange simulate` on the command line — the harmonic
//! oscillator's state at t = π/2 against cos and sin, the double pendulum's energy error at
//! 1e-10, the CSV grid, the text summary (snapshot), and every bad input as a one-line error.

use crate::helpers::{lagrange, mask_numbers, value_after};

const DOUBLE_PENDULUM: &str = "(m1 + m2)/2*l1^2*theta1'^2 + m2/2*l2^2*theta2'^2 \
    + m2*l1*l2*theta1'*theta2'*cos(theta1 - theta2) + (m1 + m2)*g*l1*cos(theta1) \
    + m2*g*l2*cos(theta2)";
const DP_PARAMS: &str = "m1=1, m2=1, l1=1, l2=1, g=9.81";
const OSCILLATOR: &str = "m*x'^2/2 - k*x^2/2";

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = lagrange(args);
    assert_eq!(code, 0, "{err}");
    serde_json::from_str(&out).unwrap()
}

/// The error's exit code and its one-line message (the help line aside).
fn error(args: &[&str]) -> (i32, String) {
    let (code, out, err) = lagrange(args);
    assert!(out.is_empty(), "{out}");
    assert!(!err.contains("panicked"), "{err}");
    let first = err.lines().next().unwrap_or_default().to_string();
    (code, first)
}

#[test]
fn the_oscillator_at_a_quarter_period_is_cos_and_sin() {
    let half_pi = std::f64::consts::FRAC_PI_2.to_string();
    let v = json(&[
        "simulate",
        "-L",
        OSCILLATOR,
        "--coords",
        "x",
        "--params",
        "m=1, k=1",
        "--init",
        "x=1, x'=0.5",
        "--t-end",
        &half_pi,
        "--report-at",
        "1",
        "--json",
    ]);
    let keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    let mut want = [
        "start",
        "params",
        "method",
        "steps",
        "rejected",
        "rhs_evals",
        "h_start",
        "h_end",
        "max_rel_energy_error",
        "h_expected_constant",
        "reports",
        "final",
    ];
    let mut got = keys.clone();
    got.sort_unstable();
    want.sort_unstable();
    assert_eq!(got, want);
    let t = std::f64::consts::FRAC_PI_2;
    let x = |t: f64| t.cos() + 0.5 * t.sin();
    let v_ = |t: f64| -t.sin() + 0.5 * t.cos();
    let f = &v["final"];
    assert!((f["x"].as_f64().unwrap() - x(t)).abs() < 1e-9, "{f}");
    assert!((f["x'"].as_f64().unwrap() - v_(t)).abs() < 1e-9, "{f}");
    let r = &v["reports"][0];
    assert_eq!(r["t"].as_f64(), Some(1.0));
    assert!((r["state"]["x"].as_f64().unwrap() - x(1.0)).abs() < 1e-9);
    assert_eq!(v["method"], "dop853");
    assert!((v["h_start"].as_f64().unwrap() - 0.625).abs() < 1e-15);
}

#[test]
fn the_double_pendulum_keeps_its_energy_to_4e_9() {
    let v = json(&[
        "simulate",
        "-L",
        DOUBLE_PENDULUM,
        "--coords",
        "theta1,theta2",
        "--params",
        DP_PARAMS,
        "--init",
        "theta1=2, theta2=2",
        "--t-end",
        "20",
        "--rtol",
        "1e-10",
        "--atol",
        "1e-10",
        "--json",
    ]);
    let e = v["max_rel_energy_error"].as_f64().unwrap();
    assert!(e <= 4e-9, "{e}");
    assert!(v["steps"].as_u64().unwrap() > 100);
    assert!(v["rhs_evals"].as_u64().unwrap() > v["steps"].as_u64().unwrap());
}

#[test]
fn a_problem_of_the_bank_needs_only_the_parameters_of_its_motion() {
    let v = json(&[
        "simulate",
        "double-pendulum",
        "--params",
        DP_PARAMS,
        "--init",
        "theta1=2, theta2=2",
        "--t-end",
        "20",
        "--json",
    ]);
    let e = v["max_rel_energy_error"].as_f64().unwrap();
    assert!(e <= 4e-9, "{e}");
}

#[test]
fn gauss_and_rk4_run_at_a_fixed_step() {
    for method in ["gauss", "rk4"] {
        let v = json(&[
            "simulate", "-L", OSCILLATOR, "--coords", "x", "--params", "m=1, k=1", "--init", "x=1",
            "--t-end", "1", "--method", method, "--dt", "0.001", "--json",
        ]);
        assert_eq!(v["method"], method);
        assert_eq!(v["steps"], 1000);
        assert!((v["final"]["x"].as_f64().unwrap() - 1f64.cos()).abs() < 1e-9);
    }
}

#[test]
fn out_writes_the_even_grid_with_h() {
    let dir = crate::helpers::scratch("simcli");
    let path = dir.join("run.csv");
    let (code, _, err) = lagrange(&[
        "simulate",
        "-L",
        OSCILLATOR,
        "--coords",
        "x",
        "--params",
        "m=1, k=1",
        "--init",
        "x=1",
        "--t-end",
        "2",
        "--samples",
        "21",
        "--out",
        path.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&path).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "t,x,x',h");
    assert_eq!(lines.len(), 22);
    let last: Vec<f64> = lines[21].split(',').map(|v| v.parse().unwrap()).collect();
    assert_eq!(last[0], 2.0);
    assert!((last[1] - 2f64.cos()).abs() < 1e-9);
    assert!((last[3] - 0.5).abs() < 1e-9);
}

#[test]
fn the_text_summary() {
    let (code, out, err) = lagrange(&[
        "simulate",
        "-L",
        OSCILLATOR,
        "--coords",
        "x",
        "--params",
        "m=1, k=4",
        "--init",
        "x=1",
        "--t-end",
        "3",
        "--report-at",
        "1.5",
    ]);
    assert_eq!(code, 0, "{err}");
    // Physics, not digits: x = cos 2t, x' = −2 sin 2t, h = ½x'² + 2x² = 2 throughout.
    let line = |start: &str| {
        out.lines()
            .find(|l| l.starts_with(start))
            .unwrap_or_else(|| panic!("no `{start}` line in\n{out}"))
    };
    let (at, last) = (line("t = 1.5: "), line("Final: "));
    for (l, t) in [(at, 1.5f64), (last, 3.0)] {
        assert!(
            (value_after(l, "x = ") - (2.0 * t).cos()).abs() < 1e-8,
            "{l}"
        );
        assert!(
            (value_after(l, "x' = ") + 2.0 * (2.0 * t).sin()).abs() < 1e-8,
            "{l}"
        );
    }
    let energy = line("Energy: ");
    assert_eq!(value_after(energy, "h(0) = "), 2.0, "{energy}");
    assert!(
        (value_after(energy, "h(end) = ") - 2.0).abs() < 2e-9,
        "{energy}"
    );
    assert!(value_after(energy, "drift ") < 1e-9, "{energy}");
    // Adaptive steps: some taken, every one costing right-hand-side evaluations.
    let steps = line("Steps: ");
    let accepted = value_after(steps, "Steps: ");
    let evaluations = value_after(steps, "rejected, ");
    assert!(accepted >= 1.0 && evaluations > accepted, "{steps}");
    // The wording and layout, numbers masked.
    insta::assert_snapshot!(mask_numbers(&out));
}

#[test]
fn a_damped_run_says_h_is_not_constant() {
    let (code, out, _) = lagrange(&[
        "simulate", "-L", OSCILLATOR, "--coords", "x", "--params", "m=1, k=1", "--force",
        "-0.1*x'", "--init", "x=1", "--t-end", "1",
    ]);
    assert_eq!(code, 0);
    assert!(out.contains("h is not expected to be constant"), "{out}");
}

#[test]
fn bad_input_is_one_clear_line() {
    let base = ["simulate", "-L", OSCILLATOR, "--coords", "x"];
    let with = |extra: &[&str]| error(&[&base[..], extra].concat());
    let cases: [(&[&str], i32, &str); 6] = [
        (
            &["--params", "m=1, k=1", "--init", "xx=1", "--t-end", "1"],
            2,
            "`xx` in --init is not a coordinate or velocity of the system (did you mean `x`?)",
        ),
        (&["--params", "m=1", "--t-end", "1"], 2, "parameter `k`"),
        (
            &["--params", "m=1, k=1", "--t-end", "0"],
            2,
            "--t-end must be a positive",
        ),
        (
            &["--params", "m=1, k=1", "--t-end", "-3"],
            2,
            "--t-end must be a positive",
        ),
        (
            &["--params", "m=1, k=1", "--t-end", "1", "--method", "rk4"],
            2,
            "give its step with --dt",
        ),
        (
            &[
                "--params",
                "m=1, k=1",
                "--t-end",
                "1",
                "--samples",
                "2000000",
            ],
            2,
            "over the limit of 1000000",
        ),
    ];
    for (extra, code, text) in cases {
        let (got, line) = with(extra);
        assert_eq!(got, code, "{extra:?}: {line}");
        assert!(line.contains(text), "{extra:?}: {line}");
    }
    let (code, line) = error(&[
        "simulate",
        "-L",
        DOUBLE_PENDULUM,
        "--coords",
        "theta1,theta2",
        "--params",
        DP_PARAMS,
        "--init",
        "theta3=1",
        "--t-end",
        "1",
    ]);
    assert_eq!(code, 2);
    assert!(line.contains("did you mean `theta1`?") || line.contains("did you mean `theta2`?"));
}

#[test]
fn a_motion_that_cannot_be_followed_is_a_no() {
    let singular = error(&[
        "simulate",
        "-L",
        "t*x'^2/2 - x^2/2",
        "-q",
        "x",
        "--init",
        "x=1",
        "--t-end",
        "1",
    ]);
    assert_eq!(singular.0, 1);
    assert!(
        singular
            .1
            .contains("the mass matrix became singular at t = 0"),
        "{}",
        singular.1
    );
    // V = −x⁴ sends x to infinity in finite time.
    let blow_up = "x'^2/2 + x^4";
    let rk4 = error(&[
        "simulate", "-L", blow_up, "-q", "x", "--init", "x=1", "--t-end", "5", "--method", "rk4",
        "--dt", "0.1",
    ]);
    assert_eq!(rk4.0, 1);
    assert!(
        rk4.1.contains("the solution diverges near t = "),
        "{}",
        rk4.1
    );
    let dop = error(&[
        "simulate", "-L", blow_up, "-q", "x", "--init", "x=1", "--t-end", "5",
    ]);
    assert_eq!(dop.0, 1);
    assert!(
        dop.1.contains("step size underflowed") || dop.1.contains("diverges"),
        "{}",
        dop.1
    );
}

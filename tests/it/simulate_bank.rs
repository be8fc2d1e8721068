//! Issue 14: every bank problem simulates from its own suggested numbers (parameter values,
//! `[simulation]` start and end time) with its energy function kept, constrained systems
//! move as the textbook says, and a start off a constraint is refused with the reason.

use crate::helpers::lagrange;

fn json(args: &[&str]) -> serde_json::Value {
    let (code, out, err) = lagrange(args);
    assert_eq!(code, 0, "{args:?}: {err}");
    serde_json::from_str(&out).unwrap()
}

#[test]
fn every_bank_problem_simulates_from_its_suggested_start() {
    let (_, list, _) = lagrange(&["problems", "list"]);
    let ids: Vec<&str> = (list.lines())
        .filter(|l| !l.starts_with(' ') && !l.is_empty())
        .filter_map(|l| l.split_whitespace().next())
        .collect();
    assert!(ids.len() >= 16, "{ids:?}");
    for id in ids {
        let v = json(&["simulate", id, "--json"]);
        let drift = v["max_rel_energy_error"].as_f64().unwrap();
        // Every bank system is autonomous and its forces do no work: h is a constant.
        assert!(drift < 1e-8, "{id}: h drifts by {drift}");
        assert!(v["steps"].as_u64().unwrap() > 0, "{id}");
    }
}

#[test]
fn the_constrained_atwood_machine_falls_at_the_textbook_rate() {
    // Heights up, y1 + y2 = c: the heavier m1 goes down with (m1 − m2) g / (m1 + m2).
    let v = json(&[
        "simulate",
        "atwood-tension",
        "--params",
        "m1=3, m2=1, g=9.8, c=2",
        "--init",
        "y1=0.5, y2=1.5",
        "--t-end",
        "1",
        "--json",
    ]);
    let a = (3.0 - 1.0) * 9.8 / 4.0;
    let y1 = v["final"]["y1"].as_f64().unwrap();
    let v1 = v["final"]["y1'"].as_f64().unwrap();
    assert!((y1 - (0.5 - a / 2.0)).abs() < 1e-9, "{y1}");
    assert!((v1 + a).abs() < 1e-9, "{v1}");
    assert!(v["constraint_drift"].as_f64().unwrap() < 1e-9);
}

#[test]
fn the_rolling_disk_accelerates_at_two_thirds_g_sin_alpha() {
    // A uniform disk rolling without slipping: x'' = (2/3) g sin α.
    let v = json(&[
        "simulate",
        "rolling-disk",
        "--params",
        "M=1, R=0.5, g=9.81, alpha=0.5",
        "--t-end",
        "2",
        "--json",
    ]);
    let a = 2.0 / 3.0 * 9.81 * 0.5f64.sin();
    let x = v["final"]["x"].as_f64().unwrap();
    assert!((x - a * 2.0).abs() < 1e-9, "{x} vs {}", 2.0 * a);
}

#[test]
fn a_start_off_a_constraint_is_refused_with_the_constraint() {
    let (code, _, err) = lagrange(&["simulate", "atwood-tension", "--init", "y1=0.5, y2=1"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("off constraint 1") && err.contains("positions"),
        "{err}"
    );
    let (code, _, err) = lagrange(&[
        "simulate",
        "atwood-tension",
        "--init",
        "y1=0.5, y2=0.5, y1'=1",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("velocities"), "{err}");
}

#[test]
fn missing_parameters_are_named_together_and_t_end_is_asked_for() {
    let (code, _, err) = lagrange(&[
        "simulate",
        "-L",
        "m*l^2*theta'^2/2 + m*g*l*cos(theta)",
        "-q",
        "theta",
        "--t-end",
        "1",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("`g`, `l`, `m`"), "{err}");
    let (code, _, err) = lagrange(&["simulate", "-L", "x'^2/2 - x^2/2", "-q", "x"]);
    assert_eq!(code, 2);
    assert!(err.contains("--t-end"), "{err}");
}

#[test]
fn a_fixed_step_run_that_would_not_fit_in_memory_is_refused_up_front() {
    let (code, _, err) = lagrange(&[
        "simulate",
        "simple-pendulum",
        "--method",
        "rk4",
        "--dt",
        "1e-6",
        "--t-end",
        "100",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("more than the") && err.contains("a run may store"),
        "{err}"
    );
}

#[test]
fn chaos_refuses_a_constrained_system_with_the_reason() {
    let (code, _, err) = lagrange(&["chaos", "atwood-tension", "--t-end", "10"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("1 constraint(s)") && err.contains("independent coordinates"),
        "{err}"
    );
}

/// Found by trying the commands as a new user: settings that used to be ignored or to give
/// nonsense with exit 0 are refused up front (exit 2) with what to change.
#[test]
fn settings_that_cannot_give_a_meaningful_run_are_refused() {
    let cases: &[(&[&str], &str)] = &[
        (&["simulate"], "give a problem id"),
        (
            &["simulate", "simple-pendlum"],
            "did you mean `simple-pendulum`",
        ),
        (
            &["simulate", "simple-pendulum", "--dt", "0.01"],
            "dop853 chooses its own steps",
        ),
        (
            &[
                "simulate",
                "simple-pendulum",
                "--method",
                "rk4",
                "--dt",
                "-0.1",
            ],
            "positive",
        ),
        (
            &[
                "simulate",
                "simple-pendulum",
                "--method",
                "rk4",
                "--dt",
                "20",
            ],
            "longer than the run",
        ),
        (
            &["simulate", "simple-pendulum", "--plot", "x.jpg"],
            ".svg or .png",
        ),
        (
            &["simulate", "simple-pendulum", "--phase", "-"],
            "not to the terminal",
        ),
        (
            &["simulate", "simple-pendulum", "--plot", "no-such-dir/x.png"],
            "no folder",
        ),
        (
            &["simulate", "simple-pendulum", "--params", "g=9.81, g=10"],
            "given twice",
        ),
        (
            &["simulate", "simple-pendulum", "--samples", "1"],
            "too few",
        ),
        (
            &[
                "simulate",
                "double-pendulum",
                "--grid",
                "theta1=-1:1:3",
                "--until-flip",
                "--method",
                "gauss",
            ],
            "not available there",
        ),
        (
            &["chaos", "double-pendulum", "--plot", "-"],
            "not to the terminal",
        ),
    ];
    for (args, want) in cases {
        let (code, out, err) = lagrange(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(out.is_empty(), "{args:?}: {out}");
        assert!(err.contains(want), "{args:?}: {err}");
    }
}

#[test]
fn a_conserved_h_that_drifts_far_is_flagged_as_untrustworthy() {
    let (code, out, err) = lagrange(&[
        "simulate",
        "simple-pendulum",
        "--method",
        "rk4",
        "--dt",
        "2",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("not to be trusted"), "{out}");
    let (_, out, _) = lagrange(&["simulate", "simple-pendulum"]);
    assert!(!out.contains("not to be trusted"), "{out}");
    assert!(out.contains("Start: theta = 1, theta' = 0"), "{out}");
    assert!(out.contains("Parameters: g = 9.81, l = 1, m = 1"), "{out}");
}

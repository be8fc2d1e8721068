//! SymPy's physics.mechanics test systems, ported (issue 13, item 11): each file of
//! `tests/sympy/` holds a Lagrangian in lagrange's syntax with SymPy's accelerations
//! (`LagrangesMethod`, solved at 30 digits) at a few states; lagrange must agree to 1e-9
//! relative. Regenerate with `python3 scripts/sympy-port/gen.py` (see its README).
//! Also `derive --at`: accelerations and multipliers of constrained systems at a state,
//! against closed forms.

use lagrange::mechanics::System;
use lagrange::report::derivation_at::{StateError, derivation_at};
use serde_json::Value;

use crate::helpers::lagrange;

/// Relative agreement required with SymPy.
const TOLERANCE: f64 = 1e-9;

/// The system of one ported file.
fn build(case: &Value) -> System {
    let coords: Vec<&str> = case["coordinates"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap())
        .collect();
    let mut sys = System::from_lagrangian(case["lagrangian"].as_str().unwrap(), &coords).unwrap();
    for c in case["constraints"].as_array().unwrap() {
        sys.add_constraint(&format!("{} = 0", c.as_str().unwrap()))
            .unwrap();
    }
    if let Some(f) = case["forces"].as_str() {
        sys.set_forces(f).unwrap();
    }
    sys
}

/// The largest relative difference between lagrange's and SymPy's accelerations over the
/// states of one case.
fn worst_difference(case: &Value) -> f64 {
    let sys = build(case);
    let coords: Vec<&str> = case["coordinates"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap())
        .collect();
    let params: Vec<(String, String)> = case["params"]
        .as_object()
        .unwrap()
        .iter()
        .map(|(k, v)| (k.clone(), format!("{:?}", v.as_f64().unwrap())))
        .collect();
    let mut worst = 0.0f64;
    for state in case["states"].as_array().unwrap() {
        let num = |key: &str| -> Vec<f64> {
            state[key]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap())
                .collect()
        };
        let (q, qd, expected) = (num("q"), num("qd"), num("qdd"));
        let mut at = vec![(
            "t".to_string(),
            format!("{:?}", state["t"].as_f64().unwrap()),
        )];
        for (i, c) in coords.iter().enumerate() {
            at.push((c.to_string(), format!("{:?}", q[i])));
            at.push((format!("{c}'"), format!("{:?}", qd[i])));
        }
        let report =
            derivation_at(&sys, &params, &at).unwrap_or_else(|e| panic!("{}: {e}", case["name"]));
        let got = report.at.unwrap().accelerations;
        let scale = expected.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        for (g, e) in got.iter().zip(&expected) {
            worst = worst.max((g - e).abs() / scale);
        }
    }
    worst
}

#[test]
fn sympy_mechanics_systems_agree() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/sympy");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .collect();
    files.sort();
    assert!(files.len() >= 15, "only {} ported systems", files.len());
    let mut failures = Vec::new();
    let mut overall = 0.0f64;
    for f in &files {
        let case: Value = serde_json::from_str(&std::fs::read_to_string(f).unwrap()).unwrap();
        let worst = worst_difference(&case);
        overall = overall.max(worst);
        if worst > TOLERANCE {
            failures.push(format!("{}: {worst:e}", case["name"]));
        }
    }
    assert!(failures.is_empty(), "disagree with SymPy: {failures:?}");
    eprintln!(
        "{} systems agree with SymPy; worst relative difference {overall:e}",
        files.len()
    );
}

/// A pendulum written in x, y with x² + y² = l²: at angle θ from the vertical with speed v,
/// the rod's tension is m(v²/l + g cos θ), so λ = −T/(2l) and ẍ = 2λx/m.
#[test]
fn cartesian_pendulum_at_a_state() {
    let mut sys = System::from_lagrangian("1/2*m*(x'^2 + y'^2) - m*g*y", &["x", "y"]).unwrap();
    sys.add_constraint("x^2 + y^2 = l^2").unwrap();
    let params = pairs("m=2, g=9.81, l=1");
    // θ with sin θ = 0.6, speed 1 along the circle.
    let r = derivation_at(&sys, &params, &pairs("x=0.6, y=-0.8, x'=0.8, y'=0.6")).unwrap();
    let s = r.at.unwrap();
    let tension = 2.0 * (1.0 + 9.81 * 0.8);
    close(s.multipliers[0], -tension / 2.0);
    close(s.accelerations[0], -tension * 0.6 / 2.0);
    close(s.accelerations[1], tension * 0.8 / 2.0 - 9.81);
}

/// An upright disc rolling on a plane (two rolling conditions, four coordinates: too large
/// for the closed form): the heading and spin rates are constant and the centre turns,
/// ẍ = −R φ̇ θ̇ sin θ, ÿ = R φ̇ θ̇ cos θ; the multipliers are the floor's forces m ẍ, m ÿ.
#[test]
fn rolling_disc_with_two_conditions_at_a_state() {
    let mut sys = System::from_lagrangian(
        "1/2*m*(x'^2 + y'^2) + 1/2*I1*theta'^2 + 1/2*J*phi'^2",
        &["x", "y", "theta", "phi"],
    )
    .unwrap();
    sys.add_constraint("x' = R*phi'*cos(theta)").unwrap();
    sys.add_constraint("y' = R*phi'*sin(theta)").unwrap();
    let plain = lagrange::report::derivation(&sys).unwrap();
    assert!(plain.multipliers.is_none());
    let at = "x=0, y=0, phi=0, theta=0.3, theta'=2, phi'=3, x'=1.5*cos(0.3), y'=1.5*sin(0.3)";
    let r = derivation_at(&sys, &pairs("m=1.5, I1=0.06, J=0.12, R=0.5"), &pairs(at)).unwrap();
    let s = r.at.unwrap();
    let (ax, ay) = (-3.0 * 0.3f64.sin(), 3.0 * 0.3f64.cos());
    close(s.accelerations[0], ax);
    close(s.accelerations[1], ay);
    close(s.accelerations[2], 0.0);
    close(s.accelerations[3], 0.0);
    close(s.multipliers[0], 1.5 * ax);
    close(s.multipliers[1], 1.5 * ay);
}

/// A parallelogram four-bar linkage (crank = rocker = l, coupler = ground = d; masses m at
/// the crank's and the rocker's tips, the coupler's mass neglected but its moment of inertia J
/// kept so that M is regular), three angles and two closure
/// conditions: with the coupler level the two tips swing as one pendulum,
/// θ̈₁ = θ̈₃ = −(g/l) sin θ, θ̈₂ = 0, and the coupler carries no force (each tip moves as a free
/// pendulum would), so both multipliers are 0.
#[test]
fn four_bar_linkage_at_a_state() {
    let mut sys = System::from_lagrangian(
        "1/2*m*l^2*(a'^2 + c'^2) + 1/2*J*b'^2 + m*g*l*(cos(a) + cos(c))",
        &["a", "b", "c"],
    )
    .unwrap();
    sys.add_constraint("l*sin(a) + d*cos(b) - d - l*sin(c) = 0")
        .unwrap();
    sys.add_constraint("-l*cos(a) + d*sin(b) + l*cos(c) = 0")
        .unwrap();
    let params = pairs("m=0.7, l=1.3, d=2, g=9.81, J=0.2");
    let r = derivation_at(&sys, &params, &pairs("a=0.4, b=0, c=0.4, a'=1.1, c'=1.1")).unwrap();
    let s = r.at.unwrap();
    let want = -9.81 / 1.3 * 0.4f64.sin();
    close(s.accelerations[0], want);
    close(s.accelerations[1], 0.0);
    close(s.accelerations[2], want);
    close(s.multipliers[0], 0.0);
    close(s.multipliers[1], 0.0);
}

#[test]
fn a_state_off_the_constraints_is_refused_with_its_residual() {
    let mut sys = System::from_lagrangian("1/2*m*(x'^2 + y'^2) - m*g*y", &["x", "y"]).unwrap();
    sys.add_constraint("x^2 + y^2 = l^2").unwrap();
    let params = pairs("m=1, g=9.81, l=1");
    let e = derivation_at(&sys, &params, &pairs("x=0.6, y=-0.7")).unwrap_err();
    assert_eq!(e.code(), "state-violates-constraint", "{e}");
    assert!(
        e.to_string().contains("position") && e.to_string().contains("-1.500e-1"),
        "{e}"
    );
    // On the circle but moving across it: 2(x ẋ + y ẏ) = 1.2.
    let e = derivation_at(&sys, &params, &pairs("x=0.6, y=-0.8, x'=1")).unwrap_err();
    assert!(
        matches!(
            e,
            StateError::Violates {
                level: "velocity",
                ..
            }
        ),
        "{e}"
    );
    // Exact values on the circle are accepted.
    derivation_at(&sys, &params, &pairs("x=1/2, y=-sqrt(3)/2")).unwrap();
}

#[test]
fn a_constraint_no_real_state_satisfies_is_refused() {
    let (code, _, err) = lagrange(&[
        "derive",
        "-L",
        "1/2*m*(x'^2 + y'^2)",
        "--coords",
        "x,y",
        "--constraint",
        "x^2 = -1",
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("no real state satisfies constraint 1"),
        "{err}"
    );
    // 1/x = 0 has no state either, but the search cannot tell (it runs off): not claimed.
    let (code, _, err) = lagrange(&[
        "derive",
        "-L",
        "1/2*m*(x'^2 + y'^2)",
        "--coords",
        "x,y",
        "--constraint",
        "1/x = 0",
    ]);
    assert!(!err.contains("no real state"), "{code} {err}");
    // A parameter's sign is not known: x^2 = -a is not judged.
    let (code, _, err) = lagrange(&[
        "derive",
        "-L",
        "1/2*m*(x'^2 + y'^2)",
        "--coords",
        "x,y",
        "--constraint",
        "x^2 = -a",
    ]);
    assert!(!err.contains("no real state"), "{code} {err}");
}

#[test]
fn derive_at_prints_accelerations_and_multipliers() {
    let args = [
        "derive",
        "-L",
        "1/2*m*(x'^2 + y'^2) - m*g*y",
        "--coords",
        "x,y",
        "--constraint",
        "x^2 + y^2 = l^2",
        "--params",
        "m=2, g=10, l=1",
        "--at",
        "x=0, y=-1, x'=1",
    ];
    let (code, out, err) = lagrange(&args);
    assert_eq!(code, 0, "{err}");
    let tail = &out[out.find("At the state").unwrap()..];
    insta::assert_snapshot!("derive_at_cartesian_pendulum", tail);
    let mut json = args.to_vec();
    json.push("--json");
    let (_, out, _) = lagrange(&json);
    let v: Value = serde_json::from_str(&out).unwrap();
    // At the bottom with speed 1: tension m(v²/l + g) = 22, λ = −11, ÿ = v²/l = 1.
    assert_eq!(v["at"]["multipliers"][0].as_f64(), Some(-11.0));
    assert_eq!(v["at"]["accelerations"][1].as_f64(), Some(1.0));
    let mut latex = args.to_vec();
    latex.extend(["--format", "latex"]);
    let (_, out, _) = lagrange(&latex);
    assert!(
        out.contains(r"\lambda_{1} &= -11 && \text{(at the state)}"),
        "{out}"
    );
    // Values without a state would be silently unused: refused.
    let (code, _, err) = lagrange(&args[..args.len() - 2]);
    assert_eq!(code, 2);
    assert!(err.contains("--params gives values for --at"), "{err}");
}

fn pairs(text: &str) -> Vec<(String, String)> {
    lagrange::report::modes::assignments(text).unwrap()
}

fn close(got: f64, want: f64) {
    assert!(
        (got - want).abs() <= 1e-12 * (1.0 + want.abs()),
        "{got} vs {want}"
    );
}

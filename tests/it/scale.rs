//! Scale and magnitude (issue 9, section 2, mechanics side): every zero test of the
//! mechanics engine is relative to the size of the quantities. Masses of 1e-30, springs of
//! 1e-12 and parameters at 1e12 give the physically right answers (scaled frequencies, the
//! same equilibria), and a value that overflows is reported as an overflow.

use crate::helpers::lagrange;

use lagrange::check::Checker;
use lagrange::check::verdict::Status;
use lagrange::mechanics::equilibria::Stability;
use lagrange::mechanics::{MechError, System};

/// Relative closeness (the values here range from 1e-15 to 1e15).
fn rel_close(got: f64, want: f64) -> bool {
    (got - want).abs() <= 1e-8 * want.abs()
}

/// A system from `lagrangian` with every parameter given a numeric value.
fn numeric(lagrangian: &str, coords: &[&str], params: &[(&str, &str)]) -> System {
    let mut sys = System::from_lagrangian(lagrangian, coords).unwrap();
    let values: Vec<(String, String)> = params
        .iter()
        .map(|(n, v)| (n.to_string(), v.to_string()))
        .collect();
    sys.substitute_parameters(&values).unwrap();
    assert!(sys.parameters.is_empty(), "a parameter has no value");
    sys
}

/// The equilibria with their stability and frequencies, as `modes` finds them.
fn equilibria_and_frequencies(sys: &mut System) -> Vec<(Vec<f64>, Stability, Vec<f64>)> {
    let d = sys.derive().unwrap();
    let eq = sys.equilibria(&d, &[]).unwrap();
    assert!(!eq.continuum, "the equilibria were called a continuum");
    eq.points
        .into_iter()
        .map(|(q, st)| {
            let m = sys.modes_at(&d, &[], &q).unwrap();
            (q, st, m.frequencies)
        })
        .collect()
}

// ---- a tiny mass is not a missing kinetic term ----

#[test]
fn derive_accepts_a_mass_of_1e_minus_9() {
    // Issue 9 §2: "1/2*1e-9*x'^2 - 1/2*x^2" was called degenerate.
    let mut sys = System::from_lagrangian("1/2*1e-9*x'^2 - 1/2*x^2", &["x"]).unwrap();
    let d = sys.derive().expect("a mass of 1e-9 is a kinetic term");
    let dynamics = lagrange::mechanics::accel::Dynamics::new(&sys, &d).unwrap();
    let layout = sys.state_layout();
    let mut point = layout.at_rest(&[1.0], &[]);
    point[layout.qdot(0)] = 0.5;
    let a = dynamics
        .accelerations(&point, &mut dynamics.scratch())
        .unwrap();
    // x'' = −x / 1e-9
    assert!(rel_close(a[0], -1e9), "{a:?}");
}

#[test]
fn cli_derive_accepts_a_mass_of_1e_minus_9() {
    let (code, out, err) = lagrange(&[
        "derive",
        "--lagrangian",
        "1/2*1e-9*x'^2 - 1/2*x^2",
        "--coords",
        "x",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(!err.contains("degenerate"), "{err}");
    assert!(out.contains("Coordinate x"), "{out}");
}

#[test]
fn an_electron_on_a_spring_has_its_frequency() {
    // "1/2*9.1e-31*x'^2 - 1/2*k*x^2" with k = 1: ω = √(k/m) ≈ 1.048e15.
    let mut sys = numeric("1/2*9.1e-31*x'^2 - 1/2*k*x^2", &["x"], &[("k", "1")]);
    let found = equilibria_and_frequencies(&mut sys);
    assert_eq!(found.len(), 1, "{found:?}");
    let (q, st, w) = &found[0];
    assert_eq!((q.as_slice(), *st), (&[0.0][..], Stability::Stable));
    assert_eq!(w.len(), 1);
    assert!(rel_close(w[0], (1.0 / 9.1e-31f64).sqrt()), "{w:?}");
}

#[test]
fn cli_modes_of_an_electron_on_a_spring() {
    let (code, out, err) = lagrange(&[
        "modes",
        "--lagrangian",
        "1/2*9.1e-31*x'^2 - 1/2*k*x^2",
        "--coords",
        "x",
        "--params",
        "k=1",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("equilibrium x = 0: stable"), "{out}");
}

#[test]
fn a_tiny_mass_does_not_make_the_coordinate_cyclic() {
    // ∂L/∂x = −1e-9·x is not zero: x is not cyclic, and h is conserved (whether it is
    // T + V cannot be told from L alone).
    let mut sys = System::from_lagrangian("1/2*1e-9*x'^2 - 1/2*1e-9*x^2", &["x"]).unwrap();
    let d = sys.derive().unwrap();
    let e = sys.energy(&d);
    assert!(e.cyclic.is_empty(), "x called cyclic");
    assert!(e.conserved && e.is_total.is_none());
}

// ---- problems with an electron's mass: load, verify, check ----

fn fixture(name: &str) -> lagrange::problem::Problem {
    let path = format!("{}/tests/scale/{name}", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).unwrap();
    lagrange::bank::load_str(&format!("scale/{name}"), &text).unwrap_or_else(|f| panic!("{f}"))
}

fn findings(p: &lagrange::problem::Problem) -> Vec<String> {
    lagrange::bank::verify::verify(p)
        .iter()
        .map(|f| f.to_string())
        .collect()
}

fn check_all(p: &lagrange::problem::Problem, cases: &[(&str, &str, Status)]) {
    let mut checker = Checker::new(p);
    for &(part, answer, want) in cases {
        let v = checker
            .check(part, answer)
            .unwrap_or_else(|e| panic!("{part}: {answer}: {e}"));
        assert_eq!(v.status, want, "{part}: {answer}: {v:?}");
    }
}

#[test]
fn a_pendulum_with_an_electron_mass_verifies() {
    // Issue 9 §2: a bank with m in [9e-31, 1e-30] failed to verify ("L does not depend on
    // θ' quadratically").
    let p = fixture("electron-pendulum.toml");
    let found = findings(&p);
    assert!(found.is_empty(), "\n{}", found.join("\n"));
}

#[test]
fn a_pendulum_with_an_electron_mass_checks_answers() {
    // Issue 9 §2: every `check` on such a problem errored.
    check_all(
        &fixture("electron-pendulum.toml"),
        &[
            ("kinetic", "1/2*m*l^2*theta'^2", Status::Correct),
            ("kinetic", "1/2*m*l*theta'^2", Status::Incorrect),
            ("eom", "theta'' = -g/l*sin(theta)", Status::Correct),
            (
                "eom",
                "m*l^2*theta'' + m*g*l*sin(theta) = 0",
                Status::Correct,
            ),
            ("eom", "theta'' + g/l*theta = 0", Status::Incorrect),
            (
                "eom",
                "m*l^2*theta'' - m*g*l*sin(theta) = 0",
                Status::Incorrect,
            ),
            (
                "lagrangian",
                "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)",
                Status::Correct,
            ),
            (
                "lagrangian",
                "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)",
                Status::Incorrect,
            ),
            ("momentum", "m*l^2*theta'", Status::Correct),
            ("momentum", "m*l*theta'", Status::Incorrect),
            ("equilibria", "theta = 0, theta = pi", Status::Correct),
            ("equilibria", "theta = 0", Status::Incorrect),
            ("frequencies", "sqrt(g/l)", Status::Correct),
            ("frequencies", "g/l", Status::Incorrect),
        ],
    );
}

#[test]
fn a_spring_with_an_electron_mass_loads_and_checks() {
    // The spring-incline problem with m in [9e-31, 1e-30] (k, g of everyday size): it loads,
    // every part prepares, right answers are right and wrong ones that differ in the spring
    // or in the kinetic terms are wrong.
    check_all(
        &fixture("electron-spring.toml"),
        &[
            ("kinetic", "1/2*m*x'^2", Status::Correct),
            ("kinetic", "1/2*m*x'^2*sin(alpha)", Status::Incorrect),
            ("eom", "m*x'' = -k*x + m*g*sin(alpha)", Status::Correct),
            ("eom", "x'' = -k/m*x + g*sin(alpha)", Status::Correct),
            ("eom", "m*x'' = -2*k*x + m*g*sin(alpha)", Status::Incorrect),
            (
                "lagrangian",
                "1/2*m*x'^2 - 1/2*k*x^2 + m*g*x*sin(alpha)",
                Status::Correct,
            ),
            // The part asks for the stability too (issue 19 §3).
            (
                "equilibria",
                "x = m*g*sin(alpha)/k (stable)",
                Status::Correct,
            ),
            ("frequencies", "sqrt(k/m)", Status::Correct),
            ("frequencies", "k/m", Status::Incorrect),
        ],
    );
}

#[test]
fn a_spring_with_an_electron_mass_verifies() {
    // With m ≈ 1e-30 and k ≈ 10, `m*x'' = -k*x + m*g*cos(alpha)` and the potential
    // `1/2*k*x^2 + m*g*x*sin(alpha)` differ from the reference only in terms 1e-30 times the
    // others at the problem's scale; the checker's free sample points (every parameter in
    // [0.01, 100]) make those terms comparable, so the wrong examples are wrong.
    let p = fixture("electron-spring.toml");
    let found = findings(&p);
    assert!(found.is_empty(), "\n{}", found.join("\n"));
    check_all(
        &p,
        &[
            ("eom", "m*x'' = -k*x", Status::Incorrect),
            ("eom", "m*x'' = -k*x + m*g*cos(alpha)", Status::Incorrect),
            ("equilibria", "x = m*g/k", Status::Incorrect),
            // "your L is −1 times the reference": the kinetic term is 1e-30 of the rest.
            (
                "lagrangian",
                "1/2*m*x'^2 + 1/2*k*x^2 + m*g*x*sin(alpha)",
                Status::Incorrect,
            ),
        ],
    );
}

// ---- a weak force is not "every point an equilibrium" ----

#[test]
fn a_weak_spring_has_one_equilibrium_and_its_frequency() {
    // Issue 9 §2: k = 1e-12 made every point an equilibrium; ω = √(k/m) = 1e-6.
    let mut sys = numeric(
        "1/2*m*x'^2 - 1/2*k*x^2",
        &["x"],
        &[("m", "1"), ("k", "1e-12")],
    );
    let found = equilibria_and_frequencies(&mut sys);
    assert_eq!(found.len(), 1, "{found:?}");
    let (q, st, w) = &found[0];
    assert_eq!((q.as_slice(), *st), (&[0.0][..], Stability::Stable));
    assert_eq!(w.len(), 1);
    assert!(rel_close(w[0], 1e-6), "{w:?}");
}

#[test]
fn cli_modes_of_a_weak_spring() {
    let (code, out, err) = lagrange(&[
        "modes",
        "--lagrangian",
        "1/2*m*x'^2 - 1/2*k*x^2",
        "--coords",
        "x",
        "--params",
        "m=1,k=1e-12",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(!out.contains("every point"), "{out}");
    assert!(out.contains("equilibrium x = 0: stable"), "{out}");
    assert!(
        out.contains("frequencies ω: 1e-6") || out.contains("0.000001"),
        "{out}"
    );
}

#[test]
fn a_pendulum_in_weak_gravity_has_two_equilibria() {
    // g = 1e-10: θ = 0 stable with ω = √(g/l) = 1e-5, θ = π unstable with growth rate 1e-5.
    let mut sys = numeric(
        "1/2*m*l^2*theta'^2 + m*g*l*cos(theta)",
        &["theta"],
        &[("m", "1"), ("l", "1"), ("g", "1e-10")],
    );
    let d = sys.derive().unwrap();
    let eq = sys.equilibria(&d, &[]).unwrap();
    assert!(!eq.continuum);
    let pi = std::f64::consts::PI;
    assert_eq!(
        eq.points,
        vec![
            (vec![0.0], Stability::Stable),
            (vec![pi], Stability::Unstable)
        ]
    );
    let m = sys.modes_at(&d, &[], &[pi]).unwrap();
    assert!(rel_close(m.growth_rates[0], 1e-5), "{m:?}");
}

// ---- overflow is an overflow ----

#[test]
fn an_overflowing_mass_is_reported_as_an_overflow() {
    // Issue 9 §2: "1/2*exp(1000)*x'^2 - 1/2*x^2" was reported as a singular mass matrix.
    let mut sys = System::from_lagrangian("1/2*exp(1000)*x'^2 - 1/2*x^2", &["x"]).unwrap();
    let err = sys.derive().unwrap_err();
    assert!(
        matches!(&err, MechError::Overflow { expr } if expr == "exp(1000)"),
        "{err:?}"
    );
    assert_eq!(err.code(), "overflow");
}

#[test]
fn an_overflowing_potential_is_reported_as_an_overflow() {
    // "1/2*m*x'^2 - exp(1000)*x^2": modes said "no equilibrium was found".
    let mut sys = numeric("1/2*m*x'^2 - exp(1000)*x^2", &["x"], &[("m", "1")]);
    let d = sys.derive().unwrap();
    let err = sys.equilibria(&d, &[]).unwrap_err();
    assert!(
        matches!(&err, MechError::Overflow { expr } if expr == "exp(1000)"),
        "{err:?}"
    );
}

#[test]
fn an_overflow_at_every_sampled_point_is_named() {
    // Not a constant, but overflowing for every parameter value sampled (m in [0.5, 2] gives exp(1500) at least):
    // the mass matrix was "singular", the equilibria "not found".
    let mut sys = System::from_lagrangian("1/2*exp(1000*m + 1000)*x'^2 - 1/2*x^2", &["x"]).unwrap();
    let err = sys.derive().unwrap_err();
    assert!(
        matches!(&err, MechError::Overflow { expr } if expr == "exp(1000*m + 1000)"),
        "{err:?}"
    );
    let mut sys = System::from_lagrangian("1/2*m*x'^2 - exp(1000*m + 1000)*x^2", &["x"]).unwrap();
    let d = sys.derive().unwrap();
    let err = sys.equilibria(&d, &[1.0]).unwrap_err();
    assert!(
        matches!(&err, MechError::Overflow { expr } if expr == "exp(1000*m + 1000)"),
        "{err:?}"
    );
}

#[test]
fn cli_reports_an_overflow_by_name() {
    for args in [
        &[
            "derive",
            "--lagrangian",
            "1/2*exp(1000)*x'^2 - 1/2*x^2",
            "--coords",
            "x",
        ][..],
        &[
            "modes",
            "--lagrangian",
            "1/2*m*x'^2 - exp(1000)*x^2",
            "--coords",
            "x",
            "--params",
            "m=1",
        ][..],
    ] {
        let (code, _, err) = lagrange(args);
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(err.contains("error[overflow]"), "{args:?}: {err}");
        assert!(err.contains("exp(1000)"), "{args:?}: {err}");
        assert!(!err.contains("singular"), "{args:?}: {err}");
    }
}

// ---- parameters at 1e-12 and 1e12: the same physics, scaled ----

const DOUBLE_PENDULUM: &str = "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 \
    + m2*l1*l2*theta1'*theta2'*cos(theta1-theta2) + (m1+m2)*g*l1*cos(theta1) \
    + m2*g*l2*cos(theta2)";

#[test]
fn double_pendulum_at_every_scale() {
    // Equal masses and lengths: ω² = (2 ∓ √2) g/l, whatever the masses; four equilibria
    // (0,0) stable, (0,π) and (π,0) unstable, (π,π) unstable.
    let pi = std::f64::consts::PI;
    for s in [1e-12, 1.0, 1e12] {
        for (m, g) in [(s, 1.0), (1.0, s), (s, s)] {
            let (ms, gs) = (format!("{m:e}"), format!("{g:e}"));
            let mut sys = numeric(
                DOUBLE_PENDULUM,
                &["theta1", "theta2"],
                &[
                    ("m1", &ms),
                    ("m2", &ms),
                    ("l1", "1"),
                    ("l2", "1"),
                    ("g", &gs),
                ],
            );
            let found = equilibria_and_frequencies(&mut sys);
            let points: Vec<(Vec<f64>, Stability)> =
                found.iter().map(|(q, st, _)| (q.clone(), *st)).collect();
            assert_eq!(
                points,
                vec![
                    (vec![0.0, 0.0], Stability::Stable),
                    (vec![0.0, pi], Stability::Unstable),
                    (vec![pi, 0.0], Stability::Unstable),
                    (vec![pi, pi], Stability::Unstable),
                ],
                "m = {m}, g = {g}"
            );
            let w = &found[0].2;
            let want = [(2.0 - 2f64.sqrt()) * g, (2.0 + 2f64.sqrt()) * g].map(f64::sqrt);
            assert!(
                w.len() == 2 && rel_close(w[0], want[0]) && rel_close(w[1], want[1]),
                "m = {m}, g = {g}: {w:?}"
            );
        }
    }
}

#[test]
fn spring_on_an_incline_at_every_scale() {
    // x₀ = m g sin α / k, ω = √(k/m), for masses and springs from 1e-12 to 1e12.
    for (m, k) in [
        (1e-12, 1e-12),
        (1e-12, 1.0),
        (1.0, 1e-12),
        (1e12, 1e12),
        (1e12, 1e6),
    ] {
        let (ms, ks) = (format!("{m:e}"), format!("{k:e}"));
        let mut sys = numeric(
            "1/2*m*x'^2 - 1/2*k*x^2 + m*g*x*sin(alpha)",
            &["x"],
            &[("m", &ms), ("k", &ks), ("g", "10"), ("alpha", "1/2")],
        );
        let x0 = m * 10.0 * 0.5f64.sin() / k;
        let width = 2.0 * x0.abs().max(1.0);
        sys.coordinates[0].range = (-width, width);
        let found = equilibria_and_frequencies(&mut sys);
        assert_eq!(found.len(), 1, "m = {m}, k = {k}: {found:?}");
        let (q, st, w) = &found[0];
        assert!(rel_close(q[0], x0), "m = {m}, k = {k}: {q:?} vs {x0}");
        assert_eq!(*st, Stability::Stable);
        assert!(rel_close(w[0], (k / m).sqrt()), "m = {m}, k = {k}: {w:?}");
    }
}

#[test]
fn a_wrong_equilibrium_is_rejected_at_small_scales() {
    // With every parameter near 1e-12 the residual of a wrong candidate is ~1e-24: an
    // absolute zero test called it an equilibrium.
    let mut sys =
        System::from_lagrangian("1/2*m*x'^2 - 1/2*k*x^2 + m*g*x*sin(alpha)", &["x"]).unwrap();
    for p in sys.parameters.iter_mut().filter(|p| p.name != "alpha") {
        p.range = (1e-12, 2e-12);
    }
    let d = sys.derive().unwrap();
    let ctx = sys.open_context();
    let right = sys.read("m*g*sin(alpha)/k", "x0", &ctx).unwrap();
    let wrong = sys.read("m*g/k", "x0", &ctx).unwrap();
    assert!(sys.verify_equilibrium(&d, &[right]).unwrap());
    assert!(!sys.verify_equilibrium(&d, &[wrong]).unwrap());
}

#[test]
fn is_zero_is_relative_to_the_terms() {
    // Rounding in a cancelling sum is zero at any scale; a single term is never zero.
    let mut sys = System::from_lagrangian("1/2*m*x'^2", &["x"]).unwrap();
    for scale in [1e-30, 1.0, 1e30] {
        sys.parameters[0].range = (scale, 2.0 * scale);
        let ctx = sys.open_context();
        for (text, zero) in [
            ("m*(cos(x)^2 + sin(x)^2) - m", true),
            ("m*(cos(x)^2 + sin(x)^2 - 1)", true),
            ("m", false),
            ("m*x^2*1e-6", false),
            ("m*(cos(x)^2 + sin(x)^2) - m*(1 + 1e-6)", false),
        ] {
            let e = sys.read(text, "e", &ctx).unwrap();
            assert_eq!(sys.is_zero(e), zero, "{text} at scale {scale}");
        }
    }
}

// ---- the audit: Coriolis terms and indefinite masses at every scale ----

#[test]
fn a_rotating_frame_keeps_its_coriolis_terms_at_small_masses() {
    // In a frame rotating at W, an isotropic oscillator has ω = √(k/m) ± W = 1 and 3. The
    // velocity coupling C = 2·m·W was called zero below 1e-12 (absolute), giving √3 twice.
    let l = "1/2*m*(x'^2 + y'^2) + m*W*(x*y' - y*x') + 1/2*m*W^2*(x^2+y^2) \
             - 1/2*k*(x^2+y^2)";
    for m in [1e-15, 1.0, 1e15] {
        let (ms, ks) = (format!("{m:e}"), format!("{:e}", 4.0 * m));
        let mut sys = numeric(l, &["x", "y"], &[("m", &ms), ("W", "1"), ("k", &ks)]);
        let d = sys.derive().unwrap();
        let modes = sys.modes_at(&d, &[], &[0.0, 0.0]).unwrap();
        assert!(modes.gyroscopic, "m = {m}");
        let w = &modes.frequencies;
        assert!(
            w.len() == 2 && rel_close(w[0], 1.0) && rel_close(w[1], 3.0),
            "m = {m}: {w:?}"
        );
        assert_eq!(modes.stability, Stability::Stable);
    }
}

#[test]
fn an_indefinite_mass_matrix_solves_at_extreme_scales() {
    // M = s·diag(1, −1, 1) is invertible at every scale s; the old test compared det(M)
    // with 1e-12·sⁿ, which underflows (s = 1e-110) or overflows (s = 1e110) for n = 3.
    for s in [1e-110, 1.0, 1e110] {
        let ss = format!("{s:e}");
        let mut sys = numeric(
            "1/2*a*(x'^2 - y'^2 + z'^2) - 1/2*a*(x^2 + y^2 + z^2)",
            &["x", "y", "z"],
            &[("a", &ss)],
        );
        let d = sys.derive().unwrap();
        let dynamics = lagrange::mechanics::accel::Dynamics::new(&sys, &d).unwrap();
        let point = sys.state_layout().at_rest(&[1.0, 1.0, 1.0], &[]);
        let acc = dynamics
            .accelerations(&point, &mut dynamics.scratch())
            .unwrap_or_else(|e| panic!("s = {s}: {e}"));
        // x'' = −x, y'' = +y, z'' = −z
        assert!(
            rel_close(acc[0], -1.0) && rel_close(acc[1], 1.0) && rel_close(acc[2], -1.0),
            "s = {s}: {acc:?}"
        );
    }
}

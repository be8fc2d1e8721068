//! Issue 13: steady motions through the Routhian, and symbolic modes beyond two coordinates
//! and with gyroscopic terms — each against a closed form from the textbook, not the tool's
//! own output.

use lagrange::expr::{Id, read_expr};
use lagrange::mechanics::System;
use lagrange::mechanics::equilibria::Stability;
use lagrange::report::{ModesError, ModesOptions, ModesReport, modes};

fn pairs(text: &[(&str, &str)]) -> Vec<(String, String)> {
    text.iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect()
}

/// The numeric modes of `l` with fixed momenta `steady` and parameter values `params`.
fn steady_modes(
    l: &str,
    coords: &[&str],
    params: &[(&str, &str)],
    steady: &[(&str, &str)],
) -> ModesReport {
    let sys = System::from_lagrangian(l, coords).unwrap();
    let opts = ModesOptions {
        default_range: Some((0.01, 10.0)),
        params: pairs(params),
        steady: pairs(steady),
        ..ModesOptions::default()
    };
    modes(&sys, &opts).unwrap()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-7 * a.abs().max(b.abs()).max(1.0)
}

const CENTRAL: &str = "1/2*m*(r'^2 + r^2*phi'^2) - V";

#[test]
fn kepler_circular_orbit_has_radial_frequency_equal_to_its_angular_velocity() {
    // V = −k/r: r₀ = p²/(m k), φ' = p/(m r₀²), and ω_r = φ' (the orbits close).
    let (m, k, p) = (1.5, 2.0, 0.7);
    let l = CENTRAL.replace('V', "(-k/r)");
    let rep = steady_modes(
        &l,
        &["r", "phi"],
        &[("m", "1.5"), ("k", "2")],
        &[("p_phi", "0.7")],
    );
    assert_eq!(rep.equilibria.len(), 1);
    let e = &rep.equilibria[0];
    let r0 = p * p / (m * k);
    assert!(close(e.coordinates[0], r0), "{:?}", e.coordinates);
    assert_eq!(e.stability, Stability::Stable);
    let phidot = p / (m * r0 * r0);
    assert_eq!(e.frequencies.len(), 1);
    assert!(
        close(e.frequencies[0], phidot),
        "{} vs {phidot}",
        e.frequencies[0]
    );
}

#[test]
fn power_law_circular_orbit_has_radial_frequency_sqrt_n_plus_2_times_phidot() {
    // V = k rⁿ/n (n > −2): m r₀ φ'² = k r₀ⁿ⁻¹ and ω_r² = (n + 2) φ'².
    for (n, text) in [(2.0f64, "k*r^2/2"), (4.0, "k*r^4/4"), (1.0, "k*r")] {
        let (m, k, p): (f64, f64, f64) = (1.0, 3.0, 1.3);
        let l = CENTRAL.replace('V', &format!("({text})"));
        let rep = steady_modes(
            &l,
            &["r", "phi"],
            &[("m", "1"), ("k", "3")],
            &[("p_phi", "1.3")],
        );
        assert_eq!(rep.equilibria.len(), 1, "n = {n}");
        let r0: f64 = (p * p / (m * k)).powf(1.0 / (n + 2.0));
        let e = &rep.equilibria[0];
        assert!(
            close(e.coordinates[0], r0),
            "n = {n}: {:?} vs {r0}",
            e.coordinates
        );
        let phidot = p / (m * r0 * r0);
        let want = ((n + 2.0) * phidot * phidot).sqrt();
        assert!(
            close(e.frequencies[0], want),
            "n = {n}: {:?} vs {want}",
            e.frequencies
        );
    }
}

#[test]
fn conical_pendulum_steady_motion_and_its_oscillation() {
    // φ'² = g/(l cos α) on the cone θ = α; about it ω² = φ'² (1 + 3 cos² α).
    let l = "1/2*m*l^2*(theta'^2 + sin(theta)^2*phi'^2) + m*g*l*cos(theta)";
    let (g, len, p) = (9.81, 0.8, 0.4);
    let rep = steady_modes(
        l,
        &["theta", "phi"],
        &[("m", "1"), ("l", "0.8"), ("g", "9.81")],
        &[("p_phi", "0.4")],
    );
    let e = rep
        .equilibria
        .iter()
        .find(|e| e.coordinates[0] > 0.0)
        .unwrap();
    let a = e.coordinates[0];
    let phidot = p / (len * len * a.sin().powi(2));
    assert!(close(phidot * phidot, g / (len * a.cos())), "α = {a}");
    assert_eq!(e.rates.len(), 1);
    assert_eq!(e.rates[0].0, "phi'");
    assert!(close(e.rates[0].1, phidot), "{:?}", e.rates);
    let want = phidot * (1.0 + 3.0 * a.cos().powi(2)).sqrt();
    assert_eq!(e.stability, Stability::Stable);
    assert!(
        close(e.frequencies[0], want),
        "{:?} vs {want}",
        e.frequencies
    );
}

#[test]
fn mass_on_a_table_through_a_hole() {
    // m₁ on the table, m₂ hanging: m₁ r₀ φ'² = m₂ g and ω² = 3 m₁ φ'²/(m₁ + m₂).
    let l = "1/2*(m1 + m2)*r'^2 + 1/2*m1*r^2*phi'^2 - m2*g*r";
    let (m1, m2, g, p) = (1.0, 2.0, 9.81, 1.1);
    let rep = steady_modes(
        l,
        &["r", "phi"],
        &[("m1", "1"), ("m2", "2"), ("g", "9.81")],
        &[("p_phi", "1.1")],
    );
    assert_eq!(rep.equilibria.len(), 1);
    let r0 = rep.equilibria[0].coordinates[0];
    let phidot = p / (m1 * r0 * r0);
    assert!(close(m1 * r0 * phidot * phidot, m2 * g));
    let want = (3.0 * m1 * phidot * phidot / (m1 + m2)).sqrt();
    assert!(close(rep.equilibria[0].frequencies[0], want));
}

#[test]
fn a_coordinate_that_is_not_cyclic_is_refused_with_the_reason() {
    let sys = System::from_lagrangian(
        "1/2*m*l^2*(theta'^2 + sin(theta)^2*phi'^2) + m*g*l*cos(theta)",
        &["theta", "phi"],
    )
    .unwrap();
    let opts = ModesOptions {
        params: pairs(&[("m", "1"), ("l", "1"), ("g", "1")]),
        steady: pairs(&[("p_theta", "1")]),
        ..ModesOptions::default()
    };
    let err = modes(&sys, &opts).unwrap_err();
    assert!(matches!(err, ModesError::Steady(_)), "{err:?}");
    assert!(
        err.to_string()
            .contains("theta is not cyclic: L depends on it"),
        "{err}"
    );
}

/// Symbolic ω² of `l` at `at`, as expressions in the system's pool.
fn symbolic(l: &str, coords: &[&str], at: &[&str]) -> (System, Result<Vec<Id>, String>) {
    let mut sys = System::from_lagrangian(l, coords).unwrap();
    let d = sys.derive().unwrap();
    let ctx = sys.open_context();
    let at: Vec<Id> = at
        .iter()
        .map(|a| read_expr(a, &ctx, &mut sys.pool).unwrap())
        .collect();
    let r = sys
        .symbolic_modes(&d, &at)
        .map(|s| s.omega_squared)
        .map_err(|e| e.to_string());
    (sys, r)
}

/// Whether the roots `got` are the expressions `want`, in some order.
fn same_roots(sys: &mut System, got: &[Id], want: &[&str]) -> bool {
    let ctx = sys.open_context();
    let want: Vec<Id> = want
        .iter()
        .map(|w| read_expr(w, &ctx, &mut sys.pool).unwrap())
        .collect();
    got.len() == want.len()
        && want.iter().all(|&w| {
            got.iter().any(|&g| {
                let d = sys.pool.sub(g, w);
                sys.is_zero(d)
            })
        })
}

#[test]
fn three_masses_on_two_springs_factor_as_omega_squared_times_a_quadratic() {
    let (mut sys, r) = symbolic(
        "1/2*m*(x1'^2 + x2'^2 + x3'^2) - 1/2*k*((x2 - x1)^2 + (x3 - x2)^2)",
        &["x1", "x2", "x3"],
        &["0", "0", "0"],
    );
    let r = r.unwrap();
    assert!(same_roots(&mut sys, &r, &["0", "k/m", "3*k/m"]), "{r:?}");
}

#[test]
fn elastic_pendulum_roots_are_k_over_m_and_g_over_the_stretched_length() {
    let (mut sys, r) = symbolic(
        "1/2*m*(r'^2 + r^2*theta'^2) + m*g*r*cos(theta) - 1/2*k*(r - l0)^2",
        &["r", "theta"],
        &["l0 + m*g/k", "0"],
    );
    let r = r.unwrap();
    assert!(same_roots(&mut sys, &r, &["k/m", "g*k/(k*l0 + m*g)"]));
    // No square root of a polynomial is left over: the factors divided out exactly.
    let shown: Vec<String> = r.iter().map(|&w| sys.pool.plain(w)).collect();
    assert!(shown.iter().all(|s| !s.contains("sqrt")), "{shown:?}");
}

#[test]
fn rotating_trap_symbolic_frequencies_are_two_minus_and_plus_omega() {
    // In the frame rotating at Ω, trap frequency 2: ω = 2 ∓ Ω, never ω² = 4 − Ω² twice.
    let (mut sys, r) = symbolic(
        "1/2*((x' - Omega*y)^2 + (y' + Omega*x)^2) - 2*x^2 - 2*y^2",
        &["x", "y"],
        &["0", "0"],
    );
    let r = r.unwrap();
    assert!(same_roots(
        &mut sys,
        &r,
        &["(2 - Omega)^2", "(2 + Omega)^2"]
    ));
}

#[test]
fn damping_gets_no_closed_form_but_a_reason() {
    let mut sys = System::from_lagrangian("1/2*m*x'^2 - 1/2*k*x^2", &["x"]).unwrap();
    sys.set_forces("-c*x'").unwrap();
    let d = sys.derive().unwrap();
    let zero = sys.pool.zero();
    let err = sys.symbolic_modes(&d, &[zero]).unwrap_err();
    assert_eq!(err.code(), "closed-form-not-gyroscopic");
    assert!(err.to_string().contains("not gyroscopic"), "{err}");
}

#[test]
fn conical_pendulum_symbolic_frequency_at_the_cone_angle() {
    // With p_φ = m l² sin²α √(g/(l cos α)) the steady motion is θ = α and
    // ω² = g (1 + 3 cos² α)/(l cos α).
    let sys = System::from_lagrangian(
        "1/2*m*l^2*(theta'^2 + sin(theta)^2*phi'^2) + m*g*l*cos(theta)",
        &["theta", "phi"],
    )
    .unwrap();
    let opts = ModesOptions {
        steady: pairs(&[("p_phi", "m*l^2*sin(alpha)^2*sqrt(g/(l*cos(alpha)))")]),
        at: Some(pairs(&[("theta", "alpha")])),
        symbolic: true,
        ..ModesOptions::default()
    };
    let rep = modes(&sys, &opts).unwrap();
    let w = rep.omega_squared.unwrap();
    assert_eq!(w.len(), 1);
    let mut check = System::from_lagrangian(&w[0].plain, &["alpha"]).unwrap();
    let ctx = check.open_context();
    let want = read_expr(
        "g*(1 + 3*cos(alpha)^2)/(l*cos(alpha))",
        &ctx,
        &mut check.pool,
    )
    .unwrap();
    let d = check.pool.sub(check.lagrangian, want);
    assert!(check.is_zero(d), "{}", w[0].plain);
}

#[test]
fn the_conical_pendulum_bank_problem_is_proved_and_a_wrong_rate_is_not() {
    let bank = lagrange::bank::embedded::bank();
    let problem = bank
        .problems
        .iter()
        .find(|p| p.id == "conical-pendulum")
        .unwrap();
    assert!(lagrange::bank::verify::verify(problem).is_empty());
    let text = include_str!("../../problems/conical-pendulum.toml")
        .replace("answer = \"g/(l*cos(alpha))\"", "answer = \"g/l\"")
        .replace("wrong = [\"g/l\", ", "wrong = [");
    let bad = lagrange::bank::load_str("bad.toml", &text).unwrap();
    let findings = lagrange::bank::verify::verify(&bad);
    assert_eq!(findings.len(), 1, "{findings:?}");
    assert_eq!(findings[0].code, "not-steady");
}

#[test]
fn heavy_symmetric_top_steady_precession() {
    // Ω (C ω₃ − A Ω cos θ₀) = M g h with ω₃ = p_ψ/C, Ω = (p_φ − p_ψ cos θ)/(A sin² θ); the
    // nutation frequency is √(V_eff''(θ₀)/A) with V_eff = (p_φ − p_ψ cos θ)²/(2A sin² θ) + M g h cos θ.
    let l = "1/2*A*(theta'^2 + sin(theta)^2*phi'^2) + 1/2*C*(psi' + cos(theta)*phi')^2 - M*g*h*cos(theta)";
    let (a, c, mgh, pphi, ppsi) = (1.0f64, 2.0f64, 1.0f64, 3.0f64, 4.0f64);
    let rep = steady_modes(
        l,
        &["theta", "phi", "psi"],
        &[("A", "1"), ("C", "2"), ("M", "1"), ("g", "1"), ("h", "1")],
        &[("p_phi", "3"), ("p_psi", "4")],
    );
    let e = rep
        .equilibria
        .iter()
        .find(|e| e.coordinates[0] > 0.0)
        .unwrap();
    let th = e.coordinates[0];
    let w3 = ppsi / c;
    let om = (pphi - ppsi * th.cos()) / (a * th.sin().powi(2));
    assert!(close(om * (c * w3 - a * om * th.cos()), mgh), "θ₀ = {th}");
    let veff =
        |t: f64| (pphi - ppsi * t.cos()).powi(2) / (2.0 * a * t.sin().powi(2)) + mgh * t.cos();
    let hstep = 1e-4;
    let second = (veff(th + hstep) - 2.0 * veff(th) + veff(th - hstep)) / (hstep * hstep);
    let want = (second / a).sqrt();
    assert!(
        (e.frequencies[0] - want).abs() < 1e-5 * want,
        "{:?} vs {want}",
        e.frequencies
    );
}

#[test]
fn modes_steady_prints_the_routhian_the_rate_and_the_oscillation() {
    let (code, out, err) = crate::helpers::lagrange(&[
        "modes",
        "-L",
        "1/2*m*(r'^2 + r^2*phi'^2) + k/r",
        "-q",
        "r,phi",
        "--params",
        "m=1, k=1",
        "--range",
        "r=0.1:10",
        "--steady",
        "p_phi=1",
    ]);
    assert_eq!(code, 0, "{err}");
    insta::assert_snapshot!("modes_steady_kepler", out);
    let (code, out, err) = crate::helpers::lagrange(&[
        "modes",
        "-L",
        "1/2*((x' - Omega*y)^2 + (y' + Omega*x)^2) - 2*x^2 - 2*y^2",
        "-q",
        "x,y",
        "--at",
        "x=0, y=0",
        "--symbolic",
    ]);
    assert_eq!(code, 0, "{err}");
    insta::assert_snapshot!("modes_symbolic_rotating_trap", out);
    let (code, _, err) = crate::helpers::lagrange(&[
        "modes",
        "-L",
        "1/2*m*r'^2 - k*r^2",
        "-q",
        "r",
        "--params",
        "m=1, k=1",
        "--steady",
        "p_r=1",
    ]);
    assert_ne!(code, 0);
    insta::assert_snapshot!("modes_steady_not_cyclic", err);
}

#[test]
fn three_masses_between_fixed_walls_have_the_textbook_frequencies() {
    // Four equal springs, three equal masses: ω² = (2 − √2) k/m, 2 k/m, (2 + √2) k/m.
    let (mut sys, r) = symbolic(
        "1/2*m*(x1'^2 + x2'^2 + x3'^2) - 1/2*k*(x1^2 + (x2 - x1)^2 + (x3 - x2)^2 + x3^2)",
        &["x1", "x2", "x3"],
        &["0", "0", "0"],
    );
    let r = r.unwrap();
    assert!(same_roots(
        &mut sys,
        &r,
        &["(2 - sqrt(2))*k/m", "2*k/m", "(2 + sqrt(2))*k/m"]
    ));
}

#[test]
fn a_momentum_given_twice_or_misnamed_is_refused() {
    let sys = System::from_lagrangian("1/2*m*(r'^2 + r^2*phi'^2) + k/r", &["r", "phi"]).unwrap();
    for (steady, code) in [
        (
            &[("p_phi", "1"), ("p_phi", "2")][..],
            "momentum-given-twice",
        ),
        (&[("phi", "1")][..], "not-a-momentum"),
    ] {
        let opts = ModesOptions {
            params: pairs(&[("m", "1"), ("k", "1")]),
            steady: pairs(steady),
            ..ModesOptions::default()
        };
        match modes(&sys, &opts) {
            Err(ModesError::Steady(e)) => assert_eq!(e.code(), code),
            other => panic!("{steady:?}: {other:?}"),
        }
    }
}

/// A mass m₁ on a table tied through a hole to a hanging m₂, with one steady-motion part.
fn table_problem(part: &str) -> String {
    format!(
        r#"
id = "table-hole"
title = "Mass on a table through a hole"
coordinates = [
  {{ name = "r", range = [0.5, 2.0] }},
  {{ name = "phi", periodic = true }},
]
lagrangian = "1/2*(m1 + m2)*r'^2 + 1/2*m1*r^2*phi'^2 - m2*g*r"

[parameters]
m1 = {{ dimension = "M", range = [0.5, 2.0] }}
m2 = {{ dimension = "M", range = [0.5, 2.0] }}
g = {{ dimension = "L T^-2", range = [5.0, 15.0] }}
R = {{ dimension = "L", range = [0.5, 2.0] }}

[[parts]]
id = "steady"
kind = "steady-motion"
prompt = "p"
{part}
"#
    )
}

#[test]
fn steady_motion_parts_prove_rates_and_refuse_what_they_cannot_prove() {
    let verify = |part: &str| {
        let p = lagrange::bank::load_str("t.toml", &table_problem(part)).unwrap();
        lagrange::bank::verify::verify(&p)
            .into_iter()
            .map(|f| f.code)
            .collect::<Vec<_>>()
    };
    // m₁ R φ'² = m₂ g.
    assert!(verify("answer = \"sqrt(m2*g/(m1*R))\"\nat = { r = \"R\" }").is_empty());
    assert!(verify("answer = \"m2*g/(m1*R)\"\nsquared = true\nat = { r = \"R\" }").is_empty());
    assert_eq!(
        verify("answer = \"sqrt(g/R)\"\nat = { r = \"R\" }"),
        vec!["not-steady"]
    );
    // r is not cyclic: it cannot be the coordinate that moves.
    assert_eq!(
        verify("answer = \"1\"\nat = { phi = \"0\" }"),
        vec!["not-cyclic"]
    );
    // Every coordinate named: nothing moves.
    assert_eq!(
        verify("answer = \"1\"\nat = { r = \"R\", phi = \"0\" }"),
        vec!["bad-steady"]
    );
}

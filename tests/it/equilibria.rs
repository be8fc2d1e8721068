//! Issue 13, equilibria: continua of equilibria (a cyclic x, a free chain), explicit time
//! refused, `--at` checked, degenerate minima found once. Physics from closed forms: the
//! cart-pendulum's ω² = (M + m) g/(M l) about θ = 0 with x arbitrary; the free chain's
//! translation; V = x⁴ has one equilibrium at 0.

use lagrange::bank::{load_str, verify::verify};
use lagrange::mechanics::equilibria::Stability;
use lagrange::mechanics::{MechError, System};
use lagrange::report::{ModesError, ModesOptions, ModesReport};

const CART: &str =
    "1/2*(M+m)*x'^2 + m*l*x'*theta'*cos(theta) + 1/2*m*l^2*theta'^2 + m*g*l*cos(theta)";

fn pairs(text: &str) -> Vec<(String, String)> {
    lagrange::report::modes::assignments(text).unwrap()
}

fn modes(
    l: &str,
    coords: &[&str],
    params: &str,
    at: Option<&str>,
) -> Result<ModesReport, ModesError> {
    let sys = System::from_lagrangian(l, coords).unwrap();
    let opts = ModesOptions {
        default_range: Some((-10.0, 10.0)),
        ranges: Vec::new(),
        params: pairs(params),
        at: at.map(pairs),
        symbolic: false,
        steady: Vec::new(),
    };
    lagrange::report::modes(&sys, &opts)
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-7 * (1.0 + a.abs().max(b.abs()))
}

#[test]
fn the_cart_pendulum_is_x_arbitrary_theta_zero_with_the_textbook_frequency() {
    let (big, m, l, g) = (2.0, 1.0, 1.5, 9.8);
    let r = modes(CART, &["x", "theta"], "M=2, m=1, l=1.5, g=9.8", None).unwrap();
    assert_eq!(
        r.equilibria.len(),
        2,
        "one continuum per θ, not a row of points"
    );
    let bottom = &r.equilibria[0];
    assert_eq!(bottom.free, vec![vec![1.0, 0.0]]);
    assert_eq!(bottom.coordinates[1], 0.0);
    assert_eq!(bottom.stability, Stability::Stable);
    let w2 = (big + m) * g / (big * l);
    assert!(
        bottom.frequencies.iter().any(|w| close(w * w, w2)),
        "{:?}",
        bottom.frequencies
    );
    let top = &r.equilibria[1];
    assert!(close(top.coordinates[1].abs(), std::f64::consts::PI));
    assert_eq!(top.stability, Stability::Unstable);
    let text = r.render(lagrange::expr::Style::Plain, &lagrange::report::Plain);
    assert!(text.contains("x arbitrary, theta = 0: stable"), "{text}");
}

#[test]
fn a_free_chain_is_one_continuum_along_its_translation() {
    let l = "1/2*x1'^2 + 1/2*x2'^2 + 1/2*x3'^2 - 1/2*(x1-x2)^2 - 1/2*(x2-x3)^2";
    let r = modes(l, &["x1", "x2", "x3"], "", None).unwrap();
    assert_eq!(r.equilibria.len(), 1);
    assert_eq!(r.equilibria[0].free, vec![vec![1.0, 1.0, 1.0]]);
    assert_eq!(r.equilibria[0].coordinates, vec![0.0, 0.0, 0.0]);
}

#[test]
fn a_degenerate_minimum_is_one_equilibrium_and_not_harmonic() {
    let r = modes("1/2*x'^2 - x^4", &["x"], "", None).unwrap();
    assert_eq!(r.equilibria.len(), 1, "not 44 points at ±1e-4");
    assert_eq!(r.equilibria[0].coordinates, vec![0.0]);
    assert!(r.equilibria[0].not_harmonic);
    assert_eq!(r.equilibria[0].stability, Stability::Marginal);
    // Regression (found using it): its zero mode was printed as "free motion along (1)", but
    // V = x⁴ restores; it is not free.
    let text = r.render(lagrange::expr::Style::Plain, &lagrange::report::Plain);
    assert!(!text.contains("free motion"), "{text}");
    assert!(text.contains("no linear restoring force"), "{text}");
}

#[test]
fn the_hoop_at_the_critical_spin_has_its_bottom_exactly_at_zero() {
    // R ω² = g: the bottom is a quartic minimum, θ = 0 exactly, not θ = 1e-8.
    let l = "1/2*R^2*theta'^2 + 1/2*w^2*R^2*sin(theta)^2 + g*R*cos(theta)";
    let r = modes(l, &["theta"], "R=1, g=4, w=2", None).unwrap();
    let pts: Vec<f64> = r.equilibria.iter().map(|e| e.coordinates[0]).collect();
    assert_eq!(pts.len(), 2, "{pts:?}");
    assert_eq!(pts[0], 0.0);
    assert!(r.equilibria[0].not_harmonic);
}

#[test]
fn an_explicit_time_dependence_is_refused() {
    // The Kapitza pendulum: the support oscillates as a cos(ν t).
    let l = "1/2*l^2*theta'^2 - l*a*nu*sin(nu*t)*sin(theta)*theta' + g*l*cos(theta)";
    let err = modes(l, &["theta"], "l=1, a=0.1, nu=50, g=9.8", None).unwrap_err();
    assert!(
        matches!(err, ModesError::Mech(MechError::ExplicitTime { .. })),
        "{err}"
    );
    // In closed form too: no ω² with a cos(ν t) in it.
    let sys = System::from_lagrangian(l, &["theta"]).unwrap();
    let opts = ModesOptions {
        default_range: None,
        ranges: Vec::new(),
        params: Vec::new(),
        at: Some(pairs("theta = 0")),
        symbolic: true,
        steady: Vec::new(),
    };
    let err = lagrange::report::modes(&sys, &opts).unwrap_err();
    assert!(
        matches!(err, ModesError::Mech(MechError::ExplicitTime { .. })),
        "{err}"
    );
}

#[test]
fn a_point_that_is_not_an_equilibrium_is_refused_with_the_force() {
    let err = modes(
        "1/2*theta'^2 + cos(theta)",
        &["theta"],
        "",
        Some("theta = 1"),
    )
    .unwrap_err();
    let text = err.to_string();
    assert!(text.contains("not an equilibrium"), "{text}");
    // ∂V/∂θ = sin 1.
    assert!(text.contains("0.841471"), "{text}");
}

#[test]
fn the_point_given_may_be_an_expression_in_the_parameters() {
    let l = "1/2*m*(r'^2 + r^2*theta'^2) + m*g*r*cos(theta) - 1/2*k*(r-l0)^2";
    let r = modes(
        l,
        &["r", "theta"],
        "m=1, g=9.8, k=10, l0=1",
        Some("r = l0 + m*g/k, theta = 0"),
    )
    .unwrap();
    let e = &r.equilibria[0];
    assert!(close(e.coordinates[0], 1.98));
    // Radial ω² = k/m, swing ω² = g/r₀.
    let w2 = &e.omega_squared;
    assert!(w2.iter().any(|w| close(*w, 10.0)), "{w2:?}");
    assert!(w2.iter().any(|w| close(*w, 9.8 / 1.98)), "{w2:?}");
}

const SPRING_CART: &str = r#"
id = "t-spring-cart"
title = "t"
source = "test"
statement = "A block on a spring riding a free cart."
coordinates = [
  { name = "x", range = [-2.0, 2.0] },
  { name = "s", range = [-1.0, 1.0] },
]
lagrangian = "1/2*M*x'^2 + 1/2*m*(x' + s')^2 - 1/2*k*s^2"

[parameters]
M = { dimension = "M", range = [0.5, 2.0] }
m = { dimension = "M", range = [0.5, 2.0] }
k = { dimension = "M T^-2", range = [1.0, 5.0] }

[[parts]]
id = "equilibria"
kind = "equilibria"
prompt = "Equilibria?"
answer = ANSWER
stability = ["stable"]
"#;

fn findings(answer: &str) -> Vec<(String, String)> {
    let text = SPRING_CART.replace("ANSWER", answer);
    let p = load_str("t.toml", &text).unwrap();
    verify(&p)
        .into_iter()
        .map(|f| (f.code.to_string(), f.message))
        .collect()
}

#[test]
fn a_continuum_is_statable_with_any_and_verifies() {
    assert_eq!(findings(r#"["x = any, s = 0"]"#), vec![]);
}

#[test]
fn a_continuum_stated_as_a_point_is_named_not_reported_missing() {
    let f = findings(r#"["x = 0, s = 0"]"#);
    assert_eq!(f.len(), 1, "{f:?}");
    assert_eq!(f[0].0, "not-isolated", "{f:?}");
    assert!(f[0].1.contains("x = any"), "{f:?}");
}

#[test]
fn any_on_a_coordinate_that_is_not_free_fails() {
    let f = findings(r#"["x = any, s = any"]"#);
    assert_eq!(f.len(), 1, "{f:?}");
}

const ELASTIC: &str = r#"
id = "t-elastic"
title = "t"
source = "test"
statement = "A bob on a spring swinging in a vertical plane."
coordinates = [
  { name = "r", range = [0.1, 5.0] },
  { name = "theta", periodic = true },
]
lagrangian = "1/2*m*(r'^2 + r^2*theta'^2) + m*g*r*cos(theta) - 1/2*k*(r - l0)^2"
assume = ["k*l0 > m*g"]

[parameters]
m = { dimension = "M", range = [0.5, 2.0] }
g = { dimension = "L T^-2", range = [5.0, 15.0] }
k = { dimension = "M T^-2", range = [20.0, 50.0] }
l0 = { dimension = "L", range = [0.5, 2.0] }

[[bodies]]
kind = "point"
mass = "m"
position = ["r*sin(theta)", "-r*cos(theta)"]

[[potentials]]
kind = "gravity"
g = "g"
axis = "y"

[[potentials]]
kind = "spring"
k = "k"
natural = "l0"
from = ["0", "0"]
to = 1

[[parts]]
id = "frequencies"
kind = "frequencies"
prompt = "Frequencies?"
answer = ["sqrt(k/m)", "sqrt(g*k/(k*l0 + m*g))"]
at = { r = "AT", theta = "0" }

[[parts]]
id = "equilibria"
kind = "equilibria"
prompt = "Equilibria?"
answer = ["r = l0 + m*g/k, theta = 0", "r = l0 - m*g/k, theta = pi"]
stability = ["stable", "unstable"]
"#;

fn elastic_findings(at: &str) -> Vec<(String, String)> {
    let p = load_str("t.toml", &ELASTIC.replace("AT", at)).unwrap();
    verify(&p)
        .into_iter()
        .map(|f| (f.code.to_string(), f.message))
        .collect()
}

#[test]
fn the_elastic_pendulum_with_bodies_verifies_under_its_assumption() {
    // Radial ω² = k/m; swing ω² = g/r₀ = g k/(k l₀ + m g).
    assert_eq!(elastic_findings("l0 + m*g/k"), vec![]);
}

#[test]
fn a_frequency_part_at_a_point_that_is_not_an_equilibrium_fails() {
    let f = elastic_findings("l0");
    assert_eq!(f.len(), 1, "{f:?}");
    assert_eq!(f[0].0, "not-an-equilibrium", "{f:?}");
    assert!(f[0].1.contains("∂V/∂r"), "{f:?}");
}

#[test]
fn the_spherical_pendulum_at_its_pole_is_explained_not_refused() {
    let l = "1/2*m*l^2*(theta'^2 + sin(theta)^2*phi'^2) + m*g*l*cos(theta)";
    let r = modes(l, &["theta", "phi"], "m=1, l=1, g=9.8", None).unwrap();
    assert_eq!(r.equilibria.len(), 2);
    for e in &r.equilibria {
        assert_eq!(e.singular_chart, vec!["φ".to_string()]);
        assert!(e.frequencies.is_empty() && e.growth_rates.is_empty());
    }
    let at = modes(
        l,
        &["theta", "phi"],
        "m=1, l=1, g=9.8",
        Some("theta = 0, phi = 0"),
    )
    .unwrap();
    assert_eq!(at.equilibria[0].singular_chart.len(), 1);
}

#[test]
fn six_uncoupled_pendula_have_every_one_of_their_729_equilibria() {
    // Each qᵢ in [−4, 4] rests at −π, 0 or π: 3⁶ points, one of them (all at 0) stable.
    let names = ["q1", "q2", "q3", "q4", "q5", "q6"];
    let l: Vec<String> = names
        .iter()
        .map(|q| format!("1/2*{q}'^2 + cos({q})"))
        .collect();
    let sys = System::from_lagrangian(&l.join(" + "), &names).unwrap();
    let opts = ModesOptions {
        default_range: Some((-4.0, 4.0)),
        ranges: Vec::new(),
        params: Vec::new(),
        at: None,
        symbolic: false,
        steady: Vec::new(),
    };
    let r = lagrange::report::modes(&sys, &opts).unwrap();
    assert_eq!(r.equilibria.len(), 729);
    let stable: Vec<_> = r
        .equilibria
        .iter()
        .filter(|e| e.stability == Stability::Stable)
        .collect();
    assert_eq!(stable.len(), 1);
    assert_eq!(stable[0].coordinates, vec![0.0; 6]);
    let search = r.search.as_ref().unwrap();
    assert_eq!(search.blocks.len(), 6);
    let text = r.render(lagrange::expr::Style::Plain, &lagrange::report::Plain);
    assert!(text.contains("decouple into 6 blocks"), "{text}");
    assert!(text.contains("may be missing"), "{text}");
    assert!(!text.contains("every equilibrium"), "{text}");
}

#[test]
fn a_weak_spring_beside_a_stiff_one_is_harmonic_and_stable() {
    // ω² = 1e-12 and 1: both real restoring forces, neither degenerate.
    let l = "1/2*x'^2 + 1/2*y'^2 - 1/2*1e-12*x^2 - 1/2*y^2";
    let r = modes(l, &["x", "y"], "", None).unwrap();
    assert_eq!(r.equilibria.len(), 1);
    let e = &r.equilibria[0];
    assert_eq!(e.stability, Stability::Stable);
    assert!(!e.not_harmonic);
    assert!(e.free.is_empty());
    assert!(
        e.frequencies.iter().any(|w| close(*w, 1e-6)),
        "{:?}",
        e.frequencies
    );
}

#[test]
fn a_translating_chain_is_named_as_a_continuum_not_a_missing_point() {
    let text = r#"
id = "t-chain"
title = "t"
source = "test"
statement = "Two masses joined by a spring on a free rail."
coordinates = [
  { name = "x1", range = [-3.0, 3.0] },
  { name = "x2", range = [-3.0, 3.0] },
]
lagrangian = "1/2*m*(x1'^2 + x2'^2) - 1/2*k*(x1 - x2)^2"

[parameters]
m = { dimension = "M", range = [0.5, 2.0] }
k = { dimension = "M T^-2", range = [1.0, 5.0] }

[[parts]]
id = "equilibria"
kind = "equilibria"
prompt = "Equilibria?"
answer = ["x1 = 0, x2 = 0"]
"#;
    let p = load_str("t.toml", text).unwrap();
    let f: Vec<_> = verify(&p)
        .into_iter()
        .map(|f| (f.code, f.message))
        .collect();
    assert_eq!(f.len(), 1, "{f:?}");
    assert_eq!(f[0].0, "not-isolated", "{f:?}");
    assert!(f[0].1.contains("along (1, 1)"), "{f:?}");
    assert!(!f[0].1.contains("x1 = -3"), "{f:?}");
}

/// Regression (found when merging): `any` was read as 0 on both sides, so a student's single
/// point `x = 0, s = 0` passed for the continuum `x = any, s = 0`.
#[test]
fn a_point_of_a_continuum_is_not_the_continuum() {
    let bank = lagrange::bank::embedded::bank();
    let p = bank.problem("spring-cart").expect("in the bank");
    let mut c = lagrange::check::Checker::new(p);
    let v = c.check("equilibria", "x = 0, s = 0").expect("a part");
    assert_eq!(v.status, lagrange::check::Status::Incorrect);
    assert!(
        v.diagnoses.iter().any(|d| d.message.contains("`x = any`")),
        "{:?}",
        v.diagnoses
    );
    // The part asks for stability (issue 19 §3), stated here after the point.
    let v = c
        .check("equilibria", "s = 0 (stable), x = any")
        .expect("a part");
    assert_eq!(v.status, lagrange::check::Status::Correct);
    assert_eq!(v.reading.unicode, "x = any, s = 0");
}

//! Issue 13, modes: zero modes and free coordinates, gyroscopic and damped systems, and
//! small oscillations on a constraint manifold — each against the textbook's closed form,
//! never against the tool's own output.

use lagrange::mechanics::equilibria::Stability;
use lagrange::mechanics::modes::Modes;
use lagrange::mechanics::{MechError, System};

use super::helpers::lagrange;

/// Parameter values in the system's order.
fn values(sys: &System, pairs: &[(&str, f64)]) -> Vec<f64> {
    sys.parameters
        .iter()
        .map(|p| pairs.iter().find(|(n, _)| *n == p.name).unwrap().1)
        .collect()
}

fn modes(sys: &mut System, pairs: &[(&str, f64)], q0: &[f64]) -> Result<Modes, MechError> {
    let d = sys.derive().unwrap();
    let params = values(sys, pairs);
    sys.modes_at(&d, &params, q0)
}

fn assert_list(got: &[f64], want: &[f64]) {
    assert_eq!(got.len(), want.len(), "{got:?} vs {want:?}");
    for (a, b) in got.iter().zip(want) {
        assert!(
            (a - b).abs() <= 1e-9 * (1.0 + b.abs()),
            "{got:?} vs {want:?}"
        );
    }
}

/// Three equal masses joined by two equal springs, free to slide: ω = 0 (the chain
/// translates), √(k/m), √(3k/m). Values chosen so ω² = 0 comes out as rounding, not 0.
#[test]
fn free_three_mass_chain_has_a_zero_mode() {
    let l = "1/2*m*(x1'^2 + x2'^2 + x3'^2) - 1/2*k*(x2 - x1)^2 - 1/2*k*(x3 - x2)^2";
    for (m, k) in [(1.0, 1.0), (0.3, 7.1), (2.9, 0.11)] {
        let mut sys = System::from_lagrangian(l, &["x1", "x2", "x3"]).unwrap();
        let r = modes(&mut sys, &[("m", m), ("k", k)], &[0.1, 0.1, 0.1]).unwrap();
        let w = f64::sqrt(k / m);
        assert_list(&r.frequencies, &[0.0, w, 3f64.sqrt() * w]);
        assert!(r.growth_rates.is_empty(), "{:?}", r.growth_rates);
        assert_eq!(r.stability, Stability::Marginal);
        assert_eq!(r.free_directions.len(), 1);
        assert_list(&r.free_directions[0], &[1.0, 1.0, 1.0]);
        // The middle mass stands still in the antisymmetric mode: exactly 0, not 1e-17.
        let anti = r
            .modes
            .iter()
            .find(|x| (x.omega_squared - k / m).abs() < 1e-9);
        assert_eq!(anti.unwrap().shape[1], 0.0);
    }
}

/// A pendulum on a freely sliding cart: ω = 0 and ω² = (M + m) g/(M l).
#[test]
fn cart_pendulum_zero_mode_and_recoil_frequency() {
    let l = "1/2*(M+m)*x'^2 + m*l*x'*theta'*cos(theta) + 1/2*m*l^2*theta'^2 + m*g*l*cos(theta)";
    let (big, m, len, g) = (1.3, 0.7, 0.9, 9.81);
    let mut sys = System::from_lagrangian(l, &["x", "theta"]).unwrap();
    let pairs = [("M", big), ("m", m), ("l", len), ("g", g)];
    let r = modes(&mut sys, &pairs, &[0.4, 0.0]).unwrap();
    assert_list(
        &r.frequencies,
        &[0.0, f64::sqrt((big + m) * g / (big * len))],
    );
    assert_eq!(r.stability, Stability::Marginal);
    assert_list(&r.free_directions[0], &[1.0, 0.0]);
    let names = ["x".to_string(), "θ".to_string()];
    let described = r.describe(&names);
    assert!(
        described.iter().any(|d| d.contains("free motion")),
        "{described:?}"
    );
    // The swinging mode: cart and bob move in antiphase, x/θ = −m l/(M + m).
    let swing = r.modes.iter().find(|x| x.omega_squared > 0.0).unwrap();
    let ratio = swing.shape[0] / swing.shape[1];
    assert!((ratio + m * len / (big + m)).abs() < 1e-9, "{ratio}");
    // Upside down: one growth rate, the same magnitude, and still the free mode.
    let r = modes(&mut sys, &pairs, &[0.0, std::f64::consts::PI]).unwrap();
    assert_eq!(r.stability, Stability::Unstable);
    assert_list(&r.growth_rates, &[f64::sqrt((big + m) * g / (big * len))]);
    assert_list(&r.frequencies, &[0.0]);
}

const ROTATING_TRAP: &str = "1/2*m*((x' - W*y)^2 + (y' + W*x)^2) - 1/2*(kx*x^2 + ky*y^2)";

fn trap(kx: f64, ky: f64, w: f64) -> Modes {
    let mut sys = System::from_lagrangian(ROTATING_TRAP, &["x", "y"]).unwrap();
    let pairs = [("m", 1.0), ("kx", kx), ("ky", ky), ("W", w)];
    modes(&mut sys, &pairs, &[0.0, 0.0]).unwrap()
}

/// Isotropic trap of frequency 2 in a frame rotating at Ω: ω = |2 ∓ Ω|, stable for every Ω
/// — including Ω > 2, where K < 0 and only the Coriolis coupling stabilises it.
#[test]
fn rotating_isotropic_trap_frequencies_are_two_minus_and_plus_omega() {
    for w in [0.3, 1.0, 1.7, 2.5, 4.0] {
        let r = trap(4.0, 4.0, w);
        assert!(r.gyroscopic && !r.damping);
        assert_eq!(r.stability, Stability::Stable, "Ω = {w}");
        let mut want = [(2.0f64 - w).abs(), 2.0 + w];
        want.sort_by(f64::total_cmp);
        assert_list(&r.frequencies, &want);
        assert!(r.modes.is_empty(), "no real shapes for a gyroscopic mode");
    }
}

/// Anisotropic trap ω_x = 1, ω_y = 3: unstable exactly for ω_x < Ω < ω_y; outside the window
/// the frequencies solve ω⁴ − (ω_x² + ω_y² + 2Ω²) ω² + (ω_x² − Ω²)(ω_y² − Ω²) = 0.
#[test]
fn rotating_anisotropic_trap_has_its_stability_window() {
    let (a, b) = (1.0f64, 9.0f64);
    for w in [0.5, 0.9, 1.1, 2.0, 2.9, 3.1, 5.0] {
        let r = trap(a, b, w);
        let inside = 1.0 < w && w < 3.0;
        let want = if inside {
            Stability::Unstable
        } else {
            Stability::Stable
        };
        assert_eq!(r.stability, want, "Ω = {w}");
        let s = a + b + 2.0 * w * w;
        let p = (a - w * w) * (b - w * w);
        let disc = (s * s - 4.0 * p).sqrt();
        let (lo, hi) = ((s - disc) / 2.0, (s + disc) / 2.0);
        if inside {
            // p < 0: one ω² < 0 is a growth rate √(−ω²), the other an oscillation.
            assert_list(&r.growth_rates, &[(-lo).sqrt()]);
            assert_list(&r.frequencies, &[hi.sqrt()]);
            assert!(
                r.decay_rates.is_empty(),
                "the decaying partner is not a mode"
            );
        } else {
            assert_list(&r.frequencies, &[lo.sqrt(), hi.sqrt()]);
        }
    }
}

/// m ẍ + c ẋ + k x = 0 is damping, not gyroscopic: decay rate c/(2m), damping ratio
/// c/(2√(km)), damped frequency √(k/m − c²/4m²); overdamped: two decay rates.
#[test]
fn damping_is_reported_as_damping() {
    let (m, k, c) = (2.0, 18.0, 1.2);
    let mut sys = System::from_lagrangian("1/2*m*x'^2 - 1/2*k*x^2", &["x"]).unwrap();
    sys.set_forces("-c*x'").unwrap();
    let r = modes(&mut sys, &[("m", m), ("k", k), ("c", c)], &[0.0]).unwrap();
    assert!(r.damping && !r.gyroscopic);
    assert_eq!(r.stability, Stability::Stable);
    assert!(r.frequencies.is_empty() && r.growth_rates.is_empty());
    let d = r.damped[0];
    assert!((d.decay_rate - c / (2.0 * m)).abs() < 1e-12);
    assert!((d.damping_ratio - c / (2.0 * (k * m).sqrt())).abs() < 1e-12);
    assert!((d.frequency - (k / m - c * c / (4.0 * m * m)).sqrt()).abs() < 1e-12);
    let c = 20.0;
    let r = modes(&mut sys, &[("m", m), ("k", k), ("c", c)], &[0.0]).unwrap();
    let g = c / (2.0 * m);
    let s = (g * g - k / m).sqrt();
    assert_list(&r.decay_rates, &[g - s, g + s]);
}

/// The Cartesian pendulum x² + y² = L²: linearized on the circle, ω² = g/L.
#[test]
fn cartesian_pendulum_is_linearized_on_its_constraint() {
    let (g, len) = (9.81, 1.7);
    let mut sys = System::from_lagrangian("1/2*m*(x'^2 + y'^2) - m*g*y", &["x", "y"]).unwrap();
    sys.add_constraint("x^2 + y^2 = L^2").unwrap();
    let pairs = [("m", 0.4), ("g", g), ("L", len)];
    let r = modes(&mut sys, &pairs, &[0.0, -len]).unwrap();
    assert_eq!(r.stability, Stability::Stable);
    assert_list(&r.frequencies, &[(g / len).sqrt()]);
    // On top: unstable with the same rate.
    let r = modes(&mut sys, &pairs, &[0.0, len]).unwrap();
    assert_eq!(r.stability, Stability::Unstable);
    assert_list(&r.growth_rates, &[(g / len).sqrt()]);
    // Off the circle, or on it but not balanced: refused.
    let e = modes(&mut sys, &pairs, &[0.0, -1.0]).unwrap_err();
    assert!(matches!(e, MechError::OffConstraint { index: 1 }), "{e:?}");
    let e = modes(&mut sys, &pairs, &[len, 0.0]).unwrap_err();
    assert!(
        matches!(e, MechError::NotConstrainedEquilibrium { .. }),
        "{e:?}"
    );
}

/// A rolling condition restricts velocities, not positions: refused, not a sliding disc's
/// modes.
#[test]
fn rolling_constraint_modes_are_refused() {
    let mut sys = System::from_lagrangian("1/2*M*x'^2 + 1/4*M*R^2*phi'^2", &["x", "phi"]).unwrap();
    sys.add_constraint("x' - R*phi' = 0").unwrap();
    let e = modes(&mut sys, &[("M", 1.0), ("R", 0.5)], &[0.0, 0.0]).unwrap_err();
    assert!(matches!(e, MechError::ModesRolling), "{e:?}");
}

#[test]
fn cli_shows_free_motion_and_never_a_round_off_growth_rate() {
    let (code, out, err) = lagrange(&[
        "modes",
        "-L",
        "1/2*m*(x1'^2 + x2'^2 + x3'^2) - 1/2*k*(x2 - x1)^2 - 1/2*k*(x3 - x2)^2",
        "-q",
        "x1,x2,x3",
        "--params",
        "m=0.3, k=7.1",
        "--at",
        "x1=0, x2=0, x3=0",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("ω = 0: free motion along (1, 1, 1)"), "{out}");
    assert!(!out.contains("growth"), "{out}");
    assert!(!out.contains("0.000000"), "{out}");
}

#[test]
fn cli_constraint_without_a_point_is_refused_with_the_reason() {
    let (code, _, err) = lagrange(&[
        "modes",
        "-L",
        "1/2*m*(x'^2 + y'^2) - m*g*y",
        "-q",
        "x,y",
        "--constraint",
        "x^2 + y^2 = L^2",
        "--params",
        "m=1, g=9.81, L=2",
    ]);
    assert_ne!(code, 0);
    assert!(err.contains("--at"), "{err}");
    assert!(!err.contains("no equilibrium"), "{err}");
}

/// `modes` and `problems verify` agree on the gyroscopic trap; the cart-pendulum's free mode
/// is part of its answer.
#[test]
fn bank_verifies_the_gyroscopic_trap_and_the_cart_zero_mode() {
    let (code, out, err) = lagrange(&["problems", "verify"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("✓ rotating-trap ("), "{out}");
    // Stable although K < 0: verify and `modes` agree (both keep the Coriolis terms).
    assert!(out.contains("✓ rotating-trap-fast"), "{out}");
    assert!(out.contains("✓ cart-pendulum"), "{out}");
    let (_, out, _) = lagrange(&[
        "check",
        "cart-pendulum",
        "frequencies",
        "0, sqrt((M+m)*g/(M*l))",
    ]);
    assert!(
        out.contains("correct") && !out.contains("incorrect"),
        "{out}"
    );
    let (_, out, _) = lagrange(&["modes", "rotating-trap", "--params", "m=1, k=4, Omega=3"]);
    assert!(
        out.contains("stable") && out.contains("frequencies ω: 1, 5"),
        "{out}"
    );
}

/// On a sphere x² + y² + z² = L² under gravity (the spherical pendulum in Cartesian
/// coordinates): ω² = g/L twice, a degenerate pair whose shapes are not singled out; on the
/// parabola y = x²/(2a): ω² = g/a (the curvature radius at the bottom is a).
#[test]
fn constrained_pendula_match_their_textbook_frequencies() {
    let (g, len, a) = (9.81, 1.3, 0.7);
    let mut sys =
        System::from_lagrangian("1/2*m*(x'^2 + y'^2 + z'^2) - m*g*z", &["x", "y", "z"]).unwrap();
    sys.add_constraint("x^2 + y^2 + z^2 = L^2").unwrap();
    let r = modes(
        &mut sys,
        &[("m", 2.0), ("g", g), ("L", len)],
        &[0.0, 0.0, -len],
    )
    .unwrap();
    let w = (g / len).sqrt();
    assert_list(&r.frequencies, &[w, w]);
    let names: Vec<String> = ["x", "y", "z"].iter().map(|s| s.to_string()).collect();
    assert!(
        r.describe(&names)
            .iter()
            .all(|d| d.starts_with("degenerate")),
        "{:?}",
        r.describe(&names)
    );
    let mut sys = System::from_lagrangian("1/2*m*(x'^2 + y'^2) - m*g*y", &["x", "y"]).unwrap();
    sys.add_constraint("y = x^2/(2*a)").unwrap();
    let r = modes(&mut sys, &[("m", 0.3), ("g", g), ("a", a)], &[0.0, 0.0]).unwrap();
    assert_list(&r.frequencies, &[(g / a).sqrt()]);
    // A bead on a horizontal ring: nothing restores it, ω = 0 along the ring.
    let mut sys = System::from_lagrangian("1/2*m*(x'^2 + y'^2)", &["x", "y"]).unwrap();
    sys.add_constraint("x^2 + y^2 = R^2").unwrap();
    let r = modes(&mut sys, &[("m", 1.0), ("R", 2.0)], &[0.0, -2.0]).unwrap();
    assert_eq!(r.stability, Stability::Marginal);
    assert_list(&r.frequencies, &[0.0]);
    assert_list(&r.free_directions[0], &[1.0, 0.0]);
}

/// What `modes` prints for a free chain, a rotating trap, a damped oscillator and a
/// Cartesian pendulum.
#[test]
fn modes_reports_snapshot() {
    let cases: [&[&str]; 4] = [
        &[
            "-L",
            "1/2*m*(x1'^2 + x2'^2 + x3'^2) - 1/2*k*(x2 - x1)^2 - 1/2*k*(x3 - x2)^2",
            "-q",
            "x1,x2,x3",
            "--params",
            "m=1, k=1",
            "--at",
            "x1=0, x2=0, x3=0",
        ],
        &[
            "-L",
            "1/2*((x' - W*y)^2 + (y' + W*x)^2) - 2*(x^2 + y^2)",
            "-q",
            "x,y",
            "--params",
            "W=3",
            "--at",
            "x=0, y=0",
        ],
        &[
            "-L",
            "1/2*x'^2 - 9/2*x^2",
            "-q",
            "x",
            "--force",
            "-0.6*x'",
            "--at",
            "x=0",
        ],
        &[
            "-L",
            "1/2*m*(x'^2 + y'^2) - m*g*y",
            "-q",
            "x,y",
            "--constraint",
            "x^2 + y^2 = L^2",
            "--params",
            "m=1, g=9.81, L=2",
            "--at",
            "x=0, y=-2",
        ],
    ];
    let mut all = String::new();
    for args in cases {
        let mut full = vec!["modes"];
        full.extend_from_slice(args);
        let (code, out, err) = lagrange(&full);
        assert_eq!(code, 0, "{err}");
        all.push_str(&format!("$ {}\n{out}\n", args.join(" ")));
    }
    insta::assert_snapshot!(all);
}

/// A charge in a uniform magnetic field (L = ½ m v² + q B x ẏ): the cyclotron frequency
/// qB/m and two neutral directions (the guiding centre can sit anywhere), no growth.
#[test]
fn charge_in_a_magnetic_field_has_the_cyclotron_frequency() {
    let mut sys = System::from_lagrangian("1/2*m*(x'^2 + y'^2) + e*B*x*y'", &["x", "y"]).unwrap();
    let (m, e, b) = (0.7, 1.3, 2.1);
    let r = modes(&mut sys, &[("m", m), ("e", e), ("B", b)], &[0.2, -0.4]).unwrap();
    assert!(r.gyroscopic && !r.damping);
    assert_eq!(r.stability, Stability::Marginal);
    // The guiding centre's X and Y are one degree of freedom, of frequency 0.
    assert_list(&r.frequencies, &[0.0, e * b / m]);
    assert!(r.growth_rates.is_empty());
    assert_eq!(r.free_directions.len(), 2);
}

/// Just off the critical rotation of an isotropic trap the slow mode |ω₀ − Ω| is below what
/// the solver resolves: it is one mode of frequency 0, not two, beside ω₀ + Ω.
#[test]
fn a_mode_too_slow_to_resolve_is_one_zero() {
    let r = trap(4.0, 4.0, 2.0 * (1.0 + 1e-7));
    assert_eq!(r.frequencies.len(), 2, "{:?}", r.frequencies);
    assert!((r.frequencies[1] - 4.0).abs() < 1e-5, "{:?}", r.frequencies);
}

/// A free mode's 0 written as an expression that vanishes only up to rounding is the 0 the
/// part asks for.
#[test]
fn a_zero_frequency_up_to_rounding_is_accepted() {
    let answer = "sqrt((M+m)^2*g/(M^2*l)) - (M+m)/M*sqrt(g/l), sqrt((M+m)*g/(M*l))";
    let (_, out, err) = lagrange(&["check", "cart-pendulum", "frequencies", answer]);
    assert!(
        out.contains("\ncorrect") && !out.contains("incorrect"),
        "{out}{err}"
    );
}

//! The mechanics engine against results derived independently (by hand, from Newton's laws
//! or from textbook formulas), on every system of the course notes and a few more.

use lagrange::expr::{Context, Id, Pool, read_expr};
use lagrange::mechanics::bodies::{Body, Potential};
use lagrange::mechanics::equilibria::Stability;
use lagrange::mechanics::system::Coordinate;
use lagrange::mechanics::{MechError, System};

/// Asserts that `got` and `want` (text) are the same expression after expansion.
fn same(sys: &mut System, got: Id, want: &str) {
    let ctx = sys.open_context();
    let w = read_expr(want, &ctx, &mut sys.pool).unwrap();
    let d = sys.pool.sub(got, w);
    assert!(
        sys.is_zero(d),
        "got {} but expected {}",
        sys.pool.unicode(got),
        sys.pool.unicode(w)
    );
}

fn values(sys: &System, pairs: &[(&str, f64)]) -> Vec<f64> {
    sys.parameters
        .iter()
        .map(|p| {
            pairs
                .iter()
                .find(|(n, _)| *n == p.name)
                .unwrap_or_else(|| panic!("no value for {}", p.name))
                .1
        })
        .collect()
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-8 * (1.0 + a.abs().max(b.abs()))
}

/// Builds a system from point masses whose positions are typed text.
fn from_points(
    coords: &[(&str, bool, (f64, f64))],
    points: &[(&str, &[&str])],
    gravity: Option<(&str, usize)>,
) -> System {
    let mut pool = Pool::new();
    let coordinates: Vec<Coordinate> = coords
        .iter()
        .map(|&(name, periodic, range)| Coordinate {
            name: name.to_string(),
            sym: pool.symbol(name),
            periodic,
            range,
            domain: lagrange::mechanics::Domain::ANY,
        })
        .collect();
    let ctx = Context::open().with_coordinates(coords.iter().map(|c| c.0));
    let rd = |s: &str, pool: &mut Pool| read_expr(s, &ctx, pool).unwrap();
    let bodies: Vec<Body> = points
        .iter()
        .map(|(m, pos)| Body::Point {
            mass: rd(m, &mut pool),
            position: pos.iter().map(|p| rd(p, &mut pool)).collect(),
        })
        .collect();
    let potentials: Vec<Potential> = gravity
        .map(|(g, axis)| Potential::Gravity {
            g: rd(g, &mut pool),
            axis,
        })
        .into_iter()
        .collect();
    System::from_bodies(pool, coordinates, &bodies, &potentials)
}

const PI: f64 = std::f64::consts::PI;

#[test]
fn simple_pendulum() {
    let mut sys =
        System::from_lagrangian("1/2*m*l^2*theta'^2 + m*g*l*cos(theta)", &["theta"]).unwrap();
    let d = sys.derive().unwrap();
    same(&mut sys, d.steps[0].momentum, "m*l^2*theta'");
    same(&mut sys, d.steps[0].force, "-m*g*l*sin(theta)");
    same(
        &mut sys,
        d.steps[0].equation,
        "m*l^2*theta'' + m*g*l*sin(theta)",
    );
    same(&mut sys, d.mass[0][0], "m*l^2");
    same(&mut sys, d.forcing[0], "-m*g*l*sin(theta)");
    let e = sys.energy(&d);
    same(
        &mut sys,
        e.function,
        "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)",
    );
    // From L alone T and V are not known: whether h = T + V cannot be told.
    assert!(e.conserved && e.is_total.is_none() && e.cyclic.is_empty());
    let p = values(&sys, &[("m", 1.3), ("l", 0.7), ("g", 9.81)]);
    let eq = sys.equilibria(&d, &p).unwrap();
    let pts: Vec<(f64, Stability)> = eq.points.iter().map(|(q, s)| (q[0], *s)).collect();
    assert_eq!(pts.len(), 2, "{pts:?}");
    assert!(
        close(pts[0].0, 0.0) && pts[0].1 == Stability::Stable,
        "{pts:?}"
    );
    assert!(
        close(pts[1].0, PI) && pts[1].1 == Stability::Unstable,
        "{pts:?}"
    );
    let modes = sys.modes_at(&d, &p, &[0.0]).unwrap();
    assert!(close(modes.frequencies[0], (9.81f64 / 0.7).sqrt()));
    let at_top = sys.modes_at(&d, &p, &[PI]).unwrap();
    assert!(close(at_top.growth_rates[0], (9.81f64 / 0.7).sqrt()));
    let zero = sys.pool.zero();
    let sm = sys.symbolic_modes(&d, &[zero]).unwrap();
    assert_eq!(sm.omega_squared.len(), 1);
    same(&mut sys, sm.omega_squared[0], "g/l");
}

#[test]
fn bead_on_rotating_straight_wire() {
    // Inertial position of a bead at distance r on a horizontal wire turning at ω.
    let mut sys = from_points(
        &[("r", false, (-2.0, 2.0))],
        &[("m", &["r*cos(omega*t)", "r*sin(omega*t)"])],
        None,
    );
    let t = sys.kinetic.unwrap();
    same(&mut sys, t, "1/2*m*(r'^2 + r^2*omega^2)");
    let d = sys.derive().unwrap();
    same(&mut sys, d.steps[0].equation, "m*r'' - m*omega^2*r");
    let e = sys.energy(&d);
    // h = ½mṙ² − ½mr²ω² is conserved (L has no explicit t) but is not T + V.
    same(&mut sys, e.function, "1/2*m*r'^2 - 1/2*m*r^2*omega^2");
    assert!(e.conserved);
    assert_eq!(e.is_total, Some(false));
    let p = values(&sys, &[("m", 1.0), ("omega", 1.5)]);
    let eq = sys.equilibria(&d, &p).unwrap();
    assert_eq!(eq.points.len(), 1);
    assert!(close(eq.points[0].0[0], 0.0));
    assert_eq!(eq.points[0].1, Stability::Unstable);
    let m = sys.modes_at(&d, &p, &[0.0]).unwrap();
    assert!(close(m.growth_rates[0], 1.5), "{m:?}");
}

fn double_pendulum() -> System {
    from_points(
        &[("theta1", true, (-PI, PI)), ("theta2", true, (-PI, PI))],
        &[
            ("m1", &["l1*sin(theta1)", "-l1*cos(theta1)"]),
            (
                "m2",
                &[
                    "l1*sin(theta1) + l2*sin(theta2)",
                    "-l1*cos(theta1) - l2*cos(theta2)",
                ],
            ),
        ],
        Some(("g", 1)),
    )
}

#[test]
fn double_pendulum_equations() {
    let mut sys = double_pendulum();
    let l = sys.lagrangian;
    same(
        &mut sys,
        l,
        "1/2*(m1+m2)*l1^2*theta1'^2 + 1/2*m2*l2^2*theta2'^2 + m2*l1*l2*theta1'*theta2'*cos(theta1-theta2) + (m1+m2)*g*l1*cos(theta1) + m2*g*l2*cos(theta2)",
    );
    let d = sys.derive().unwrap();
    same(
        &mut sys,
        d.steps[0].equation,
        "(m1+m2)*l1^2*theta1'' + m2*l1*l2*theta2''*cos(theta1-theta2) + m2*l1*l2*theta2'^2*sin(theta1-theta2) + (m1+m2)*g*l1*sin(theta1)",
    );
    same(
        &mut sys,
        d.steps[1].equation,
        "m2*l2^2*theta2'' + m2*l1*l2*theta1''*cos(theta1-theta2) - m2*l1*l2*theta1'^2*sin(theta1-theta2) + m2*g*l2*sin(theta2)",
    );
    let e = sys.energy(&d);
    assert!(e.conserved && e.is_total == Some(true));
    // The simplified equations print compactly: cos(θ₁ − θ₂), not products of sines.
    let text = sys.pool.plain(d.steps[0].equation);
    assert!(text.contains("cos(theta1 - theta2)"), "{text}");
}

#[test]
fn double_pendulum_modes() {
    let mut sys = double_pendulum();
    sys.substitute_parameters(&[
        ("m1".into(), "m".into()),
        ("m2".into(), "m".into()),
        ("l1".into(), "l".into()),
        ("l2".into(), "l".into()),
    ])
    .unwrap();
    let d = sys.derive().unwrap();
    let zero = sys.pool.zero();
    let sm = sys.symbolic_modes(&d, &[zero, zero]).unwrap();
    assert_eq!(sm.omega_squared.len(), 2);
    same(&mut sys, sm.omega_squared[0], "(2 - sqrt(2))*g/l");
    same(&mut sys, sm.omega_squared[1], "(2 + sqrt(2))*g/l");
    let shown: Vec<String> = sm
        .omega_squared
        .iter()
        .map(|&w| sys.pool.unicode(w))
        .collect();
    assert_eq!(shown, vec!["(2 − √2)·g/l", "(2 + √2)·g/l"]);
    let p = values(&sys, &[("m", 0.8), ("l", 1.2), ("g", 9.81)]);
    let modes = sys.modes_at(&d, &p, &[0.0, 0.0]).unwrap();
    let gl = 9.81 / 1.2;
    assert!(close(
        modes.frequencies[0],
        ((2.0 - 2f64.sqrt()) * gl).sqrt()
    ));
    assert!(close(
        modes.frequencies[1],
        ((2.0 + 2f64.sqrt()) * gl).sqrt()
    ));
    let r0 = modes.modes[0].shape[1] / modes.modes[0].shape[0];
    let r1 = modes.modes[1].shape[1] / modes.modes[1].shape[0];
    assert!(close(r0, 2f64.sqrt()), "slow mode in phase, ratio √2: {r0}");
    assert!(
        close(r1, -(2f64.sqrt())),
        "fast mode antiphase, ratio −√2: {r1}"
    );
    let names = vec!["theta1".to_string(), "theta2".to_string()];
    assert!(modes.describe(&names)[0].starts_with("in phase"));
    assert!(modes.describe(&names)[1].starts_with("antiphase"));
    // The notes' characteristic equation ω⁴ − 4(g/l)ω² + 2(g/l)² = 0, up to a factor m²l⁴.
    let ctx = sys.open_context();
    let want = read_expr(
        "m^2*l^4*(omega^4 - 4*g/l*omega^2 + 2*g^2/l^2)",
        &ctx,
        &mut sys.pool,
    )
    .unwrap();
    let (a, b) = (sys.pool.expand(sm.characteristic), sys.pool.expand(want));
    assert_eq!(a, b, "{}", sys.pool.unicode(sm.characteristic));
}

#[test]
fn atwood_machine() {
    let mut sys = System::from_lagrangian("1/2*(m1+m2)*x'^2 + (m1-m2)*g*x", &["x"]).unwrap();
    let d = sys.derive().unwrap();
    let dynamics = lagrange::mechanics::accel::Dynamics::new(&sys, &d).unwrap();
    let mut point = vec![0.0; 4];
    point.extend(values(&sys, &[("g", 9.81), ("m1", 3.0), ("m2", 1.0)]));
    let mut scratch = dynamics.scratch();
    let a = dynamics.accelerations(&point, &mut scratch).unwrap();
    assert!(close(a[0], (3.0 - 1.0) / (3.0 + 1.0) * 9.81));
    // Tension by a multiplier: both heights as coordinates, string constraint y1 + y2 = c.
    let mut sys = System::from_lagrangian(
        "1/2*m1*y1'^2 + 1/2*m2*y2'^2 - m1*g*y1 - m2*g*y2",
        &["y1", "y2"],
    )
    .unwrap();
    sys.add_constraint("y1 + y2 = c").unwrap();
    let d = sys.derive().unwrap();
    let rows = sys.constraint_rows();
    let lambda = sys.multipliers_symbolic(&d, &rows).unwrap();
    same(&mut sys, lambda[0], "2*m1*m2*g/(m1 + m2)");
    let mut point = vec![0.0; 7];
    point.extend(values(
        &sys,
        &[("c", 1.0), ("g", 9.81), ("m1", 3.0), ("m2", 1.0)],
    ));
    let (acc, lam) = sys.multipliers_at(&d, &rows, &point).unwrap();
    assert!(close(lam[0], 2.0 * 3.0 * 1.0 * 9.81 / 4.0));
    assert!(close(acc[0], -acc[1]));
}

#[test]
fn pendulum_rod_tension_from_a_multiplier() {
    let mut sys = System::from_lagrangian("1/2*m*(x'^2 + y'^2) - m*g*y", &["x", "y"]).unwrap();
    sys.add_constraint("x^2 + y^2 = l^2").unwrap();
    let d = sys.derive().unwrap();
    let rows = sys.constraint_rows();
    let (m, g, l) = (1.7, 9.81, 0.9);
    for &(theta, w) in &[(0.3, 1.1), (-1.2, 0.4), (2.5, -2.0)] {
        let (x, y) = (l * f64::sin(theta), -l * f64::cos(theta));
        let (vx, vy) = (l * f64::cos(theta) * w, l * f64::sin(theta) * w);
        let mut point = vec![0.0, x, vx, 0.0, y, vy, 0.0];
        point.extend(values(&sys, &[("g", g), ("l", l), ("m", m)]));
        let (_, lam) = sys.multipliers_at(&d, &rows, &point).unwrap();
        // Force magnitude |λ|·|∇f| = |λ|·2l equals the tension m(g cos θ + l θ'²).
        let tension = lam[0].abs() * 2.0 * l;
        let want = m * (g * f64::cos(theta) + l * w * w);
        assert!(close(tension, want.abs()), "{tension} vs {want}");
    }
    let symbolic = sys.multipliers_symbolic(&d, &rows).unwrap();
    same(
        &mut sys,
        symbolic[0],
        "m*(g*y - x'^2 - y'^2)/(2*(x^2 + y^2))",
    );
}

#[test]
fn rolling_disk_nonholonomic() {
    // A disk rolling without slipping along x: x' = R φ'. The multiplier is the friction.
    let mut sys = System::from_lagrangian("1/2*M*x'^2 + 1/4*M*R^2*phi'^2", &["x", "phi"]).unwrap();
    sys.set_forces("F; 0").unwrap();
    sys.add_constraint("x' - R*phi' = 0").unwrap();
    assert_eq!(
        sys.constraints[0].kind,
        lagrange::mechanics::ConstraintKind::Nonholonomic
    );
    let d = sys.derive().unwrap();
    let rows = sys.constraint_rows();
    let mut point = vec![0.0; 7];
    point.extend(values(&sys, &[("F", 3.0), ("M", 2.0), ("R", 0.5)]));
    let (acc, lam) = sys.multipliers_at(&d, &rows, &point).unwrap();
    // A pushed solid disk accelerates at 2F/(3M); friction −F/3 opposes the push.
    assert!(close(acc[0], 2.0 * 3.0 / (3.0 * 2.0)), "{acc:?}");
    assert!(close(lam[0], -1.0), "{lam:?}");
}

#[test]
fn bead_on_rotating_parabola() {
    let mut sys = from_points(
        &[("r", false, (-3.0, 3.0))],
        &[("m", &["r*cos(omega*t)", "a*r^2", "r*sin(omega*t)"])],
        Some(("g", 1)),
    );
    let d = sys.derive().unwrap();
    same(
        &mut sys,
        d.steps[0].equation,
        "m*(1 + 4*a^2*r^2)*r'' + 4*m*a^2*r*r'^2 - m*r*omega^2 + 2*m*g*a*r",
    );
    let e = sys.energy(&d);
    assert!(e.conserved && e.is_total == Some(false));
    // ω² < 2ga: only r = 0, stable, with ω_osc² = 2ga − ω².
    let p = values(&sys, &[("a", 1.0), ("g", 9.81), ("m", 1.0), ("omega", 3.0)]);
    let eq = sys.equilibria(&d, &p).unwrap();
    assert!(!eq.continuum);
    assert_eq!(eq.points.len(), 1);
    assert_eq!(eq.points[0].1, Stability::Stable);
    let modes = sys.modes_at(&d, &p, &[0.0]).unwrap();
    assert!(close(modes.frequencies[0], (2.0 * 9.81 - 9.0f64).sqrt()));
    // ω² = 2ga: every r is an equilibrium (the notes put this continuum at ω² > 2ga).
    let p = values(&sys, &[("a", 1.0), ("g", 8.0), ("m", 1.0), ("omega", 4.0)]);
    assert!(sys.equilibria(&d, &p).unwrap().continuum);
    // ω² > 2ga: only r = 0, unstable.
    let p = values(&sys, &[("a", 1.0), ("g", 4.0), ("m", 1.0), ("omega", 3.0)]);
    let eq = sys.equilibria(&d, &p).unwrap();
    assert_eq!(eq.points.len(), 1);
    assert_eq!(eq.points[0].1, Stability::Unstable);
}

#[test]
fn spring_on_incline() {
    let mut sys =
        System::from_lagrangian("1/2*m*x'^2 - 1/2*k*x^2 + m*g*x*sin(alpha)", &["x"]).unwrap();
    let d = sys.derive().unwrap();
    let ctx = sys.open_context();
    let x0 = read_expr("m*g*sin(alpha)/k", &ctx, &mut sys.pool).unwrap();
    assert!(sys.verify_equilibrium(&d, &[x0]).unwrap());
    let wrong = read_expr("m*g/k", &ctx, &mut sys.pool).unwrap();
    assert!(!sys.verify_equilibrium(&d, &[wrong]).unwrap());
    let sm = sys.symbolic_modes(&d, &[x0]).unwrap();
    same(&mut sys, sm.omega_squared[0], "k/m");
    let p = values(
        &sys,
        &[("alpha", 0.4), ("g", 9.81), ("k", 20.0), ("m", 1.5)],
    );
    let eq = sys.equilibria(&d, &p).unwrap();
    assert_eq!(eq.points.len(), 1);
    assert!(close(eq.points[0].0[0], 1.5 * 9.81 * f64::sin(0.4) / 20.0));
}

#[test]
fn charged_particle_in_a_field_is_gyroscopic() {
    // L = ½m(ẋ² + ẏ²) + ½qB(x ẏ − y ẋ) − ½k(x² + y²): at the origin the velocity-linear
    // terms survive; ω± = √(k/m + (qB/2m)²) ± qB/2m.
    let mut sys = System::from_lagrangian(
        "1/2*m*(x'^2 + y'^2) + 1/2*q*B*(x*y' - y*x') - 1/2*k*(x^2 + y^2)",
        &["x", "y"],
    )
    .unwrap();
    let d = sys.derive().unwrap();
    let p = values(&sys, &[("B", 2.0), ("k", 3.0), ("m", 1.5), ("q", 0.5)]);
    let modes = sys.modes_at(&d, &p, &[0.0, 0.0]).unwrap();
    assert!(modes.gyroscopic);
    let c: f64 = 0.5 * 2.0 / (2.0 * 1.5);
    let base = (3.0f64 / 1.5 + c * c).sqrt();
    let want = [base - c, base + c];
    // Eigenvalues ±iω₋, ±iω₊: two frequencies.
    assert_eq!(modes.frequencies.len(), 2, "{modes:?}");
    assert!(
        modes.frequencies.iter().any(|&f| close(f, want[0])),
        "{modes:?}"
    );
    assert!(
        modes.frequencies.iter().any(|&f| close(f, want[1])),
        "{modes:?}"
    );
}

#[test]
fn damping_breaks_energy_conservation_and_cyclic_coordinates_conserve_momentum() {
    let mut sys = System::from_lagrangian("1/2*m*x'^2 - 1/2*k*x^2", &["x"]).unwrap();
    sys.set_forces("-b*x'").unwrap();
    let d = sys.derive().unwrap();
    same(&mut sys, d.steps[0].equation, "m*x'' + k*x + b*x'");
    assert!(!sys.energy(&d).conserved);
    let mut sys =
        System::from_lagrangian("1/2*m*(r'^2 + r^2*phi'^2) + k/r", &["r", "phi"]).unwrap();
    let d = sys.derive().unwrap();
    let e = sys.energy(&d);
    assert_eq!(e.cyclic, vec![1]);
    same(&mut sys, d.steps[1].momentum, "m*r^2*phi'");
}

#[test]
fn explicit_time_dependence_is_not_conserved() {
    let mut sys = System::from_lagrangian("1/2*m*x'^2 - 1/2*k*x^2 + F*x*cos(w*t)", &["x"]).unwrap();
    let d = sys.derive().unwrap();
    assert!(!sys.energy(&d).conserved);
}

#[test]
fn degenerate_systems_are_named() {
    let mut sys = System::from_lagrangian("1/2*m*x'^2 - k*y^2", &["x", "y"]).unwrap();
    assert_eq!(
        sys.derive().unwrap_err(),
        MechError::NoKineticTerm { name: "y".into() }
    );
    let mut sys = System::from_lagrangian("1/2*m*(x' + y')^2", &["x", "y"]).unwrap();
    assert!(matches!(
        sys.derive().unwrap_err(),
        MechError::SingularMass { .. }
    ));
    let err = sys
        .substitute_parameters(&[("zz".into(), "1".into())])
        .unwrap_err();
    assert!(err.to_string().contains("not a parameter"), "{err}");
}

#[test]
fn rotor_and_spring_bodies() {
    use lagrange::mechanics::bodies::Anchor;
    // Atwood machine with a pulley of inertia I and radius R: a = (m1 − m2) g / (m1 + m2 + I/R²).
    let mut pool = Pool::new();
    let x = Coordinate {
        name: "x".into(),
        sym: pool.symbol("x"),
        periodic: false,
        range: (-2.0, 2.0),
        domain: lagrange::mechanics::Domain::ANY,
    };
    let ctx = Context::open().with_coordinates(["x"]);
    let mut rd = |s: &str| read_expr(s, &ctx, &mut pool).unwrap();
    let bodies = vec![
        Body::Point {
            mass: rd("m1"),
            position: vec![rd("0"), rd("-x")],
        },
        Body::Point {
            mass: rd("m2"),
            position: vec![rd("1"), rd("x")],
        },
        Body::Rotor {
            inertia: rd("I"),
            angle: rd("x/R"),
        },
    ];
    let g = rd("g");
    let mut sys = System::from_bodies(pool, vec![x], &bodies, &[Potential::Gravity { g, axis: 1 }]);
    let d = sys.derive().unwrap();
    let dynamics = lagrange::mechanics::accel::Dynamics::new(&sys, &d).unwrap();
    let mut point = vec![0.0; 4];
    point.extend(values(
        &sys,
        &[
            ("I", 0.3),
            ("R", 0.2),
            ("g", 9.81),
            ("m1", 3.0),
            ("m2", 1.0),
        ],
    ));
    let mut scratch = dynamics.scratch();
    let a = dynamics.accelerations(&point, &mut scratch).unwrap();
    assert!(close(a[0], 2.0 * 9.81 / (4.0 + 0.3 / 0.04)), "{a:?}");

    // A mass on a spring (natural length L0) to a fixed anchor, along a line: equilibria at
    // ±L0 (stable) and the anchor itself (unstable), ω = √(k/m).
    let mut pool = Pool::new();
    let x = Coordinate {
        name: "x".into(),
        sym: pool.symbol("x"),
        periodic: false,
        range: (-3.0, 3.0),
        domain: lagrange::mechanics::Domain::ANY,
    };
    let ctx = Context::open().with_coordinates(["x"]);
    let mut rd = |s: &str| read_expr(s, &ctx, &mut pool).unwrap();
    let bodies = vec![Body::Point {
        mass: rd("m"),
        position: vec![rd("x"), rd("0")],
    }];
    let spring = Potential::Spring {
        k: rd("k"),
        natural: rd("L0"),
        a: Anchor::Body(0),
        b: Anchor::Fixed(vec![rd("0"), rd("0")]),
    };
    let mut sys = System::from_bodies(pool, vec![x], &bodies, &[spring]);
    let v = sys.potential.unwrap();
    same(&mut sys, v, "1/2*k*(abs(x) - L0)^2");
    let d = sys.derive().unwrap();
    let p = values(&sys, &[("L0", 1.5), ("k", 8.0), ("m", 2.0)]);
    let eq = sys.equilibria(&d, &p).unwrap();
    let xs: Vec<f64> = eq.points.iter().map(|(q, _)| q[0]).collect();
    assert_eq!(
        xs.len(),
        2,
        "{xs:?} (x = 0 is a kink of |x|, not a smooth equilibrium)"
    );
    assert!(close(xs[0], -1.5) && close(xs[1], 1.5), "{xs:?}");
    let modes = sys.modes_at(&d, &p, &[1.5]).unwrap();
    assert!(close(modes.frequencies[0], 2.0));
}

#[test]
fn many_coordinates_use_random_starts_only() {
    // Twelve uncoupled oscillators: a full grid would be 2^12 starts; the search stays small
    // and finds the single equilibrium.
    let names: Vec<String> = (1..=12).map(|i| format!("x{i}")).collect();
    let l: String = names
        .iter()
        .map(|x| format!(" + 1/2*{x}'^2 - 1/2*k*{x}^2"))
        .collect();
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let mut sys = System::from_lagrangian(&l, &refs).unwrap();
    let d = sys.derive().unwrap();
    let eq = sys.equilibria(&d, &[2.0]).unwrap();
    assert_eq!(eq.points.len(), 1);
    assert!(eq.points[0].0.iter().all(|x| x.abs() < 1e-9));
    assert_eq!(eq.points[0].1, Stability::Stable);
    let zero = sys.pool.zero();
    let err = sys.symbolic_modes(&d, &[zero; 12]).unwrap_err();
    assert!(err.to_string().contains("up to 3 coordinates"), "{err}");
}

//! Issue 13, item 11: rigid bodies (planar angle, Euler angles, body angular velocities) and
//! forces given as vectors at a point — each against a textbook closed form, not the tool's
//! own output.

use lagrange::bank::load_str;
use lagrange::bank::verify::verify;
use lagrange::expr::Id;
use lagrange::mechanics::System;
use lagrange::report::{ModesOptions, modes};

use super::helpers::{eval, lagrange};

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
}

/// A problem file from its body: `[parameters]`, bodies, potentials and parts.
fn problem(id: &str, coords: &str, rest: &str) -> lagrange::problem::Problem {
    let text = format!("id = \"{id}\"\ntitle = \"{id}\"\ncoordinates = {coords}\n{rest}");
    match load_str(&format!("{id}.toml"), &text) {
        Ok(p) => p,
        Err(f) => panic!("{id} does not load: {f:?}"),
    }
}

/// Every part of the problem is proved by the verifier.
fn proved(p: &lagrange::problem::Problem) {
    let findings = verify(p);
    assert!(findings.is_empty(), "{findings:#?}");
}

/// `e` and `hand` (text in the system's symbols) agree at every sample point.
fn same_at(sys: &mut System, e: Id, hand: &str, samples: &[Vec<(&str, f64)>]) {
    let ctx = sys.open_context();
    let h = sys.read(hand, "hand-written", &ctx).unwrap();
    for s in samples {
        let (a, b) = (
            eval(&sys.pool, e, s).unwrap(),
            eval(&sys.pool, h, s).unwrap(),
        );
        assert!(close(a, b), "{a} vs {b} at {s:?}");
    }
}

const ROD: &str = r#"
[parameters]
m = { dimension = "M", range = [0.5, 2.0] }
l = { dimension = "L", range = [0.5, 2.0] }
g = { dimension = "L T^-2", range = [5.0, 15.0] }

[[bodies]]
kind = "rigid"
mass = "m"
position = ["l/2*sin(theta)", "-l/2*cos(theta)"]
inertia = "m*l^2/12"
angle = "theta"

[[potentials]]
kind = "gravity"
"#;

#[test]
fn compound_pendulum_rod_about_its_end() {
    // T = ⅙ m l² θ̇² (I about the end = ⅓ m l²), ω² = 3g/(2l).
    let parts = r#"
[[parts]]
id = "kinetic"
kind = "expression"
prompt = "T"
answer = "1/6*m*l^2*theta'^2"

[[parts]]
id = "frequencies"
kind = "frequencies"
prompt = "omega"
answer = ["sqrt(3*g/(2*l))"]
at = { theta = "0" }
"#;
    let mut p = problem(
        "rod",
        r#"[{ name = "theta", periodic = true }]"#,
        &format!("lagrangian = \"1/6*m*l^2*theta'^2 + 1/2*m*g*l*cos(theta)\"\n{ROD}{parts}"),
    );
    proved(&p);
    let t = p.system.kinetic.unwrap();
    let samples: Vec<Vec<(&str, f64)>> = [(0.3, 1.1, 0.7), (-2.0, -0.4, 1.9)]
        .iter()
        .map(|&(th, w, l)| vec![("theta", th), ("theta'", w), ("l", l), ("m", 1.3)])
        .collect();
    same_at(&mut p.system, t, "1/6*m*l^2*theta'^2", &samples);
    let opts = ModesOptions {
        params: vec![
            ("m".into(), "1.3".into()),
            ("l".into(), "0.8".into()),
            ("g".into(), "9.81".into()),
        ],
        at: Some(vec![("theta".into(), "0".into())]),
        ..ModesOptions::default()
    };
    let rep = modes(&p.system, &opts).unwrap();
    let w = rep.equilibria[0].frequencies[0];
    assert!(close(w * w, 3.0 * 9.81 / (2.0 * 0.8)), "{w}");
}

#[test]
fn disc_rolling_down_an_incline_as_a_rigid_body() {
    // A uniform disc (I = ½ M R² about its centre) rolling without slipping: a = ⅔ g sin α.
    let rest = r#"
constraints = ["x' - R*phi' = 0"]

[parameters]
M = { dimension = "M", range = [0.5, 2.0] }
R = { dimension = "L", range = [0.2, 1.0] }
g = { dimension = "L T^-2", range = [5.0, 15.0] }
alpha = { dimension = "1", range = [0.1, 1.2] }

[[bodies]]
kind = "rigid"
mass = "M"
position = ["x*cos(alpha)", "-x*sin(alpha)"]
inertia = "1/2*M*R^2"
angle = "phi"

[[potentials]]
kind = "gravity"

[[parts]]
id = "acceleration"
kind = "expression"
quantity = "acceleration"
coordinate = "x"
prompt = "x''"
answer = "2/3*g*sin(alpha)"
"#;
    let mut p = problem(
        "disc",
        r#"[{ name = "x" }, { name = "phi", periodic = true }]"#,
        rest,
    );
    proved(&p);
    let sys = &mut p.system;
    let d = sys.derive().unwrap();
    let rows = sys.constraint_rows();
    let (alpha, g) = (0.4, 9.81);
    let mut point = vec![0.0; lagrange::mechanics::Layout::new(sys.n()).params_start()];
    for prm in &sys.parameters {
        point.push(match prm.name.as_str() {
            "M" => 1.5,
            "R" => 0.3,
            "g" => g,
            _ => alpha,
        });
    }
    let (acc, _) = sys.multipliers_at(&d, &rows, &point).unwrap();
    assert!(close(acc[0], 2.0 / 3.0 * g * f64::sin(alpha)), "{acc:?}");
}

const TOP_T: &str =
    "1/2*(A + m*l^2)*(theta'^2 + phi'^2*sin(theta)^2) + 1/2*C*(psi' + phi'*cos(theta))^2";

const TOP: &str = r#"
[parameters]
m = { dimension = "M", range = [0.5, 2.0] }
l = { dimension = "L", range = [0.5, 2.0] }
g = { dimension = "L T^-2", range = [5.0, 15.0] }
A = { dimension = "M L^2", range = [0.5, 2.0] }
C = { dimension = "M L^2", range = [0.5, 2.0] }

[[bodies]]
kind = "rigid"
mass = "m"
position = ["l*sin(theta)*sin(phi)", "-l*sin(theta)*cos(phi)", "l*cos(theta)"]
moments = ["A", "A", "C"]
euler = ["phi", "theta", "psi"]

[[potentials]]
kind = "gravity"
axis = "z"
"#;

const TOP_COORDS: &str = r#"[{ name = "phi", periodic = true }, { name = "theta", periodic = true }, { name = "psi", periodic = true }]"#;

#[test]
fn heavy_symmetric_top_from_euler_angles() {
    // About the fixed tip, I₁ = A + m l² (parallel axes): T = ½ I₁(θ̇² + φ̇² sin²θ) +
    // ½ I₃(ψ̇ + φ̇ cos θ)², V = m g l cos θ; φ and ψ are cyclic, so p_φ and p_ψ are conserved.
    let mut p = problem(
        "top",
        TOP_COORDS,
        &format!("lagrangian = \"{TOP_T} - m*g*l*cos(theta)\"\nparts = []\n{TOP}"),
    );
    proved(&p);
    let t = p.system.kinetic.unwrap();
    let samples: Vec<Vec<(&str, f64)>> = [
        (0.3, 1.1, -0.7, 0.5, -1.3, 2.0),
        (2.1, 0.2, 1.9, -1.5, 0.8, 0.4),
    ]
    .iter()
    .map(|&(ph, th, ps, dph, dth, dps)| {
        vec![
            ("phi", ph),
            ("theta", th),
            ("psi", ps),
            ("phi'", dph),
            ("theta'", dth),
            ("psi'", dps),
            ("m", 1.2),
            ("l", 0.7),
            ("A", 0.9),
            ("C", 1.6),
        ]
    })
    .collect();
    same_at(&mut p.system, t, TOP_T, &samples);
    let d = p.system.derive().unwrap();
    let e = p.system.energy(&d);
    let names: Vec<&str> = e
        .cyclic
        .iter()
        .map(|&i| p.system.coordinates[i].name.as_str())
        .collect();
    assert_eq!(names, ["phi", "psi"]);
    // p_ψ = I₃ (ψ̇ + φ̇ cos θ), the spin about the figure axis.
    let p_psi = d.steps[2].momentum;
    same_at(&mut p.system, p_psi, "C*(psi' + phi'*cos(theta))", &samples);
}

#[test]
fn body_rates_and_a_tensor_give_the_same_top() {
    // The same top with ω given in the body frame and the inertia as a diagonal tensor.
    let rates = TOP
        .replace(
            r#"moments = ["A", "A", "C"]"#,
            r#"tensor = [["A", "0", "0"], ["0", "A", "0"], ["0", "0", "C"]]"#,
        )
        .replace(
            r#"euler = ["phi", "theta", "psi"]"#,
            r#"omega_body = ["phi'*sin(theta)*sin(psi) + theta'*cos(psi)", "phi'*sin(theta)*cos(psi) - theta'*sin(psi)", "phi'*cos(theta) + psi'"]"#,
        );
    let p = problem(
        "top-rates",
        TOP_COORDS,
        &format!("lagrangian = \"{TOP_T} - m*g*l*cos(theta)\"\nparts = []\n{rates}"),
    );
    proved(&p);
    // The check has teeth: without the parallel-axis term m l² the stated L disagrees.
    let wrong = TOP_T.replace("(A + m*l^2)", "A");
    let text = format!(
        "id = \"w\"\ntitle = \"w\"\ncoordinates = {TOP_COORDS}\nlagrangian = \"{wrong} - m*g*l*cos(theta)\"\nparts = []\n{rates}"
    );
    let refused = load_str("w.toml", &text).map_or(true, |p| !verify(&p).is_empty());
    assert!(refused, "a wrong hand-written T passed");
}

#[test]
fn constant_force_at_a_point_on_a_pendulum() {
    // F = (F, 0) at the bob r = (l sin θ, −l cos θ): Q_θ = F·∂r/∂θ = F l cos θ.
    let rest = r#"
[parameters]
m = { dimension = "M", range = [0.5, 2.0] }
l = { dimension = "L", range = [0.5, 2.0] }
g = { dimension = "L T^-2", range = [5.0, 15.0] }
F = { dimension = "M L T^-2", range = [0.5, 2.0] }

[[bodies]]
kind = "point"
mass = "m"
position = ["l*sin(theta)", "-l*cos(theta)"]

[[potentials]]
kind = "gravity"

[[point_forces]]
at = ["l*sin(theta)", "-l*cos(theta)"]
vector = ["F", "0"]

[[parts]]
id = "equation"
kind = "expression"
quantity = "acceleration"
coordinate = "theta"
prompt = "theta''"
answer = "(F*cos(theta) - m*g*sin(theta))/(m*l)"
"#;
    let mut p = problem("pushed", r#"[{ name = "theta", periodic = true }]"#, rest);
    proved(&p);
    let q = p.system.forces[0];
    let samples: Vec<Vec<(&str, f64)>> = [0.3, -1.2, 2.5]
        .iter()
        .map(|&th| vec![("theta", th), ("l", 0.8), ("F", 1.7)])
        .collect();
    same_at(&mut p.system, q, "F*l*cos(theta)", &samples);
}

#[test]
fn ill_posed_rigid_bodies_and_forces_are_refused_with_the_reason() {
    let coords = r#"[{ name = "theta", periodic = true }]"#;
    let cases = [
        // A planar angle with three moments.
        (
            ROD.replace("inertia = \"m*l^2/12\"", "moments = [\"1\", \"2\", \"3\"]"),
            "one moment",
        ),
        // Two orientations.
        (
            ROD.replace(
                "angle = \"theta\"",
                "angle = \"theta\"\neuler = [\"theta\", \"0\", \"0\"]",
            ),
            "exactly one of",
        ),
        // A planar angle with a 3-D centre of mass.
        (
            ROD.replace("\"-l/2*cos(theta)\"]", "\"-l/2*cos(theta)\", \"0\"]"),
            "planar angle",
        ),
        // A point of application with a velocity.
        (
            format!("{ROD}\n[[point_forces]]\nat = [\"theta'\", \"0\"]\nvector = [\"1\", \"0\"]\n"),
            "velocity",
        ),
        // Force and point of different dimensions.
        (
            format!(
                "{ROD}\n[[point_forces]]\nat = [\"l\", \"0\"]\nvector = [\"1\", \"0\", \"0\"]\n"
            ),
            "components",
        ),
    ];
    for (rest, why) in cases {
        let text =
            format!("id = \"bad\"\ntitle = \"bad\"\ncoordinates = {coords}\nparts = []\n{rest}");
        let f = load_str("bad.toml", &text).expect_err("refused");
        assert!(f.message.contains(why), "{why}: {}", f.message);
    }
    // An asymmetric tensor.
    let asym = TOP.replace(
        r#"moments = ["A", "A", "C"]"#,
        r#"tensor = [["A", "1", "0"], ["0", "A", "0"], ["0", "0", "C"]]"#,
    );
    let text =
        format!("id = \"bad\"\ntitle = \"bad\"\ncoordinates = {TOP_COORDS}\nparts = []\n{asym}");
    let f = load_str("bad.toml", &text).expect_err("refused");
    assert!(f.message.contains("not symmetric"), "{}", f.message);
}

#[test]
fn command_line_rigid_body_gravity_and_force_at() {
    let (code, out, err) = lagrange(&[
        "derive",
        "-q",
        "theta",
        "--rigid",
        "mass=m; position=l/2*sin(theta), -l/2*cos(theta); inertia=m*l^2/12; angle=theta",
        "--gravity",
        "g",
        "--force-at",
        "l*sin(theta), -l*cos(theta): F, 0",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("⅙·m·l²·θ̇²"), "{out}");
    assert!(out.contains("F·l·cos(θ)"), "{out}");
    let (code, out, err) = lagrange(&[
        "modes",
        "-q",
        "theta",
        "--rigid",
        "mass=m; position=l/2*sin(theta), -l/2*cos(theta); inertia=m*l^2/12; angle=theta",
        "--gravity",
        "g",
        "--params",
        "m=1, l=2, g=4",
        "--at",
        "theta=0",
    ]);
    assert_eq!(code, 0, "{err}");
    // ω² = 3g/(2l) = 3.
    assert!(out.contains("1.732051"), "{out}");
    let (code, _, err) = lagrange(&[
        "derive",
        "-q",
        "theta",
        "--rigid",
        "mass=m; position=0, 0; moments=1, 2, 3; angle=theta",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("inertia-shape"), "{err}");
}

#[test]
fn command_line_and_problem_file_share_the_rigid_body_names_and_checker() {
    // The same wrong body (two orientations) gets the same refusal from both faces.
    let (code, _, err) = lagrange(&[
        "derive",
        "-q",
        "theta",
        "--rigid",
        "mass=m; position=0, 0; inertia=I; angle=theta; euler=theta, 0, 0",
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("exactly one of `angle` (planar), `omega_body` or `euler`"),
        "{err}"
    );
    let body = r#"
[parameters]
m = { dimension = "M", range = [0.5, 2.0] }
I = { dimension = "M L^2", range = [0.5, 2.0] }

[[bodies]]
kind = "rigid"
mass = "m"
position = ["0", "0"]
inertia = "I"
angle = "theta"
euler = ["theta", "0", "0"]
"#;
    let text =
        format!("id = \"bad\"\ntitle = \"bad\"\ncoordinates = {TOP_COORDS}\nparts = []\n{body}");
    let f = load_str("bad.toml", &text).expect_err("refused");
    assert!(
        f.message
            .contains("exactly one of `angle` (planar), `omega_body` or `euler`"),
        "{}",
        f.message
    );
    // The command line's old names say what they are called now.
    for (flag, spec, old, now) in [
        (
            "--rigid",
            "mass=m; at=0, 0; inertia=I; angle=theta",
            "at",
            "position",
        ),
        ("--point", "mass=m; at=0, 0", "at", "position"),
        (
            "--rigid",
            "mass=m; position=0, 0, 0; moments=1, 2, 3; omega=1, 2, 3",
            "omega",
            "omega_body",
        ),
    ] {
        let (code, _, err) = lagrange(&["derive", "-q", "theta", flag, spec]);
        assert_eq!(code, 2, "{spec}");
        assert!(err.contains(&format!("`{old}=` is now `{now}=`")), "{err}");
    }
    // A tensor of the wrong size on the command line.
    let (code, _, err) = lagrange(&[
        "derive",
        "-q",
        "phi, theta, psi",
        "--rigid",
        "mass=m; position=0, 0, 0; tensor=1, 0, 0, 0, 1, 0, 0, 0; euler=phi, theta, psi",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("`tensor` is 3 rows of 3 entries"), "{err}");
}

#[test]
fn the_derivation_ladder_walks_a_rigid_body() {
    // The rod's ladder: its centre of mass, that point's speed², the angular speed², then T
    // — every step's own reference accepted by the checker.
    use lagrange::check::Status;
    use lagrange::tutor::ladder::{check_step, ladder};
    let p = problem(
        "rod",
        r#"[{ name = "theta", periodic = true }]"#,
        &format!("parts = []\n{ROD}"),
    );
    let steps = ladder(&p).unwrap();
    let ids: Vec<&str> = steps.iter().map(|s| s.id.as_str()).collect();
    assert!(
        ids.starts_with(&[
            "position:1",
            "speed-squared:1",
            "angular-speed-squared:1",
            "kinetic"
        ]),
        "{ids:?}"
    );
    let top = problem("top", TOP_COORDS, &format!("parts = []\n{TOP}"));
    for p in [&p, &top] {
        for s in ladder(p).unwrap() {
            let answer = s.reference_text(p.system.coordinates.len());
            let v = check_step(p, &s, &answer).unwrap();
            assert_eq!(v.status, Status::Correct, "{} `{answer}`", s.id);
        }
    }
}

#[test]
fn heavy_top_steady_precession_from_the_rigid_body() {
    // Steady precession at θ₀ with φ̇ = Ω and spin ω₃ = ψ̇ + φ̇ cos θ₀ needs
    // m g l = Ω (I₃ ω₃ − I₁ Ω cos θ₀), I₁ = A + m l² about the tip (Goldstein §5.7). Choose g
    // so that it holds; the Routhian's equilibrium with p_ψ = I₃ ω₃ and
    // p_φ = I₁ Ω sin²θ₀ + I₃ ω₃ cos θ₀ is then θ₀.
    let p = problem("top", TOP_COORDS, &format!("parts = []\n{TOP}"));
    let (m, l, a, c) = (1.0, 0.5, 0.2, 0.3);
    let (theta0, omega, spin) = (0.6_f64, 2.0, 10.0);
    let i1 = a + m * l * l;
    let g = omega * (c * spin - i1 * omega * theta0.cos()) / (m * l);
    let p_psi = c * spin;
    let p_phi = i1 * omega * theta0.sin().powi(2) + c * spin * theta0.cos();
    let num = |x: f64| format!("{x:.17}");
    let opts = ModesOptions {
        params: vec![
            ("m".into(), num(m)),
            ("l".into(), num(l)),
            ("A".into(), num(a)),
            ("C".into(), num(c)),
            ("g".into(), num(g)),
        ],
        steady: vec![("p_phi".into(), num(p_phi)), ("p_psi".into(), num(p_psi))],
        ..ModesOptions::default()
    };
    let rep = modes(&p.system, &opts).unwrap();
    let found: Vec<f64> = rep.equilibria.iter().map(|e| e.coordinates[0]).collect();
    assert!(
        found.iter().any(|&t| (t - theta0).abs() < 1e-6),
        "{found:?} vs {theta0}"
    );
}

#[test]
fn command_line_points_and_a_spring() {
    // Two masses m joined by a spring k on a line: ω = 0 (free translation) and √(2k/m).
    let (code, out, err) = lagrange(&[
        "modes",
        "-q",
        "x1,x2",
        "--point",
        "mass=m; position=x1, 0",
        "--point",
        "mass=m; position=x2, 0",
        "--spring",
        "k=k; from=1; to=2; natural=a",
        "--params",
        "m=2, k=4, a=1",
        "--at",
        "x1=0, x2=1",
    ]);
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("frequencies ω: 0, 2\n"), "{out}");
    let (code, _, err) = lagrange(&["derive", "-q", "x", "--spring", "from=0, 0; to=x, 0"]);
    assert_eq!(code, 2);
    assert!(err.contains("act on bodies"), "{err}");
}

/// Regression (found by using `problems new` as an instructor): a body's fields written with
/// commas instead of `;` are refused with the form that works, not only "needs mass and
/// position".
#[test]
fn body_fields_separated_by_commas_are_told_the_semicolon_form() {
    for spec in ["mass=m,position=(l*sin(theta), -l*cos(theta))", "m at x"] {
        let (code, out, err) = lagrange(&["derive", "-q", "theta", "--point", spec]);
        assert_eq!(code, 2, "{spec}");
        assert!(out.is_empty(), "{out}");
        assert!(err.contains("separated by `;`"), "{spec}: {err}");
    }
    // The form the message shows is read.
    let (code, out, _) = lagrange(&[
        "derive",
        "-q",
        "theta",
        "--point",
        "mass=m; position=l*sin(theta), -l*cos(theta)",
        "--gravity",
        "g",
    ]);
    assert_eq!(code, 0);
    assert!(out.contains("sin(θ)"), "{out}");
}

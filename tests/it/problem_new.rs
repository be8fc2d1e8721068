//! `lagrange problems new`: a problem file drafted from a system passes `problems verify`
//! unedited, and its references are the physics — each drafted file is checked here with the
//! textbook answers (the pendulum's √(g/l), the double pendulum's √((2 ∓ √2) g/l), the cart's
//! 0 and √((M + m) g/(M l)), the hanging spring's rest at m g/k). T and V are stated only
//! from bodies, and a part with no closed form is left out with a comment giving the reason.

use crate::helpers::{lagrange, scratch};

/// Drafts `id` into `dir` with the system flags `system`; the file's text and the notes.
fn drafted(dir: &std::path::Path, id: &str, system: &[&str]) -> (String, String) {
    let file = dir.join(format!("{id}.toml")).display().to_string();
    let mut args = vec!["problems", "new", "--id", id, "-o", &file];
    args.extend_from_slice(system);
    let (code, out, notes) = lagrange(&args);
    assert_eq!(code, 0, "{id}: {out}{notes}");
    assert!(out.starts_with(&format!("wrote {file}")), "{out}");
    // Unedited, the file is proved again by the verifier.
    let (code, out, err) = lagrange(&["problems", "verify", &file]);
    assert_eq!(code, 0, "{id}: {out}{err}");
    assert!(out.contains("0 failing"), "{out}");
    (std::fs::read_to_string(&file).unwrap(), notes)
}

/// `lagrange --problems DIR check ID PART ANSWER` is correct.
fn correct(dir: &std::path::Path, id: &str, part: &str, answer: &str) {
    let d = dir.display().to_string();
    let (code, out, err) = lagrange(&["--problems", &d, "check", id, part, answer]);
    assert_eq!(code, 0, "{id}/{part} {answer}: {out}{err}");
    assert!(
        out.starts_with("✓ correct") || out.contains("correct"),
        "{id}/{part} {answer}: {out}"
    );
    assert!(!out.contains("incorrect"), "{id}/{part} {answer}: {out}");
}

const PENDULUM: &[&str] = &[
    "--coords",
    "theta",
    "--point",
    "mass=m; position=l*sin(theta), -l*cos(theta)",
    "--gravity",
    "g",
];

#[test]
fn a_pendulum_from_bodies_states_every_part_and_they_are_the_physics() {
    let dir = scratch("new-pendulum");
    let (text, notes) = drafted(&dir, "pend", PENDULUM);
    for part in [
        "kinetic",
        "potential",
        "lagrangian",
        "momentum",
        "cyclic",
        "eom",
        "energy-function",
        "equilibria",
        "frequencies",
    ] {
        assert!(
            text.contains(&format!("id = \"{part}\"")),
            "{part}:\n{text}"
        );
    }
    assert!(notes.contains("9 parts stated"), "{notes}");
    // Placeholders to edit are obvious, and valid as they stand.
    assert!(text.contains("title = \"EDIT: "), "{text}");
    assert!(text.contains("statement = \"\"\"\nEDIT: "), "{text}");
    correct(&dir, "pend", "kinetic", "1/2*m*l^2*theta'^2");
    correct(&dir, "pend", "potential", "-m*g*l*cos(theta)");
    correct(&dir, "pend", "eom", "theta'' = -g/l*sin(theta)");
    correct(&dir, "pend", "frequencies", "sqrt(g/l)");
    correct(
        &dir,
        "pend",
        "equilibria",
        "theta = 0 (stable), theta = pi (unstable)",
    );
    correct(
        &dir,
        "pend",
        "energy-function",
        "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)",
    );
    correct(&dir, "pend", "cyclic", "none");
}

#[test]
fn a_double_pendulum_has_the_two_textbook_frequencies() {
    let dir = scratch("new-double");
    let (text, _) = drafted(
        &dir,
        "dp",
        &[
            "--coords",
            "theta1,theta2",
            "--point",
            "mass=m; position=l*sin(theta1), -l*cos(theta1)",
            "--point",
            "mass=m; position=l*sin(theta1)+l*sin(theta2), -l*cos(theta1)-l*cos(theta2)",
            "--gravity",
            "g",
        ],
    );
    assert!(text.contains("kind = \"equations\""), "{text}");
    correct(
        &dir,
        "dp",
        "frequencies",
        "sqrt((2-sqrt(2))*g/l), sqrt((2+sqrt(2))*g/l)",
    );
    correct(
        &dir,
        "dp",
        "momentum-theta2",
        "m*l^2*theta2' + m*l^2*cos(theta1-theta2)*theta1'",
    );
}

#[test]
fn a_lagrangian_alone_states_no_kinetic_or_potential_part_and_says_why() {
    let dir = scratch("new-atwood");
    let (text, notes) = drafted(
        &dir,
        "atw",
        &[
            "--coords",
            "x",
            "--lagrangian",
            "1/2*(m1+m2)*x'^2 + (m1-m2)*g*x",
        ],
    );
    assert!(!text.contains("id = \"kinetic\""), "{text}");
    assert!(!text.contains("id = \"potential\""), "{text}");
    assert!(!text.contains("[[bodies]]"), "{text}");
    assert!(
        text.contains(
            "# - kinetic: the system is given by its Lagrangian, which does not fix T and V"
        ),
        "{text}"
    );
    assert!(notes.contains("kinetic left out"), "{notes}");
    correct(&dir, "atw", "eom", "(m1+m2)*x'' = (m1-m2)*g");
    // A constant force: no equilibrium (for m1 ≠ m2), nothing oscillates.
    correct(&dir, "atw", "equilibria", "none");
    assert!(
        text.contains("# - frequencies: no equilibrium is stable"),
        "{text}"
    );
}

#[test]
fn a_hanging_spring_rests_at_mg_over_k_and_the_range_holds_it() {
    let dir = scratch("new-spring");
    let (text, _) = drafted(
        &dir,
        "sm",
        &[
            "--coords",
            "x",
            "--point",
            "mass=m; position=0, -x",
            "--gravity",
            "g",
            "--spring",
            "k=k; from=1; to=0, 0",
        ],
    );
    assert!(text.contains("k = { dimension = \"M T^-2\""), "{text}");
    correct(&dir, "sm", "equilibria", "x = m*g/k (stable)");
    correct(&dir, "sm", "frequencies", "sqrt(k/m)");
    correct(&dir, "sm", "eom", "m*x'' = m*g - k*x");
}

#[test]
fn a_rotating_hoop_leaves_out_the_equilibria_of_one_regime_with_the_reason() {
    let dir = scratch("new-hoop");
    let (text, notes) = drafted(
        &dir,
        "hoop",
        &[
            "--coords",
            "theta",
            "--point",
            "mass=m; position=R*sin(theta)*cos(omega*t), R*sin(theta)*sin(omega*t), -R*cos(theta)",
            "--gravity",
            "g, z",
        ],
    );
    // The side equilibria cos θ = g/(R ω²) exist only when R ω² > g: no list holds for every
    // parameter value, so neither equilibria nor frequencies are stated.
    assert!(!text.contains("id = \"equilibria\""), "{text}");
    assert!(text.contains("# - equilibria: "), "{text}");
    assert!(notes.contains("equilibria left out"), "{notes}");
    correct(
        &dir,
        "hoop",
        "eom",
        "R*theta'' = R*omega^2*sin(theta)*cos(theta) - g*sin(theta)",
    );
    correct(
        &dir,
        "hoop",
        "kinetic",
        "1/2*m*R^2*(theta'^2 + omega^2*sin(theta)^2)",
    );
}

#[test]
fn a_free_cart_with_a_pendulum_has_a_zero_frequency_and_a_cyclic_x() {
    let dir = scratch("new-cart");
    let (_, _) = drafted(
        &dir,
        "cart",
        &[
            "--coords",
            "x,theta",
            "--point",
            "mass=M; position=x, 0",
            "--point",
            "mass=m; position=x+l*sin(theta), -l*cos(theta)",
            "--gravity",
            "g",
        ],
    );
    correct(&dir, "cart", "cyclic", "x");
    correct(&dir, "cart", "frequencies", "0, sqrt((M+m)*g/(M*l))");
    correct(
        &dir,
        "cart",
        "equilibria",
        "x = any, theta = 0 (stable); x = any, theta = pi (unstable)",
    );
    correct(
        &dir,
        "cart",
        "momentum-x",
        "(M+m)*x' + m*l*cos(theta)*theta'",
    );
}

#[test]
fn a_parameter_whose_dimension_is_not_told_by_its_name_needs_param() {
    let dir = scratch("new-param");
    let file = dir.join("damped.toml").display().to_string();
    let base = [
        "problems",
        "new",
        "--id",
        "p",
        "--coords",
        "x",
        "--lagrangian",
        "1/2*m*x'^2 - 1/2*kappa2*x^2 - zeta*x",
        "-o",
        &file,
    ];
    let (code, _, err) = lagrange(&base);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("`zeta`") && err.contains("--param"), "{err}");
    let mut with = base.to_vec();
    with.extend(["--param", "zeta=M L T^-2"]);
    let (code, _, err) = lagrange(&with);
    assert_eq!(code, 0, "{err}");
    let (code, out, _) = lagrange(&["problems", "verify", &file]);
    assert_eq!(code, 0, "{out}");
    // A wrong dimension makes L no energy: refused with the verifier's finding.
    let other = dir.join("wrong.toml").display().to_string();
    let mut wrong = base.to_vec();
    wrong[9] = &other;
    wrong.extend(["--param", "zeta=M"]);
    let (code, _, err) = lagrange(&wrong);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("dimension"), "{err}");
    assert!(!std::path::Path::new(&other).exists());
    // An existing file is not replaced without --force.
    let (code, _, err) = lagrange(&with);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--force"), "{err}");
}

#[test]
fn hostile_ids_and_expressions_are_refused_or_escaped() {
    let (code, _, err) = lagrange(&[
        "problems",
        "new",
        "--id",
        "../x",
        "--coords",
        "x",
        "--lagrangian",
        "1/2*m*x'^2",
    ]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("bad-id"), "{err}");
    // A title with quotes and newlines stays one TOML string.
    let (code, out, err) = lagrange(&[
        "problems",
        "new",
        "--id",
        "q",
        "--title",
        "a \"quoted\"\ntitle = \"injected\"",
        "--coords",
        "x",
        "--lagrangian",
        "1/2*m*x'^2 - 1/2*k*x^2",
    ]);
    assert_eq!(code, 0, "{err}");
    let p = lagrange::bank::load_str("q.toml", &out).expect("loads");
    assert_eq!(p.title, "a \"quoted\"\ntitle = \"injected\"");
    let (code, _, err) = lagrange(&[
        "problems",
        "new",
        "--id",
        "r",
        "--coords",
        "x",
        "--lagrangian",
        "1/2*m*x'^2 +",
    ]);
    assert_eq!(code, 2, "{err}");
}

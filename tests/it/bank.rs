//! The problem bank: every problem in `problems/` (and the embedded copy) verifies, and a
//! folder of deliberately broken problems is rejected, each with its specific message.

use lagrange::bank::{embedded, load_dir, verify::verify};

fn root() -> std::path::PathBuf {
    std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

#[test]
fn every_problem_in_the_bank_verifies() {
    let bank = load_dir(&root().join("problems")).unwrap();
    assert!(
        bank.failures.is_empty(),
        "files that do not load: {:#?}",
        bank.failures
    );
    let mut findings = Vec::new();
    for p in &bank.problems {
        for f in verify(p) {
            findings.push(f.to_string());
        }
    }
    assert!(findings.is_empty(), "\n{}", findings.join("\n"));
    assert_eq!(
        bank.problems.len(),
        embedded::FILES.len(),
        "problems/ and the embedded list differ"
    );
}

/// Loads and verifies one file, returning every finding.
fn findings_of(path: &std::path::Path) -> Vec<lagrange::bank::Finding> {
    let text = std::fs::read_to_string(path).unwrap();
    let name = format!("broken/{}", path.file_name().unwrap().to_string_lossy());
    match lagrange::bank::load_str(&name, &text) {
        Err(f) => vec![f],
        Ok(p) => verify(&p),
    }
}

#[test]
fn broken_problems_are_rejected_with_their_specific_message() {
    let dir = root().join("tests/broken");
    let mut paths: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .collect();
    paths.sort();
    assert!(paths.len() >= 14);
    let mut report = String::new();
    for path in &paths {
        let stem = path.file_stem().unwrap().to_string_lossy().to_string();
        let found = findings_of(path);
        assert!(!found.is_empty(), "{stem} was accepted");
        // The file name says what must be caught: `code.toml`, or `code--variant.toml` for
        // several fixtures of one code.
        let code = match stem.split("--").next().unwrap_or(&stem) {
            "undeclared-symbol" | "dimension-error" => {
                if stem == "dimension-error" {
                    "dimension"
                } else {
                    "undeclared-symbol"
                }
            }
            s => s,
        };
        assert!(
            found.iter().any(|f| f.code == code),
            "{stem}: expected code {code}, got {found:#?}"
        );
        for f in &found {
            report.push_str(&format!("{f}\n"));
        }
    }
    insta::assert_snapshot!("broken_problems", report);
}

#[test]
fn one_bad_file_does_not_stop_the_others() {
    let tmp = crate::helpers::scratch("bank");
    std::fs::copy(
        root().join("problems/simple-pendulum.toml"),
        tmp.join("a.toml"),
    )
    .unwrap();
    std::fs::copy(
        root().join("tests/broken/toml-syntax.toml"),
        tmp.join("b.toml"),
    )
    .unwrap();
    std::fs::write(tmp.join("c.toml"), [0xff, 0xfe, 0x00]).unwrap();
    std::fs::copy(root().join("problems/atwood.toml"), tmp.join("d.toml")).unwrap();
    let bank = load_dir(&tmp).unwrap();
    assert_eq!(bank.problems.len(), 2);
    assert_eq!(bank.failures.len(), 2);
    assert!(bank.failures.iter().any(|f| f.code == "not-utf8"));
}

#[test]
fn hostile_toml_never_panics() {
    let huge = format!("id = \"{}\"", "x".repeat(2 << 20));
    let nested = format!("a = {}1{}", "[".repeat(100_000), "]".repeat(100_000));
    let inline = format!("a = {}", "{ b = ".repeat(10_000));
    for text in [
        huge.as_str(),
        nested.as_str(),
        inline.as_str(),
        "",
        "id = 5",
        "parts = \"x\"",
        "\u{0}",
    ] {
        let r = lagrange::bank::load_str("hostile.toml", text);
        assert!(r.is_err());
    }
}

#[test]
fn the_default_bank_has_the_required_problems_and_hints() {
    let bank = embedded::bank();
    type Row<'a> = (&'a str, &'a [&'a str], &'a [&'a str], &'a [&'a str]);
    let required: &[Row] = &[
        (
            "simple-pendulum",
            &["theta"],
            &["m", "l", "g"],
            &[
                "kinetic",
                "potential",
                "lagrangian",
                "momentum",
                "eom",
                "equilibria",
                "frequencies",
                "energy-function",
            ],
        ),
        (
            "bead-wire",
            &["r"],
            &["m", "omega"],
            &[
                "kinetic",
                "potential",
                "lagrangian",
                "momentum",
                "eom",
                "equilibria",
                "energy-function",
            ],
        ),
        (
            "double-pendulum",
            &["theta1", "theta2"],
            &["m1", "m2", "l1", "l2", "g"],
            &[
                "kinetic",
                "potential",
                "lagrangian",
                "eom",
                "frequencies",
                "energy-function",
            ],
        ),
        (
            "atwood",
            &["x"],
            &["m1", "m2", "g"],
            &[
                "kinetic",
                "potential",
                "lagrangian",
                "momentum",
                "eom",
                "energy-function",
            ],
        ),
        (
            "bead-parabola",
            &["r"],
            &["m", "a", "g", "omega"],
            &[
                "kinetic",
                "potential",
                "lagrangian",
                "momentum",
                "eom",
                "equilibria",
                "frequencies",
                "energy-function",
            ],
        ),
        (
            "spring-incline",
            &["x"],
            &["m", "k", "g", "alpha"],
            &[
                "kinetic",
                "potential",
                "lagrangian",
                "momentum",
                "eom",
                "equilibria",
                "frequencies",
                "energy-function",
            ],
        ),
        (
            "atwood-tension",
            &["y1", "y2"],
            &["m1", "m2", "g"],
            &["tension"],
        ),
        (
            "rolling-disk",
            &["x", "phi"],
            &["M", "R", "g", "alpha"],
            &["acceleration", "friction"],
        ),
        (
            "rotating-hoop",
            &["theta"],
            &["m", "R", "g", "omega"],
            &["energy-function"],
        ),
    ];
    for (id, coords, params, parts) in required {
        let p = bank.problem(id).unwrap_or_else(|| panic!("{id} missing"));
        let c: Vec<&str> = p
            .system
            .coordinates
            .iter()
            .map(|c| c.name.as_str())
            .collect();
        assert_eq!(&c, coords, "{id}");
        for q in *params {
            assert!(
                p.system.parameters.iter().any(|x| x.name == *q),
                "{id}: parameter {q}"
            );
        }
        for part in *parts {
            assert!(p.part(part).is_some(), "{id}: part {part}");
        }
        for part in &p.parts {
            assert!(
                (2..=4).contains(&part.hints.len()),
                "{id}/{}: {} hints",
                part.id,
                part.hints.len()
            );
        }
    }
    // The rolling disk's constraint is on velocities, the hoop's h is conserved but not T + V.
    let disk = bank.problem("rolling-disk").unwrap();
    assert_eq!(
        disk.system.constraints[0].kind,
        lagrange::mechanics::ConstraintKind::Nonholonomic
    );
    let mut hoop = bank.problem("rotating-hoop").unwrap().system.clone();
    let d = hoop.derive().unwrap();
    let e = hoop.energy(&d);
    assert!(e.conserved && e.is_total == Some(false));
}

#[test]
fn one_embedded_problem_loads_by_id() {
    for (name, _) in embedded::FILES {
        let id = name.trim_end_matches(".toml");
        assert_eq!(embedded::problem(id).map(|p| p.id), Some(id.to_string()));
    }
    assert!(embedded::problem("no-such-problem").is_none());
}

/// Regression (fuzz toml, seed 2026): one equation of a two-coordinate system stated times a
/// factor that vanishes (ṙ, r) verified, because a lone equation without a reference was never
/// judged for degeneracy. It is now judged against the Euler–Lagrange equation it multiplies.
#[test]
fn a_lone_reference_equation_times_a_vanishing_factor_is_refused() {
    let text = include_str!("../../problems/central-force.toml");
    let right = "m*r'' - m*r*phi'^2 + k/r^2 = 0";
    assert!(
        text.contains(&format!("answer = \"{right}\"")),
        "the bank's radial equation"
    );
    // r' vanishes at regular states (turning points). r vanishes only at r = 0, where the
    // force k/r² is not finite: Kepler's radial equation with its denominator cleared
    // (issue 19) is right, so r is no longer a wrong factor here.
    for factor in ["r'", "(m*r^3*phi'^2 - k)"] {
        let bad = format!("({}) * {factor} = 0", right.trim_end_matches(" = 0"));
        let file = text.replace(
            &format!("answer = \"{right}\""),
            &format!("answer = \"{bad}\""),
        );
        let p = lagrange::bank::load_str("central-force.toml", &file).expect("still loads");
        let findings: Vec<String> = verify(&p).iter().map(|f| f.to_string()).collect();
        assert!(
            findings
                .iter()
                .any(|f| f.contains("multiplied by") && f.contains("vanishes")),
            "{factor}: {findings:?}"
        );
    }
    // The equation itself (and a constant multiple of it) still verifies.
    let doubled = text.replace(
        &format!("answer = \"{right}\""),
        "answer = \"2*m*r'' - 2*m*r*phi'^2 + 2*k/r^2 = 0\"",
    );
    let p = lagrange::bank::load_str("central-force.toml", &doubled).expect("loads");
    assert!(
        verify(&p).is_empty(),
        "{:?}",
        verify(&p).iter().map(|f| f.to_string()).collect::<Vec<_>>()
    );
}

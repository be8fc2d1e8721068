//! Issue 19 §5: two problem files with one id are refused at load, naming both files, by
//! every command that loads problems (a check and a grade once judged by different files).

use std::path::Path;

use crate::helpers::lagrange;

/// A folder holding the simple pendulum twice: `simple-pendulum.toml` and `z-copy.toml`.
fn twin_folder(name: &str) -> crate::helpers::Scratch {
    let dir = crate::helpers::scratch(&format!("twin-{name}"));
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("problems/simple-pendulum.toml");
    std::fs::copy(&src, dir.join("simple-pendulum.toml")).unwrap();
    std::fs::copy(&src, dir.join("z-copy.toml")).unwrap();
    dir
}

#[test]
fn a_folder_with_two_files_of_one_id_loads_neither() {
    let dir = twin_folder("lib");
    let bank = lagrange::load_dir(&dir).unwrap();
    let one = lagrange::bank::load::load_one(&dir, "simple-pendulum");
    assert!(bank.problem("simple-pendulum").is_none());
    let f = &bank.failures;
    assert_eq!(f.len(), 1, "{f:?}");
    assert_eq!(f[0].code, "duplicate-id");
    for file in ["simple-pendulum.toml", "z-copy.toml"] {
        assert!(f[0].message.contains(file), "{}", f[0].message);
    }
    let err = one.expect_err("two files define the id").to_string();
    assert!(
        err.contains("simple-pendulum.toml") && err.contains("z-copy.toml"),
        "{err}"
    );
}

#[test]
fn every_command_refuses_a_duplicated_id_and_names_both_files() {
    let dir = twin_folder("cli");
    let d = dir.display().to_string();
    let csv = dir.join("class.csv");
    std::fs::write(
        &csv,
        "student,problem,part,answer\na,simple-pendulum,frequencies,sqrt(g/l)\n",
    )
    .unwrap();
    let csv = csv.display().to_string();
    let out_dir = dir.join("out").display().to_string();
    let runs: [(&str, Vec<&str>); 4] = [
        (
            "check",
            vec![
                "--problems",
                &d,
                "check",
                "simple-pendulum",
                "frequencies",
                "sqrt(g/l)",
            ],
        ),
        (
            "grade",
            vec!["--problems", &d, "grade", &csv, "--out", &out_dir],
        ),
        ("problems list", vec!["--problems", &d, "problems", "list"]),
        (
            "problems verify",
            vec!["--problems", &d, "problems", "verify"],
        ),
    ];
    let mut results = Vec::new();
    for (what, args) in runs {
        results.push((what, lagrange(&args)));
    }
    for (what, (code, out, err)) in results {
        assert_ne!(code, 0, "{what}: {out}{err}");
        let said = format!("{out}{err}");
        assert!(
            said.contains("defined by two files")
                && said.contains("simple-pendulum.toml")
                && said.contains("z-copy.toml"),
            "{what}: {said}"
        );
    }
}

#[test]
fn the_embedded_bank_has_one_file_per_id() {
    let bank = lagrange::embedded::bank();
    assert!(bank.failures.is_empty(), "{:?}", bank.failures);
    let mut ids: Vec<&str> = bank.problems.iter().map(|p| p.id.as_str()).collect();
    let n = ids.len();
    ids.sort_unstable();
    ids.dedup();
    assert_eq!(ids.len(), n);
    assert_eq!(n, lagrange::embedded::FILES.len());
}

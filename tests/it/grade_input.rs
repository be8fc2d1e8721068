//! Issue 20 §2: the class file as spreadsheets and LMSs export it — nothing lost, every row at
//! its real line, one student per person, the instructor's parts counted, every encoding and
//! delimiter read or refused by name. Each case is a file in `tests/grade/`.

use std::path::{Path, PathBuf};
use std::process::Command;

fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/grade")
        .join(name)
}

/// `lagrange grade FIXTURE --out TMP EXTRA…`: (exit code, stderr, the output folder).
fn grade(name: &str, extra: &[&str]) -> (i32, String, tempfile::TempDir) {
    let out = tempfile::tempdir().expect("temp dir");
    let run = Command::new(env!("CARGO_BIN_EXE_lagrange"))
        .arg("grade")
        .arg(fixture(name))
        .arg("--out")
        .arg(out.path())
        .args(extra)
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&run.stderr).into_owned();
    (run.status.code().unwrap_or(-1), err, out)
}

/// A CSV output's records, header first.
fn records(dir: &Path, name: &str) -> Vec<Vec<String>> {
    let bytes = std::fs::read(dir.join(name)).expect("output");
    csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(bytes.as_slice())
        .records()
        .map(|r| r.expect("CSV").iter().map(str::to_string).collect())
        .collect()
}

/// results.csv as (row, student, status).
fn rows(dir: &Path) -> Vec<(String, String, String)> {
    records(dir, "results.csv")
        .into_iter()
        .skip(1)
        .map(|r| (r[0].clone(), r[1].clone(), r[5].clone()))
        .collect()
}

/// The four rows every variant of the same class file must give.
fn the_four_rows() -> Vec<(String, String, String)> {
    [
        ("2", "a", "correct"),
        ("3", "b", "correct"),
        ("4", "c", "incorrect"),
        ("5", "d", "correct"),
    ]
    .iter()
    .map(|(a, b, c)| (a.to_string(), b.to_string(), c.to_string()))
    .collect()
}

#[test]
fn crlf_cr_only_bom_and_utf16_files_give_the_real_lines() {
    for name in ["crlf.csv", "cr-only.csv", "bom.csv", "utf16.csv"] {
        let (code, err, out) = grade(name, &[]);
        assert_eq!(code, 0, "{name}: {err}");
        assert_eq!(rows(out.path()), the_four_rows(), "{name}");
    }
}

#[test]
fn an_unbalanced_quote_is_refused_with_the_line_it_opens_on() {
    // Five rows in; the quote on line 3 used to swallow the rest: two rows out, exit 0.
    let (code, err, out) = grade("unbalanced.csv", &[]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("line 3: a quoted field opened here is never closed"),
        "{err}"
    );
    assert!(!out.path().join("results.csv").exists());
}

#[test]
fn a_legacy_8_bit_file_is_refused_at_its_first_bad_line() {
    let (code, err, _) = grade("latin1.csv", &[]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("line 3 is not UTF-8") && err.contains("CSV UTF-8"),
        "{err}"
    );
}

#[test]
fn a_semicolon_file_keeps_the_semicolons_of_a_quoted_system() {
    let (code, err, out) = grade("semicolon.csv", &[]);
    assert_eq!(code, 0, "{err}");
    let r = records(out.path(), "results.csv");
    assert_eq!(r.len(), 3, "{r:?}");
    assert_eq!(r[1][5], "correct");
    assert_eq!(r[2][4], "(m1+m2)*l1*theta1'' = 0; l2*theta2'' = 0");
    assert_ne!(r[2][5], "error", "{:?}", r[2]);
}

#[test]
fn keys_differing_only_in_case_or_spaces_are_one_student() {
    let (code, err, out) = grade("case-keys.csv", &[]);
    assert_eq!(code, 0, "{err}");
    assert!(err.contains("differ only in case"), "{err}");
    let book = records(out.path(), "gradebook.csv");
    assert_eq!(book.len(), 3, "two students: {book:?}");
    assert_eq!(book[1][0], "Sophia.Hughes@uni.example");
    assert_eq!(book[1][book[0].len() - 1], "100.0", "{book:?}");
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.path().join("summary.json")).expect("json"))
            .expect("valid");
    assert_eq!(json["students"], 2);
}

#[test]
fn mixed_keys_are_refused_for_moodle_and_decided_per_row_for_gradescope() {
    let (code, err, out) = grade("mixed-keys.csv", &["--lms", "moodle"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("`20231234`"), "{err}");
    assert!(!out.path().join("results.csv").exists());
    let (code, err, out) = grade("mixed-keys.csv", &["--lms", "gradescope"]);
    assert_eq!(code, 0, "{err}");
    let g = records(out.path(), "gradescope.csv");
    assert_eq!(g[1][..2], ["", "ada@uni.example"]);
    assert_eq!(g[3][..2], ["20231234", ""]);
}

#[test]
fn the_maximum_counts_every_part_the_instructor_set() {
    // Wide: nobody answered the frequencies column; it still counts in every maximum.
    let (code, err, out) = grade("wide-unanswered.csv", &["--lms", "canvas"]);
    assert_eq!(code, 0, "{err}");
    let book = records(out.path(), "gradebook.csv");
    assert!(book[0].contains(&"simple-pendulum/frequencies".to_string()));
    let max = book[0].iter().position(|c| c == "max").expect("max");
    assert!(book[1..].iter().all(|r| r[max] == "3"), "{book:?}");
    assert_eq!(records(out.path(), "canvas.csv")[1][5], "3");
    // Long, with --parts: the listed parts, answered or not.
    let parts = "simple-pendulum/potential,simple-pendulum/eom,simple-pendulum/kinetic";
    let (code, err, out) = grade("case-keys.csv", &["--parts", parts]);
    assert_eq!(code, 0, "{err}");
    let book = records(out.path(), "gradebook.csv");
    assert_eq!(
        book[0].join(","),
        format!("student,{parts},total,max,percent")
    );
    assert_eq!(book[2].join(","), "ben@uni.example,0,,,0,3,0.0");
    let (code, err, _) = grade("case-keys.csv", &["--parts", "simple-pendulum/eqm"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--parts"), "{err}");
}

#[test]
fn no_output_holds_a_negative_zero() {
    let (code, err, out) = grade("wide-unanswered.csv", &["--lms", "gradescope"]);
    assert_eq!(code, 0, "{err}");
    for name in [
        "results.csv",
        "gradebook.csv",
        "gradescope.csv",
        "summary.json",
        "summary.md",
    ] {
        let text = std::fs::read_to_string(out.path().join(name)).expect("output");
        assert!(
            !text.contains("-0.0") && !text.contains(",-0"),
            "{name}: {text}"
        );
    }
}

#[cfg(unix)]
#[test]
fn a_fifo_given_as_the_class_file_is_refused_not_read_forever() {
    let dir = tempfile::tempdir().expect("temp dir");
    let fifo = dir.path().join("class.csv");
    let made = Command::new("mkfifo").arg(&fifo).status();
    if !made.is_ok_and(|s| s.success()) {
        return;
    }
    let run = Command::new(env!("CARGO_BIN_EXE_lagrange"))
        .arg("grade")
        .arg(&fifo)
        .arg("--out")
        .arg(dir.path().join("out"))
        .output()
        .expect("runs");
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{err}");
    assert!(err.contains("not a regular file"), "{err}");
}

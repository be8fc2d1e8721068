//! `lagrange grade`, run as an instructor would: class files in, results, gradebook, summary
//! and LMS files out. Expectations are physics (the simple pendulum's EOM and potential).

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

/// The fixtures folder.
fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/grade")
        .join(name)
}

/// A fresh, empty temporary folder for one test.
fn scratch(name: &str) -> crate::helpers::Scratch {
    crate::helpers::scratch(&format!("grade-{name}"))
}

/// Runs `lagrange grade ARGS` with extra environment and optional stdin.
fn grade(args: &[&str], env: &[(&str, &str)], stdin: Option<&[u8]>) -> (i32, String, String) {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_lagrange"));
    cmd.arg("grade").args(args).env("NO_COLOR", "1");
    for (k, v) in env {
        cmd.env(k, v);
    }
    cmd.stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    let mut child = cmd.spawn().expect("the binary runs");
    if let Some(mut pipe) = child.stdin.take() {
        pipe.write_all(stdin.unwrap_or_default()).expect("stdin");
    }
    let out = child.wait_with_output().expect("the binary ends");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Grades `input` into a scratch folder and returns the folder.
fn graded(input: &Path, name: &str, extra: &[&str]) -> crate::helpers::Scratch {
    let out = scratch(name);
    let mut args = vec![
        input.to_str().unwrap_or_default(),
        "--out",
        out.to_str().unwrap_or_default(),
    ];
    args.extend_from_slice(extra);
    let (code, stdout, stderr) = grade(&args, &[], None);
    assert_eq!(code, 0, "{stdout}\n{stderr}");
    out
}

/// The records of a CSV output (header first).
fn records(path: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut r = csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(text.as_slice());
    r.records()
        .map(|x| x.expect("valid CSV").iter().map(str::to_string).collect())
        .collect()
}

/// results.csv rows as (row, student, part, status, score, codes, message).
fn results(dir: &Path) -> Vec<Vec<String>> {
    records(&dir.join("results.csv"))
        .into_iter()
        .skip(1)
        .collect()
}

#[test]
fn long_format_grades_the_physics_and_ignores_extra_columns() {
    let dir = graded(&fixture("long.csv"), "long", &[]);
    let header = &records(&dir.join("results.csv"))[0];
    assert_eq!(
        header.join(","),
        "row,student,problem,part,answer,status,score,codes,message,override,run"
    );
    let rows = results(&dir);
    assert_eq!(rows.len(), 6);
    assert_eq!(
        (
            rows[0][0].as_str(),
            rows[0][5].as_str(),
            rows[0][6].as_str()
        ),
        ("2", "correct", "1")
    );
    // V = m g l cos θ has its sign flipped.
    assert_eq!(rows[1][5], "incorrect");
    assert!(rows[1][7].contains("sign-error"), "{:?}", rows[1]);
    // ω² for ω.
    assert!(rows[5][7].contains("omega-squared"), "{:?}", rows[5]);
}

#[test]
fn wide_format_gives_one_row_per_answered_cell() {
    let dir = graded(&fixture("wide.csv"), "wide", &[]);
    let rows = results(&dir);
    let got: Vec<(&str, &str, &str, &str)> = rows
        .iter()
        .map(|r| (r[0].as_str(), r[1].as_str(), r[3].as_str(), r[5].as_str()))
        .collect();
    assert_eq!(
        got,
        [
            ("2", "w1", "eom", "correct"),
            ("2", "w1", "potential", "correct"),
            ("3", "w2", "potential", "incorrect"),
            ("4", "w3", "eom", "incorrect"),
        ]
    );
    let book = records(&dir.join("gradebook.csv"));
    assert_eq!(
        book[0].join(","),
        "student,simple-pendulum/potential,simple-pendulum/eom,total,max,percent"
    );
    assert_eq!(book[2].join(","), "w2,0,,0,2,0.0");
}

#[test]
fn the_last_attempt_counts_unless_best() {
    let last = graded(&fixture("attempts.csv"), "last", &[]);
    let book = records(&last.join("gradebook.csv"));
    assert_eq!(book[1][..2].join(","), "a,0");
    assert_eq!(book[2][..2].join(","), "b,1");
    let best = graded(&fixture("attempts.csv"), "best", &["--best"]);
    let book = records(&best.join("gradebook.csv"));
    assert_eq!(book[1][..2].join(","), "a,1");
    assert_eq!(book[2][..2].join(","), "b,1");
    // Every attempt is still a row.
    assert_eq!(results(&best).len(), 4);
}

/// A class file with every kind of bad row, as bytes (a control byte and a 1 MB answer; bytes
/// that are not UTF-8 refuse the whole file, see `grade_input.rs`).
fn hostile_file() -> Vec<u8> {
    let mut f = b"student,problem,part,answer\n".to_vec();
    f.extend_from_slice(b"s,simple-pendulum,eom\n"); // 3 fields
    f.extend_from_slice(b"s,simple-pendulum,potential,-m*g*l*cos(\x01)\n"); // a control byte
    f.extend_from_slice(b"s,simple-pendulm,eom,x = 0\n"); // unknown problem
    f.extend_from_slice(b"s,simple-pendulum,eqm,x = 0\n"); // unknown part
    f.extend_from_slice(b"s,simple-pendulum,eom,\n"); // empty answer
    f.extend_from_slice(b"s,simple-pendulum,eom,");
    f.extend(std::iter::repeat_n(b'x', 1_000_000)); // 1 MB answer
    f.extend_from_slice(b"\ns,simple-pendulum,eom,m*l^2*theta'' + m*g*l*sin(theta) = 0\n");
    f
}

#[test]
fn every_bad_row_is_kept_with_its_reason() {
    let dir = scratch("hostile");
    let input = dir.join("hostile.csv");
    std::fs::write(&input, hostile_file()).expect("write");
    let out = dir.join("out");
    let (code, _, stderr) = grade(
        &[
            input.to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
        ],
        &[],
        None,
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(stderr.contains("4 rows had errors, see"), "{stderr}");
    let rows = results(&out);
    assert_eq!(rows.len(), 7, "rows in = rows out");
    let lines: Vec<&str> = rows.iter().map(|r| r[0].as_str()).collect();
    assert_eq!(lines, ["2", "3", "4", "5", "6", "7", "8"]);
    let status: Vec<&str> = rows.iter().map(|r| r[5].as_str()).collect();
    assert_eq!(
        status,
        [
            "error", "invalid", "error", "error", "error", "invalid", "correct"
        ]
    );
    let message = |i: usize| rows[i][8].as_str();
    assert!(
        message(0).contains("line 2: 3 fields, the header has 4"),
        "{}",
        message(0)
    );
    assert_eq!(
        rows[1][4], "'-m*g*l*cos(\u{1})",
        "kept as typed, neutralised"
    );
    assert!(
        message(2).contains("did you mean `simple-pendulum`"),
        "{}",
        message(2)
    );
    assert!(message(3).contains("did you mean `eom`"), "{}", message(3));
    assert!(
        message(4).contains("line 6: empty answer"),
        "{}",
        message(4)
    );
    assert!(
        message(5).contains("over the checker's limit of 20000"),
        "{}",
        message(5)
    );
}

#[test]
fn a_bad_header_or_an_unreadable_file_exits_2_in_one_line() {
    let out = scratch("bad");
    let o = out.to_str().unwrap_or_default();
    let (code, _, err) = grade(
        &[
            fixture("bad-header.csv").to_str().unwrap_or_default(),
            "--out",
            o,
        ],
        &[],
        None,
    );
    assert_eq!(code, 2);
    assert!(
        err.contains("student,problem,part,answer") && err.contains("PROBLEM/PART"),
        "{err}"
    );
    let (code, _, err) = grade(&["/nonexistent/class.csv", "--out", o], &[], None);
    assert_eq!(code, 2);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    let (code, _, err) = grade(&[o, "--out", o], &[], None);
    assert_eq!(code, 2, "{err}");
    let (code, _, err) = grade(
        &[
            fixture("long.csv").to_str().unwrap_or_default(),
            "--follow-through-credit",
            "2",
        ],
        &[],
        None,
    );
    assert_eq!(code, 2, "{err}");
}

/// Every output file of a folder, by name.
fn outputs(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .expect("out dir")
        .map(|e| {
            let e = e.expect("entry");
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).expect("read"),
            )
        })
        .collect();
    files.sort();
    files
}

#[test]
fn outputs_are_byte_identical_across_runs_and_thread_counts() {
    let input = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/class.csv");
    let mut seen = Vec::new();
    for (i, threads) in ["1", "2", "2"].iter().enumerate() {
        let out = scratch(&format!("det{i}"));
        let args = [
            input.to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
            "--lms",
            "canvas",
            "--follow-through",
        ];
        let (code, _, err) = grade(&args, &[("RAYON_NUM_THREADS", threads)], None);
        assert_eq!(code, 0, "{err}");
        seen.push(outputs(&out));
    }
    // results, gradebook, canvas, review, summary.md, summary.json.
    assert_eq!(seen[0].len(), 6);
    assert_eq!(seen[0], seen[1], "1 thread vs 2");
    assert_eq!(seen[1], seen[2], "two runs");
}

#[test]
fn equivalent_spellings_are_one_group() {
    let dir = graded(&fixture("long.csv"), "groups", &["--json"]);
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dir.join("summary.json")).expect("json"))
            .expect("valid");
    let groups = &json["parts"]["simple-pendulum/eom"]["wrong"];
    assert_eq!(groups.as_array().map(Vec::len), Some(1), "{groups}");
    assert_eq!(groups[0]["count"], 2);
    assert_eq!(groups[0]["codes"][0], "sign-error");
    let examples: Vec<&str> = groups[0]["examples"]
        .as_array()
        .map(|a| a.iter().filter_map(|x| x.as_str()).collect())
        .unwrap_or_default();
    assert_eq!(
        examples,
        [
            "m l^2 θ'' - m g l sin(θ) = 0",
            "m*l^2*theta'' - m*g*l*sin(theta) = 0"
        ]
    );
}

#[test]
fn follow_through_credits_the_eom_of_a_wrong_lagrangian() {
    let rows = results(&graded(&fixture("follow.csv"), "follow-off", &[]));
    assert_eq!(rows[1][6], "0");
    let rows = results(&graded(
        &fixture("follow.csv"),
        "follow",
        &["--follow-through"],
    ));
    assert_eq!(rows[1][5], "incorrect");
    assert_eq!(rows[1][6], "0.5");
    assert!(
        rows[1][7].starts_with("follows-from-earlier"),
        "{:?}",
        rows[1]
    );
    assert!(rows[1][8].contains("the mistake is in L"), "{:?}", rows[1]);
    // The same answer without the wrong L before it earns nothing.
    assert_eq!(
        (rows[2][6].as_str(), rows[2][7].contains("follows")),
        ("0", false)
    );
    let rows = results(&graded(
        &fixture("follow.csv"),
        "follow-q",
        &["--follow-through-credit", "0.25"],
    ));
    assert_eq!(rows[1][6], "0.25");
}

#[test]
fn each_lms_file_has_the_columns_its_lms_imports() {
    let input = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/class.csv");
    let want = [
        (
            "canvas",
            "Student,ID,SIS User ID,SIS Login ID,Section,lagrange class",
        ),
        ("moodle", "Email address,lagrange class"),
        ("gradescope", "SID,Email,Score,Max Points"),
    ];
    for (lms, header) in want {
        let dir = graded(&input, &format!("lms-{lms}"), &["--lms", lms]);
        let r = records(&dir.join(format!("{lms}.csv")));
        assert_eq!(r[0].join(","), header, "{lms}");
    }
    let canvas = records(&graded(&input, "lms-canvas2", &["--lms", "canvas"]).join("canvas.csv"));
    assert_eq!(canvas[1][0].trim(), "Points Possible");
    assert_eq!(canvas[2][3], "ada@uni.example");
    // Keys that are not emails go to Moodle's ID number.
    let dir = graded(
        &fixture("attempts.csv"),
        "lms-moodle-id",
        &["--lms", "moodle"],
    );
    assert_eq!(records(&dir.join("moodle.csv"))[0][0], "ID number");
}

#[test]
fn standard_input_is_read_with_a_dash() {
    let out = scratch("stdin");
    let text = std::fs::read(fixture("long.csv")).expect("fixture");
    let (code, stdout, err) = grade(
        &["-", "--out", out.to_str().unwrap_or_default()],
        &[],
        Some(&text),
    );
    assert_eq!(code, 0, "{err}");
    assert!(
        stdout.contains("3 students, 6 answers (long format)"),
        "{stdout}"
    );
    assert_eq!(results(&out).len(), 6);
    assert!(err.is_empty(), "no progress bar or note on a pipe: {err}");
}

#[test]
fn json_prints_the_summary_object() {
    let out = scratch("json");
    let (code, stdout, _) = grade(
        &[
            fixture("long.csv").to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
            "--json",
        ],
        &[],
        None,
    );
    assert_eq!(code, 0);
    let v: serde_json::Value = serde_json::from_str(&stdout).expect("JSON on stdout");
    assert_eq!(v["rows"], 6);
    assert_eq!(v["students"], 3);
}

#[test]
fn summary_of_a_small_class() {
    let input = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/class.csv");
    let dir = graded(&input, "snapshot", &["--follow-through"]);
    let md = std::fs::read_to_string(dir.join("summary.md")).expect("summary.md");
    insta::assert_snapshot!("grade_summary_class", md);
}

#[test]
fn a_file_over_512_mb_is_refused_unread() {
    let dir = scratch("huge");
    let input = dir.join("huge.csv");
    // Sparse: the size is checked before anything is read.
    let f = std::fs::File::create(&input).expect("create");
    f.set_len(513 * 1024 * 1024).expect("set_len");
    let (code, _, err) = grade(
        &[
            input.to_str().unwrap_or_default(),
            "--out",
            dir.to_str().unwrap_or_default(),
        ],
        &[],
        None,
    );
    assert_eq!(code, 2);
    assert!(
        err.contains("over 512 MB") && err.trim().lines().count() == 1,
        "{err}"
    );
}

#[test]
fn a_wide_line_with_the_wrong_field_count_is_one_error_row() {
    let dir = scratch("wide-bad");
    let input = dir.join("wide.csv");
    std::fs::write(
        &input,
        "student,simple-pendulum/eom,simple-pendulum/potential\nw1,x\nw2,,-m*g*l*cos(theta)\n",
    )
    .expect("write");
    let out = dir.join("out");
    let (code, _, err) = grade(
        &[
            input.to_str().unwrap_or_default(),
            "--out",
            out.to_str().unwrap_or_default(),
        ],
        &[],
        None,
    );
    assert_eq!(code, 0, "{err}");
    let rows = results(&out);
    let got: Vec<(&str, &str, &str)> = rows
        .iter()
        .map(|r| (r[0].as_str(), r[1].as_str(), r[5].as_str()))
        .collect();
    assert_eq!(got, [("2", "w1", "error"), ("3", "w2", "correct")]);
    assert!(err.contains("1 row had an error, see"), "{err}");
}

#[test]
fn the_summary_does_not_depend_on_row_order() {
    // No repeated attempts here, so which row counts cannot change with the order.
    let text = std::fs::read_to_string(fixture("long.csv")).expect("fixture");
    let mut lines: Vec<&str> = text.lines().collect();
    let header = lines.remove(0);
    lines.reverse();
    let dir = scratch("reversed");
    let reversed = dir.join("reversed.csv");
    std::fs::write(&reversed, format!("{header}\n{}\n", lines.join("\n"))).expect("write");
    let a = graded(&fixture("long.csv"), "order-a", &[]);
    let b = graded(&reversed, "order-b", &[]);
    let read = |d: &Path| std::fs::read(d.join("summary.md")).expect("summary");
    assert_eq!(read(&a), read(&b), "summary.md");
    // summary.json differs only in the run id (the input's bytes differ).
    let json = |d: &Path| {
        let mut v: serde_json::Value =
            serde_json::from_slice(&std::fs::read(d.join("summary.json")).expect("summary"))
                .expect("valid JSON");
        let run = v["run"].take();
        (run, v)
    };
    let ((run_a, a), (run_b, b)) = (json(&a), json(&b));
    assert_eq!(a, b, "summary.json");
    assert_ne!(run_a, run_b, "different class files, different runs");
}

#[test]
fn the_default_out_dir_is_grades_beside_the_input_or_here_for_stdin() {
    let dir = scratch("default-out");
    let input = dir.join("class.csv");
    std::fs::copy(fixture("long.csv"), &input).expect("copy");
    let (code, _, err) = grade(&[input.to_str().unwrap_or_default()], &[], None);
    assert_eq!(code, 0, "{err}");
    assert!(dir.join("grades/results.csv").is_file());
    let here = dir.join("here");
    std::fs::create_dir_all(&here).expect("mkdir");
    let out = Command::new(env!("CARGO_BIN_EXE_lagrange"))
        .args(["grade", "-"])
        .current_dir(&here)
        .stdin(std::fs::File::open(&input).expect("open"))
        .output()
        .expect("runs");
    assert_eq!(out.status.code(), Some(0));
    assert!(here.join("grades/summary.md").is_file());
}

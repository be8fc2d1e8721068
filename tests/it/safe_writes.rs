//! Issue 20 §3: every file lagrange writes is written safely — only regular files it names are
//! replaced (never through a link, never a device), a temporary file is unique and never left
//! behind, a run is identifiable, and no cell or line a spreadsheet, a browser or a terminal
//! would act on is written as such.

use std::path::Path;
use std::process::Command;

use crate::helpers::lagrange;

const OSCILLATOR: &str = "m*x'^2/2 - k*x^2/2";

/// `lagrange simulate` of the oscillator from x = 1 for 2 s, then `extra` (where it writes).
fn simulate_oscillator(extra: &[&str]) -> (i32, String, String) {
    let mut args = vec![
        "simulate", "-L", OSCILLATOR, "--coords", "x", "--params", "m=1, k=1", "--init", "x=1",
        "--t-end", "2",
    ];
    args.extend_from_slice(extra);
    lagrange(&args)
}

/// A class file with a formula for a student key, answers starting with `-`, `=`, `@` and
/// `+`, and an answer holding a terminal escape and HTML.
const HOSTILE: &str = "student,problem,part,answer\n\
=HYPERLINK(\"http://x.example\"),simple-pendulum,potential,-m*g*l*cos(theta)\n\
@ben,simple-pendulum,potential,=1+2\n\
+cy,simple-pendulum,potential,@SUM(A1)\n\
dee,simple-pendulum,potential,\"<img src=x onerror=alert(1)> \u{1b}[31m*bold*\"\n";

/// Runs `lagrange grade ARGS` in `cwd`: (exit code, stdout, stderr).
fn grade_in(cwd: &Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_lagrange"))
        .arg("grade")
        .args(args)
        .current_dir(cwd)
        .env("NO_COLOR", "1")
        .output()
        .expect("the binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// The records of a CSV file, header included.
fn records(path: &Path) -> Vec<Vec<String>> {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(bytes.as_slice())
        .records()
        .map(|r| r.expect("valid CSV").iter().map(str::to_string).collect())
        .collect()
}

/// The names in a folder, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .expect("list")
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

#[test]
fn out_dot_replaces_only_the_files_grade_names() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    std::fs::write(d.join("class.csv"), HOSTILE).expect("write");
    // Files of the instructor's, including names an older lagrange used for temp files.
    for (name, text) in [
        ("notes.txt", "mine"),
        (".results.csv.1234.tmp", "mine too"),
        ("results.csv.bak", "backup"),
    ] {
        std::fs::write(d.join(name), text).expect("write");
    }
    let (code, _, err) = grade_in(d, &["class.csv", "--out", ".", "--lms", "gradescope"]);
    assert_eq!(code, 0, "{err}");
    assert_eq!(
        names(d),
        [
            ".results.csv.1234.tmp",
            "class.csv",
            "gradebook.csv",
            "gradescope.csv",
            "notes.txt",
            "results.csv",
            "results.csv.bak",
            "review.csv",
            "summary.json",
            "summary.md",
        ]
    );
    assert_eq!(
        std::fs::read_to_string(d.join("notes.txt")).ok().as_deref(),
        Some("mine")
    );
    assert_eq!(
        std::fs::read_to_string(d.join(".results.csv.1234.tmp"))
            .ok()
            .as_deref(),
        Some("mine too")
    );
    assert_eq!(
        std::fs::read_to_string(d.join("class.csv")).ok().as_deref(),
        Some(HOSTILE)
    );
}

#[test]
fn a_stale_temporary_file_of_a_killed_run_is_removed_by_the_next() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    std::fs::write(d.join("class.csv"), HOSTILE).expect("write");
    std::fs::create_dir(d.join("out")).expect("mkdir");
    let stale = d.join("out/.results.csv.Ab12Cd.lagrange-tmp");
    std::fs::write(&stale, "half a file").expect("write");
    let (code, _, err) = grade_in(d, &["class.csv", "--out", "out"]);
    assert_eq!(code, 0, "{err}");
    assert!(!stale.exists(), "{:?}", names(&d.join("out")));
    assert!(names(&d.join("out")).iter().all(|n| !n.contains("tmp")));
}

#[test]
fn every_file_of_a_run_carries_its_run_id() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    std::fs::write(d.join("class.csv"), HOSTILE).expect("write");
    let (code, _, err) = grade_in(d, &["class.csv", "--out", "out"]);
    assert_eq!(code, 0, "{err}");
    let rows = records(&d.join("out/results.csv"));
    assert_eq!(rows[0].last().map(String::as_str), Some("run"));
    let json: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("out/summary.json")).expect("read"))
            .expect("JSON");
    let run = json["run"].as_str().unwrap_or_default().to_string();
    assert_eq!(run.len(), 16, "{run}");
    assert!(rows[1..].iter().all(|r| r.last() == Some(&run)));
    // Another class file, another run id.
    std::fs::write(d.join("class.csv"), HOSTILE.replace("dee", "dan")).expect("write");
    let (code, _, err) = grade_in(d, &["class.csv", "--out", "out2"]);
    assert_eq!(code, 0, "{err}");
    let other: serde_json::Value =
        serde_json::from_slice(&std::fs::read(d.join("out2/summary.json")).expect("read"))
            .expect("JSON");
    assert_ne!(other["run"], json["run"]);
}

#[cfg(unix)]
#[test]
fn a_link_or_a_fifo_at_an_output_name_is_exit_2_and_left_as_it_was() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    std::fs::write(d.join("class.csv"), HOSTILE).expect("write");
    std::fs::write(d.join("precious.txt"), "keep").expect("write");
    std::fs::create_dir(d.join("out")).expect("mkdir");
    std::os::unix::fs::symlink(d.join("precious.txt"), d.join("out/gradebook.csv"))
        .expect("symlink");
    let (code, _, err) = grade_in(d, &["class.csv", "--out", "out"]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("symbolic link") && err.contains("gradebook.csv"),
        "{err}"
    );
    assert_eq!(
        std::fs::read_to_string(d.join("precious.txt"))
            .ok()
            .as_deref(),
        Some("keep")
    );
    assert!(
        !d.join("out/results.csv").exists(),
        "refused before anything is written"
    );
    // A FIFO at an output name: refused at once, not a run that waits for a reader.
    std::fs::remove_file(d.join("out/gradebook.csv")).expect("rm");
    let made = Command::new("mkfifo")
        .arg(d.join("out/summary.md"))
        .status();
    if made.is_ok_and(|s| s.success()) {
        let (code, _, err) = grade_in(d, &["class.csv", "--out", "out"]);
        assert_eq!(code, 2, "{err}");
        assert!(err.contains("summary.md"), "{err}");
    }
}

#[cfg(unix)]
#[test]
fn a_symlinked_out_folder_the_user_names_is_followed() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    std::fs::write(d.join("class.csv"), HOSTILE).expect("write");
    std::fs::create_dir(d.join("real")).expect("mkdir");
    std::os::unix::fs::symlink(d.join("real"), d.join("linked")).expect("symlink");
    let (code, _, err) = grade_in(d, &["class.csv", "--out", "linked"]);
    assert_eq!(code, 0, "{err}");
    assert!(d.join("real/results.csv").is_file());
}

#[test]
fn a_class_file_named_like_an_output_is_never_overwritten() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    std::fs::write(d.join("results.csv"), HOSTILE).expect("write");
    let (code, _, err) = grade_in(d, &["results.csv", "--out", "."]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("one of grade's outputs"), "{err}");
    assert_eq!(
        std::fs::read_to_string(d.join("results.csv"))
            .ok()
            .as_deref(),
        Some(HOSTILE)
    );
    assert_eq!(names(d), ["results.csv"]);
}

#[test]
fn formula_cells_are_neutralised_and_read_back_as_typed() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    std::fs::write(d.join("class.csv"), HOSTILE).expect("write");
    let (code, _, err) = grade_in(d, &["class.csv", "--out", "a", "--lms", "canvas"]);
    assert_eq!(code, 0, "{err}");
    let rows = records(&d.join("a/results.csv"));
    let students: Vec<&str> = rows[1..].iter().map(|r| r[1].as_str()).collect();
    assert_eq!(
        students,
        ["'=HYPERLINK(\"http://x.example\")", "'@ben", "'+cy", "dee"]
    );
    let answers: Vec<&str> = rows[1..].iter().map(|r| r[4].as_str()).collect();
    assert_eq!(&answers[..3], ["'-m*g*l*cos(theta)", "'=1+2", "'@SUM(A1)"]);
    let formula = |cell: &String| cell.starts_with(['=', '+', '-', '@', '\t', '\r']);
    for file in ["results.csv", "gradebook.csv", "canvas.csv"] {
        for r in records(&d.join("a").join(file)).iter().skip(1) {
            // Numbers (scores) are numbers; no text cell starts like a formula.
            assert!(
                r.iter().all(|c| !formula(c) || c.parse::<f64>().is_ok()),
                "{file}: {r:?}"
            );
        }
    }
    // results.csv is a long class file: graded again, every answer reads as it was typed.
    let (code, _, err) = grade_in(d, &["a/results.csv", "--out", "b"]);
    assert_eq!(code, 0, "{err}");
    let again = records(&d.join("b/results.csv"));
    let pick = |rows: &[Vec<String>]| -> Vec<(String, String, String)> {
        rows[1..]
            .iter()
            .map(|r| (r[1].clone(), r[4].clone(), r[5].clone()))
            .collect()
    };
    assert_eq!(pick(&again), pick(&rows));
    assert_eq!(rows[1][5], "correct", "-m g l cos θ is the pendulum's V");
}

#[test]
fn summary_md_and_stdout_show_html_markdown_and_escapes_as_text() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    std::fs::write(d.join("class.csv"), HOSTILE).expect("write");
    let (code, stdout, err) = grade_in(d, &["class.csv", "--out", "out"]);
    assert_eq!(code, 0, "{err}");
    let md = std::fs::read_to_string(d.join("out/summary.md")).expect("summary.md");
    for text in [&md, &stdout, &err] {
        assert!(!text.contains('\u{1b}'), "a raw escape: {text}");
    }
    // The hostile answer is shown only inside a code span, where nothing is interpreted.
    let line = md
        .lines()
        .find(|l| l.contains("<img"))
        .unwrap_or_else(|| panic!("the answer is listed: {md}"));
    let before = &line[..line.find("<img").unwrap_or(0)];
    assert_eq!(
        before.matches('`').count() % 2,
        1,
        "inside a code span: {line}"
    );
    assert!(line.contains("\\u{1b}"), "the escape is shown: {line}");
}

#[cfg(unix)]
#[test]
fn simulate_streams_into_dev_null_and_never_replaces_it() {
    use std::os::unix::fs::FileTypeExt as _;
    let (code, _, err) = simulate_oscillator(&["--out", "/dev/null"]);
    assert_eq!(code, 0, "{err}");
    let kind = std::fs::symlink_metadata("/dev/null")
        .expect("stat")
        .file_type();
    assert!(kind.is_char_device(), "/dev/null is still the device");
}

#[cfg(unix)]
#[test]
fn simulate_refuses_a_link_at_its_csv_or_picture_name() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    std::fs::write(d.join("precious.txt"), "keep").expect("write");
    for (flag, name) in [("--out", "grid.csv"), ("--plot", "q.svg")] {
        let link = d.join(name);
        std::os::unix::fs::symlink(d.join("precious.txt"), &link).expect("symlink");
        let path = link.to_str().unwrap_or_default();
        let (code, _, err) = simulate_oscillator(&[flag, path]);
        assert_eq!(code, 2, "{flag}: {err}");
        assert!(err.contains("symbolic link"), "{flag}: {err}");
        assert_eq!(
            std::fs::read_to_string(d.join("precious.txt"))
                .ok()
                .as_deref(),
            Some("keep")
        );
    }
}

#[test]
fn pictures_are_written_whole_with_no_temporary_file_left() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    let (svg, png) = (d.join("q.svg"), d.join("phase.png"));
    std::fs::write(&svg, "an older picture").expect("write");
    let (code, _, err) = simulate_oscillator(&[
        "--plot",
        svg.to_str().unwrap_or_default(),
        "--phase",
        png.to_str().unwrap_or_default(),
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(&svg).expect("svg");
    assert!(
        text.starts_with("<svg") && text.trim_end().ends_with("</svg>"),
        "{text:.80}"
    );
    let bytes = std::fs::read(&png).expect("png");
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(names(d), ["phase.png", "q.svg"]);
}

#[cfg(unix)]
#[test]
fn out_naming_a_device_or_a_file_is_exit_2_in_one_line() {
    let dir = tempfile::tempdir().expect("temp dir");
    let d = dir.path();
    std::fs::write(d.join("class.csv"), HOSTILE).expect("write");
    for out in ["/dev/null", "class.csv"] {
        let (code, _, err) = grade_in(d, &["class.csv", "--out", out]);
        assert_eq!(code, 2, "{out}: {err}");
        assert!(err.contains("is not a folder"), "{out}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
    }
    assert_eq!(
        std::fs::read_to_string(d.join("class.csv")).ok().as_deref(),
        Some(HOSTILE)
    );
}

//! The instructor's side of `lagrange grade`: an assignment file and its policy (credit per
//! diagnosis code, a penalty per extra attempt, best or last, follow-through), the review
//! queue and the decisions given back with `--overrides`, and one feedback file per student.
//! Every total is recomputed here from results.csv and the policy.

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;

use crate::helpers::scratch;

/// Runs `lagrange grade ARGS` in `dir`: (exit code, stdout, stderr).
fn grade_in(dir: &Path, args: &[&str]) -> (i32, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_lagrange"))
        .arg("grade")
        .args(args)
        .current_dir(dir)
        .env("NO_COLOR", "1")
        .output()
        .expect("the binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A CSV file's records, header first, each cell with a spreadsheet's `'` guard removed.
fn records(path: &Path) -> Vec<Vec<String>> {
    let text = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut r = csv::ReaderBuilder::new()
        .has_headers(false)
        .from_reader(text.as_slice());
    r.records()
        .map(|x| {
            x.expect("valid CSV")
                .iter()
                .map(|c| match c.strip_prefix('\'') {
                    Some(rest) if rest.starts_with(['=', '+', '-', '@']) => rest.to_string(),
                    _ => c.to_string(),
                })
                .collect()
        })
        .collect()
}

/// The records of a CSV file as maps from column name to cell.
fn table(path: &Path) -> Vec<BTreeMap<String, String>> {
    let rows = records(path);
    let header = rows[0].clone();
    (rows[1..].iter())
        .map(|r| header.iter().cloned().zip(r.iter().cloned()).collect())
        .collect()
}

/// The simple pendulum's potential, Lagrangian and equation of motion, with the mistakes the
/// policy prices: a sign error (credit 0.5), an attempt after a wrong one (penalty 0.25),
/// follow-through from a wrong L, and answers the checker cannot read.
const CLASS: &str = "\
student,problem,part,answer
ana,simple-pendulum,potential,m*g*l*cos(theta)
ana,simple-pendulum,potential,-m*g*l*cos(theta)
ana,simple-pendulum,eom,m*l^2*theta'' - m*g*l*sin(theta) = 0
bo,simple-pendulum,potential,-m*g*l*cos(theta)
bo,simple-pendulum,lagrangian,1/2*m*l^2*theta'^2 - m*g*l*cos(theta)
bo,simple-pendulum,eom,m*l^2*theta'' - m*g*l*sin(theta) = 0
cy,simple-pendulum,eom,m*l^2*theta'' = 0
cy,simple-pendulum,eom,m*l^2*theta'' + m*g*l*sin(theta) = 0
cy,simple-pendulum,eom,m*l^2*theta'' + m*g*l*sin(theta) = 0
cy,simple-pendulum,potential,m*g*l
dee,simple-pendulum,potential,-m*g*l*cos(theta)
dee,simple-pendulum,eom,\"m*l^2*theta'' + m*g*l*sin(theta = 0\"
eli,simple-pendulum,eom,\"m*l^2*theta'' + m*g*l*sin(theta = 0\"
eli,simple-pendulum,lagrangian,m*g*l
";

const ASSIGNMENT: &str = r#"title = "Pendulum set"
seed = 20261126

[policy]
attempts = "best"
penalty = 0.25
follow-through = 0.5
credit = { sign-error = 0.5, constant-factor = 0.25 }

[[problems]]
id = "simple-pendulum"
parts = ["potential", "lagrangian", "eom"]
points = { eom = 2 }
"#;

/// The points of each part the assignment sets.
fn points() -> BTreeMap<&'static str, f64> {
    BTreeMap::from([
        ("simple-pendulum/potential", 1.0),
        ("simple-pendulum/lagrangian", 1.0),
        ("simple-pendulum/eom", 2.0),
    ])
}

/// Every student's total recomputed from results.csv: each part's attempts in row order, the
/// penalty taken once per earlier attempt (never below 0), the best one counted.
fn recomputed(results: &[BTreeMap<String, String>], penalty: f64) -> BTreeMap<String, f64> {
    let points = points();
    let mut attempts: BTreeMap<(String, String), Vec<f64>> = BTreeMap::new();
    for r in results {
        let part = format!("{}/{}", r["problem"], r["part"]);
        if r["status"] == "error" || !points.contains_key(part.as_str()) {
            continue;
        }
        let score: f64 = r["score"].parse().expect("a number");
        attempts
            .entry((r["student"].clone(), part))
            .or_default()
            .push(score);
    }
    let mut totals: BTreeMap<String, f64> = BTreeMap::new();
    for ((student, part), scores) in attempts {
        let best = (scores.iter().enumerate())
            .map(|(k, s)| (s - penalty * points[part.as_str()] * k as f64).max(0.0))
            .fold(0.0, f64::max);
        *totals.entry(student).or_default() += best;
    }
    totals
}

#[test]
fn every_total_is_recomputed_from_results_and_the_policy() {
    let dir = scratch("grade-policy-totals");
    let d: &Path = &dir;
    std::fs::write(d.join("class.csv"), CLASS).expect("write");
    std::fs::write(d.join("set.toml"), ASSIGNMENT).expect("write");
    let (code, _, err) = grade_in(
        d,
        &["class.csv", "--out", "out", "--assignment", "set.toml"],
    );
    assert_eq!(code, 0, "{err}");
    let results = table(&d.join("out/results.csv"));
    let book = table(&d.join("out/gradebook.csv"));
    let totals = recomputed(&results, 0.25);
    for row in &book {
        let total: f64 = row["total"].parse().expect("a number");
        let want = totals.get(&row["student"]).copied().unwrap_or(0.0);
        assert!(
            (total - want).abs() < 1e-9,
            "{}: {total} vs {want}",
            row["student"]
        );
        assert_eq!(row["max"], "4", "potential 1 + lagrangian 1 + eom 2");
    }
    let score = |student: &str, part: &str, nth: usize| -> String {
        let rows: Vec<_> = (results.iter())
            .filter(|r| r["student"] == student && r["part"] == part)
            .collect();
        rows[nth]["score"].clone()
    };
    // A sign error earns half the points: 0.5 of the potential's 1, 1 of the equation's 2.
    assert_eq!(score("ana", "potential", 0), "0.5");
    assert_eq!(score("ana", "eom", 0), "1");
    // Ana's right potential at the second attempt counts 1 − 0.25 = 0.75 (over the first
    // attempt's 0.5): her total is 0.75 + 1.
    let total = |s: &str| book.iter().find(|r| r["student"] == s).expect("a row")["total"].clone();
    assert_eq!(total("ana"), "1.75");
    // Bo's equation follows from his wrong L (T + V): follow-through credit 0.5 of 2 points
    // — also 1 as a sign error: the larger applies, never both.
    assert!(score("bo", "eom", 0) == "1", "{results:?}");
    // Cy's third attempt at the equation is right but costs 2 × 0.25 × 2: the second (1.5)
    // counts, the best after the penalty.
    assert_eq!(score("cy", "eom", 2), "2");
    assert_eq!(total("cy"), "1.5");
}

#[test]
fn the_command_line_options_are_shorthands_over_the_assignment() {
    let dir = scratch("grade-policy-flags");
    let d: &Path = &dir;
    std::fs::write(d.join("class.csv"), CLASS).expect("write");
    let last = ASSIGNMENT.replace("\"best\"", "\"last\"");
    std::fs::write(d.join("set.toml"), last).expect("write");
    let (code, _, err) = grade_in(
        d,
        &["class.csv", "--out", "last", "--assignment", "set.toml"],
    );
    assert_eq!(code, 0, "{err}");
    let (code, _, err) = grade_in(
        d,
        &[
            "class.csv",
            "--out",
            "best",
            "--assignment",
            "set.toml",
            "--best",
        ],
    );
    assert_eq!(code, 0, "{err}");
    let cy = |out: &str| {
        let book = table(&d.join(out).join("gradebook.csv"));
        book.iter().find(|r| r["student"] == "cy").expect("cy")["total"].clone()
    };
    // The last of Cy's three equations: 2 − 2 × 0.25 × 2 = 1; the best: the second, 1.5.
    assert_eq!(cy("last"), "1");
    assert_eq!(cy("best"), "1.5");
}

#[test]
fn a_bad_assignment_file_is_refused_with_its_line_and_column() {
    let dir = scratch("grade-policy-bad");
    let d: &Path = &dir;
    std::fs::write(d.join("class.csv"), CLASS).expect("write");
    let cases = [
        (
            "sign-error = 0.5",
            "sign-eror = 0.5",
            "set.toml:8:24:",
            "did you mean `sign-error`",
        ),
        (
            "penalty = 0.25",
            "penalty = 2",
            "set.toml:6:11:",
            "between 0 and 1",
        ),
        (
            "\"eom\"]",
            "\"eon\"]",
            "set.toml:10:1:",
            "did you mean `eom`",
        ),
        (
            "seed = 20261126",
            "seed = \"x\"",
            "set.toml:2:",
            "wrong-type",
        ),
    ];
    for (from, to, at, says) in cases {
        std::fs::write(d.join("set.toml"), ASSIGNMENT.replace(from, to)).expect("write");
        let (code, _, err) = grade_in(
            d,
            &["class.csv", "--out", "out", "--assignment", "set.toml"],
        );
        assert_eq!(code, 2, "{to}: {err}");
        assert!(err.contains(at) && err.contains(says), "{to}: {err}");
        assert!(err.contains("help: "), "{err}");
        assert!(!d.join("out").exists(), "nothing is written");
    }
}

#[test]
fn the_review_queue_lists_what_needs_a_human_and_overrides_apply_visibly() {
    let dir = scratch("grade-policy-review");
    let d: &Path = &dir;
    std::fs::write(d.join("class.csv"), CLASS).expect("write");
    let (code, _, err) = grade_in(d, &["class.csv", "--out", "out"]);
    assert_eq!(code, 0, "{err}");
    let queue = table(&d.join("out/review.csv"));
    let answers: Vec<(&str, &str, &str)> = (queue.iter())
        .map(|r| {
            (
                r["answer"].as_str(),
                r["students"].as_str(),
                r["status"].as_str(),
            )
        })
        .collect();
    // The unclosed parenthesis (2 students) first; `m g l` for the Lagrangian and for the
    // potential, bare not-equals; nothing with a named mistake (the sign errors).
    assert_eq!(
        answers,
        [
            ("m*l^2*theta'' + m*g*l*sin(theta = 0", "2", "invalid"),
            ("m*g*l", "1", "incorrect"),
            ("m*g*l", "1", "incorrect"),
        ],
        "{queue:?}"
    );
    assert_eq!(queue[1]["codes"], "not-equal");
    assert_eq!(queue[1]["read_as"], "m·g·l");
    assert!(queue[0]["message"].contains("never closed"), "{queue:?}");
    assert!(queue.iter().all(|r| r["decision"].is_empty()));
    // The instructor decides: the unclosed parenthesis is right, `m g l` for V is worth half.
    let mut filled = records(&d.join("out/review.csv"));
    filled[1][9] = "correct".to_string();
    let v = filled
        .iter()
        .position(|r| r[1] == "potential")
        .expect("V row");
    filled[v][9] = "50%".to_string();
    let mut w = csv::Writer::from_path(d.join("decisions.csv")).expect("create");
    for r in &filled {
        w.write_record(r).expect("write");
    }
    w.flush().expect("flush");
    drop(w);
    let (code, _, err) = grade_in(
        d,
        &["class.csv", "--out", "out", "--overrides", "decisions.csv"],
    );
    assert_eq!(code, 0, "{err}");
    let results = table(&d.join("out/results.csv"));
    let overridden: Vec<(&str, &str, &str, &str)> = (results.iter())
        .filter(|r| !r["override"].is_empty())
        .map(|r| {
            (
                r["student"].as_str(),
                r["status"].as_str(),
                r["score"].as_str(),
                r["override"].as_str(),
            )
        })
        .collect();
    assert_eq!(
        overridden,
        [
            ("cy", "incorrect", "0.5", "0.5"),
            ("dee", "correct", "1", "correct"),
            ("eli", "correct", "1", "correct"),
        ]
    );
    let dee = results
        .iter()
        .find(|r| r["student"] == "dee" && r["part"] == "eom");
    let message = &dee.expect("dee's equation")["message"];
    assert!(message.contains("instructor's decision: correct") && message.contains("invalid"));
    // The next queue keeps the decisions, so grading again loses none.
    let queue = table(&d.join("out/review.csv"));
    let decisions: Vec<&str> = queue.iter().map(|r| r["decision"].as_str()).collect();
    assert_eq!(decisions, ["correct", "", "50%"]);
    // A decision the file cannot read is refused with its line.
    std::fs::write(
        d.join("bad.csv"),
        "problem,part,answer,decision\nsimple-pendulum,eom,x,perhaps\n",
    )
    .expect("write");
    let (code, _, err) = grade_in(d, &["class.csv", "--out", "out", "--overrides", "bad.csv"]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("line 2") && err.contains("perhaps"), "{err}");
}

#[test]
fn feedback_files_are_named_safely_and_escape_what_students_typed() {
    let dir = scratch("grade-policy-feedback");
    let d: &Path = &dir;
    let class = "student,problem,part,answer\n\
                 ../../x,simple-pendulum,potential,<script>alert(1)</script>\n\
                 ../../x,simple-pendulum,eom,m*l^2*theta'' - m*g*l*sin(theta) = 0\n\
                 .hidden,simple-pendulum,potential,-m*g*l*cos(theta)\n";
    std::fs::create_dir(d.join("class")).expect("mkdir");
    std::fs::write(d.join("class/class.csv"), class).expect("write");
    let (code, _, err) = grade_in(d, &["class/class.csv", "--out", "class/out", "--feedback"]);
    assert_eq!(code, 0, "{err}");
    let feedback = d.join("class/out/feedback");
    let mut names: Vec<String> = std::fs::read_dir(&feedback)
        .expect("the feedback folder")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "%2E.%2F..%2Fx.html",
            "%2E.%2F..%2Fx.md",
            "%2Ehidden.html",
            "%2Ehidden.md"
        ]
    );
    // Nothing outside the output folder.
    assert!(!d.join("x.md").exists() && !d.join("class/x.md").exists());
    let html = std::fs::read_to_string(feedback.join("%2E.%2F..%2Fx.html")).expect("read");
    assert!(
        html.contains("&lt;script&gt;alert(1)&lt;/script&gt;"),
        "{html}"
    );
    assert!(!html.contains("<script>"), "{html}");
    assert!(html.contains("Feedback for ../../x"), "{html}");
    let md = std::fs::read_to_string(feedback.join("%2E.%2F..%2Fx.md")).expect("read");
    // The sign error, how it was read, its verdict and the tutor's first hint for the part.
    assert!(
        md.contains("- Read as: `m·l²·θ̈ − m·g·l·sin(θ) = 0`"),
        "{md}"
    );
    assert!(md.contains("- Verdict: incorrect, 0 of 1 point"), "{md}");
    assert!(md.contains("(sign-error)"), "{md}");
    assert!(md.contains("- Next hint: "), "{md}");
    assert!(md.contains("`<script>alert(1)</script>`"), "{md}");
    let hidden = std::fs::read_to_string(feedback.join("%2Ehidden.md")).expect("read");
    assert!(
        hidden.contains("- Verdict: correct, 1 of 1 point"),
        "{hidden}"
    );
    // A link where the feedback folder goes is refused before anything is graded.
    #[cfg(unix)]
    {
        std::fs::create_dir(d.join("elsewhere")).expect("mkdir");
        std::fs::create_dir(d.join("out2")).expect("mkdir");
        std::os::unix::fs::symlink(d.join("elsewhere"), d.join("out2/feedback")).expect("link");
        let (code, _, err) = grade_in(d, &["class/class.csv", "--out", "out2", "--feedback"]);
        assert_eq!(code, 2, "{err}");
        assert_eq!(
            std::fs::read_dir(d.join("elsewhere")).expect("dir").count(),
            0
        );
        assert!(!d.join("out2/results.csv").exists());
    }
}

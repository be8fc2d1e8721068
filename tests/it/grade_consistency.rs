//! Issue 20 §1: `lagrange grade` checks each distinct answer once and shares the verdict —
//! but every row must get exactly the verdict `check` gives that row alone. Over the whole
//! labelled corpus (plus each equilibrium answer with its stated stability flipped, and each
//! list with its items reversed), in several seeded row orders and with 1 and 2 threads,
//! every row's status, score, codes and message equal `lagrange::check::check`'s. (An empty
//! answer is left out: grade gives it the status `error` before any checking, by design.)

use std::collections::HashMap;
use std::path::Path;
use std::process::Command;

use lagrange::bank::embedded;
use lagrange::check::{Status, check};

/// (problem, part, answer) of every corpus line, and the variants that once shared a wrong
/// verdict: stability flipped, list items reversed.
fn cases() -> Vec<(String, String, String)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus");
    let mut names: Vec<_> = std::fs::read_dir(&dir)
        .expect("tests/corpus")
        .flatten()
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|e| e == "txt"))
        .collect();
    names.sort();
    let mut out = Vec::new();
    for path in names {
        let text = std::fs::read_to_string(&path).expect("corpus file");
        for line in text.lines().filter(|l| !l.starts_with('#')) {
            let f: Vec<&str> = line.splitn(5, '|').map(str::trim).collect();
            if f.len() < 5 {
                continue;
            }
            let (problem, part, answer) = (f[0], f[1], f[4]);
            // An empty answer is a row grade cannot grade (status `error`, documented), not
            // an answer to check.
            if answer.trim().is_empty() {
                continue;
            }
            // `grade` runs on the built-in bank; curvilinear.txt's systems are files of their own.
            if lagrange::bank::embedded::problem(problem).is_none() {
                continue;
            }
            let mut push = |a: String| out.push((problem.to_string(), part.to_string(), a));
            push(answer.to_string());
            if answer.contains("unstable") || answer.contains("stable") {
                push(
                    answer
                        .replace("unstable", "\u{1}")
                        .replace("stable", "unstable")
                        .replace('\u{1}', "stable"),
                );
            }
            if answer.contains(", ") && !answer.contains('(') {
                let mut items: Vec<&str> = answer.split(", ").collect();
                items.reverse();
                push(items.join(", "));
            }
        }
    }
    out
}

/// A seeded shuffle (xorshift), the same on every machine.
fn shuffled<T: Clone>(items: &[T], seed: u64) -> Vec<T> {
    let mut v = items.to_vec();
    let mut s = seed.wrapping_mul(0x9e37_79b9_7f4a_7c15) | 1;
    for i in (1..v.len()).rev() {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        v.swap(i, (s % (i as u64 + 1)) as usize);
    }
    v
}

/// A score as results.csv prints it.
fn num(x: f64) -> String {
    let s = format!("{x:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" { "0".into() } else { s.into() }
}

/// The cell as typed, without the `'` that neutralises a formula.
fn unquote(s: &str) -> &str {
    match s.strip_prefix('\'') {
        Some(r) if r.starts_with(['=', '+', '-', '@', '\t', '\r', '\'']) => r,
        _ => s,
    }
}

#[test]
fn every_row_gets_the_verdict_check_gives_it_alone() {
    let bank = embedded::bank();
    let cases = cases();
    assert!(cases.len() > 900, "{}", cases.len());
    // What `check` says of each distinct answer, alone.
    let mut alone: HashMap<(String, String, String), [String; 4]> = HashMap::new();
    for (problem, part, answer) in &cases {
        let key = (problem.clone(), part.clone(), answer.clone());
        if alone.contains_key(&key) {
            continue;
        }
        let p = bank.problem(problem).expect("corpus problem in the bank");
        let q = p.part(part).expect("corpus part in the bank");
        let v = check(p, q, answer).expect("checkable");
        let status = match v.status {
            Status::Correct => "correct",
            Status::Incorrect => "incorrect",
            Status::Invalid => "invalid",
        };
        let codes: Vec<String> = v.diagnoses.iter().map(|d| d.code.to_string()).collect();
        let message = v
            .diagnoses
            .first()
            .map_or(String::new(), |d| d.message.clone());
        alone.insert(
            key,
            [
                status.into(),
                num(v.score * q.points),
                codes.join(";"),
                message,
            ],
        );
    }
    let dir = tempfile::tempdir().expect("temp dir");
    for seed in [1, 2, 3] {
        let rows = shuffled(&cases, seed);
        let mut w = csv::Writer::from_writer(Vec::new());
        w.write_record(["student", "problem", "part", "answer"])
            .expect("header");
        for (i, (p, q, a)) in rows.iter().enumerate() {
            w.write_record([&format!("s{i}"), p, q, a]).expect("row");
        }
        let input = dir.path().join(format!("class{seed}.csv"));
        std::fs::write(&input, w.into_inner().expect("csv")).expect("write");
        for threads in ["1", "2"] {
            let out = dir.path().join(format!("out{seed}-{threads}"));
            let run = Command::new(env!("CARGO_BIN_EXE_lagrange"))
                .args(["grade", input.to_str().unwrap_or_default(), "--out"])
                .arg(&out)
                .env("RAYON_NUM_THREADS", threads)
                .output()
                .expect("runs");
            assert_eq!(run.status.code(), Some(0), "{run:?}");
            let text = std::fs::read(out.join("results.csv")).expect("results");
            let mut r = csv::Reader::from_reader(text.as_slice());
            let mut wrong = Vec::new();
            for (rec, (p, q, a)) in r.records().zip(&rows) {
                let rec = rec.expect("record");
                let got = [
                    rec[5].to_string(),
                    rec[6].to_string(),
                    rec[7].to_string(),
                    unquote(&rec[8]).to_string(),
                ];
                let want = &alone[&(p.clone(), q.clone(), a.clone())];
                if &got != want {
                    wrong.push(format!("{p}/{q} `{a}`:\n  grade {got:?}\n  check {want:?}"));
                }
            }
            assert!(
                wrong.is_empty(),
                "order {seed}, {threads} thread(s): {} rows differ from check alone:\n{}",
                wrong.len(),
                wrong.join("\n")
            );
        }
    }
}

#[test]
fn stated_stability_is_part_of_what_an_answer_shares() {
    // `r = 0 (unstable)` first used to give `r = 0 (stable)` its verdict (and the reverse).
    let input = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/grade/stability.csv");
    let dir = tempfile::tempdir().expect("temp dir");
    let run = Command::new(env!("CARGO_BIN_EXE_lagrange"))
        .arg("grade")
        .arg(&input)
        .arg("--out")
        .arg(dir.path())
        .output()
        .expect("runs");
    assert_eq!(run.status.code(), Some(0), "{run:?}");
    let text = std::fs::read(dir.path().join("results.csv")).expect("results");
    let got: Vec<(String, String)> = csv::Reader::from_reader(text.as_slice())
        .records()
        .map(|r| r.expect("record"))
        .map(|r| (r[5].to_string(), r[6].to_string()))
        .collect();
    let want = [
        ("incorrect", "0"),
        ("correct", "1"),
        ("incorrect", "0"),
        ("correct", "1"),
        ("correct", "1"),
    ];
    let want: Vec<(String, String)> = want
        .iter()
        .map(|(a, b)| (a.to_string(), b.to_string()))
        .collect();
    assert_eq!(got, want);
}

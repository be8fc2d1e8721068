//! The REPL's face, driven through a pipe (no terminal): transcripts of a session per bank
//! problem pinned by snapshots, the JSON-lines protocol, the progress file (saved, reloaded,
//! a corrupt one moved aside) and `lagrange` with no command and no terminal.

use std::io::Write;
use std::path::Path;
use std::process::{Command, Stdio};

/// A fresh `LAGRANGE_HOME` for one test.
fn home(name: &str) -> crate::helpers::Scratch {
    crate::helpers::scratch(&format!("repl-{name}"))
}

/// Runs `lagrange ARGS` with `input` piped in; (exit code, stdout, stderr).
fn repl(home: &Path, args: &[&str], input: &str) -> (i32, String, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_lagrange"))
        .args(args)
        .env("LAGRANGE_HOME", home)
        .env("NO_COLOR", "1")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    child
        .stdin
        .take()
        .expect("stdin piped")
        .write_all(input.as_bytes())
        .expect("input written");
    let out = child.wait_with_output().expect("the binary ends");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A wrong answer built from a right one: a doubled expression, a shifted equation, the
/// first item of a list.
fn wrong(answer: &str) -> String {
    if let Some((lhs, rhs)) = answer.split_once('=') {
        format!("{lhs} + 1 = {rhs}")
    } else if answer.contains(',') || answer.contains(';') {
        "0".to_string()
    } else {
        format!("2*({answer})")
    }
}

#[test]
fn a_session_per_bank_problem() {
    let dir = home("transcripts");
    for p in &lagrange::embedded::bank().problems {
        let part = &p.parts[0];
        let right = &part.answers[0];
        let script = format!(":open {}\n{}\nhint\n{right}\n:next\n", p.id, wrong(right));
        let (code, out, err) = repl(&dir, &["repl", "--no-save"], &script);
        assert_eq!(code, 0, "{}: {err}", p.id);
        assert!(out.contains("incorrect"), "{}: {out}", p.id);
        assert!(out.contains("\ncorrect"), "{}: {out}", p.id);
        insta::assert_snapshot!(format!("repl_{}", p.id), format!("{script}---\n{out}"));
    }
}

#[test]
fn json_gives_one_object_per_line() {
    let dir = home("json");
    let script = ":problems\n:open simple-pendulum\n1/2 m l^2 theta'^2\n\nhint\n:oppen x\n";
    let (code, out, _) = repl(&dir, &["repl", "--json", "--no-save"], script);
    assert_eq!(code, 0);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), script.lines().count(), "{out}");
    let objects: Vec<serde_json::Value> = lines
        .iter()
        .map(|l| serde_json::from_str(l).expect("one JSON object per line"))
        .collect();
    let kinds: Vec<&str> = objects
        .iter()
        .map(|o| o["kind"].as_str().unwrap_or(""))
        .collect();
    assert_eq!(
        kinds,
        ["problems", "statement", "verdict", "none", "hint", "error"]
    );
    // The opened problem's current part comes along in "more".
    assert_eq!(objects[1]["more"][0]["kind"], "part");
    // The verdict has the fields of `lagrange check --json`: T = ½·m·l²·θ̇² is correct.
    assert_eq!(objects[2]["status"], "correct");
    assert_eq!(objects[2]["part"], "kinetic");
    assert_eq!(objects[2]["score"], 1.0);
    assert_eq!(objects[5]["suggestion"], ":open");
}

#[test]
fn progress_is_saved_and_reloaded() {
    let dir = home("progress");
    let (code, _, err) = repl(&dir, &["repl", "simple-pendulum"], "1/2 m l^2 theta'^2\n");
    assert_eq!(code, 0, "{err}");
    let saved = std::fs::read_to_string(dir.join("progress.json")).expect("progress written");
    assert!(saved.contains("simple-pendulum"), "{saved}");
    // Reopened, the solved part (T = ½·m·l²·θ̇²) is skipped.
    let (_, out, _) = repl(&dir, &["repl"], ":open simple-pendulum\n:progress\n");
    assert!(out.contains("part 2: potential"), "{out}");
    assert!(out.contains("1 of"), "{out}");
    // --no-save leaves the file as it was.
    let (_, _, _) = repl(&dir, &["repl", "--no-save", "simple-pendulum"], "0\n");
    let after = std::fs::read_to_string(dir.join("progress.json")).expect("still there");
    assert_eq!(saved, after);
}

#[test]
fn a_corrupt_progress_file_is_moved_aside() {
    let dir = home("corrupt");
    std::fs::write(dir.join("progress.json"), "{\"version\": tru").expect("written");
    let (code, out, err) = repl(&dir, &["repl"], ":progress\n");
    assert_eq!(code, 0);
    assert!(
        err.contains("warning") && err.contains("corrupt-1"),
        "{err}"
    );
    assert!(out.contains("total: 0 of"), "{out}");
    let aside = std::fs::read_to_string(dir.join("progress.json.corrupt-1")).expect("kept");
    assert_eq!(aside, "{\"version\": tru");
}

#[test]
fn without_a_terminal_lagrange_prints_help() {
    let dir = home("help");
    let (code, out, err) = repl(&dir, &[], "");
    assert_eq!(code, 2);
    assert!(out.is_empty());
    assert!(err.contains("Usage: lagrange"), "{err}");
    assert!(err.contains("repl"), "{err}");
}

#[test]
fn the_global_problems_folder_is_the_bank() {
    let dir = home("folder");
    let bank = dir.join("bank");
    std::fs::create_dir_all(&bank).expect("a folder");
    let src = concat!(env!("CARGO_MANIFEST_DIR"), "/problems/atwood.toml");
    std::fs::copy(src, bank.join("atwood.toml")).expect("copied");
    let folder = bank.to_string_lossy().into_owned();
    let (code, out, err) = repl(
        &dir,
        &["--problems", &folder, "repl", "--no-save"],
        ":problems\n",
    );
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("atwood"), "{out}");
    assert!(!out.contains("simple-pendulum"), "{out}");
}

/// A wrong answer to a tutor step, chosen by what the step asks so that its diagnosis is a
/// telling one: ω² for ω (and ω for ω²), a list with its last item dropped, one term's sign
/// flipped in a Lagrangian or an equation (a constant multiple of either is still right), any
/// other expression doubled.
fn wrong_step(step: &lagrange::tutor::ladder::Step, reference: &str) -> String {
    let id = step.id.as_str();
    if reference == "0" {
        return "1".to_string();
    }
    if id == "frequencies" {
        return reference
            .split(", ")
            .map(|w| format!("({w})^2"))
            .collect::<Vec<_>>()
            .join(", ");
    }
    if id == "characteristic" {
        return reference
            .split(", ")
            .map(|w| format!("sqrt({w})"))
            .collect::<Vec<_>>()
            .join(", ");
    }
    // A continuum (`x = any, s = 0`) is one item: move its fixed coordinate instead.
    if id == "equilibria" && reference.contains("= any") && reference.contains("= 0") {
        return reference.replacen("= 0", "= 1", 1);
    }
    // One equilibrium of several coordinates (`x = 0, y = 0`): move its first coordinate.
    let first_name = |x: &str| x.split_once('=').map(|(q, _)| q.trim().to_string());
    let several_coordinates = reference
        .split(", ")
        .any(|x| first_name(x) != first_name(reference));
    if id == "equilibria"
        && !reference.contains(';')
        && several_coordinates
        && let Some((q, rest)) = reference.split_once('=')
    {
        return format!("{q}= 1 +{rest}");
    }
    if id == "equilibria" || id.starts_with("position:") {
        let items: Vec<&str> = reference.split(", ").collect();
        return match items.as_slice() {
            // One equilibrium: give another point instead.
            [one] => match one.split_once('=') {
                Some((q, _)) => format!("{q}= 1"),
                None => "1".to_string(),
            },
            _ => items[..items.len() - 1].join(", "),
        };
    }
    // A constant multiple of L, or of an equation, is still right: flip one term's sign.
    if id == "lagrangian" || id.starts_with("eom:") || id == "linearized" {
        return match (reference.find(" + "), reference.find(" - ")) {
            (Some(i), Some(j)) if j < i => format!("{} + {}", &reference[..j], &reference[j + 3..]),
            (Some(i), _) => format!("{} - {}", &reference[..i], &reference[i + 3..]),
            (None, Some(j)) => format!("{} + {}", &reference[..j], &reference[j + 3..]),
            // One term: multiplied by the coordinate's velocity, the energy-law slip.
            (None, None) => match (id.strip_prefix("eom:"), reference.split_once(" = ")) {
                (Some(q), Some((lhs, rhs))) => format!("{q}'*({lhs}) = {rhs}"),
                _ => format!("2*({reference})"),
            },
        };
    }
    format!("2*({reference})")
}

#[test]
fn a_tutor_session_per_bank_problem() {
    let dir = home("tutor-transcripts");
    for p in &lagrange::embedded::bank().problems {
        let steps = lagrange::tutor::ladder::ladder(p).expect("the ladder builds");
        let mut script = format!(":open {}\n:tutor\n", p.id);
        for s in &steps {
            let reference = s.reference_text(p.system.n());
            script.push_str(&format!("{}\n{reference}\n", wrong_step(s, &reference)));
        }
        let (code, out, err) = repl(&dir, &["repl", "--no-save"], &script);
        assert_eq!(code, 0, "{}: {err}", p.id);
        // Every step's reference is accepted: one `correct` per step.
        let correct = out.matches("\ncorrect  score 100%").count();
        assert_eq!(correct, steps.len(), "{}:\n{out}", p.id);
        // And every step's wrong answer is judged wrong, with a reason.
        let wrong = out.matches("\nincorrect  score").count();
        assert_eq!(wrong, steps.len(), "{}:\n{out}", p.id);
        assert!(
            out.contains("every step of the derivation is done"),
            "{}",
            p.id
        );
        insta::assert_snapshot!(format!("tutor_{}", p.id), format!("{script}\n---\n{out}"));
    }
}

#[test]
fn a_line_that_is_not_utf8_is_an_error_reply_and_the_session_goes_on() {
    let home = tempfile::tempdir().expect("temp dir");
    let mut child = Command::new(env!("CARGO_BIN_EXE_lagrange"))
        .args(["repl", "simple-pendulum", "--json"])
        .env("LAGRANGE_HOME", home.path())
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs");
    child
        .stdin
        .take()
        .expect("stdin piped")
        .write_all(b"1/2 m l^2 theta'^2 \xff\n1/2 m l^2 theta'^2\n")
        .expect("input written");
    let out = child.wait_with_output().expect("the binary ends");
    assert_eq!(out.status.code(), Some(0));
    let lines: Vec<serde_json::Value> = String::from_utf8_lossy(&out.stdout)
        .lines()
        .map(|l| serde_json::from_str(l).expect("one JSON object a line"))
        .collect();
    assert_eq!(lines.len(), 3, "{lines:?}");
    assert_eq!(lines[1]["code"], "not-utf8", "{}", lines[1]);
    assert_eq!(
        lines[2]["status"], "correct",
        "the next line is answered: {}",
        lines[2]
    );
}

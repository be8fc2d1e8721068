//! Issue 9, section 3: nothing runs away. Hostile ranges, files that are not files, inputs
//! whose derivatives explode, answers with thousands of terms and banks of thousands of
//! files: each is the exact case from the issue, run as a user would run it, with a
//! deadline (a hang fails the test instead of stalling it) and, where memory was the
//! problem, under an address-space limit.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// What a run of the binary gave.
struct Run {
    code: Option<i32>,
    stdout: String,
    stderr: String,
}

/// Runs `lagrange ARGS`, killing it past `deadline` (then the test fails, naming the run).
/// With `max_kb`, the run's address space is limited to that many KiB (`ulimit -v`).
fn run(args: &[&str], deadline: Duration, max_kb: Option<u64>) -> Run {
    let bin = env!("CARGO_BIN_EXE_lagrange");
    let mut cmd = match max_kb {
        Some(kb) => {
            let mut c = Command::new("sh");
            c.arg("-c")
                .arg(format!("ulimit -v {kb} && exec \"$0\" \"$@\""))
                .arg(bin);
            c
        }
        None => Command::new(bin),
    };
    let mut child = cmd
        .args(args)
        .env("NO_COLOR", "1")
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary starts");
    // Both pipes are drained while the child runs, so a large output cannot block it.
    let drain = |mut r: Box<dyn Read + Send>| {
        std::thread::spawn(move || {
            let mut s = Vec::new();
            r.read_to_end(&mut s).ok();
            String::from_utf8_lossy(&s).into_owned()
        })
    };
    let out = drain(Box::new(child.stdout.take().expect("piped")));
    let err = drain(Box::new(child.stderr.take().expect("piped")));
    let start = Instant::now();
    let status = loop {
        if let Some(s) = child.try_wait().expect("the child can be waited on") {
            break s;
        }
        if start.elapsed() > deadline {
            child.kill().ok();
            child.wait().ok();
            panic!("`lagrange {}` ran past {deadline:?}", short(args));
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    Run {
        code: status.code(),
        stdout: out.join().expect("stdout is read"),
        stderr: err.join().expect("stderr is read"),
    }
}

/// The arguments, each cut to 60 characters (for a failure message).
fn short(args: &[&str]) -> String {
    args.iter()
        .map(|a| a.chars().take(60).collect::<String>())
        .collect::<Vec<_>>()
        .join(" ")
}

/// A fresh, empty temporary folder for one test.
fn temp_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("lagrange-res-{name}-{}", std::process::id()));
    std::fs::remove_dir_all(&dir).ok();
    std::fs::create_dir_all(&dir).expect("a temporary folder");
    dir
}

fn problem_text(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("problems")
        .join(format!("{name}.toml"));
    std::fs::read_to_string(path).expect("a bank problem")
}

const SECONDS_30: Duration = Duration::from_secs(30);

#[test]
fn modes_with_a_coordinate_range_of_1e308_does_not_panic() {
    let r = run(
        &[
            "modes",
            "--lagrangian",
            "1/2 x'^2 - 1/2 x^2",
            "--coords",
            "x",
            "--range",
            "x=-1e308:1e308",
        ],
        SECONDS_30,
        None,
    );
    assert!(!r.stderr.contains("panicked"), "{}", r.stderr);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    assert!(
        r.stdout.contains("equilibrium x = 0: stable"),
        "{}",
        r.stdout
    );
}

#[test]
fn a_toml_coordinate_range_of_1e308_does_not_panic() {
    let dir = temp_dir("range");
    let text = problem_text("atwood").replace("range = [-2.0, 2.0]", "range = [-1e308, 1e308]");
    assert!(text.contains("[-1e308, 1e308]"));
    std::fs::write(dir.join("atwood.toml"), text).unwrap();
    let d = dir.to_str().unwrap();
    let check = run(
        &[
            "--problems",
            d,
            "check",
            "atwood",
            "eom",
            "x'' = (m1 - m2)/(m1 + m2)*g",
        ],
        SECONDS_30,
        None,
    );
    let verify = run(&["--problems", d, "problems", "verify"], SECONDS_30, None);
    std::fs::remove_dir_all(&dir).ok();
    assert!(!check.stderr.contains("panicked"), "{}", check.stderr);
    assert_eq!(check.code, Some(0), "{}{}", check.stdout, check.stderr);
    assert!(check.stdout.contains("correct"), "{}", check.stdout);
    assert!(!verify.stderr.contains("panicked"), "{}", verify.stderr);
    assert!(matches!(verify.code, Some(0 | 1)), "{}", verify.stderr);
}

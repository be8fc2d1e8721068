//! Issue 9, section 3: nothing runs away. Hostile ranges, files that are not files, inputs
//! whose derivatives explode, answers with thousands of terms and banks of thousands of
//! files: each is the exact case from the issue, run as a user would run it, with a
//! deadline (a hang fails the test instead of stalling it) and, where memory was the
//! problem, under an address-space limit.

use std::io::Read;
use std::path::Path;
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
fn temp_dir(name: &str) -> crate::helpers::Scratch {
    crate::helpers::scratch(&format!("res-{name}"))
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
    assert!(!check.stderr.contains("panicked"), "{}", check.stderr);
    assert_eq!(check.code, Some(0), "{}{}", check.stdout, check.stderr);
    assert!(check.stdout.contains("correct"), "{}", check.stdout);
    assert!(!verify.stderr.contains("panicked"), "{}", verify.stderr);
    assert!(matches!(verify.code, Some(0 | 1)), "{}", verify.stderr);
}

#[cfg(unix)]
#[test]
fn a_fifo_named_a_toml_is_a_finding_not_a_hang() {
    let dir = temp_dir("fifo");
    let fifo = dir.join("a.toml");
    let made = Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .expect("mkfifo runs");
    assert!(made.success());
    std::fs::write(dir.join("atwood.toml"), problem_text("atwood")).unwrap();
    let d = dir.to_str().unwrap();
    let list = run(&["--problems", d, "problems", "list"], SECONDS_30, None);
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
    let explicit = run(
        &["problems", "verify", fifo.to_str().unwrap()],
        SECONDS_30,
        None,
    );
    // In this process only once the binary has shown that it does not open the FIFO.
    let bank = lagrange::bank::load_dir(&dir).expect("the folder reads");
    assert_eq!(list.code, Some(0), "{}", list.stderr);
    assert!(list.stdout.contains("atwood"), "{}", list.stdout);
    assert!(
        list.stdout
            .contains("a.toml:1: this is a named pipe (FIFO)"),
        "{}",
        list.stdout
    );
    assert!(list.stdout.contains("[not-a-file]"), "{}", list.stdout);
    assert_eq!(check.code, Some(0), "{}", check.stderr);
    assert_eq!(explicit.code, Some(1), "{}", explicit.stderr);
    assert!(
        explicit.stdout.contains("[not-a-file]"),
        "{}",
        explicit.stdout
    );
    assert_eq!(bank.problems.len(), 1);
    assert_eq!(bank.failures.len(), 1);
    assert_eq!(bank.failures[0].code, "not-a-file");
}

#[cfg(unix)]
#[test]
fn dev_zero_linked_as_a_toml_is_a_finding_within_bounded_memory() {
    let dir = temp_dir("zero");
    std::os::unix::fs::symlink("/dev/zero", dir.join("x.toml")).unwrap();
    std::fs::write(dir.join("atwood.toml"), problem_text("atwood")).unwrap();
    let d = dir.to_str().unwrap();
    // 400 MB of address space: reading /dev/zero to the end would exhaust it.
    let list = run(
        &["--problems", d, "problems", "list"],
        SECONDS_30,
        Some(400_000),
    );
    assert_eq!(list.code, Some(0), "{}", list.stderr);
    assert!(
        list.stdout.contains("x.toml:1: this is a device"),
        "{}",
        list.stdout
    );
    // In this process only once the binary has shown that it does not read the device.
    let bank = lagrange::bank::load_dir(&dir).expect("the folder reads");
    assert_eq!(bank.failures.len(), 1);
    assert_eq!(bank.failures[0].code, "not-a-file");
}

#[cfg(unix)]
#[test]
fn a_large_file_is_refused_by_its_size_before_it_is_read() {
    let dir = temp_dir("large");
    // 1.5 GB, sparse: no disk is used, but reading it whole would take 1.5 GB of memory.
    let big = std::fs::File::create(dir.join("big.toml")).unwrap();
    big.set_len(1_500_000_000).unwrap();
    drop(big);
    let d = dir.to_str().unwrap();
    let list = run(
        &["--problems", d, "problems", "list"],
        SECONDS_30,
        Some(400_000),
    );
    let explicit = run(
        &["problems", "verify", dir.join("big.toml").to_str().unwrap()],
        SECONDS_30,
        Some(400_000),
    );
    assert_eq!(list.code, Some(0), "{}", list.stderr);
    assert!(
        list.stdout.contains(&format!(
            "the file is 1500000000 bytes; at most {} are read",
            lagrange::bank::load::MAX_FILE_BYTES
        )),
        "{}",
        list.stdout
    );
    assert!(list.stdout.contains("[too-large]"), "{}", list.stdout);
    assert_eq!(explicit.code, Some(1), "{}", explicit.stderr);
    assert!(
        explicit.stdout.contains("[too-large]"),
        "{}",
        explicit.stdout
    );
}

/// `1/2 x'^2 + (x'+2)^(x'+2)^…`, `levels` powers high.
fn power_tower(levels: usize) -> String {
    format!("1/2 x'^2 + {}", vec!["(x'+2)"; levels].join("^"))
}

#[test]
fn derive_of_a_power_tower_is_refused_naming_the_limit() {
    // 79 s, 1.15 GB and 574 MB of output before.
    let l = power_tower(50);
    let r = run(
        &["derive", "--lagrangian", &l, "--coords", "x"],
        SECONDS_30,
        Some(400_000),
    );
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    assert!(r.stdout.is_empty());
    assert!(
        r.stderr
            .contains("error[too-large]: the derivation grows past 25000 nodes"),
        "{}",
        r.stderr
    );
    assert!(r.stderr.contains("help: write the expression more simply"));
}

#[test]
fn derive_of_a_product_of_sixty_cosines_is_refused_naming_the_limit() {
    // The momentum of L is a product of 60 cosines of x'; its time derivative has 3,600
    // terms of 60 factors each (2 s and 4.6 MB of output in a release build before).
    let cosines: Vec<String> = (1..=60).map(|k| format!("cos({k}x')")).collect();
    let l = format!("1/2 x'^2 + {}", cosines.join("*"));
    let r = run(
        &["derive", "--lagrangian", &l, "--coords", "x"],
        SECONDS_30,
        Some(400_000),
    );
    assert_eq!(r.code, Some(2), "{}", r.stderr);
    assert!(r.stderr.contains("[too-large]"), "{}", r.stderr);
}

#[test]
fn the_derivative_of_a_product_of_1900_factors_is_refused_at_once() {
    // Under the input limit; the product rule would build 1,900 products of 1,900 factors
    // (over 100 s and 900 MB before).
    let cosines: Vec<String> = (1..=1900).map(|k| format!("cos({k}x)")).collect();
    let product = cosines.join("*");
    assert!(product.len() < 20_000);
    let mut pool = lagrange::expr::Pool::new();
    let ctx = lagrange::expr::Context::new().with_coordinates(["x"]);
    let e = lagrange::expr::read_expr(&product, &ctx, &mut pool).unwrap();
    let x = pool.symbol("x");
    let start = Instant::now();
    let d = pool.try_diff(e, x, 0);
    assert_eq!(
        d,
        Err(lagrange::expr::pool::TooLarge {
            limit: lagrange::expr::pool::MAX_TREE_SIZE
        })
    );
    assert!(start.elapsed() < Duration::from_secs(5));
}

#[test]
fn a_20kb_answer_of_1700_terms_checks_quickly() {
    // 7 s in a release build before (the one-term searches were quadratic).
    let mut answer = String::from("1/2 m l^2 theta'^2");
    for k in 2.. {
        let term = format!("+sin({k}θ)");
        if answer.len() + term.len() > 19_990 {
            break;
        }
        answer.push_str(&term);
    }
    let r = run(
        &["check", "simple-pendulum", "kinetic", &answer],
        Duration::from_secs(10),
        None,
    );
    assert_eq!(r.code, Some(1), "{}", r.stderr);
    assert!(r.stdout.contains("incorrect"), "{}", r.stdout);
    assert!(r.stdout.contains("[dimension]"), "{}", r.stdout);
}

#[test]
fn check_in_a_folder_of_many_problems_builds_only_the_one_asked_for() {
    // A bank of 30,000 files took 8 s and 434 MB per `check` (release build) before, as
    // long as listing the bank: here 2,000 files, and `check` must cost a small fraction of
    // `problems list` (a ratio, so that a loaded machine slows both alike).
    let dir = temp_dir("many");
    let atwood = problem_text("atwood");
    for i in 0..2000 {
        let text = atwood.replacen("id = \"atwood\"", &format!("id = \"p{i:05}\""), 1);
        std::fs::write(dir.join(format!("p{i:05}.toml")), text).unwrap();
    }
    // A problem whose file is not named after it is still found.
    std::fs::write(dir.join("zz-other-name.toml"), atwood).unwrap();
    let d = dir.to_str().unwrap();
    let eom = "x'' = (m1 - m2)/(m1 + m2)*g";
    let timed = |args: &[&str]| {
        let start = Instant::now();
        let r = run(args, Duration::from_secs(120), None);
        (r, start.elapsed())
    };
    let (list, list_time) = timed(&["--problems", d, "problems", "list"]);
    let (named, named_time) = timed(&["--problems", d, "check", "p01234", "eom", eom]);
    let (other, _) = timed(&["--problems", d, "check", "atwood", "eom", eom]);
    let (missing, _) = timed(&["--problems", d, "check", "nope", "eom", eom]);
    let (derived, derived_time) = timed(&["--problems", d, "derive", "p00007"]);
    assert_eq!(list.code, Some(0), "{}", list.stderr);
    assert_eq!(named.code, Some(0), "{}", named.stderr);
    assert!(named.stdout.contains("correct"));
    assert!(
        named_time * 5 < list_time && derived_time * 5 < list_time,
        "check {named_time:?}, derive {derived_time:?}, list {list_time:?}"
    );
    assert_eq!(other.code, Some(0), "{}", other.stderr);
    assert_eq!(missing.code, Some(2));
    assert!(
        missing.stderr.contains("no problem `nope`"),
        "{}",
        missing.stderr
    );
    assert_eq!(derived.code, Some(0), "{}", derived.stderr);
    assert!(
        derived.stdout.contains("Coordinate x"),
        "{}",
        derived.stdout
    );
}

#[test]
fn read_of_a_nested_fraction_prints_in_linear_time() {
    // Found beyond the list: the LaTeX printer printed the denominator of a lone
    // fraction twice, doubling the work at each level (4.7 s at 20 levels, release build).
    let l = format!("1/2 x'^2 + {}x'{}", "1/(1+".repeat(90), ")".repeat(90));
    let r = run(&["read", &l, "--coords", "x"], SECONDS_30, None);
    assert_eq!(r.code, Some(0), "{}", r.stderr);
    let latex = r.stdout.lines().find(|l| l.starts_with("latex:")).unwrap();
    // ½ and the 90 levels, each closed by its `+ 1`.
    assert_eq!(latex.matches("\\frac{1}{").count(), 91, "{latex}");
    assert_eq!(latex.matches(" + 1}").count(), 90, "{latex}");
}

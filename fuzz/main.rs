//! The fuzzer: long seeded runs of the harness's targets on the stable toolchain.
//!
//! ```sh
//! cargo run --release --example fuzz -- TARGET|all --runs N [--seed S] [--start K]
//!     [--max-mb M] [--hang-secs H] [--keep K] [--verbose]
//! cargo run --release --example fuzz -- TARGET --replay FILE…
//! ```
//!
//! The `grade` target runs the `lagrange` binary beside the fuzzer (`target/release/lagrange`):
//! `cargo build --release` before it, so that it grades with the code under test.
//!
//! The process you start is a supervisor: it runs the inputs in a child process (itself, with
//! `--worker`) under an address-space limit (`ulimit -v`, default 1024 MB), reads the index of
//! each input before it runs, and when the child dies (out of memory, stack overflow) or hangs
//! past `--hang-secs` (default 3 s, which the child's watchdog enforces), records that input
//! and restarts the child after it. Every input is a pure function of (seed, target, index),
//! so a failure is regenerated from its index and saved under
//! `tests/fuzz-corpus/<target>/pending/<hash>` (the first `--keep` of each class, default 3),
//! and printed.

mod harness;

use std::collections::BTreeMap;
use std::io::{BufRead, BufReader, Write};
use std::process::{Command, ExitCode, Stdio};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

use harness::{Target, run_one, save_pending, show, time_limit};

/// The command line.
#[derive(Clone, Debug)]
struct Opts {
    targets: Vec<Target>,
    runs: u64,
    seed: u64,
    start: u64,
    max_mb: u64,
    hang_secs: u64,
    keep: usize,
    worker: bool,
    /// Print every failure's class and message (`--verbose`), not only the kept ones.
    verbose: bool,
    /// Files to run once each (`--replay FILE…`), instead of generated inputs.
    replay: Vec<std::path::PathBuf>,
}

fn parse_opts() -> Result<Opts, String> {
    let mut o = Opts {
        targets: Vec::new(),
        runs: 10_000,
        seed: 1,
        start: 0,
        max_mb: 1024,
        hang_secs: 3,
        keep: 3,
        worker: false,
        verbose: false,
        replay: Vec::new(),
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut num = |name: &str| -> Result<u64, String> {
            let v = args.next().ok_or(format!("{name} needs a value"))?;
            v.replace('_', "")
                .parse()
                .map_err(|_| format!("{name} takes a whole number, not `{v}`"))
        };
        match a.as_str() {
            "--runs" => o.runs = num("--runs")?,
            "--seed" => o.seed = num("--seed")?,
            "--start" => o.start = num("--start")?,
            "--max-mb" => o.max_mb = num("--max-mb")?,
            "--hang-secs" => o.hang_secs = num("--hang-secs")?,
            "--keep" => o.keep = num("--keep")? as usize,
            "--worker" => o.worker = true,
            "--verbose" => o.verbose = true,
            "--replay" => o.replay.extend(args.by_ref().map(Into::into)),
            "all" => o.targets.extend(Target::ALL),
            name => o.targets.push(Target::named(name).ok_or(format!(
                "no target `{name}` (parse, check, toml, cli-args, grade or all)"
            ))?),
        }
    }
    if o.targets.is_empty() {
        return Err("name a target: parse, check, toml, cli-args, grade or all".into());
    }
    Ok(o)
}

fn main() -> ExitCode {
    let o = match parse_opts() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    if !o.replay.is_empty() {
        return replay(o.targets[0], &o.replay);
    }
    if o.worker {
        worker(&o, o.targets[0]);
        return ExitCode::SUCCESS;
    }
    let mut failing = 0;
    for &t in &o.targets {
        failing += supervise(&o, t);
    }
    ExitCode::from(u8::from(failing > 0))
}

/// Runs each file once through the target, printing `ok` or the failure.
fn replay(target: Target, files: &[std::path::PathBuf]) -> ExitCode {
    let mut failing = 0;
    for f in files {
        let Ok(input) = std::fs::read(f) else {
            println!("{}: cannot read", f.display());
            failing += 1;
            continue;
        };
        match run_one(target, &input, time_limit()) {
            None => println!("{}: ok", f.display()),
            Some(e) => {
                failing += 1;
                println!("{}: {e}", f.display());
            }
        }
    }
    ExitCode::from(u8::from(failing > 0))
}

/// The worker: runs inputs start..runs of one target, announcing each index before it runs
/// (`at I`), each failure (`fail I CLASS<TAB>MESSAGE`) and the end (`done`). A watchdog
/// thread ends the process when one input runs past the hang limit.
fn worker(o: &Opts, target: Target) {
    let started = Instant::now();
    let current = Arc::new(AtomicU64::new(o.start));
    let since = Arc::new(AtomicU64::new(0));
    {
        let (current, since, hang) = (current.clone(), since.clone(), o.hang_secs * 1000);
        std::thread::spawn(move || {
            loop {
                std::thread::sleep(Duration::from_millis(100));
                let now = started.elapsed().as_millis() as u64;
                let began = since.load(Ordering::SeqCst);
                if began > 0 && now.saturating_sub(began) > hang {
                    println!("hang {} {}", current.load(Ordering::SeqCst), now - began);
                    std::process::exit(3);
                }
            }
        });
    }
    // One line per write, never holding the lock: the watchdog prints too.
    let out = || std::io::stdout();
    let (mut max, mut max_at) = (Duration::ZERO, o.start);
    for i in o.start..o.runs {
        let input = target.generate(o.seed, i);
        let _ = writeln!(out(), "at {i}");
        current.store(i, Ordering::SeqCst);
        since.store(started.elapsed().as_millis() as u64 + 1, Ordering::SeqCst);
        let t0 = Instant::now();
        let failure = run_one(target, &input, time_limit());
        let took = t0.elapsed();
        since.store(0, Ordering::SeqCst);
        if took > max {
            (max, max_at) = (took, i);
        }
        if let Some(f) = failure {
            let message = f.to_string().replace('\n', "⏎");
            let _ = writeln!(out(), "fail {i} {}\t{message}", f.class());
        }
    }
    let _ = writeln!(out(), "done {} {:.6} {max_at}", o.runs, max.as_secs_f64());
}

/// What a supervisor saw of one target.
#[derive(Default)]
struct Tally {
    classes: BTreeMap<String, usize>,
    max: f64,
    max_at: u64,
}

/// Runs one target in child processes until every input ran; prints the failures and a
/// summary line. Returns the number of failing inputs.
fn supervise(o: &Opts, target: Target) -> usize {
    let started = Instant::now();
    let mut tally = Tally::default();
    let mut next = o.start;
    while next < o.runs {
        let (last, end) = run_child(o, target, next, &mut tally);
        let Some(i) = last else {
            eprintln!("error: the worker did not start");
            return 1;
        };
        // A child that hung or died on input `i` goes on after it.
        match end {
            End::Done => break,
            End::Hung => {}
            End::Died => {
                let why = "the worker died (memory limit, stack overflow or abort)";
                report(o, target, i, "crash", why, &mut tally);
            }
        }
        next = i + 1;
    }
    let secs = started.elapsed().as_secs_f64();
    let runs = o.runs - o.start;
    let failing: usize = tally.classes.values().sum();
    println!(
        "{}: {runs} inputs in {secs:.1} s ({:.0}/s), slowest {:.3} s (input {}), {failing} failing {:?}",
        target.name(),
        runs as f64 / secs,
        tally.max,
        tally.max_at,
        tally.classes
    );
    failing
}

/// How a child ended.
enum End {
    /// Every input ran.
    Done,
    /// Its watchdog ended it on a hanging input.
    Hung,
    /// It died (a signal or an abort).
    Died,
}

/// One child from input `from`: returns the last index it announced and how it ended.
fn run_child(o: &Opts, target: Target, from: u64, tally: &mut Tally) -> (Option<u64>, End) {
    let exe = std::env::current_exe().expect("the fuzzer knows its own path");
    let script = format!("ulimit -v {}; exec \"$0\" \"$@\"", o.max_mb * 1024);
    let child = Command::new("sh")
        .arg("-c")
        .arg(script)
        .arg(exe)
        .args([target.name(), "--worker"])
        .args(["--runs", &o.runs.to_string(), "--seed", &o.seed.to_string()])
        .args([
            "--start",
            &from.to_string(),
            "--hang-secs",
            &o.hang_secs.to_string(),
        ])
        .stdout(Stdio::piped())
        .spawn();
    let Ok(mut child) = child else {
        return (None, End::Died);
    };
    let stdout = child.stdout.take().expect("stdout is piped");
    let (mut last, mut end) = (None, End::Died);
    for line in BufReader::new(stdout).lines().map_while(Result::ok) {
        let mut words = line.splitn(3, ' ');
        let (kind, index) = (words.next(), words.next().and_then(|w| w.parse().ok()));
        match (kind, index) {
            (Some("at"), Some(i)) => last = Some(i),
            (Some("fail"), Some(i)) => {
                let rest = words.next().unwrap_or_default();
                let (class, message) = rest.split_once('\t').unwrap_or((rest, ""));
                report(o, target, i, class, message, tally);
            }
            (Some("hang"), Some(i)) => {
                report(o, target, i, "hang", "over the hang limit", tally);
                end = End::Hung;
            }
            (Some("done"), _) => {
                let mut w = line.split(' ').skip(2);
                tally.max = tally
                    .max
                    .max(w.next().and_then(|x| x.parse().ok()).unwrap_or(0.0));
                tally.max_at = w.next().and_then(|x| x.parse().ok()).unwrap_or(0);
                end = End::Done;
            }
            _ => {}
        }
    }
    let _ = child.wait();
    (last, end)
}

/// Counts a failure; the first `--keep` of its class are saved and printed in full.
fn report(o: &Opts, target: Target, i: u64, class: &str, message: &str, tally: &mut Tally) {
    let n = tally.classes.entry(class.to_string()).or_default();
    *n += 1;
    if *n > o.keep {
        if o.verbose {
            println!("fail {} #{i} [{class}] {message}", target.name());
        }
        return;
    }
    let input = target.generate(o.seed, i);
    let saved = save_pending(target, &input)
        .map(|p| p.display().to_string())
        .unwrap_or_else(|e| format!("(not saved: {e})"));
    println!(
        "FAIL {} #{i} [{class}] {message}\n  input: {}\n  saved: {saved}",
        target.name(),
        show(&input)
    );
    let _ = std::io::stdout().flush();
}

//! The fuzz harness, shared by the `fuzz` example (long seeded runs) and the integration test
//! `fuzz_replay` (the corpus replayed as ordinary tests): five targets, each a generator and
//! an oracle, and one runner that catches panics and times every input.
//!
//! An input is bytes: raw text for `parse` and `toml`, a JSON case for `check` and
//! `cli-args` (which need more than one string), a settings line and a class file for
//! `grade` (which runs the `lagrange` binary). The oracle of every target is: no panic, no
//! input over the time limit, and the target's own soundness checks (no false accept of a
//! constructed wrong answer, printing reads back to the same node, …).

// Each of the two crates that include this module uses only part of it.
#![allow(dead_code)]

pub mod check;
pub mod cli_args;
pub mod grade;
pub mod inputs;
pub mod parse;
pub mod text;
pub mod toml;

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// A fuzz target.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Target {
    /// The reader, printers and round trip.
    Parse,
    /// The answer checker on every part of the embedded bank.
    Check,
    /// Problem files: loading and verification.
    Toml,
    /// The values of the command-line arguments, through the library calls the CLI makes.
    CliArgs,
    /// Class files through `lagrange grade` in a temporary folder.
    Grade,
}

impl Target {
    /// Every target.
    pub const ALL: [Target; 5] = [
        Target::Parse,
        Target::Check,
        Target::Toml,
        Target::CliArgs,
        Target::Grade,
    ];

    /// The name on the command line and of the corpus folder.
    pub fn name(self) -> &'static str {
        match self {
            Target::Parse => "parse",
            Target::Check => "check",
            Target::Toml => "toml",
            Target::CliArgs => "cli-args",
            Target::Grade => "grade",
        }
    }

    /// The target named `s`.
    pub fn named(s: &str) -> Option<Target> {
        Target::ALL.into_iter().find(|t| t.name() == s)
    }

    /// Input `index` of the run seeded `seed`.
    pub fn generate(self, seed: u64, index: u64) -> Vec<u8> {
        let mut r = inputs::rng_for(seed, self.name(), index);
        match self {
            Target::Parse => parse::generate(&mut r),
            Target::Check => check::generate(&mut r),
            Target::Toml => toml::generate(&mut r),
            Target::CliArgs => cli_args::generate(&mut r),
            Target::Grade => grade::generate(&mut r),
        }
    }

    /// Runs one input through the target's oracle: `Err` is a finding (other than a panic or
    /// a slow input, which [`run_one`] detects).
    pub fn execute(self, input: &[u8]) -> Result<(), String> {
        match self {
            Target::Parse => parse::execute(input),
            Target::Check => check::execute(input),
            Target::Toml => toml::execute(input),
            Target::CliArgs => cli_args::execute(input),
            Target::Grade => grade::execute(input),
        }
    }
}

/// What went wrong with one input.
#[derive(Clone, Debug, PartialEq)]
pub enum Failure {
    /// The code panicked, with this message.
    Panic(String),
    /// The input took this long (over the limit).
    Slow(Duration),
    /// The oracle's finding (a false accept, a round trip that changes the node, …).
    Oracle(String),
}

impl Failure {
    /// The class of the failure, for counting.
    pub fn class(&self) -> String {
        match self {
            Failure::Panic(m) => format!("panic[{}]", m.chars().take(60).collect::<String>()),
            Failure::Slow(_) => "slow".into(),
            Failure::Oracle(m) => m.split(": ").next().unwrap_or("oracle").to_string(),
        }
    }
}

impl std::fmt::Display for Failure {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Failure::Panic(m) => write!(f, "panic: {m}"),
            Failure::Slow(d) => write!(f, "slow: took {:.3} s", d.as_secs_f64()),
            Failure::Oracle(m) => f.write_str(m),
        }
    }
}

/// The time one input may take: 1 s optimized; unoptimized code (the replay under `cargo
/// test`) runs about ten times slower, so it gets ten times longer.
pub fn time_limit() -> Duration {
    if cfg!(debug_assertions) {
        Duration::from_secs(10)
    } else {
        Duration::from_secs(1)
    }
}

thread_local! {
    /// Where the last panic on this thread happened (the hook records it).
    static PANICKED_AT: std::cell::RefCell<String> = const { std::cell::RefCell::new(String::new()) };
}

/// Installs, once, a panic hook that records where a panic happened instead of printing it
/// (a run may panic thousands of times; the failure report shows the place).
fn quiet_panics() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        std::panic::set_hook(Box::new(|info| {
            let at = info
                .location()
                .map(|l| format!("{}:{}", l.file(), l.line()))
                .unwrap_or_default();
            PANICKED_AT.with(|p| *p.borrow_mut() = at);
        }));
    });
}

/// Runs one input: catches a panic, times it, and applies the oracle. A `grade` input runs a
/// process on a whole class file, so it gets ten times the limit.
pub fn run_one(target: Target, input: &[u8], limit: Duration) -> Option<Failure> {
    quiet_panics();
    let limit = if target == Target::Grade {
        limit * 10
    } else {
        limit
    };
    let start = Instant::now();
    let outcome = catch_unwind(AssertUnwindSafe(|| target.execute(input)));
    let took = start.elapsed();
    match outcome {
        Err(payload) => {
            let at = PANICKED_AT.with(|p| p.borrow().clone());
            Some(Failure::Panic(format!(
                "{} at {at}",
                panic_message(payload.as_ref())
            )))
        }
        Ok(Err(m)) => Some(Failure::Oracle(m)),
        Ok(Ok(())) if took > limit => Some(Failure::Slow(took)),
        Ok(Ok(())) => None,
    }
}

/// The message of a panic payload.
fn panic_message(p: &(dyn std::any::Any + Send)) -> String {
    if let Some(s) = p.downcast_ref::<&str>() {
        (*s).to_string()
    } else if let Some(s) = p.downcast_ref::<String>() {
        s.clone()
    } else {
        "(non-string panic payload)".into()
    }
}

/// A finding if `text` (a message shown to a person) holds a raw control character, bidi
/// override or zero-width character: those must be shown escaped or named (issue 9, §5).
pub fn no_raw_controls(text: &str, what: &str) -> Result<(), String> {
    let bad = |c: char| {
        (c.is_control() && c != '\n' && c != '\t')
            || ('\u{200b}'..='\u{200f}').contains(&c)
            || ('\u{202a}'..='\u{202e}').contains(&c)
            || ('\u{2066}'..='\u{2069}').contains(&c)
    };
    match text.chars().find(|c| bad(*c)) {
        Some(c) => Err(format!(
            "raw-control: the {what} shows {} raw",
            c.escape_unicode()
        )),
        None => Ok(()),
    }
}

/// The corpus folder of a target.
pub fn corpus_dir(target: Target) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fuzz-corpus")
        .join(target.name())
}

/// A short stable name for an input.
pub fn short_hash(input: &[u8]) -> String {
    format!("{:012x}", inputs::fnv1a(input) >> 16)
}

/// Saves a failing input under `tests/fuzz-corpus/<target>/pending/` (not replayed until a
/// fix lands and the file is moved up a level), returning its path.
pub fn save_pending(target: Target, input: &[u8]) -> std::io::Result<PathBuf> {
    let dir = corpus_dir(target).join("pending");
    std::fs::create_dir_all(&dir)?;
    let path = dir.join(short_hash(input));
    std::fs::write(&path, input)?;
    Ok(path)
}

/// An input for a person: text as is when it is short UTF-8 without control characters
/// other than newlines, else escaped and cut.
pub fn show(input: &[u8]) -> String {
    let text = String::from_utf8_lossy(input);
    let mut s: String = text
        .chars()
        .take(600)
        .flat_map(char::escape_debug)
        .collect();
    if text.chars().count() > 600 {
        s.push_str(&format!("… ({} bytes)", input.len()));
    }
    s
}

//! The fuzz corpus replayed as ordinary tests: every file under
//! `tests/fuzz-corpus/<target>/` (not `pending/`, which holds inputs that fail until a fix
//! lands) runs through the same target function and oracles as the fuzzer
//! (`cargo run --release --example fuzz`), so a bug it found stays a regression test.
//!
//! `LAGRANGE_FUZZ_RUNS=N` also runs N fresh generated inputs per target (seed
//! `LAGRANGE_FUZZ_SEED`, default 1); it is 0 unless set, so CI replays the corpus only.

#[path = "../../fuzz/harness/mod.rs"]
mod harness;

use harness::{Target, run_one, show, time_limit};

/// Replays one target's corpus, and then N generated inputs if asked; fails listing every
/// failing input.
fn replay(target: Target) {
    let mut failures = Vec::new();
    let dir = harness::corpus_dir(target);
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .map(|d| d.filter_map(|e| Some(e.ok()?.path())).collect())
        .unwrap_or_default();
    files.retain(|p| p.is_file());
    files.sort();
    assert!(!files.is_empty(), "no corpus in {}", dir.display());
    for path in &files {
        let input = std::fs::read(path).expect("a corpus file reads");
        if let Some(f) = run_one(target, &input, time_limit()) {
            failures.push(format!("{}: {f}", path.display()));
        }
    }
    let runs: u64 = std::env::var("LAGRANGE_FUZZ_RUNS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0);
    let seed: u64 = std::env::var("LAGRANGE_FUZZ_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1);
    for i in 0..runs {
        let input = target.generate(seed, i);
        if let Some(f) = run_one(target, &input, time_limit()) {
            let saved = harness::save_pending(target, &input)
                .map(|p| p.display().to_string())
                .unwrap_or_default();
            failures.push(format!(
                "generated #{i} ({saved}): {f}\n    {}",
                show(&input)
            ));
        }
    }
    assert!(
        failures.is_empty(),
        "{} failing input(s) of `{}`:\n{}",
        failures.len(),
        target.name(),
        failures.join("\n")
    );
}

#[test]
fn parse_corpus_replays_clean() {
    replay(Target::Parse);
}

#[test]
fn check_corpus_replays_clean() {
    replay(Target::Check);
}

#[test]
fn toml_corpus_replays_clean() {
    replay(Target::Toml);
}

#[test]
fn cli_args_corpus_replays_clean() {
    replay(Target::CliArgs);
}

#[test]
fn grade_corpus_replays_clean() {
    replay(Target::Grade);
}

#[test]
fn generation_is_deterministic() {
    for t in Target::ALL {
        for i in 0..20 {
            assert_eq!(t.generate(7, i), t.generate(7, i), "{} #{i}", t.name());
        }
    }
}

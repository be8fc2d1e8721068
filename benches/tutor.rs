//! Benchmarks of the tutor session (issue 10, item 8): a scripted session of 100 answers over
//! the bank (each problem opened, then right and wrong answers to its parts, so follow-through
//! and diagnoses run too), measured per response; and opening a session.
//!
//! Opening the REPL as a process is timed from the shell (see the closing note).

use divan::{Bencher, black_box};
use lagrange::embedded;
use lagrange::tutor::{Progress, Session};

fn main() {
    divan::main();
}

/// 100 answer lines over the bank: for each part, a wrong answer (the part's first `wrong`
/// example, or a slip) and then its reference; `:open` lines in between.
fn script() -> Vec<String> {
    let bank = embedded::bank();
    let mut lines = Vec::new();
    let mut answers = 0;
    'all: for p in &bank.problems {
        lines.push(format!(":open {}", p.id));
        for part in &p.parts {
            let wrong = part
                .wrong
                .first()
                .cloned()
                .unwrap_or_else(|| "0".to_string());
            for a in [wrong, part.reference_text(p.system.n())] {
                lines.push(a);
                answers += 1;
                if answers == 100 {
                    break 'all;
                }
            }
        }
    }
    lines
}

#[divan::bench(sample_count = 10)]
fn scripted_session_of_100_answers(b: Bencher) {
    let lines = script();
    b.with_inputs(|| Session::new(embedded::bank(), Progress::new()))
        .bench_local_values(|mut s| {
            for l in &lines {
                black_box(s.handle(black_box(l)));
            }
        });
}

#[divan::bench]
fn open_a_session(b: Bencher) {
    b.bench_local(|| black_box(Session::new(embedded::bank(), Progress::new())));
}

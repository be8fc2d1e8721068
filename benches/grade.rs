//! Benchmark of what `lagrange grade` does per distinct answer (issue 20 §5): a class where
//! every answer differs cannot share verdicts, so each one is read for its canonical form,
//! checked (a wrong one fully diagnosed) and fingerprinted for the summary — the library work
//! of `grade`'s "distinct" path, as `scripts/bench-grade` feeds it, without the CSV around it.
//!
//! One checker per problem serves a run of answers, as in `grade` (a checker prepares each
//! part once). The per-answer cost of each kind of answer is reported separately, and a mixed
//! run of all five kinds gives the throughput per CPU-second of one core.

use divan::{Bencher, black_box};
use lagrange::bank::embedded;
use lagrange::check::{Checker, Status};

fn main() {
    divan::main();
}

/// The five kinds of answer `scripts/bench-grade-gen.py distinct` writes, each with a varying
/// coefficient `{c}` (every answer wrong but near the right one: fully diagnosed).
const TEMPLATES: [(&str, &str, &str); 5] = [
    ("simple-pendulum", "potential", "-{c}*m*g*l*cos(theta)"),
    (
        "simple-pendulum",
        "eom",
        "m*l^2*theta'' + {c}*m*g*l*sin(theta) = 0",
    ),
    ("simple-pendulum", "frequencies", "sqrt({c}*g/l)"),
    ("spring-incline", "eom", "m*x'' = -{c}*k*x + m*g*sin(alpha)"),
    ("atwood", "eom", "(m1+m2)*x'' = {c}*(m1-m2)*g"),
];

/// The `i`th answer of a template, as the generator writes it.
fn answer(template: &str, i: usize) -> String {
    template.replace("{c}", &format!("{:.6}", 1.0 + (i + 1) as f64 / 1e6))
}

/// What `grade` does for one distinct answer: its canonical form, its verdict and, wrong,
/// its fingerprint.
fn grade_one(checker: &mut Checker, part: &str, text: &str) -> usize {
    let form = checker.canonical(part, text).expect("part exists");
    let verdict = checker.check(part, text).expect("part exists");
    let print = (verdict.status != Status::Correct)
        .then(|| checker.fingerprint(part, text).expect("part exists"))
        .flatten();
    form.map_or(0, |f| f.len()) + verdict.diagnoses.len() + print.map_or(0, |p| p.len())
}

/// One distinct answer of each kind, graded by a checker that has read 100 before it.
#[divan::bench(args = [0, 1, 2, 3, 4])]
fn distinct_answer(b: Bencher, kind: usize) {
    let bank = embedded::bank();
    let (problem, part, template) = TEMPLATES[kind];
    let problem = bank.problem(problem).expect("in the bank");
    let mut checker = Checker::new(problem);
    for i in 0..100 {
        grade_one(&mut checker, part, &answer(template, i));
    }
    let mut i = 100;
    b.bench_local(|| {
        i += 1;
        black_box(grade_one(&mut checker, part, &answer(template, i)))
    });
}

/// 1,000 distinct answers, 200 of each kind, with fresh checkers (preparation included, as a
/// chunk of `grade`'s work): divide by 1,000 for the time per answer on one core.
#[divan::bench(sample_count = 5)]
fn thousand_distinct_answers(b: Bencher) {
    let bank = embedded::bank();
    let answers: Vec<(usize, String)> = (0..1000)
        .map(|i| (i % 5, answer(TEMPLATES[i % 5].2, i)))
        .collect();
    b.bench_local(|| {
        let mut checkers: Vec<Checker> = TEMPLATES
            .iter()
            .map(|(p, _, _)| Checker::new(bank.problem(p).expect("in the bank")))
            .collect();
        let mut n = 0;
        for (k, text) in &answers {
            n += grade_one(&mut checkers[*k], TEMPLATES[*k].1, text);
        }
        black_box(n)
    });
}

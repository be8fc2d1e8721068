//! Benchmarks of the answer checker (issue: answer checker):
//! - median in-process check of the simple-pendulum `eom` and of the double-pendulum `eom`
//!   system, with the part prepared once (as a grader or a tutoring session does);
//! - the same including preparation (derivation and sampling), i.e. a first check;
//! - a wrong answer, which also runs the diagnosis searches;
//! - hostile answers: a vanishing factor (the determinant test), a 20 KB answer.
//!
//! `lagrange check` as a whole process is timed from the shell (see the closing note).

use divan::{Bencher, black_box};
use lagrange::bank::embedded;
use lagrange::check::{Checker, check};

fn main() {
    divan::main();
}

const DP_EOM: &str = "(m1+m2)*l1*theta1'' + m2*l2*theta2''*cos(theta1-theta2) + m2*l2*theta2'^2*sin(theta1-theta2) + (m1+m2)*g*sin(theta1) = 0; l2*theta2'' + l1*theta1''*cos(theta1-theta2) - l1*theta1'^2*sin(theta1-theta2) + g*sin(theta2) = 0";

#[divan::bench(args = ["correct", "wrong"])]
fn simple_pendulum_eom(b: Bencher, which: &str) {
    let bank = embedded::bank();
    let problem = bank.problem("simple-pendulum").expect("in the bank");
    let mut checker = Checker::new(problem);
    let answer = if which == "correct" {
        "theta'' = -g/l sin(theta)"
    } else {
        "m*l^2*theta'' - m*g*l*sin(theta) = 0"
    };
    checker.check("eom", answer).expect("checks");
    b.bench_local(|| black_box(checker.check("eom", black_box(answer)).expect("checks")));
}

#[divan::bench(args = ["correct", "wrong"])]
fn double_pendulum_eom(b: Bencher, which: &str) {
    let bank = embedded::bank();
    let problem = bank.problem("double-pendulum").expect("in the bank");
    let mut checker = Checker::new(problem);
    let answer = if which == "correct" {
        DP_EOM.to_string()
    } else {
        DP_EOM.replacen("+ m2*l2*theta2'^2", "- m2*l2*theta2'^2", 1)
    };
    checker.check("eom", &answer).expect("checks");
    b.bench_local(|| black_box(checker.check("eom", black_box(&answer)).expect("checks")));
}

#[divan::bench(args = ["simple-pendulum", "double-pendulum"])]
fn first_check_including_preparation(b: Bencher, id: &str) {
    let bank = embedded::bank();
    let problem = bank.problem(id).expect("in the bank");
    let part = problem.part("eom").expect("has eom");
    let answer = if id == "simple-pendulum" {
        "theta'' = -g/l sin(theta)".to_string()
    } else {
        DP_EOM.to_string()
    };
    b.bench_local(|| black_box(check(problem, part, black_box(&answer)).expect("checks")));
}

/// Soundness (issue 9): the determinant test on a vanishing factor (the energy law, named as
/// such), and a hostile 20 KB answer of ~1,700 terms (the bounded diagnosis search).
#[divan::bench(args = ["energy-law", "sin-factor", "answer-20kb"])]
fn hostile_answers(b: Bencher, which: &str) {
    let bank = embedded::bank();
    let problem = bank.problem("simple-pendulum").expect("in the bank");
    let mut checker = Checker::new(problem);
    let (part, answer) = match which {
        "energy-law" => ("eom", "theta'*(theta'' + g/l*sin(theta)) = 0".to_string()),
        "sin-factor" => (
            "eom",
            "sin(theta)*(theta'' + g/l*sin(theta)) = 0".to_string(),
        ),
        _ => {
            let mut a = "1/2*m*l^2*theta'^2".to_string();
            let mut k = 1;
            while a.len() < 19_900 {
                a.push_str(&format!(" + m*l^2*theta'^2*theta^{k}/{k}"));
                k += 1;
            }
            ("kinetic", a)
        }
    };
    checker.check(part, &answer).expect("checks");
    b.bench_local(|| black_box(checker.check(part, black_box(&answer)).expect("checks")));
}

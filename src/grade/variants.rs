//! Per-student variants in grading: each student's answer to a part that accepts numbers is
//! judged against the problem pinned to that student's numbers. The pinned problems are
//! appended to the bank (one per distinct variant, after every problem of the bank, so each
//! bank problem keeps its index and the gradebook its columns), and a row's problem index
//! becomes its variant's: the grouping of identical answers is then per variant, since `1.5`
//! is right for one student and wrong for another.

use rustc_hash::FxHashMap;

use lagrange::bank::Bank;
use lagrange::problem::variant::pick;

/// Which pinned problem judges each student's numbers answers.
#[derive(Debug, Default)]
pub struct Variants {
    /// (student, bank problem) → index of the problem pinned to the student's variant.
    of: FxHashMap<(u32, usize), usize>,
}

impl Variants {
    /// The problem that judges `student`'s answer to part `q` of bank problem `p`: the
    /// pinned one when the part accepts numbers, else `p` itself.
    pub fn problem(&self, bank: &Bank, student: u32, p: usize, q: usize) -> usize {
        if !bank.problems[p].parts[q].numbers {
            return p;
        }
        self.of.get(&(student, p)).copied().unwrap_or(p)
    }
}

/// Appends to `bank` the problems pinned to the students' variants under `seed` (for each
/// problem with variants and a part that accepts numbers), and says which judges whom.
pub fn extend(bank: &mut Bank, students: &[String], seed: u64) -> Variants {
    let mut variants = Variants::default();
    let n = bank.problems.len();
    for p in 0..n {
        let problem = &bank.problems[p];
        if problem.variants.is_empty() || !problem.parts.iter().any(|x| x.numbers) {
            continue;
        }
        let mut by_key: FxHashMap<String, usize> = FxHashMap::default();
        let mut pinned = Vec::new();
        for (s, key) in students.iter().enumerate() {
            let Some(v) = pick(problem, seed, key) else {
                continue;
            };
            let index = *by_key.entry(v.key()).or_insert_with(|| {
                pinned.push(problem.pinned(&v));
                bank.problems.len() + pinned.len() - 1
            });
            variants.of.insert((s as u32, p), index);
        }
        bank.problems.extend(pinned);
    }
    variants
}

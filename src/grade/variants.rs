//! Per-student variants in grading: each student's answer to a part that accepts numbers is
//! judged against the problem pinned to that student's numbers. The pinned problems are
//! appended to the bank (one per distinct variant, after every problem of the bank, so each
//! bank problem keeps its index and the gradebook its columns), and a row's problem index
//! becomes its variant's: the grouping of identical answers is then per variant, since `1.5`
//! is right for one student and wrong for another.

use rustc_hash::FxHashMap;

use lagrange::bank::Bank;
use lagrange::problem::variant::pick;

use super::input::Table;

/// Which pinned problem judges each student's numbers answers.
#[derive(Debug, Default)]
pub struct Variants {
    /// (student, bank problem) → index of the problem pinned to the student's variant.
    of: FxHashMap<(u32, usize), usize>,
    /// A pinned problem's numbers as the sheet shows them (`l = 0.75 m, m = 0.4 kg`), by its
    /// index in the bank.
    labels: FxHashMap<usize, String>,
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

    /// The numbers bank problem `p` is pinned to (empty: not a pinned problem). An answer's
    /// text means one thing per variant: `1.5` is right for one student and wrong for another.
    pub fn label(&self, p: usize) -> &str {
        self.labels.get(&p).map_or("", String::as_str)
    }
}

/// Appends to `bank` the problems pinned to the students' variants under `seed` (for each
/// problem with variants and a part that accepts numbers that some row of `table` names),
/// and says which judges whom.
pub fn extend(bank: &mut Bank, table: &Table, seed: u64) -> Variants {
    let mut variants = Variants::default();
    let named = named(table);
    let students = &table.students;
    let n = bank.problems.len();
    for p in 0..n {
        let problem = &bank.problems[p];
        // A problem no row names needs no student's numbers (a class of 10,000 students
        // would otherwise pick them all for every such problem of the bank).
        if problem.variants.is_empty()
            || !problem.parts.iter().any(|x| x.numbers)
            || !named.contains(problem.id.as_str())
        {
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
                let index = bank.problems.len() + pinned.len() - 1;
                let label = lagrange::report::sheets::numbers_of(problem, &v).join(", ");
                variants.labels.insert(index, label);
                index
            });
            variants.of.insert((s as u32, p), index);
        }
        bank.problems.extend(pinned);
    }
    variants
}

/// The ids of the problems the class answers whose numbers differ per student (variants and a
/// part that accepts numbers), in bank order: grading them needs the course seed.
pub fn answered_with_variants(bank: &Bank, table: &Table) -> Vec<String> {
    let named = named(table);
    (bank.problems.iter())
        .filter(|p| !p.variants.is_empty() && p.parts.iter().any(|x| x.numbers))
        .filter(|p| named.contains(p.id.as_str()))
        .map(|p| format!("`{}`", p.id))
        .collect()
}

/// The problem and part ids the rows name, as typed.
fn named(table: &Table) -> rustc_hash::FxHashSet<&str> {
    (0..table.names.len())
        .map(|i| table.names.get(i as u32))
        .collect()
}

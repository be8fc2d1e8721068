//! Rows → verdicts, checking as little as possible: answers are deduplicated on their exact
//! text, then on the checker's canonical form, and one representative per canonical form
//! (the first in input order) is checked; every row sharing it reuses the verdict (a list only
//! with the same text: its canonical form drops stated stability and item order). The two
//! passes run in parallel (rayon), one `Checker` per worker and problem. Which answer
//! represents a form never depends on the thread count, so neither does any output.

use rustc_hash::FxHashMap;
use std::sync::Arc;

use rayon::prelude::*;

use lagrange::bank::Bank;
use lagrange::check::{Checker, Status as Checked};
use lagrange::expr::error::{MAX_INPUT_BYTES, visible};
use lagrange::problem::{Part, PartKind, Problem};
use lagrange::progress::{Interrupted, Progress};
use lagrange::tutor::command::did_you_mean;

use lagrange::policy::Policy;

use super::input::Table;

mod counted;
mod judged;
mod slim;
mod words;
use crate::face::bar::Shared;
use counted::{follow_through, mark_counted};
pub use judged::{Brief, Graded, Judged, Outcome, Rep, Status, no_codes};
pub use slim::{Codes, Slim, Words, meaning};

/// The instructor's decisions applied to judged rows (`--overrides`, in `overrides.rs`): a
/// trait so that judging does not import the file that reads the decisions.
pub trait Override: Sync + std::fmt::Debug {
    /// Applies the decisions to the rows they name; the rows changed.
    /// An answer's variant (`variants`) is part of what a decision is about.
    fn apply(
        &self,
        table: &Table,
        judged: &mut Judged,
        bank: &Bank,
        variants: &super::variants::Variants,
    ) -> Vec<usize>;
}

/// How to judge: the assignment's policy (credit per code, follow-through, attempts) and the
/// instructor's decisions on answers the checker could not settle.
#[derive(Clone, Copy, Debug)]
pub struct Settings<'s> {
    /// How verdicts become scores and which attempt counts (`lagrange::policy`).
    pub policy: &'s Policy,
    /// The instructor's decisions (`--overrides`), applied before follow-through and counting.
    pub overrides: Option<&'s dyn Override>,
    /// The problems pinned to each student's numbers (`variants.rs`).
    pub variants: &'s super::variants::Variants,
    /// Where a class of many different answers keeps its representatives' words until the
    /// outputs are written (a nameless temporary file; see `judge/words.rs`): the output
    /// folder, on the disk the outputs go to.
    pub scratch: &'s std::path::Path,
}

/// The most answers one checker reads (see [`par_map`]).
const CHUNK: usize = 1024;

/// The representatives checked at a time before their verdicts are moved out of the workers'
/// memory (see [`judge`]): large enough that the workers are rarely idle at a window's end.
const WINDOW: usize = 16 * 1024;

/// [`WINDOW`], or `LAGRANGE_GRADE_WINDOW` from the environment when it is a positive number
/// (for the test that outputs do not depend on it).
fn window_size() -> usize {
    (std::env::var("LAGRANGE_GRADE_WINDOW").ok())
        .and_then(|v| v.parse::<usize>().ok())
        .filter(|&n| n > 0)
        .unwrap_or(WINDOW)
}

/// An answer to check: the problem and part indices in the bank and its index in
/// [`Table::answers`] (its text is looked up there, not copied); 12 bytes (a class of
/// all-different answers has one per row).
type Item = (u32, u32, u32);

/// What grading needs to check a window of answers.
struct Window<'a, 'b, 's> {
    bank: &'b Bank,
    answers: &'a super::intern::Interner,
    policy: &'a Policy,
    bar: &'a Shared<'s>,
    codes: &'a Codes,
}

/// Checks a window of representatives in parallel, in order: each with its words.
fn check_window(w: &Window<'_, '_, '_>, window: &[Item]) -> Vec<(Rep, Words)> {
    par_map(
        w.bank,
        w.answers,
        window,
        |c, part, (problem, q, answer), text| {
            let (problem, q) = (problem as usize, q as usize);
            let verdict = if w.bar.tick() {
                c.check(&part.id, text).map_err(|e| e.to_string())
            } else {
                Err(Interrupted.to_string())
            };
            // Only wrong answers are grouped, so a right one needs no fingerprint.
            let wrong = verdict.as_ref().is_ok_and(|v| v.status != Checked::Correct);
            let fingerprint = wrong
                .then(|| c.fingerprint(&part.id, text).ok().flatten())
                .flatten()
                .map_or(0, |f| meaning(&f));
            // A problem pinned to a student's numbers counts as its bank problem (the first of
            // its id).
            let counted_as = (w.bank.problems[..problem].iter())
                .position(|x| x.id == w.bank.problems[problem].id)
                .unwrap_or(problem);
            let points = w.bank.problems[counted_as].parts[q].points;
            let (verdict, words) = match verdict {
                Ok(v) => {
                    let (slim, words, codes) = Slim::shared(v, w.codes);
                    (Ok((slim, codes)), Some(words))
                }
                Err(e) => (Err(Arc::from(e)), None),
            };
            let score = (verdict.as_ref()).map_or(0.0, |(v, codes)| {
                w.policy.answer_fraction(v.status, v.score, codes) * points
            });
            let verdict = verdict.map(|(v, _)| v);
            let rep = Rep {
                problem: problem as u32,
                part: q as u32,
                answer,
                counted_as: counted_as as u32,
                score,
                verdict,
            };
            let mut words = words.unwrap_or(Words {
                reading: String::new(),
                message: String::new(),
                fingerprint: 0,
            });
            words.fingerprint = fingerprint;
            (rep, words)
        },
    )
}

/// A problem and part id pair as typed: the bank part it names, or why it names none (the
/// message without its line).
type Resolved = Result<(usize, usize), String>;

/// Grades every row. `progress` hears the distinct answers read (out of all), then the
/// canonical forms checked (out of all); a `Break` ends the run with [`Interrupted`].
pub fn judge(
    table: &Table,
    bank: &Bank,
    settings: Settings<'_>,
    progress: &mut (dyn Progress + Send),
    phases: &mut super::phases::Phases,
) -> Result<Judged, Interrupted> {
    let rows = &table.rows;
    // Rows' own outcomes (errors, answers too long to read), numbered after the
    // representatives' once those are known.
    let mut own: Vec<Outcome> = Vec::new();
    let mut resolved: FxHashMap<(u32, u32), Resolved> = FxHashMap::default();
    // Exact text first: a class types the same few strings many times.
    let mut distinct: Vec<Item> = Vec::new();
    let mut by_text: FxHashMap<(u32, u32, u32), u32> = FxHashMap::default();
    // Per row: its own outcome (Err) or its distinct answer (Ok), then its representative.
    let mut row_distinct: Vec<Result<u32, u32>> = Vec::with_capacity(rows.len());
    for row in rows {
        let mut own = |o: Outcome| {
            own.push(o);
            Err(own.len() as u32 - 1)
        };
        let target = resolved
            .entry((row.problem, row.part))
            .or_insert_with(|| resolve(table.problem(row), table.part(row), bank));
        let slot = if let Some(e) = table.error(row) {
            own(unread(Status::Error, e.to_string(), None))
        } else {
            match target {
                Err(rest) => {
                    let message = format!("line {}: {rest}", row.line);
                    own(unread(Status::Error, message, None))
                }
                Ok((p, q)) if table.answer(row).len() > MAX_INPUT_BYTES => {
                    let (line, n) = (row.line, table.answer(row).len());
                    let message = format!(
                        "line {line}: the answer is {n} bytes, over the checker's limit of {MAX_INPUT_BYTES}; not read"
                    );
                    own(unread(Status::Invalid, message, Some((*p, *q))))
                }
                Ok((p, q)) => {
                    // The student's own numbers judge a part that accepts them.
                    let p = settings.variants.problem(bank, row.student, *p, *q);
                    Ok(*by_text
                        .entry((p as u32, *q as u32, row.answer))
                        .or_insert_with(|| {
                            distinct.push((p as u32, *q as u32, row.answer));
                            distinct.len() as u32 - 1
                        }))
                }
            }
        };
        row_distinct.push(slot);
    }
    // Freed before the answers are checked, which is where a class of all-different answers
    // needs its memory.
    drop((by_text, resolved));
    // Only a class of many different answers frees enough between passes to be worth giving
    // back (each time costs some milliseconds).
    let many = distinct.len() >= window_size();
    let trim = || {
        if many {
            super::memory::give_back();
        }
    };
    trim();
    phases.end("exact text");
    let bar = Shared::new(progress);
    bar.start(distinct.len() as u64);
    // A window at a time, each form kept only as its key for finding representatives.
    let mut keyed: Vec<FormKey> = Vec::with_capacity(distinct.len());
    for window in distinct.chunks(window_size()) {
        let forms = par_map(bank, &table.answers, window, |c, part, _, text| {
            if !bar.tick() {
                return None;
            }
            // A list's verdict depends on what its canonical form leaves out (the stated
            // stability of each equilibrium, labels, the items' order that messages name),
            // so lists share a verdict only with the same text.
            // Only equality of forms matters: each is kept as its 128-bit hash (a class of
            // all-different answers would otherwise hold every form's text at once).
            (!is_list(part))
                .then(|| c.canonical(&part.id, text).ok().flatten())?
                .map(|form| meaning(&form))
        });
        let first = keyed.len();
        keyed.extend(
            (window.iter().zip(forms).enumerate())
                .map(|(i, (&item, form))| form_key(first + i, item, form)),
        );
        trim();
        if bar.stopped() {
            break;
        }
    }
    let (reps_of, rep_inputs) = representatives(&distinct, keyed);
    // Each row's distinct answer becomes its representative.
    for d in row_distinct.iter_mut().flatten() {
        *d = reps_of[*d as usize];
    }
    drop((reps_of, distinct));
    trim();
    phases.end("canonical");
    if bar.stopped() {
        return Err(Interrupted);
    }
    bar.start(rep_inputs.len() as u64);
    let codes = Codes::default();
    // Room reserved at once (a reading is about as long as its answer; a message about a
    // line): growing by doubling would copy each block, the old one still held, at the peak.
    let typed: usize = (rep_inputs.iter())
        .map(|&(_, _, a)| table.answers.get(a).len())
        .sum();
    // A class of many different answers keeps its words on disk: they are about half of what
    // its representatives would hold in memory.
    let mut judged = if many {
        Judged::with_words(
            rep_inputs.len(),
            words::Store::disk(settings.scratch, rep_inputs.len()),
        )
    } else {
        Judged::with_capacity(rep_inputs.len(), 2 * typed)
    };
    let w = Window {
        bank,
        answers: &table.answers,
        policy: settings.policy,
        bar: &bar,
        codes: &codes,
    };
    // Checked a window at a time, each window's representatives then moved into this
    // thread's memory: the long-lived verdicts are not left scattered among the checkers'
    // scratch memory in the workers' heaps (which is then freed whole), so a class of
    // all-different answers needs less memory (issue 20 §5). Verdicts do not depend on which
    // checker reads an answer, so neither do the outputs on the window's size.
    for window in rep_inputs.chunks(window_size()) {
        for (rep, words) in check_window(&w, window) {
            judged.push(rep, &words);
        }
        // The checkers' scratch memory of this window, freed in the workers' heaps.
        trim();
        if bar.stopped() {
            break;
        }
    }
    judged.set_codes(codes.into_lists());
    if bar.stopped() {
        return Err(Interrupted);
    }
    phases.end("check");
    drop(rep_inputs);
    trim();
    // A representative's outcome is numbered as the representative; rows' own come after.
    let first_own = judged.reps.len() as u32;
    judged.rows = row_distinct
        .iter()
        .map(|d| Graded {
            outcome: match d {
                Ok(r) => *r,
                Err(o) => first_own + o,
            },
            counts: false,
        })
        .collect();
    judged.kept = own;
    drop(row_distinct);
    phases.end("outcomes");
    if let Some(o) = settings.overrides {
        o.apply(table, &mut judged, bank, settings.variants);
    }
    if settings.policy.follow_through.is_some() {
        follow_through(
            rows,
            &table.answers,
            &mut judged,
            bank,
            settings.policy,
            table.students.len(),
        );
        phases.end("follow-through");
    }
    mark_counted(
        rows,
        &mut judged,
        bank,
        settings.policy,
        table.students.len(),
    );
    phases.end("counted");
    Ok(judged)
}

/// The outcome of a row that is not checked.
fn unread(status: Status, message: String, target: Option<(usize, usize)>) -> Outcome {
    let brief = Brief {
        status,
        score: 0.0,
        target,
        rep: None,
    };
    Outcome::new(brief, no_codes(), Some(message))
}

/// Whether a part's answer is a list (equilibria, frequencies, values).
fn is_list(part: &Part) -> bool {
    matches!(
        part.kind,
        PartKind::Equilibria | PartKind::Frequencies | PartKind::Values
    )
}

/// Maps `f(checker, part, answer)` over `(problem, part, answer)` items in parallel, in
/// order, giving each chunk of work one checker per problem. A checker prepares each part
/// once, so chunks are not tiny; but its expression pool grows with every answer it reads,
/// which makes a long chunk slower per answer, so chunks are not long either.
fn par_map<'b, R: Send>(
    bank: &'b Bank,
    answers: &super::intern::Interner,
    items: &[Item],
    f: impl Fn(&mut Checker<'b>, &'b Part, Item, &str) -> R + Sync + Send,
) -> Vec<R> {
    let n = bank.problems.len();
    items
        .par_iter()
        .with_min_len(CHUNK / 4)
        .with_max_len(CHUNK)
        .map_init(
            || (0..n).map(|_| None).collect::<Vec<Option<Checker<'b>>>>(),
            |checkers, &(p, q, answer)| {
                let problem = &bank.problems[p as usize];
                let checker = checkers[p as usize].get_or_insert_with(|| Checker::new(problem));
                f(
                    checker,
                    &problem.parts[q as usize],
                    (p, q, answer),
                    answers.get(answer),
                )
            },
        )
        .collect()
}

/// A distinct answer's key for finding representatives: its part and whether it has a
/// canonical form (one word), the form's 128-bit hash or else the answer's own index (two
/// words), and the distinct answer's index. Sorted rather than hashed: 32 bytes each, where a
/// map of them took about 130 (a class of a million different answers has a million).
type FormKey = (u64, u64, u64, u32);

/// The [`FormKey`] of distinct answer `i`, `(p, q, answer)`, with canonical form `form`.
fn form_key(i: usize, (p, q, answer): Item, form: Option<u128>) -> FormKey {
    // An answer without a canonical form stands for itself (its distinct text).
    let (own, hi, lo) = match form {
        Some(f) => (0, (f >> 64) as u64, f as u64),
        None => (1, 0, u64::from(answer)),
    };
    ((p as u64) << 33 | (q as u64) << 1 | own, hi, lo, i as u32)
}

/// For each distinct answer, the index of its representative, and the representatives (the
/// first distinct answer of each canonical form in input order, numbered in that order;
/// unreadable answers stand for themselves), from every distinct answer's [`FormKey`].
fn representatives(distinct: &[Item], mut keyed: Vec<FormKey>) -> (Vec<u32>, Vec<Item>) {
    keyed.par_sort_unstable();
    // Each distinct answer's form's first answer (the first of its run: runs are sorted by
    // index within), then, in input order, each first answer numbered as a representative
    // and every other one given its first's number (already given: the first comes before).
    let mut of = vec![0u32; distinct.len()];
    for run in keyed.chunk_by(|a, b| (a.0, a.1, a.2) == (b.0, b.1, b.2)) {
        for w in run {
            of[w.3 as usize] = run[0].3;
        }
    }
    drop(keyed);
    let mut reps: Vec<Item> = Vec::new();
    for i in 0..of.len() {
        let first = of[i] as usize;
        of[i] = if first == i {
            reps.push(distinct[i]);
            reps.len() as u32 - 1
        } else {
            of[first]
        };
    }
    (of, reps)
}

/// Resolves a problem and part id pair to a bank part, or to the error its rows get (with
/// did-you-mean; the message without its line).
fn resolve(problem_id: &str, part_id: &str, bank: &Bank) -> Resolved {
    let Some(p) = bank.problems.iter().position(|p| p.id == problem_id) else {
        let ids = bank.problems.iter().map(|p| p.id.as_str());
        let hint = did_you_mean(problem_id, ids)
            .map_or(String::new(), |s| format!("; did you mean `{s}`?"));
        return Err(format!("no problem `{}`{hint}", visible(problem_id)));
    };
    let problem: &Problem = &bank.problems[p];
    let Some(q) = problem.parts.iter().position(|x| x.id == part_id) else {
        let ids: Vec<&str> = problem.parts.iter().map(|x| x.id.as_str()).collect();
        let hint = did_you_mean(part_id, ids.iter().copied())
            .map_or(String::new(), |s| format!("did you mean `{s}`? "));
        return Err(format!(
            "`{}` has no part `{}`; {hint}the parts are {}",
            problem.id,
            visible(part_id),
            ids.join(", ")
        ));
    };
    Ok((p, q))
}

#[cfg(test)]
mod tests {
    use super::*;
    use lagrange::check::Verdict;

    /// What grading kept of a verdict before [`Slim`] (issue 20 §5): the verdict with its ids,
    /// plain reading, note, parse error and every message but the first emptied.
    fn kept(mut v: Verdict) -> Verdict {
        v.problem = String::new();
        v.part = String::new();
        v.reading.plain = String::new();
        v.reading.note = None;
        v.parse_error = None;
        for d in v.diagnoses.iter_mut().skip(1) {
            d.message = String::new();
        }
        v
    }

    /// A slim verdict gives back exactly what grading kept of the verdict before (follow-through
    /// reads an earlier answer through it), for right, wrong and unreadable answers.
    #[test]
    fn a_slim_verdict_gives_back_what_grading_kept_of_the_verdict() {
        let bank = crate::face::load_bank(None).unwrap_or_else(|e| panic!("{e}"));
        let problem = (bank.problems.iter())
            .find(|p| p.id == "simple-pendulum")
            .unwrap_or_else(|| panic!("no simple-pendulum in the bank"));
        let mut checker = Checker::new(problem);
        let answers = [
            (
                "eom",
                "m*l^2*theta'' + m*g*l*sin(theta) = 0",
                Checked::Correct,
            ),
            (
                "eom",
                "m*l^2*theta'' + 1.000002*m*g*l*sin(theta) = 0",
                Checked::Incorrect,
            ),
            (
                "eom",
                "m*l^2*theta'' - m*g*l*sin(theta) = 0",
                Checked::Incorrect,
            ),
            ("potential", "m*g*l*cos(theta)", Checked::Incorrect),
            ("potential", "m*g*(", Checked::Invalid),
        ];
        for (part, answer, status) in answers {
            let v = checker
                .check(part, answer)
                .unwrap_or_else(|e| panic!("{answer}: {e}"));
            assert_eq!(v.status, status, "{answer}");
            let (slim, words, codes) = Slim::new(v.clone());
            let (unicode, message) = (&words.reading, &words.message);
            assert_eq!(
                slim.verdict(&codes, unicode, message),
                kept(v.clone()),
                "{answer}"
            );
            assert_eq!(
                slim.first(&codes, message),
                v.diagnoses.first().cloned(),
                "{answer}"
            );
            assert_eq!(*unicode, v.reading.unicode, "{answer}");
            if status != Checked::Correct {
                assert!(!codes.is_empty() && !message.is_empty(), "{answer}");
            }
        }
    }

    /// Distinct answers share a representative exactly when they are of one part and have
    /// one canonical form; answers without a form stand for themselves; representatives are
    /// the first of each form, numbered in input order.
    #[test]
    fn representatives_are_the_first_of_each_form_of_each_part() {
        let (a, b) = (Some(7u128 << 70 | 3), Some(7u128 << 70 | 4));
        let cases: [(Item, Option<u128>, u32); 9] = [
            ((0, 0, 10), a, 0),
            ((0, 0, 11), b, 1),
            ((0, 0, 12), a, 0),
            ((0, 1, 13), a, 2),
            ((0, 0, 14), None, 3),
            ((0, 0, 15), None, 4),
            ((1, 0, 16), b, 5),
            ((0, 0, 17), b, 1),
            ((0, 1, 18), a, 2),
        ];
        let distinct: Vec<Item> = cases.iter().map(|c| c.0).collect();
        let keyed = (cases.iter().enumerate())
            .map(|(i, &(item, form, _))| form_key(i, item, form))
            .collect();
        let (of, reps) = representatives(&distinct, keyed);
        assert_eq!(of, cases.iter().map(|c| c.2).collect::<Vec<u32>>());
        let firsts = [0, 1, 3, 4, 5, 6].map(|i| cases[i].0);
        assert_eq!(reps, firsts.to_vec());
    }

    /// Equal texts share a meaning and different ones do not (the summary's grouping key).
    #[test]
    fn meanings_are_equal_exactly_for_equal_texts() {
        assert_eq!(meaning("1.5, 2"), meaning("1.5, 2"));
        assert_ne!(meaning("1.5, 2"), meaning("1.5, 2 "));
        assert_ne!(meaning(""), meaning("text:"));
    }
}

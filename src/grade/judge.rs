//! Rows → verdicts, checking as little as possible: answers are deduplicated on their exact
//! text, then on the checker's canonical form, and one representative per canonical form
//! (the first in input order) is checked; every row sharing it reuses the verdict (a list only
//! with the same text: its canonical form drops stated stability and item order). The two
//! passes run in parallel (rayon), one `Checker` per worker and problem. Which answer
//! represents a form never depends on the thread count, so neither does any output.

use rustc_hash::FxHashMap;

use rayon::prelude::*;

use lagrange::bank::Bank;
use lagrange::check::{Checker, Code, Status as Checked};
use lagrange::expr::error::{MAX_INPUT_BYTES, visible};
use lagrange::problem::{Part, PartKind, Problem};
use lagrange::progress::{Interrupted, Progress};
use lagrange::tutor::command::did_you_mean;

use lagrange::policy::{Decision, Policy};

use super::input::Table;

mod counted;
mod slim;
use crate::face::bar::Shared;
use counted::{follow_through, mark_counted};
pub use slim::{Messages, Slim, meaning};

/// The instructor's decisions applied to judged rows (`--overrides`, in `overrides.rs`): a
/// trait so that judging does not import the file that reads the decisions.
pub trait Override: Sync + std::fmt::Debug {
    /// Applies the decisions to the rows they name; the rows changed.
    fn apply(&self, table: &Table, judged: &mut Judged, bank: &Bank) -> Vec<usize>;
}

/// The status column of results.csv.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Status {
    Correct,
    Incorrect,
    /// The answer could not be read (or is too long to read).
    Invalid,
    /// The row could not be graded at all (bad line, unknown problem or part, empty answer).
    Error,
}

impl Status {
    /// The name written in results.csv and the summary.
    pub fn name(self) -> &'static str {
        match self {
            Status::Correct => "correct",
            Status::Incorrect => "incorrect",
            Status::Invalid => "invalid",
            Status::Error => "error",
        }
    }
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
}

/// One checked representative: the verdict every row of its canonical form shares.
pub struct Rep {
    /// The problem's index in the bank.
    pub problem: usize,
    /// The part's index in the problem.
    pub part: usize,
    /// The answer checked (the first spelling of the form in input order).
    pub answer: String,
    /// The verdict ([`Slim`]: what grading reads of it), or why the part could not be
    /// checked.
    pub verdict: Result<Slim, String>,
    /// Equal for answers equal at the sample points: the summary's grouping key (the
    /// checker's fingerprint, hashed: see [`meaning`]).
    pub fingerprint: Option<u128>,
}

/// What a row is given: shared by every row with the same representative (and the same
/// follow-through question), or a row's own (an error, an answer too long to read).
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The status column.
    pub status: Status,
    /// The verdict's score times the part's points (follow-through credit included).
    pub score: f64,
    /// The diagnosis codes, most specific first (`follows-from-earlier` leading).
    pub codes: Vec<Code>,
    /// The first diagnosis, or why the row is an error or unread; `None`: the first
    /// diagnosis of the representative's verdict, or why it could not be checked (not copied:
    /// a class of all-different answers has as many outcomes as rows). See
    /// [`Judged::message`].
    pub message: Option<String>,
    /// `(problem, part)` indices into the bank, for rows that name a real part.
    pub target: Option<(usize, usize)>,
    /// The representative whose verdict this is.
    pub rep: Option<usize>,
    /// The instructor's decision that replaced the checker's (`--overrides`), if any.
    pub decision: Option<Decision>,
}

/// The outcome of one row of the input.
#[derive(Clone, Copy, Debug)]
pub struct Graded {
    /// Its outcome in [`Judged::outcomes`].
    pub outcome: u32,
    /// Whether this row is the student's answer that counts for the part.
    pub counts: bool,
}

/// Every row's outcome (same order as the input) and the representatives checked.
pub struct Judged {
    /// One entry per input row, in input order.
    pub rows: Vec<Graded>,
    /// The outcomes rows point to.
    pub outcomes: Vec<Outcome>,
    /// The answers actually checked.
    pub reps: Vec<Rep>,
    /// The score a counted row counts for when the attempt penalty lowers it below its
    /// outcome's (few rows: only later attempts, only with a penalty).
    pub penalised: FxHashMap<u32, f64>,
}

impl Judged {
    /// Row `i`'s outcome.
    pub fn outcome(&self, i: usize) -> &Outcome {
        &self.outcomes[self.rows[i].outcome as usize]
    }

    /// An outcome's message (results.csv's `message`).
    pub fn message<'s>(&'s self, o: &'s Outcome) -> &'s str {
        match (&o.message, o.rep) {
            (Some(m), _) => m,
            (None, Some(r)) => match &self.reps[r].verdict {
                Ok(v) => &v.message,
                Err(e) => e,
            },
            (None, None) => "",
        }
    }

    /// The score row `i` counts for in the gradebook (after the attempt penalty).
    pub fn counted_score(&self, i: usize) -> f64 {
        match self.penalised.get(&(i as u32)) {
            Some(&s) => s,
            None => self.outcome(i).score,
        }
    }

    /// Adds an outcome; its index.
    pub(super) fn add(&mut self, o: Outcome) -> u32 {
        self.outcomes.push(o);
        self.outcomes.len() as u32 - 1
    }
}

/// The most answers one checker reads (see [`par_map`]).
const CHUNK: usize = 1024;

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
    let mut judged = Judged {
        rows: Vec::with_capacity(rows.len()),
        outcomes: Vec::new(),
        reps: Vec::new(),
        penalised: FxHashMap::default(),
    };
    let mut resolved: FxHashMap<(u32, u32), Resolved> = FxHashMap::default();
    // Exact text first: a class types the same few strings many times.
    let mut distinct: Vec<(usize, usize, &str)> = Vec::new();
    let mut by_text: FxHashMap<(u32, u32, u32), u32> = FxHashMap::default();
    // Per row: its own outcome (Err) or its distinct answer (Ok), then its representative.
    let mut row_distinct: Vec<Result<u32, u32>> = Vec::with_capacity(rows.len());
    for row in rows {
        let own = |o: Outcome, judged: &mut Judged| Err(judged.add(o));
        let target = resolved
            .entry((row.problem, row.part))
            .or_insert_with(|| resolve(table.problem(row), table.part(row), bank));
        let slot = if let Some(e) = table.error(row) {
            own(unread(Status::Error, e.to_string(), None), &mut judged)
        } else {
            match target {
                Err(rest) => {
                    let message = format!("line {}: {rest}", row.line);
                    own(unread(Status::Error, message, None), &mut judged)
                }
                Ok((p, q)) if table.answer(row).len() > MAX_INPUT_BYTES => {
                    let (line, n) = (row.line, table.answer(row).len());
                    let message = format!(
                        "line {line}: the answer is {n} bytes, over the checker's limit of {MAX_INPUT_BYTES}; not read"
                    );
                    own(
                        unread(Status::Invalid, message, Some((*p, *q))),
                        &mut judged,
                    )
                }
                Ok((p, q)) => {
                    // The student's own numbers judge a part that accepts them.
                    let p = settings.variants.problem(bank, row.student, *p, *q);
                    Ok(*by_text
                        .entry((p as u32, *q as u32, row.answer))
                        .or_insert_with(|| {
                            distinct.push((p, *q, table.answers.get(row.answer)));
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
    phases.end("exact text");
    let bar = Shared::new(progress);
    bar.start(distinct.len() as u64);
    let canon = par_map(bank, &distinct, |c, part, (_, _, text)| {
        if !bar.tick() {
            return None;
        }
        // A list's verdict depends on what its canonical form leaves out (the stated
        // stability of each equilibrium, labels, the items' order that messages name), so
        // lists share a verdict only with the same text.
        (!is_list(part)).then(|| c.canonical(&part.id, text).ok().flatten())?
    });
    let (reps_of, rep_inputs) = representatives(&distinct, canon);
    // Each row's distinct answer becomes its representative.
    for d in row_distinct.iter_mut().flatten() {
        *d = reps_of[*d as usize] as u32;
    }
    drop((reps_of, distinct));
    phases.end("canonical");
    if bar.stopped() {
        return Err(Interrupted);
    }
    bar.start(rep_inputs.len() as u64);
    let messages = Messages::default();
    // Each representative made where it is checked (no second list of them).
    judged.reps = par_map(bank, &rep_inputs, |c, part, (problem, q, text)| {
        let rep = |verdict, fingerprint| Rep {
            problem,
            part: q,
            answer: text.to_string(),
            verdict,
            fingerprint,
        };
        if !bar.tick() {
            return rep(Err(Interrupted.to_string()), None);
        }
        let verdict = c.check(&part.id, text).map_err(|e| e.to_string());
        // Only wrong answers are grouped, so a right one needs no fingerprint.
        let wrong = verdict.as_ref().is_ok_and(|v| v.status != Checked::Correct);
        let fingerprint = wrong
            .then(|| c.fingerprint(&part.id, text).ok().flatten())
            .flatten()
            .map(|f| meaning(&f));
        rep(verdict.map(|v| Slim::shared(v, &messages)), fingerprint)
    });
    drop(messages);
    if bar.stopped() {
        return Err(Interrupted);
    }
    phases.end("check");
    drop(rep_inputs);
    judged.outcomes.reserve_exact(judged.reps.len());
    let rep_outcomes: Vec<u32> = (0..judged.reps.len())
        .map(|r| {
            let o = outcome(r, &judged.reps[r], bank, settings.policy);
            judged.add(o)
        })
        .collect();
    judged.rows = row_distinct
        .iter()
        .map(|d| Graded {
            outcome: match d {
                Ok(r) => rep_outcomes[*r as usize],
                Err(own) => *own,
            },
            counts: false,
        })
        .collect();
    drop(row_distinct);
    phases.end("outcomes");
    if let Some(o) = settings.overrides {
        o.apply(table, &mut judged, bank);
    }
    if settings.policy.follow_through.is_some() {
        follow_through(
            rows,
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
    Outcome {
        status,
        score: 0.0,
        codes: Vec::new(),
        message: Some(message),
        target,
        rep: None,
        decision: None,
    }
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
    items: &[(usize, usize, &str)],
    f: impl Fn(&mut Checker<'b>, &'b Part, (usize, usize, &str)) -> R + Sync + Send,
) -> Vec<R> {
    let n = bank.problems.len();
    items
        .par_iter()
        .with_min_len(CHUNK / 4)
        .with_max_len(CHUNK)
        .map_init(
            || (0..n).map(|_| None).collect::<Vec<Option<Checker<'b>>>>(),
            |checkers, &(p, q, text)| {
                let problem = &bank.problems[p];
                let checker = checkers[p].get_or_insert_with(|| Checker::new(problem));
                f(checker, &problem.parts[q], (p, q, text))
            },
        )
        .collect()
}

/// For each distinct answer, the index of its representative, and the representatives (the
/// first distinct answer of each canonical form; unreadable answers stand for themselves).
#[allow(clippy::type_complexity)]
fn representatives<'r>(
    distinct: &[(usize, usize, &'r str)],
    canon: Vec<Option<String>>,
) -> (Vec<usize>, Vec<(usize, usize, &'r str)>) {
    let mut reps: Vec<(usize, usize, &str)> = Vec::new();
    let mut by_form: FxHashMap<(usize, usize, String), usize> = FxHashMap::default();
    let mut of = Vec::with_capacity(distinct.len());
    for (&(p, q, text), form) in distinct.iter().zip(canon) {
        // A leading NUL cannot start a canonical form, so raw text never collides with one.
        let key = form.unwrap_or_else(|| format!("\0{text}"));
        let r = *by_form.entry((p, q, key)).or_insert_with(|| {
            reps.push((p, q, text));
            reps.len() - 1
        });
        of.push(r);
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

/// The outcome of representative `r`: its verdict scored by the policy.
fn outcome(r: usize, rep: &Rep, bank: &Bank, policy: &Policy) -> Outcome {
    let (p, q) = (rep.problem, rep.part);
    // A problem pinned to a student's numbers counts as its bank problem (the first of its id).
    let p = (bank.problems[..p].iter())
        .position(|x| x.id == bank.problems[p].id)
        .unwrap_or(p);
    let points = bank.problems[p].parts[q].points;
    let (status, score, codes) = match &rep.verdict {
        Ok(v) => (
            match v.status {
                Checked::Correct => Status::Correct,
                Checked::Incorrect => Status::Incorrect,
                Checked::Invalid => Status::Invalid,
            },
            policy.answer_fraction(v.status, v.score, &v.codes) * points,
            v.codes.to_vec(),
        ),
        Err(_) => (Status::Error, 0.0, Vec::new()),
    };
    Outcome {
        status,
        score,
        codes,
        // The verdict's first message (or the error), read through `Judged::message`.
        message: None,
        target: Some((p, q)),
        rep: Some(r),
        decision: None,
    }
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
            let slim = Slim::new(v.clone());
            assert_eq!(slim.verdict(), kept(v.clone()), "{answer}");
            assert_eq!(slim.first(), v.diagnoses.first().cloned(), "{answer}");
            assert_eq!(&*slim.unicode, v.reading.unicode.as_str(), "{answer}");
            if status != Checked::Correct {
                assert!(
                    !slim.codes.is_empty() && !slim.message.is_empty(),
                    "{answer}"
                );
            }
        }
    }

    /// Equal texts share a meaning and different ones do not (the summary's grouping key).
    #[test]
    fn meanings_are_equal_exactly_for_equal_texts() {
        assert_eq!(meaning("1.5, 2"), meaning("1.5, 2"));
        assert_ne!(meaning("1.5, 2"), meaning("1.5, 2 "));
        assert_ne!(meaning(""), meaning("text:"));
    }
}

//! Rows → verdicts, checking as little as possible: answers are deduplicated on their exact
//! text, then on the checker's canonical form, and one representative per canonical form
//! (the first in input order) is checked; every row sharing it reuses the verdict (a list only
//! with the same text: its canonical form drops stated stability and item order). The two
//! passes run in parallel (rayon), one `Checker` per worker and problem. Which answer
//! represents a form never depends on the thread count, so neither does any output.

use rustc_hash::FxHashMap;

use rayon::prelude::*;

use lagrange::bank::Bank;
use lagrange::check::{Checker, Code, Status as Checked, Verdict};
use lagrange::expr::error::{MAX_INPUT_BYTES, visible};
use lagrange::problem::{Part, PartKind, Problem};
use lagrange::progress::{Interrupted, Progress};
use lagrange::tutor::command::did_you_mean;

use super::input::Table;

mod counted;
use crate::bar::Shared;
use counted::{follow_through, mark_counted};

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

/// How to judge: follow-through credit (`None`: off) and whether the best attempt counts.
#[derive(Clone, Copy, Debug)]
pub struct Settings<'v> {
    /// The follow-through credit as a fraction of the points; `None`: no follow-through.
    pub follow_through: Option<f64>,
    /// The best attempt counts instead of the last.
    pub best: bool,
    /// The problems pinned to each student's numbers (`variants.rs`).
    pub variants: &'v super::variants::Variants,
}

/// One checked representative: the verdict every row of its canonical form shares.
pub struct Rep {
    /// The problem's index in the bank.
    pub problem: usize,
    /// The part's index in the problem.
    pub part: usize,
    /// The answer checked (the first spelling of the form in input order).
    pub answer: String,
    /// The verdict ([`slim`]: what grading reads of it), or why the part could not be
    /// checked.
    pub verdict: Result<Verdict, String>,
    /// Equal for answers equal at the sample points: the summary's grouping key.
    pub fingerprint: Option<String>,
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
                Ok(v) => v.diagnoses.first().map_or("", |d| d.message.as_str()),
                Err(e) => e,
            },
            (None, None) => "",
        }
    }

    /// Adds an outcome; its index.
    fn add(&mut self, o: Outcome) -> u32 {
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
    };
    let mut resolved: FxHashMap<(u32, u32), Resolved> = FxHashMap::default();
    // Exact text first: a class types the same few strings many times.
    let mut distinct: Vec<(usize, usize, &str)> = Vec::new();
    let mut by_text: FxHashMap<(usize, usize, u32), u32> = FxHashMap::default();
    // Per row: its own outcome (Err) or its distinct answer (Ok).
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
                    Ok(*by_text.entry((p, *q, row.answer)).or_insert_with(|| {
                        distinct.push((p, *q, table.answers.get(row.answer)));
                        distinct.len() as u32 - 1
                    }))
                }
            }
        };
        row_distinct.push(slot);
    }
    phases.end("exact text");
    let bar = Shared::new(progress);
    bar.start(distinct.len() as u64);
    let canon = par_map(bank, &distinct, |c, part, text| {
        if !bar.tick() {
            return None;
        }
        // A list's verdict depends on what its canonical form leaves out (the stated
        // stability of each equilibrium, labels, the items' order that messages name), so
        // lists share a verdict only with the same text.
        (!is_list(part)).then(|| c.canonical(&part.id, text).ok().flatten())?
    });
    let (reps_of, rep_inputs) = representatives(&distinct, canon);
    phases.end("canonical");
    if bar.stopped() {
        return Err(Interrupted);
    }
    bar.start(rep_inputs.len() as u64);
    let checked = par_map(bank, &rep_inputs, |c, part, text| {
        if !bar.tick() {
            return (Err(Interrupted.to_string()), None);
        }
        let verdict = c.check(&part.id, text).map_err(|e| e.to_string());
        // Only wrong answers are grouped, so a right one needs no fingerprint.
        let wrong = verdict.as_ref().is_ok_and(|v| v.status != Checked::Correct);
        let fingerprint = wrong
            .then(|| c.fingerprint(&part.id, text).ok().flatten())
            .flatten();
        (verdict.map(slim), fingerprint)
    });
    if bar.stopped() {
        return Err(Interrupted);
    }
    phases.end("check");
    judged.reps = rep_inputs
        .iter()
        .zip(checked)
        .map(|(&(problem, part, answer), (verdict, fingerprint))| Rep {
            problem,
            part,
            answer: answer.to_string(),
            verdict,
            fingerprint,
        })
        .collect();
    let rep_outcomes: Vec<u32> = (0..judged.reps.len())
        .map(|r| {
            let o = outcome(r, &judged.reps[r], bank);
            judged.add(o)
        })
        .collect();
    judged.rows = row_distinct
        .iter()
        .map(|d| Graded {
            outcome: match d {
                Ok(d) => rep_outcomes[reps_of[*d as usize]],
                Err(own) => *own,
            },
            counts: false,
        })
        .collect();
    drop(row_distinct);
    phases.end("outcomes");
    if let Some(credit) = settings.follow_through {
        follow_through(
            rows,
            &mut judged,
            bank,
            credit,
            table.students.len(),
            settings.best,
        );
        phases.end("follow-through");
    }
    mark_counted(rows, &mut judged, table.students.len(), settings.best);
    phases.end("counted");
    Ok(judged)
}

/// A verdict with only what grading reads of it: the status, the score, every code, the
/// first diagnosis's message (results.csv, the summary, follow-through's earlier answer) and
/// the Unicode reading (the summary). Kept for every representative until the summary is
/// made, so a class of all-different answers keeps no other message or reading.
fn slim(mut v: Verdict) -> Verdict {
    v.problem = String::new();
    v.part = String::new();
    v.reading.plain = String::new();
    v.reading.note = None;
    v.reading.unicode.shrink_to_fit();
    v.parse_error = None;
    for d in v.diagnoses.iter_mut().skip(1) {
        d.message = String::new();
    }
    if let Some(d) = v.diagnoses.first_mut() {
        d.message.shrink_to_fit();
    }
    v.diagnoses.shrink_to_fit();
    v
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
    f: impl Fn(&mut Checker<'b>, &'b Part, &str) -> R + Sync + Send,
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
                f(checker, &problem.parts[q], text)
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

/// The outcome of representative `r`.
fn outcome(r: usize, rep: &Rep, bank: &Bank) -> Outcome {
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
            v.score * points,
            v.diagnoses.iter().map(|d| d.code).collect(),
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
    }
}

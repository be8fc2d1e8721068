//! Rows → verdicts, checking as little as possible: answers are deduplicated on their exact
//! text, then on the checker's canonical form, and one representative per canonical form
//! (the first in input order) is checked; every row sharing it reuses the verdict (a list only
//! with the same text: its canonical form drops stated stability and item order). The two
//! passes run in parallel (rayon), one `Checker` per worker and problem. Which answer
//! represents a form never depends on the thread count, so neither does any output.

use std::collections::HashMap;

use indicatif::ProgressBar;
use rayon::prelude::*;

use lagrange::bank::Bank;
use lagrange::check::{Checker, Diagnosis, Status as Checked, Verdict};
use lagrange::expr::error::{MAX_INPUT_BYTES, visible};
use lagrange::problem::{Part, PartKind, Problem};
use lagrange::tutor::command::did_you_mean;
use lagrange::tutor::follow::{Earlier, accepts, follows_from_earlier};

use super::input::Row;

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
pub struct Settings {
    /// The follow-through credit as a fraction of the points; `None`: no follow-through.
    pub follow_through: Option<f64>,
    /// The best attempt counts instead of the last.
    pub best: bool,
}

/// One checked representative: the verdict every row of its canonical form shares.
pub struct Rep {
    /// The problem's index in the bank.
    pub problem: usize,
    /// The part's index in the problem.
    pub part: usize,
    /// The answer checked (the first spelling of the form in input order).
    pub answer: String,
    /// The verdict, or why the part could not be checked.
    pub verdict: Result<Verdict, String>,
    /// Equal for answers equal at the sample points: the summary's grouping key.
    pub fingerprint: Option<String>,
}

/// The outcome of one row of the input.
#[derive(Clone, Debug)]
pub struct Graded {
    /// The status column.
    pub status: Status,
    /// The verdict's score times the part's points (follow-through credit included).
    pub score: f64,
    /// The diagnosis codes, most specific first (`follows-from-earlier` leading).
    pub codes: Vec<String>,
    /// The first diagnosis, or why the row is an error or unread.
    pub message: String,
    /// `(problem, part)` indices into the bank, for rows that name a real part.
    pub target: Option<(usize, usize)>,
    /// The representative whose verdict this row shares.
    pub rep: Option<usize>,
    /// Whether this row is the student's answer that counts for the part.
    pub counts: bool,
}

/// Every row's outcome (same order as the input) and the representatives checked.
pub struct Judged {
    /// One outcome per input row, in input order.
    pub rows: Vec<Graded>,
    /// The answers actually checked.
    pub reps: Vec<Rep>,
}

/// The most answers one checker reads (see [`par_map`]).
const CHUNK: usize = 1024;

/// What a row resolves to before anything is checked.
enum Target {
    Error(String),
    /// A real part, but an answer too long to read.
    TooLong(usize, usize, String),
    Answer(usize, usize),
}

/// Grades every row. `progress` makes the bar (given the number of distinct answers): it
/// ticks once per answer read, then once per canonical form checked.
pub fn judge(
    rows: &[Row],
    bank: &Bank,
    settings: Settings,
    progress: &dyn Fn(usize) -> ProgressBar,
) -> Judged {
    let targets: Vec<Target> = rows.iter().map(|r| resolve(r, bank)).collect();
    // Exact text first: a class types the same few strings many times.
    let mut distinct: Vec<(usize, usize, &str)> = Vec::new();
    let mut by_text: HashMap<(usize, usize, &str), usize> = HashMap::new();
    let row_distinct: Vec<Option<usize>> = targets
        .iter()
        .zip(rows)
        .map(|(t, r)| match t {
            Target::Answer(p, q) => {
                Some(*by_text.entry((*p, *q, &r.answer)).or_insert_with(|| {
                    distinct.push((*p, *q, &r.answer));
                    distinct.len() - 1
                }))
            }
            Target::Error(..) | Target::TooLong(..) => None,
        })
        .collect();
    let bar = progress(distinct.len());
    bar.set_message("reading");
    let canon = par_map(bank, &distinct, |c, part, text| {
        bar.inc(1);
        // A list's verdict depends on what its canonical form leaves out (the stated
        // stability of each equilibrium, labels, the items' order that messages name), so
        // lists share a verdict only with the same text.
        (!is_list(part)).then(|| c.canonical(&part.id, text).ok().flatten())?
    });
    let (reps_of, rep_inputs) = representatives(&distinct, canon);
    bar.set_message("checking");
    bar.set_length(rep_inputs.len() as u64);
    bar.set_position(0);
    let checked = par_map(bank, &rep_inputs, |c, part, text| {
        let verdict = c.check(&part.id, text).map_err(|e| e.to_string());
        // Only wrong answers are grouped, so a right one needs no fingerprint.
        let wrong = verdict.as_ref().is_ok_and(|v| v.status != Checked::Correct);
        let fingerprint = wrong
            .then(|| c.fingerprint(&part.id, text).ok().flatten())
            .flatten();
        bar.inc(1);
        (verdict, fingerprint)
    });
    bar.finish_and_clear();
    let reps: Vec<Rep> = rep_inputs
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
    let mut graded: Vec<Graded> = targets
        .iter()
        .zip(&row_distinct)
        .map(|(t, d)| outcome(t, d.map(|d| reps_of[d]), &reps, bank))
        .collect();
    if let Some(credit) = settings.follow_through {
        follow_through(rows, &mut graded, &reps, bank, credit, settings.best);
    }
    mark_counted(rows, &mut graded, settings.best);
    Judged { rows: graded, reps }
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
    let mut by_form: HashMap<(usize, usize, String), usize> = HashMap::new();
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

/// Resolves a row to a bank part, or to the error it gets (with did-you-mean).
fn resolve(row: &Row, bank: &Bank) -> Target {
    let line = row.line;
    if let Some(e) = &row.error {
        return Target::Error(e.clone());
    }
    let Some(p) = bank.problems.iter().position(|p| p.id == row.problem) else {
        let ids = bank.problems.iter().map(|p| p.id.as_str());
        let hint = did_you_mean(&row.problem, ids)
            .map_or(String::new(), |s| format!("; did you mean `{s}`?"));
        return Target::Error(format!(
            "line {line}: no problem `{}`{hint}",
            visible(&row.problem)
        ));
    };
    let problem: &Problem = &bank.problems[p];
    let Some(q) = problem.parts.iter().position(|x| x.id == row.part) else {
        let ids: Vec<&str> = problem.parts.iter().map(|x| x.id.as_str()).collect();
        let hint = did_you_mean(&row.part, ids.iter().copied())
            .map_or(String::new(), |s| format!("did you mean `{s}`? "));
        return Target::Error(format!(
            "line {line}: `{}` has no part `{}`; {hint}the parts are {}",
            problem.id,
            visible(&row.part),
            ids.join(", ")
        ));
    };
    if row.answer.len() > MAX_INPUT_BYTES {
        let n = row.answer.len();
        return Target::TooLong(
            p,
            q,
            format!(
                "line {line}: the answer is {n} bytes, over the checker's limit of {MAX_INPUT_BYTES}; not read"
            ),
        );
    }
    Target::Answer(p, q)
}

/// A row's outcome from its target and representative.
fn outcome(t: &Target, rep: Option<usize>, reps: &[Rep], bank: &Bank) -> Graded {
    let unread = |status, message: &String, target| Graded {
        status,
        score: 0.0,
        codes: Vec::new(),
        message: message.clone(),
        target,
        rep: None,
        counts: false,
    };
    let (p, q) = match t {
        Target::Error(message) => return unread(Status::Error, message, None),
        Target::TooLong(p, q, message) => return unread(Status::Invalid, message, Some((*p, *q))),
        Target::Answer(p, q) => (*p, *q),
    };
    let points = bank.problems[p].parts[q].points;
    let r = rep.and_then(|r| reps.get(r).map(|x| (r, x)));
    let (status, score, codes, message) = match r.map(|(_, x)| &x.verdict) {
        Some(Ok(v)) => (
            match v.status {
                Checked::Correct => Status::Correct,
                Checked::Incorrect => Status::Incorrect,
                Checked::Invalid => Status::Invalid,
            },
            v.score * points,
            v.diagnoses.iter().map(|d| d.code.to_string()).collect(),
            v.diagnoses
                .first()
                .map(|d| d.message.clone())
                .unwrap_or_default(),
        ),
        Some(Err(e)) => (Status::Error, 0.0, Vec::new(), e.clone()),
        None => (Status::Error, 0.0, Vec::new(), String::new()),
    };
    Graded {
        status,
        score,
        codes,
        message,
        target: Some((p, q)),
        rep: r.map(|(i, _)| i),
        counts: false,
    }
}

/// The row that counts for each (student, problem, part): the last graded attempt, or with
/// `best` the highest-scoring one (the later of equals). Error rows never count.
fn final_rows(
    rows: &[Row],
    graded: &[Graded],
    best: bool,
) -> HashMap<(String, usize, usize), usize> {
    let mut chosen: HashMap<(String, usize, usize), usize> = HashMap::new();
    for (i, (row, g)) in rows.iter().zip(graded).enumerate() {
        let (Some((p, q)), false) = (g.target, g.status == Status::Error) else {
            continue;
        };
        let slot = chosen.entry((row.student.clone(), p, q)).or_insert(i);
        if !best || graded[*slot].score <= g.score {
            *slot = i;
        }
    }
    chosen
}

/// Sets `counts` on the rows that count.
fn mark_counted(rows: &[Row], graded: &mut [Graded], best: bool) {
    let chosen = final_rows(rows, graded, best);
    for i in chosen.into_values() {
        graded[i].counts = true;
    }
}

/// One follow-through question: a wrong answer (by representative) and the student's final
/// answers to the problem's other parts (by representative, in part order).
type FollowKey = (usize, Vec<usize>);

/// Gives credit to incorrect answers that follow from the same student's own wrong answers to
/// the other parts. Each distinct question is asked once, in parallel.
fn follow_through(
    rows: &[Row],
    graded: &mut [Graded],
    reps: &[Rep],
    bank: &Bank,
    credit: f64,
    best: bool,
) {
    let finals = final_rows(rows, graded, best);
    let mut keys: Vec<FollowKey> = Vec::new();
    let mut index: HashMap<FollowKey, usize> = HashMap::new();
    let mut asks: Vec<(usize, usize)> = Vec::new();
    for (i, (row, g)) in rows.iter().zip(graded.iter()).enumerate() {
        let (Status::Incorrect, Some((p, q)), Some(rep)) = (g.status, g.target, g.rep) else {
            continue;
        };
        let earlier: Vec<usize> = (0..bank.problems[p].parts.len())
            .filter(|&o| o != q)
            .filter_map(|o| finals.get(&(row.student.clone(), p, o)))
            .filter_map(|&j| graded[j].rep)
            .collect();
        if earlier.is_empty() {
            continue;
        }
        let key = (rep, earlier);
        let k = *index.entry(key.clone()).or_insert_with(|| {
            keys.push(key);
            keys.len() - 1
        });
        asks.push((i, k));
    }
    let answers: Vec<Option<Diagnosis>> = keys.par_iter().map(|k| follows(k, reps, bank)).collect();
    for (i, k) in asks {
        if let Some(d) = &answers[k] {
            let g = &mut graded[i];
            let (p, q) = g.target.unwrap_or_default();
            // Right for the student's own accepted L (a total derivative added): full marks.
            if accepts(d) {
                g.status = Status::Correct;
                g.score = bank.problems[p].parts[q].points;
                g.codes = vec![d.code.to_string()];
                g.message = d.message.clone();
                continue;
            }
            // A list already partly right keeps the larger of its own score and the credit.
            g.score = g.score.max(credit * bank.problems[p].parts[q].points);
            g.codes.insert(0, d.code.to_string());
            g.message = d.message.clone();
        }
    }
}

/// The `follows-from-earlier` diagnosis when the wrong answer of `key` follows from the
/// earlier answers of `key`.
fn follows(key: &FollowKey, reps: &[Rep], bank: &Bank) -> Option<Diagnosis> {
    let rep = &reps[key.0];
    let problem = &bank.problems[rep.problem];
    let part = &problem.parts[rep.part];
    let earlier: Vec<(Earlier, Option<Verdict>)> = key
        .1
        .iter()
        .map(|&r| {
            let e = &reps[r];
            let id = problem.parts[e.part].id.clone();
            (Earlier::new(id, e.answer.clone()), e.verdict.clone().ok())
        })
        .collect();
    let list: Vec<Earlier> = earlier.iter().map(|(e, _)| e.clone()).collect();
    let known = |x: &Earlier| {
        earlier
            .iter()
            .find(|(e, _)| e == x)
            .and_then(|(_, v)| v.clone())
    };
    follows_from_earlier(problem, part, &rep.answer, &list, &known)
}

//! Rows → verdicts, checking as little as possible: answers are deduplicated on their exact
//! text, then on the checker's canonical form, and one representative per canonical form
//! (the first in input order) is checked; every row sharing it reuses the verdict (a list only
//! with the same text: its canonical form drops stated stability and item order). The two
//! passes run in parallel (rayon), one `Checker` per worker and problem. Which answer
//! represents a form never depends on the thread count, so neither does any output.

use rustc_hash::FxHashMap;

use rayon::prelude::*;

use lagrange::bank::Bank;
use lagrange::check::{Checker, Code, Diagnosis, Status as Checked, Verdict};
use lagrange::expr::error::{MAX_INPUT_BYTES, visible};
use lagrange::problem::{Part, PartKind, Problem};
use lagrange::progress::{Interrupted, Progress};
use lagrange::tutor::command::did_you_mean;
use lagrange::tutor::follow::{Earlier, accepts, follows_from_earlier};

use super::input::{Row, Table};
use crate::bar::Shared;

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
    settings: Settings,
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
                Ok((p, q)) => Ok(*by_text.entry((*p, *q, row.answer)).or_insert_with(|| {
                    distinct.push((*p, *q, table.answers.get(row.answer)));
                    distinct.len() as u32 - 1
                })),
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

/// The row that counts for each (student, problem, part): the last graded attempt, or with
/// `best` the highest-scoring one (the later of equals). Error rows never count. Rows are
/// bucketed by student (a counting sort: no hash map, memory of one index per row), then each
/// student's rows are sorted by part and chosen from, students in parallel.
struct Finals {
    /// Where each student's rows start in `order` (the last bucket: rows without a student),
    /// one more entry than buckets.
    start: Vec<u32>,
    /// How many of each bucket's rows count (they come first in the bucket).
    count: Vec<u32>,
    /// Row indices per bucket: first the rows that count, sorted by (problem, part).
    order: Vec<u32>,
}

impl Finals {
    /// The rows that count, per student.
    fn new(rows: &[Row], judged: &Judged, students: usize, best: bool) -> Finals {
        let bucket = |row: &Row| (row.student as usize).min(students);
        let target = |i: u32| judged.outcome(i as usize).target;
        let graded = |i: usize| {
            let g = judged.outcome(i);
            g.target.is_some() && g.status != Status::Error
        };
        let mut start = vec![0u32; students + 3];
        for (i, row) in rows.iter().enumerate() {
            if graded(i) {
                start[bucket(row) + 2] += 1;
            }
        }
        for b in 2..start.len() {
            start[b] += start[b - 1];
        }
        // `start[b + 1]` is now where bucket b starts; filling moves it to where b ends.
        let mut order = vec![0u32; start[students + 2] as usize];
        for (i, row) in rows.iter().enumerate() {
            if graded(i) {
                let at = &mut start[bucket(row) + 1];
                order[*at as usize] = i as u32;
                *at += 1;
            }
        }
        start.pop();
        let mut slices: Vec<&mut [u32]> = Vec::with_capacity(students + 1);
        let mut rest: &mut [u32] = &mut order;
        for w in start.windows(2) {
            let (head, tail) = rest.split_at_mut((w[1] - w[0]) as usize);
            slices.push(head);
            rest = tail;
        }
        let count: Vec<u32> = slices
            .into_par_iter()
            .with_min_len(256)
            .map(|rows| {
                // A stable sort: each part's rows stay in input order.
                rows.sort_by_key(|&i| target(i));
                let mut kept = 0;
                let mut i = 0;
                while i < rows.len() {
                    let t = target(rows[i]);
                    let mut slot = rows[i];
                    let mut j = i + 1;
                    while j < rows.len() && target(rows[j]) == t {
                        let score = judged.outcome(rows[j] as usize).score;
                        if !best || judged.outcome(slot as usize).score <= score {
                            slot = rows[j];
                        }
                        j += 1;
                    }
                    rows[kept] = slot;
                    kept += 1;
                    i = j;
                }
                kept as u32
            })
            .collect();
        Finals {
            start,
            count,
            order,
        }
    }

    /// The rows that count, in no particular order.
    fn rows(&self) -> impl Iterator<Item = usize> + '_ {
        (self.count.iter().enumerate())
            .flat_map(|(b, &n)| self.chosen(b, n))
            .map(|&i| i as usize)
    }

    /// Bucket `b`'s first `n` rows.
    fn chosen(&self, b: usize, n: u32) -> &[u32] {
        let s = self.start[b] as usize;
        &self.order[s..s + n as usize]
    }

    /// The row that counts for `student` (an index of [`Table::students`], or `NONE`) on
    /// part `(p, q)`.
    fn get(&self, judged: &Judged, student: u32, target: (usize, usize)) -> Option<usize> {
        let b = (student as usize).min(self.count.len() - 1);
        let rows = self.chosen(b, self.count[b]);
        let k = rows
            .binary_search_by_key(&Some(target), |&i| judged.outcome(i as usize).target)
            .ok()?;
        Some(rows[k] as usize)
    }
}

/// Sets `counts` on the rows that count.
fn mark_counted(rows: &[Row], judged: &mut Judged, students: usize, best: bool) {
    let finals = Finals::new(rows, judged, students, best);
    for i in finals.rows() {
        judged.rows[i].counts = true;
    }
}

/// One follow-through question: a wrong answer (by representative) and the student's final
/// answers to the problem's other parts (by representative, in part order).
type FollowKey = (usize, Vec<usize>);

/// Gives credit to incorrect answers that follow from the same student's own wrong answers to
/// the other parts. Each distinct question is asked once, in parallel; the rows asking one
/// share its outcome.
fn follow_through(
    rows: &[Row],
    judged: &mut Judged,
    bank: &Bank,
    credit: f64,
    students: usize,
    best: bool,
) {
    let finals = Finals::new(rows, judged, students, best);
    // An earlier answer follow-through can start from: a wrong one, or a Lagrangian accepted
    // though it is not T − V (`accepts`). `follows_from_earlier` passes over every other one
    // without looking further, so leaving them out of a question changes no answer, and
    // makes far fewer distinct questions (most earlier answers are right).
    let source: Vec<bool> = (judged.reps.iter())
        .map(|r| match &r.verdict {
            Ok(v) => match v.status {
                Checked::Incorrect => true,
                Checked::Correct => v.diagnoses.first().is_some_and(accepts),
                Checked::Invalid => false,
            },
            Err(_) => false,
        })
        .collect();
    let mut keys: Vec<(FollowKey, u32)> = Vec::new();
    let mut index: FxHashMap<FollowKey, usize> = FxHashMap::default();
    let mut asks: Vec<(usize, usize)> = Vec::new();
    for (i, row) in rows.iter().enumerate() {
        let g = judged.outcome(i);
        let (Status::Incorrect, Some((p, q)), Some(rep)) = (g.status, g.target, g.rep) else {
            continue;
        };
        let earlier: Vec<usize> = (0..bank.problems[p].parts.len())
            .filter(|&o| o != q)
            .filter_map(|o| finals.get(judged, row.student, (p, o)))
            .filter_map(|j| judged.outcome(j).rep)
            .filter(|&r| source[r])
            .collect();
        if earlier.is_empty() {
            continue;
        }
        let key = (rep, earlier);
        let k = match index.get(&key) {
            Some(&k) => k,
            None => {
                index.insert(key.clone(), keys.len());
                keys.push((key, judged.rows[i].outcome));
                keys.len() - 1
            }
        };
        asks.push((i, k));
    }
    // `follows_from_earlier` takes the most recent earlier answer the wrong one follows from,
    // judging each earlier answer on its own: so each (answer, earlier answer) pair is asked
    // once, in parallel, and a question's answer is its first pair that follows, latest first.
    let reps = &judged.reps;
    let mut pairs: Vec<(usize, usize)> = keys
        .iter()
        .flat_map(|((rep, earlier), _)| earlier.iter().map(move |&e| (*rep, e)))
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    let pair_answers: Vec<Option<Diagnosis>> = pairs
        .par_iter()
        .map(|&(rep, e)| follows(&(rep, vec![e]), reps, bank))
        .collect();
    let pair_answer: FxHashMap<(usize, usize), &Diagnosis> = (pairs.iter().zip(&pair_answers))
        .filter_map(|(&k, d)| Some((k, d.as_ref()?)))
        .collect();
    let answers: Vec<Option<Diagnosis>> = (keys.iter())
        .map(|((rep, earlier), _)| {
            let mut latest_first = earlier.iter().rev();
            latest_first.find_map(|&e| pair_answer.get(&(*rep, e)).map(|&d| d.clone()))
        })
        .collect();
    // The outcome each question gives (`None`: the answer does not follow; it keeps its own).
    let given: Vec<Option<u32>> = keys
        .iter()
        .zip(&answers)
        .map(|((_, own), d)| {
            let d = d.as_ref()?;
            let mut g = judged.outcomes[*own as usize].clone();
            let (p, q) = g.target.unwrap_or_default();
            let points = bank.problems[p].parts[q].points;
            // Right for the student's own accepted L (a total derivative added): full marks.
            if accepts(d) {
                g.status = Status::Correct;
                g.score = points;
                g.codes = vec![d.code];
            } else {
                // A list already partly right keeps the larger of its own score and the credit.
                g.score = g.score.max(credit * points);
                g.codes.insert(0, d.code);
            }
            g.message = Some(d.message.clone());
            Some(judged.add(g))
        })
        .collect();
    for (i, k) in asks {
        if let Some(o) = given[k] {
            judged.rows[i].outcome = o;
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

//! Which rows count — each student's last (or best) attempt at each part — and the
//! follow-through credit given to a counted wrong answer that follows from the same student's
//! own counted answers to the problem's other parts. The rules (which attempt, the penalty,
//! the credit) are the library's `lagrange::policy`; this file finds the rows they apply to,
//! in parallel.

use rustc_hash::FxHashMap;

use rayon::prelude::*;

use lagrange::bank::Bank;
use lagrange::check::{Diagnosis, Status as Checked, Verdict};
use lagrange::policy::Policy;
use lagrange::tutor::follow::{Earlier, accepts, follows_from_earlier};

use super::super::input::Row;
use super::super::intern::Interner;
use super::{Judged, Status};

/// The row that counts for each (student, problem, part), as the policy chooses it (the last
/// graded attempt, or the best after the attempt penalty). Error rows never count. Rows are
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
    /// Counted rows whose score the attempt penalty lowers, with the score they count for.
    penalised: Vec<(u32, f64)>,
}

impl Finals {
    /// The rows that count, per student.
    fn new(rows: &[Row], judged: &Judged, bank: &Bank, policy: &Policy, students: usize) -> Finals {
        let bucket = |row: &Row| (row.student as usize).min(students);
        let target = |i: u32| judged.brief(i as usize).target;
        let graded = |i: usize| {
            let g = judged.brief(i);
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
        let chosen: Vec<(u32, Vec<(u32, f64)>)> = slices
            .into_par_iter()
            .with_min_len(256)
            .map(|rows| {
                // A stable sort: each part's rows stay in input order (attempt order).
                rows.sort_by_key(|&i| target(i));
                let mut penalised = Vec::new();
                let mut kept = 0;
                let mut i = 0;
                while i < rows.len() {
                    let t = target(rows[i]);
                    let mut j = i + 1;
                    while j < rows.len() && target(rows[j]) == t {
                        j += 1;
                    }
                    let points = t.map_or(0.0, |(p, q)| bank.problems[p].parts[q].points);
                    let scores = rows[i..j].iter().map(|&r| judged.brief(r as usize).score);
                    let (k, score) = policy.counted(scores, points).unwrap_or((j - i - 1, 0.0));
                    let slot = rows[i + k];
                    if score != judged.brief(slot as usize).score {
                        penalised.push((slot, score));
                    }
                    rows[kept] = slot;
                    kept += 1;
                    i = j;
                }
                (kept as u32, penalised)
            })
            .collect();
        let mut count = Vec::with_capacity(chosen.len());
        let mut penalised = Vec::new();
        for (n, p) in chosen {
            count.push(n);
            penalised.extend(p);
        }
        Finals {
            start,
            count,
            order,
            penalised,
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
            .binary_search_by_key(&Some(target), |&i| judged.brief(i as usize).target)
            .ok()?;
        Some(rows[k] as usize)
    }
}

/// Sets `counts` on the rows that count, and the score of those the attempt penalty lowers.
pub(super) fn mark_counted(
    rows: &[Row],
    judged: &mut Judged,
    bank: &Bank,
    policy: &Policy,
    students: usize,
) {
    let finals = Finals::new(rows, judged, bank, policy, students);
    for i in finals.rows() {
        judged.rows[i].counts = true;
    }
    judged.penalised = finals.penalised.into_iter().collect();
}

/// One follow-through question: a wrong answer (by representative) and the student's final
/// answers to the problem's other parts (by representative, in part order).
type FollowKey = (usize, Vec<usize>);

/// Gives credit to incorrect answers that follow from the same student's own wrong answers to
/// the other parts. Each distinct question is asked once, in parallel; the rows asking one
/// share its outcome.
pub(super) fn follow_through(
    rows: &[Row],
    answers: &Interner,
    judged: &mut Judged,
    bank: &Bank,
    policy: &Policy,
    students: usize,
) {
    let finals = Finals::new(rows, judged, bank, policy, students);
    // An earlier answer follow-through can start from: a wrong one, or a Lagrangian accepted
    // though it is not T − V (`accepts`). `follows_from_earlier` passes over every other one
    // without looking further, so leaving them out of a question changes no answer, and
    // makes far fewer distinct questions (most earlier answers are right).
    let source: Vec<bool> = (judged.reps.iter())
        .map(|r| match &r.verdict {
            Ok(v) => match v.status {
                Checked::Incorrect => true,
                Checked::Correct => {
                    (v.first(judged.codes(v), &judged.said(v)).as_ref()).is_some_and(accepts)
                }
                Checked::Invalid => false,
            },
            Err(_) => false,
        })
        .collect();
    let mut keys: Vec<(FollowKey, u32)> = Vec::new();
    let mut index: FxHashMap<FollowKey, usize> = FxHashMap::default();
    let mut asks: Vec<(usize, usize)> = Vec::new();
    for (i, row) in rows.iter().enumerate() {
        let g = judged.brief(i);
        let (Status::Incorrect, Some((p, q)), Some(rep)) = (g.status, g.target, g.rep) else {
            continue;
        };
        let earlier: Vec<usize> = (0..bank.problems[p].parts.len())
            .filter(|&o| o != q)
            .filter_map(|o| finals.get(judged, row.student, (p, o)))
            .filter_map(|j| judged.brief(j).rep)
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
    let read: &Judged = judged;
    let mut pairs: Vec<(usize, usize)> = keys
        .iter()
        .flat_map(|((rep, earlier), _)| earlier.iter().map(move |&e| (*rep, e)))
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    let pair_answers: Vec<Option<Diagnosis>> = pairs
        .par_iter()
        .map(|&(rep, e)| follows(&(rep, vec![e]), read, answers, bank))
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
            let mut g = judged.outcome_at(*own).into_owned();
            let (p, q) = g.target.unwrap_or_default();
            let points = bank.problems[p].parts[q].points;
            // Right for the student's own accepted L (a total derivative added): full marks.
            if accepts(d) {
                g.status = Status::Correct;
                g.score = points;
                g.codes = std::sync::Arc::from([d.code]);
            } else {
                // A list already partly right keeps the larger of its own score and the credit.
                let own = if points > 0.0 { g.score / points } else { 0.0 };
                g.score = policy.follow_through_fraction(own).unwrap_or(own) * points;
                g.codes = std::iter::once(d.code)
                    .chain(g.codes.iter().copied())
                    .collect();
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
fn follows(key: &FollowKey, judged: &Judged, answers: &Interner, bank: &Bank) -> Option<Diagnosis> {
    let reps = &judged.reps;
    let rep = &reps[key.0];
    let problem = &bank.problems[rep.problem as usize];
    let part = &problem.parts[rep.part as usize];
    let earlier: Vec<(Earlier, Option<Verdict>)> = key
        .1
        .iter()
        .map(|&r| {
            let e = &reps[r];
            let id = problem.parts[e.part as usize].id.clone();
            (
                Earlier::new(id, answers.get(e.answer).to_string()),
                (e.verdict.as_ref().ok())
                    .map(|v| v.verdict(judged.codes(v), &judged.reading(r), &judged.said(v))),
            )
        })
        .collect();
    let list: Vec<Earlier> = earlier.iter().map(|(e, _)| e.clone()).collect();
    let known = |x: &Earlier| {
        earlier
            .iter()
            .find(|(e, _)| e == x)
            .and_then(|(_, v)| v.clone())
    };
    follows_from_earlier(problem, part, answers.get(rep.answer), &list, &known)
}

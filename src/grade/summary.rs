//! What the class got right and wrong: per-part counts, diagnosis-code counts and the most
//! common wrong answers grouped by mathematical equivalence (the checker's fingerprint: equal
//! at the sample points). Built from counts only, in `BTreeMap`s, with ties broken by text, so
//! nothing in it depends on row order or thread count. Rendered as Markdown and JSON.

use std::collections::BTreeMap;

use rayon::prelude::*;
use rustc_hash::FxHashMap;
use std::fmt::Write as _;

use serde::Serialize;

use lagrange::bank::Bank;

use super::input::Table;
use super::judge::{Judged, Status};

/// How many wrong-answer groups are listed per part.
const MAX_GROUPS: usize = 10;
/// How long a spelling may be in the summary before it is cut.
const MAX_SHOWN: usize = 80;

/// The whole class at a glance.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// The run's id, as in every row of results.csv.
    pub run: String,
    /// Rows of results.csv (= answers in the input).
    pub rows: usize,
    /// Distinct non-empty student keys.
    pub students: usize,
    /// Rows by status (correct, incorrect, invalid, error).
    pub status: BTreeMap<String, usize>,
    /// Per `PROBLEM/PART`.
    pub parts: BTreeMap<String, PartSummary>,
    /// How many rows carry each diagnosis code.
    pub codes: BTreeMap<String, usize>,
}

/// One part's answers.
#[derive(Debug, Serialize)]
pub struct PartSummary {
    /// The part's weight.
    pub points: f64,
    /// Every attempt, counted or not.
    pub answers: usize,
    /// Attempts by status.
    pub correct: usize,
    /// Readable but wrong.
    pub incorrect: usize,
    /// Unreadable (or too long to read).
    pub invalid: usize,
    /// Not gradable (the part could not be prepared).
    pub error: usize,
    /// Students whose answer counts for this part.
    pub students: usize,
    /// Mean score (in points) of the answers that count.
    pub mean_score: f64,
    /// The most common wrong (readable, incorrect) answers, grouped by meaning.
    pub wrong: Vec<Group>,
    /// Wrong answers in groups not listed.
    pub other_wrong: usize,
    /// The most common unreadable (invalid) answers, grouped by their text: kept apart from
    /// the mistakes, which are about physics.
    pub unreadable: Vec<Group>,
    /// Unreadable answers in groups not listed.
    pub other_unreadable: usize,
}

/// Wrong answers equal at the sample points (or, unreadable, equal as typed).
#[derive(Debug, Serialize)]
pub struct Group {
    /// Students who gave an answer of the group (each counted once).
    pub students: usize,
    /// Rows (attempts) in the group.
    pub count: usize,
    /// `incorrect` or `invalid`.
    pub status: String,
    /// The group's most common reading, in Unicode.
    pub answer: String,
    /// The diagnosis codes of that reading.
    pub codes: Vec<String>,
    /// The first diagnosis of that reading.
    pub diagnosis: String,
    /// Up to two spellings as typed, most common first.
    pub examples: Vec<String>,
}

/// A group of wrong answers: its part, its status and its meaning (an index).
type GroupKey = ((usize, usize), Status, usize);

/// A group counted: rows, distinct students, rows per representative and per spelling (an
/// interned answer), each list sorted.
struct Tally {
    count: usize,
    students: usize,
    by_rep: Vec<(usize, usize)>,
    by_answer: Vec<(u32, usize)>,
}

/// Runs of equal values in a sorted list, with their lengths.
fn runs<T: PartialEq + Copy>(sorted: impl IntoIterator<Item = T>) -> Vec<(T, usize)> {
    let mut out: Vec<(T, usize)> = Vec::new();
    for x in sorted {
        match out.last_mut() {
            Some((y, n)) if *y == x => *n += 1,
            _ => out.push((x, 1)),
        }
    }
    out
}

/// Counts each group from its rows' (student, representative, answer), sorted.
fn tally(rows: &[(u32, u32, u32, u32)]) -> Tally {
    let students = runs(rows.iter().map(|r| r.1)).len();
    let mut reps: Vec<u32> = rows.iter().map(|r| r.2).collect();
    reps.sort_unstable();
    let mut answers: Vec<u32> = rows.iter().map(|r| r.3).collect();
    answers.sort_unstable();
    Tally {
        count: rows.len(),
        students,
        by_rep: runs(reps.into_iter().map(|r| r as usize)),
        by_answer: runs(answers),
    }
}

/// The summary of a judged class: counted per outcome and per group, never per row's text.
pub fn summarise(table: &Table, judged: &Judged, bank: &Bank) -> Summary {
    let rows = &table.rows;
    // Rows per outcome, then everything an outcome decides is counted once per outcome.
    let mut per_outcome = vec![0usize; judged.outcomes.len()];
    let mut parts: FxHashMap<(usize, usize), PartSummary> = FxHashMap::default();
    let mut sums: FxHashMap<(usize, usize), f64> = FxHashMap::default();
    // The meaning of each representative, interned: a group is (part, status, meaning).
    let mut meanings: FxHashMap<std::borrow::Cow<str>, usize> = FxHashMap::default();
    let meaning: Vec<usize> = judged
        .reps
        .iter()
        .map(|r| {
            let m = r.fingerprint.as_deref().map_or_else(
                || format!("text:{}", r.answer.trim()).into(),
                std::borrow::Cow::Borrowed,
            );
            let n = meanings.len();
            *meanings.entry(m).or_insert(n)
        })
        .collect();
    // Each outcome's group (wrong and unreadable answers only), numbered once.
    let mut group_ids: FxHashMap<GroupKey, u32> = FxHashMap::default();
    let mut groups: Vec<GroupKey> = Vec::new();
    let group_of: Vec<u32> = (judged.outcomes.iter())
        .map(|o| match (o.target, o.rep, o.status) {
            (Some(t), Some(rep), Status::Incorrect | Status::Invalid) => *group_ids
                .entry((t, o.status, meaning[rep]))
                .or_insert_with(|| {
                    groups.push((t, o.status, meaning[rep]));
                    groups.len() as u32 - 1
                }),
            _ => u32::MAX,
        })
        .collect();
    drop(group_ids);
    // Per row of a group: (group, student, representative, answer), sorted in parallel and
    // counted per group: no set or map per group.
    let mut members: Vec<(u32, u32, u32, u32)> = Vec::new();
    for (i, (row, g)) in rows.iter().zip(&judged.rows).enumerate() {
        per_outcome[g.outcome as usize] += 1;
        let o = judged.outcome(i);
        let Some((p, q)) = o.target else { continue };
        if g.counts {
            parts
                .entry((p, q))
                .or_insert_with(|| empty(bank.problems[p].parts[q].points))
                .students += 1;
            *sums.entry((p, q)).or_insert(0.0) += o.score;
        }
        let group = group_of[g.outcome as usize];
        if let (true, Some(rep)) = (group != u32::MAX, o.rep) {
            members.push((group, row.student, rep as u32, row.answer));
        }
    }
    members.par_sort_unstable();
    let tallies: Vec<(GroupKey, Tally)> = members
        .par_chunk_by(|a, b| a.0 == b.0)
        .map(|rows| (groups[rows[0].0 as usize], tally(rows)))
        .collect();
    drop(members);
    let mut status = BTreeMap::new();
    let mut codes = BTreeMap::new();
    for (o, &n) in judged.outcomes.iter().zip(&per_outcome) {
        if n == 0 {
            continue;
        }
        *status.entry(o.status.name().to_string()).or_insert(0) += n;
        for c in &o.codes {
            *codes.entry(c.to_string()).or_insert(0) += n;
        }
        let Some((p, q)) = o.target else { continue };
        let s = parts
            .entry((p, q))
            .or_insert_with(|| empty(bank.problems[p].parts[q].points));
        s.answers += n;
        match o.status {
            Status::Correct => s.correct += n,
            Status::Incorrect => s.incorrect += n,
            Status::Invalid => s.invalid += n,
            Status::Error => s.error += n,
        }
    }
    for (t, s) in parts.iter_mut() {
        let sum = sums.get(t).copied().unwrap_or(0.0);
        // `+ 0.0` turns a −0.0 into 0.0.
        s.mean_score = if s.students == 0 {
            0.0
        } else {
            sum / s.students as f64 + 0.0
        };
    }
    let key = |(p, q): (usize, usize)| {
        let problem = &bank.problems[p];
        format!("{}/{}", problem.id, problem.parts[q].id)
    };
    let mut parts: BTreeMap<String, PartSummary> =
        parts.into_iter().map(|(t, s)| (key(t), s)).collect();
    let tallies = tallies
        .into_iter()
        .map(|((t, status, _), tally)| ((key(t), status), tally))
        .collect();
    add_groups(&mut parts, tallies, table, judged);
    Summary {
        run: String::new(),
        rows: rows.len(),
        students: table.students.len(),
        status,
        parts,
        codes,
    }
}

/// The distinct non-empty students, in order of first appearance.
pub fn students(table: &Table) -> Vec<&str> {
    table.students.iter().map(String::as_str).collect()
}

fn empty(points: f64) -> PartSummary {
    PartSummary {
        points,
        answers: 0,
        correct: 0,
        incorrect: 0,
        invalid: 0,
        error: 0,
        students: 0,
        mean_score: 0.0,
        wrong: Vec::new(),
        other_wrong: 0,
        unreadable: Vec::new(),
        other_unreadable: 0,
    }
}

/// Turns the tallies into each part's sorted, truncated group list. Groups are ordered by
/// their counts and full text ([`Shown`]); only the listed ones are made whole (codes,
/// diagnosis, cut spellings), so a class of all-different answers keeps no more than the
/// text each is sorted by.
fn add_groups(
    parts: &mut BTreeMap<String, PartSummary>,
    tallies: Vec<((String, Status), Tally)>,
    table: &Table,
    judged: &Judged,
) {
    // Per part and kind (wrong, unreadable): the best groups so far and the rows of all.
    // Cut back to the listed few whenever many have gathered, so a class of all-different
    // answers never holds every group's text at once (the order is total up to ties, which
    // a stable sort keeps in order of first appearance, as one sort of all would).
    let order = |a: &Shown, b: &Shown| {
        b.students
            .cmp(&a.students)
            .then_with(|| b.count.cmp(&a.count))
            .then_with(|| a.full.cmp(&b.full))
    };
    let mut per_part: BTreeMap<(String, bool), (Vec<Shown>, usize)> = BTreeMap::new();
    for ((key, status), t) in tallies {
        let (best, rows) = per_part
            .entry((key, status == Status::Invalid))
            .or_default();
        *rows += t.count;
        best.push(shown(status, t, table, judged));
        if best.len() >= 8 * MAX_GROUPS {
            best.sort_by(order);
            best.truncate(MAX_GROUPS);
        }
    }
    for ((key, unreadable), (mut best, rows)) in per_part {
        best.sort_by(order);
        best.truncate(MAX_GROUPS);
        let other = rows - best.iter().map(|g| g.count).sum::<usize>();
        let listed: Vec<Group> = best.into_iter().map(|g| group(g, judged)).collect();
        if let Some(s) = parts.get_mut(&key) {
            if unreadable {
                (s.unreadable, s.other_unreadable) = (listed, other);
            } else {
                (s.wrong, s.other_wrong) = (listed, other);
            }
        }
    }
}

/// A group as it is sorted: its counts, its most common reading (ties: the smaller text) and
/// the representative giving it, and its spellings as typed (trimmed), most common first.
struct Shown {
    students: usize,
    count: usize,
    status: Status,
    rep: Option<usize>,
    /// The reading and spellings uncut: ties in the order are broken by the full text,
    /// never by the cut one.
    full: (String, Vec<String>),
}

/// How a tallied group is sorted and shown.
fn shown(status: Status, t: Tally, table: &Table, judged: &Judged) -> Shown {
    let shown_of = |rep: usize| {
        let r = &judged.reps[rep];
        match &r.verdict {
            Ok(v) if !v.reading.unicode.is_empty() => v.reading.unicode.clone(),
            _ => r.answer.trim().to_string(),
        }
    };
    let mut reps: Vec<(usize, String, usize)> =
        t.by_rep.iter().map(|&(r, n)| (n, shown_of(r), r)).collect();
    reps.sort_by(|a, b| b.0.cmp(&a.0).then_with(|| a.1.cmp(&b.1)));
    let (answer, rep) = reps
        .into_iter()
        .next()
        .map(|(_, s, r)| (s, Some(r)))
        .unwrap_or_default();
    let mut by_text: FxHashMap<&str, usize> = FxHashMap::default();
    for &(a, n) in &t.by_answer {
        *by_text.entry(table.answers.get(a).trim()).or_insert(0) += n;
    }
    let mut texts: Vec<(&str, usize)> = by_text.into_iter().collect();
    texts.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(b.0)));
    Shown {
        students: t.students,
        count: t.count,
        status,
        rep,
        full: (answer, texts.iter().map(|(s, _)| s.to_string()).collect()),
    }
}

/// One listed group: shown as its most common reading, with that reading's codes and first
/// diagnosis and its two most common spellings.
fn group(g: Shown, judged: &Judged) -> Group {
    let verdict = g.rep.and_then(|r| judged.reps[r].verdict.as_ref().ok());
    Group {
        students: g.students,
        count: g.count,
        status: g.status.name().to_string(),
        answer: cut(&g.full.0),
        codes: verdict.map_or(Vec::new(), |v| {
            v.diagnoses.iter().map(|d| d.code.to_string()).collect()
        }),
        diagnosis: verdict
            .and_then(|v| v.diagnoses.first())
            .map_or(String::new(), |d| d.message.clone()),
        examples: g.full.1.iter().take(2).map(|s| cut(s)).collect(),
    }
}

/// A text cut to [`MAX_SHOWN`] characters, on one line.
fn cut(s: &str) -> String {
    let one: String = s.split_whitespace().collect::<Vec<_>>().join(" ");
    if one.chars().count() <= MAX_SHOWN {
        return one;
    }
    let mut t: String = one.chars().take(MAX_SHOWN - 1).collect();
    t.push('…');
    t
}

/// A number as the outputs print it: at most 4 decimals, no trailing zeros.
pub fn num(x: f64) -> String {
    let s = format!("{x:.4}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s == "-0" {
        "0".to_string()
    } else {
        s.to_string()
    }
}

/// A Markdown table cell of text: control characters shown escaped (`\u{1b}`), HTML's
/// `& < >` as entities and the marks Markdown acts on inside a line (`\ ` * _ [ ] | ~`)
/// backslash-escaped, so a student's text is shown, never run (no link, no image, no tag, no
/// emphasis, no broken table). Nothing in a cell is at the start of a line.
pub(super) fn cell(s: &str) -> String {
    let s = lagrange::expr::error::visible(s);
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '\\' | '`' | '*' | '_' | '[' | ']' | '|' | '~' => {
                out.push('\\');
                out.push(c);
            }
            _ => out.push(c),
        }
    }
    out
}

/// A Markdown code span of text, in a table cell: control characters shown escaped, pipes
/// escaped (a table would split there), fenced by more backticks than the text holds in a
/// row. Inside a code span nothing is interpreted, HTML included.
fn code(s: &str) -> String {
    let s = lagrange::expr::error::visible(s).replace('|', "\\|");
    let longest = s.split(|c| c != '`').map(str::len).max().unwrap_or(0);
    if longest == 0 {
        return format!("`{s}`");
    }
    let fence = "`".repeat(longest + 1);
    format!("{fence} {s} {fence}")
}

/// The summary as Markdown (summary.md).
pub fn markdown(s: &Summary) -> String {
    let mut out = String::from("# Grading summary\n\n");
    let errors = s.status.get("error").copied().unwrap_or(0);
    let _ = writeln!(
        out,
        "{} students, {} answers; {} correct, {} incorrect, {} invalid, {errors} errors \
         (see results.csv).\n",
        s.students,
        s.rows,
        s.status.get("correct").copied().unwrap_or(0),
        s.status.get("incorrect").copied().unwrap_or(0),
        s.status.get("invalid").copied().unwrap_or(0),
    );
    out.push_str("## Parts\n\n");
    out.push_str(
        "| part | points | answers | correct | incorrect | invalid | error | mean score |\n",
    );
    out.push_str("|---|---:|---:|---:|---:|---:|---:|---:|\n");
    for (key, p) in &s.parts {
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} | {} | {} |",
            cell(key),
            num(p.points),
            p.answers,
            p.correct,
            p.incorrect,
            p.invalid,
            p.error,
            num(p.mean_score)
        );
    }
    if !s.codes.is_empty() {
        out.push_str("\n## Diagnosis codes\n\n| code | answers |\n|---|---:|\n");
        for (c, n) in &s.codes {
            let _ = writeln!(out, "| {} | {n} |", cell(c));
        }
    }
    wrong_answers(s, &mut out);
    out
}

/// The "most common wrong answers" section, then the unreadable answers apart.
fn wrong_answers(s: &Summary, out: &mut String) {
    out.push_str("\n## Most common wrong answers\n\nGrouped by meaning: answers equal at the sample points are one group; students count once per group.\n");
    for (key, p) in &s.parts {
        groups_table(out, key, &p.wrong, p.other_wrong, "wrong");
    }
    if s.parts.values().any(|p| !p.unreadable.is_empty()) {
        out.push_str("\n## Unreadable answers\n\nAnswers lagrange could not read (syntax, the wrong kind of answer), grouped by their text.\n");
        for (key, p) in &s.parts {
            groups_table(out, key, &p.unreadable, p.other_unreadable, "unreadable");
        }
    }
}

/// One part's table of groups (nothing when there are none).
fn groups_table(out: &mut String, key: &str, groups: &[Group], other: usize, what: &str) {
    if groups.is_empty() {
        return;
    }
    let _ = write!(
        out,
        "\n### {}\n\n| students | answers | answer (as read) | codes | diagnosis | typed as |\n|---:|---:|---|---|---|---|\n",
        cell(key)
    );
    for g in groups {
        let typed: Vec<String> = g.examples.iter().map(|e| code(e)).collect();
        let _ = writeln!(
            out,
            "| {} | {} | {} | {} | {} | {} |",
            g.students,
            g.count,
            code(&g.answer),
            cell(&g.codes.join(", ")),
            cell(&g.diagnosis),
            typed.join(", ")
        );
    }
    if other > 0 {
        let _ = writeln!(out, "\n{other} more {what} answers in smaller groups.");
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::grade::judge::Rep;

    /// Many wrong-answer groups in one part, most of them tied (one student, one attempt
    /// each, as in a class of all-different answers): the groups listed and the count of the
    /// others are those one sort of every group gives, though only the best few are kept
    /// while counting.
    #[test]
    fn the_listed_groups_are_the_best_of_all_however_many() {
        let mut csv = String::from("student,problem,part,answer\n");
        let n = 500;
        for i in 0..n {
            csv.push_str(&format!("s{i},p,q,answer {:03}\n", (i * 7919) % n));
        }
        let table = super::super::input::parse(csv.as_bytes(), &mut Default::default());
        let table = table.map_err(|e| e.0).unwrap_or_else(|e| panic!("{e}"));
        let reps: Vec<Rep> = (0..n)
            .map(|a| Rep {
                problem: 0,
                part: 0,
                answer: table.answers.get(a as u32).to_string(),
                verdict: Err(String::new()),
                fingerprint: None,
            })
            .collect();
        let judged = Judged {
            rows: Vec::new(),
            outcomes: Vec::new(),
            reps,
            penalised: Default::default(),
        };
        // Group g holds representative g; a few groups have more students and attempts.
        let tallies = |k: usize| -> Vec<((String, Status), Tally)> {
            (0..k)
                .map(|g| {
                    let extra = usize::from(g % 97 == 3) * (g % 5 + 1);
                    let tally = Tally {
                        count: 1 + extra,
                        students: 1 + extra / 2,
                        by_rep: vec![(g, 1 + extra)],
                        by_answer: vec![(g as u32, 1 + extra)],
                    };
                    (("p/q".to_string(), Status::Incorrect), tally)
                })
                .collect()
        };
        let mut parts = BTreeMap::from([("p/q".to_string(), empty(1.0))]);
        add_groups(&mut parts, tallies(n), &table, &judged);
        // The reference: every group shown, one stable sort, the first ten.
        let mut all: Vec<Shown> = (tallies(n).into_iter())
            .map(|((_, status), t)| shown(status, t, &table, &judged))
            .collect();
        all.sort_by(|a, b| {
            b.students
                .cmp(&a.students)
                .then_with(|| b.count.cmp(&a.count))
                .then_with(|| a.full.cmp(&b.full))
        });
        let want: Vec<(usize, usize, String)> = (all.iter().take(MAX_GROUPS))
            .map(|g| (g.students, g.count, g.full.0.clone()))
            .collect();
        let other: usize = all.iter().skip(MAX_GROUPS).map(|g| g.count).sum();
        let p = &parts["p/q"];
        let got: Vec<(usize, usize, String)> = (p.wrong.iter())
            .map(|g| (g.students, g.count, g.answer.clone()))
            .collect();
        assert_eq!(got, want);
        assert_eq!(p.other_wrong, other);
        assert!(want[0].0 > 1 && want[MAX_GROUPS - 1].0 == 1, "{want:?}");
    }
}

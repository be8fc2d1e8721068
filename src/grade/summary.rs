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

mod groups;
use groups::{Best, GROUP_BATCH, Shown, shown, tally};

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

/// What makes a group of wrong answers: its part, its status and its meaning (an index), in
/// 16 bytes (a class of all-different answers has a group per answer).
type GroupKey = ((u32, u32), Status, u32);

/// The summary of a judged class: counted per outcome and per group, never per row's text.
pub fn summarise(table: &Table, judged: &Judged, bank: &Bank) -> Summary {
    let rows = &table.rows;
    // Rows per outcome, then everything an outcome decides is counted once per outcome.
    let mut per_outcome = vec![0u32; judged.outcome_count()];
    let mut parts: FxHashMap<(usize, usize), PartSummary> = FxHashMap::default();
    let mut sums: FxHashMap<(usize, usize), f64> = FxHashMap::default();
    // The meaning of each representative as a number: a group is (part, status, meaning).
    // Meanings are 128-bit keys ([`super::judge::meaning`]), so none is kept as text; equal
    // keys are found by sorting them (24 bytes each, not a map's 32 and its spare room: a
    // class of all-different answers has a key per answer), each numbered by the first
    // representative that has it.
    // A problem pinned to a student's numbers comes after the bank problem of its id. There
    // one reading means different things for different students (the same number is right
    // for one, off by some factor for another), so what the student is told is part of it.
    let mut ids = rustc_hash::FxHashSet::default();
    let pinned: Vec<bool> = (bank.problems.iter())
        .map(|p| !ids.insert(p.id.as_str()))
        .collect();
    drop(ids);
    let mut keyed: Vec<(u64, u64, u32)> = (judged.reps.par_iter().enumerate())
        .map(|(i, r)| {
            let mut m = judged.fingerprint(i).unwrap_or_else(|| {
                super::judge::meaning(&format!("text:{}", table.answers.get(r.answer).trim()))
            });
            if let (true, Ok(v)) = (pinned[r.problem as usize], &r.verdict) {
                m ^= super::judge::meaning(&format!("told:{}", judged.said(v)));
            }
            ((m >> 64) as u64, m as u64, i as u32)
        })
        .collect();
    keyed.par_sort_unstable();
    let mut meaning = vec![0u32; judged.reps.len()];
    for run in keyed.chunk_by(|a, b| (a.0, a.1) == (b.0, b.1)) {
        for &(_, _, r) in run {
            meaning[r as usize] = run[0].2;
        }
    }
    drop(keyed);
    // Each outcome's group (wrong and unreadable answers only), numbered in order of first
    // appearance (by outcome), found by sorting the outcomes' keys rather than through a map
    // of them (a class of all-different answers has a group per answer).
    let mut keyed: Vec<(GroupKey, u32)> = (judged.briefs().enumerate())
        .filter_map(|(i, o)| match (o.target, o.rep, o.status) {
            (Some((p, q)), Some(rep), Status::Incorrect | Status::Invalid) => {
                Some((((p as u32, q as u32), o.status, meaning[rep]), i as u32))
            }
            _ => None,
        })
        .collect();
    drop(meaning);
    keyed.par_sort_unstable();
    // A group goes by its first outcome (the first of its run, the runs being sorted by
    // outcome within): numbers in order of first appearance, with no list of the groups.
    let mut group_of = vec![u32::MAX; judged.outcome_count()];
    for run in keyed.chunk_by(|a, b| a.0 == b.0) {
        for &(_, o) in run {
            group_of[o as usize] = run[0].1;
        }
    }
    drop(keyed);
    // Per row of a group: (group, student, representative, answer), sorted in parallel and
    // counted per group: no set or map per group.
    let mut members: Vec<(u32, u32, u32, u32)> = Vec::new();
    for (i, (row, g)) in rows.iter().zip(&judged.rows).enumerate() {
        per_outcome[g.outcome as usize] += 1;
        let o = judged.brief(i);
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
    let key = |(p, q): (usize, usize)| {
        let problem = &bank.problems[p];
        format!("{}/{}", problem.id, problem.parts[q].id)
    };
    // Groups counted and shown a batch at a time (in parallel), each batch's kept in the best
    // few of its part: memory bounded however many groups there are.
    let mut best = Best::default();
    let mut chunks = members.chunk_by(|a, b| a.0 == b.0);
    loop {
        let batch: Vec<&[(u32, u32, u32, u32)]> = chunks.by_ref().take(GROUP_BATCH).collect();
        if batch.is_empty() {
            break;
        }
        let shown_batch: Vec<((String, Status), Shown)> = (batch.par_iter())
            .map(|rows| {
                // A group's part and status are its first outcome's.
                let first = judged.brief_at(rows[0].0);
                let t = first.target.unwrap_or_default();
                let status = first.status;
                ((key(t), status), shown(status, tally(rows), table, judged))
            })
            .collect();
        for ((k, status), g) in shown_batch {
            best.push(k, status, g);
        }
    }
    drop(members);
    let mut status = BTreeMap::new();
    let mut codes = BTreeMap::new();
    for (o, &n) in judged.outcomes().zip(&per_outcome) {
        let n = n as usize;
        if n == 0 {
            continue;
        }
        *status.entry(o.status.name().to_string()).or_insert(0) += n;
        for c in o.codes.iter() {
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
    let mut parts: BTreeMap<String, PartSummary> =
        parts.into_iter().map(|(t, s)| (key(t), s)).collect();
    best.finish(&mut parts, judged);
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

//! review.csv: the answers that need a human — every `invalid` answer and every wrong answer
//! whose only diagnosis is a bare `not-equal` — grouped by their exact text per part (and per
//! variant, where the student's numbers decide the verdict), with how
//! the checker tried to read them and an empty `decision` column for the instructor. Filled
//! in and given back with `grade --overrides`, its decisions apply on the next run, and the
//! next review.csv carries them (also those that matched no answer this time), so no decision
//! is lost by grading again.

use std::borrow::Cow;
use std::io::Write as _;

use lagrange::bank::Bank;
use lagrange::check::{Code, Status as Checked};

use super::input::Table;
use super::judge::{Judged, Outcome, Status};
use super::output::{push_cell, push_plain};
use super::overrides::Overrides;
use super::summary::num;
use super::variants::Variants;

/// The columns of review.csv.
const HEADER: [&str; 11] = [
    "problem", "part", "variant", "answer", "students", "answers", "status", "codes", "read_as",
    "message", "decision",
];

/// What the checker said of a row, before any override: status, codes, how it read the
/// answer, its message.
struct Said<'j> {
    status: &'static str,
    codes: Vec<Code>,
    read_as: Cow<'j, str>,
    message: Cow<'j, str>,
}

/// What the checker said of an outcome (from its representative's verdict when an override
/// replaced the outcome's own status and message).
fn said<'j>(o: &'j Outcome, judged: &'j Judged) -> Said<'j> {
    let rep = o.rep.map(|r| &judged.reps[r]);
    let verdict = rep.and_then(|r| r.verdict.as_ref().ok());
    let read_as = o.rep.map_or(Cow::Borrowed(""), |r| judged.reading(r));
    if o.decision.is_none() {
        return Said {
            status: o.status.name(),
            codes: o.codes.to_vec(),
            read_as,
            message: judged.message(o),
        };
    }
    match (rep, verdict) {
        (_, Some(v)) => Said {
            status: v.status.name(),
            codes: judged.codes(v).to_vec(),
            read_as,
            message: judged.said(v),
        },
        (Some(r), None) => Said {
            status: Status::Error.name(),
            codes: Vec::new(),
            read_as,
            message: Cow::Borrowed(r.verdict.as_ref().err().map_or("", |e| &**e)),
        },
        // Only an answer too long to read has no representative.
        (None, None) => Said {
            status: Checked::Invalid.name(),
            codes: Vec::new(),
            read_as,
            message: Cow::Borrowed("the answer is over the checker's limit; not read"),
        },
    }
}

/// Whether the checker's word on an answer needs a human: it could not read it, or found it
/// wrong without saying how.
fn needs_review(s: &Said) -> bool {
    s.status == Status::Invalid.name()
        || (s.status == Status::Incorrect.name() && s.codes == [Code::NotEqual])
}

/// review.csv as bytes, and the overrides entries (by index) that matched no answer of this
/// class (kept in the file, at its end, with 0 students).
pub fn review_csv(
    table: &Table,
    judged: &Judged,
    bank: &Bank,
    variants: &Variants,
    overrides: Option<&Overrides>,
) -> (Vec<u8>, Vec<usize>) {
    // (problem, part, the problem pinned to the student's numbers, answer, student, row) of
    // every row to list: one text is one answer per variant.
    let mut listed: Vec<(usize, usize, usize, u32, u32, u32)> = Vec::new();
    for (i, row) in table.rows.iter().enumerate() {
        let o = judged.outcome(i);
        let Some((p, q)) = o.target else { continue };
        if o.status == Status::Error {
            continue;
        }
        if o.decision.is_some() || needs_review(&said(&o, judged)) {
            let pinned = judged.judged_with(&o).unwrap_or(p);
            listed.push((p, q, pinned, row.answer, row.student, i as u32));
        }
    }
    listed.sort_unstable();
    struct Group {
        p: usize,
        q: usize,
        pinned: usize,
        row: usize,
        students: usize,
        answers: usize,
    }
    let mut groups: Vec<Group> = Vec::new();
    for w in 0..listed.len() {
        let (p, q, pinned, a, s, r) = listed[w];
        let same = w > 0 && {
            let b = listed[w - 1];
            (b.0, b.1, b.2, b.3) == (p, q, pinned, a)
        };
        if !same {
            groups.push(Group {
                p,
                q,
                pinned,
                row: r as usize,
                students: 0,
                answers: 0,
            });
        }
        let Some(g) = groups.last_mut() else { continue };
        g.answers += 1;
        // Sorted by student within a group: a new student is a change from the row before.
        if !same || listed[w - 1].4 != s {
            g.students += 1;
        }
    }
    drop(listed);
    let text = |g: &Group| table.answer(&table.rows[g.row]);
    let ids = |g: &Group| {
        let problem = &bank.problems[g.p];
        (problem.id.as_str(), problem.parts[g.q].id.as_str())
    };
    groups.sort_by(|a, b| {
        (b.students, b.answers)
            .cmp(&(a.students, a.answers))
            .then_with(|| ids(a).cmp(&ids(b)))
            .then_with(|| text(a).cmp(text(b)))
    });
    let decided = overrides.map(Overrides::by_key);
    let mut matched = vec![false; overrides.map_or(0, |o| o.entries.len())];
    let mut out = Vec::new();
    for (k, h) in HEADER.iter().enumerate() {
        if k > 0 {
            out.push(b',');
        }
        push_plain(&mut out, h);
    }
    out.push(b'\n');
    for g in &groups {
        let (problem, part) = ids(g);
        let variant = variants.label(g.pinned);
        let answer = text(g);
        let o = judged.outcome(g.row);
        let s = said(&o, judged);
        let decision = decided
            .as_ref()
            .and_then(|d| d.get(&(problem, part, variant, answer)).copied());
        if let Some(e) = decision {
            matched[e] = true;
        }
        let written = match (decision, overrides) {
            (Some(e), Some(o)) => o.entries[e].written.as_str(),
            _ => "",
        };
        let codes: Vec<&str> = s.codes.iter().map(|c| c.as_str()).collect();
        line(
            &mut out,
            [problem, part, variant, answer],
            [g.students, g.answers],
            [s.status, &codes.join(";")],
            [&s.read_as, &s.message, written],
        );
    }
    let unmatched: Vec<usize> = (0..matched.len()).filter(|&e| !matched[e]).collect();
    if let Some(o) = overrides {
        for &e in &unmatched {
            let e = &o.entries[e];
            line(
                &mut out,
                [&e.problem, &e.part, &e.variant, &e.answer],
                [0, 0],
                ["", ""],
                ["", "no answer of this class has this text", &e.written],
            );
        }
    }
    (out, unmatched)
}

/// One line of review.csv: text cells neutralised against spreadsheet formulas.
fn line(
    out: &mut Vec<u8>,
    [problem, part, variant, answer]: [&str; 4],
    [students, answers]: [usize; 2],
    [status, codes]: [&str; 2],
    [read_as, message, decision]: [&str; 3],
) {
    for (k, c) in [problem, part, variant, answer].iter().enumerate() {
        if k > 0 {
            out.push(b',');
        }
        push_cell(out, c);
    }
    let _ = write!(out, ",{students},{answers},");
    push_plain(out, status);
    out.push(b',');
    push_plain(out, codes);
    for c in [read_as, message, decision] {
        out.push(b',');
        push_cell(out, c);
    }
    out.push(b'\n');
}

/// The decision column's value in results.csv: the override's decision, else empty.
pub fn override_cell(o: &Outcome) -> String {
    o.decision.map_or(String::new(), |d| match d {
        lagrange::policy::Decision::Partial(x) => num(x),
        d => d.to_string(),
    })
}

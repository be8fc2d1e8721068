//! The files `lagrange grade` writes: results.csv (one row per answer), gradebook.csv (one
//! row per student), summary.md / summary.json, and an LMS import file, as bytes (written by
//! [`crate::outfile`]). Every text cell a spreadsheet would run as a formula is neutralised.

use std::borrow::Cow;
use std::io::Write;

use rayon::prelude::*;

use lagrange::bank::Bank;

use super::input::{Row, Table};
use super::judge::Judged;
use super::summary::{Summary, num, students};

/// The learning-management systems an import file can be written for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Lms {
    /// `canvas.csv`: Canvas's gradebook import.
    Canvas,
    /// `moodle.csv`: Moodle's "Import grades → CSV file".
    Moodle,
    /// `gradescope.csv`: Gradescope's score upload.
    Gradescope,
}

/// What a spreadsheet would run as a formula at the start of a cell.
const FORMULA_START: [char; 6] = ['=', '+', '-', '@', '\t', '\r'];

/// Whether a cell must be neutralised: it starts like a formula, or it is a neutralised cell
/// already (a `'` before such a start), so that reading back strips exactly one `'`.
fn needs_quote(s: &str) -> bool {
    s.starts_with(FORMULA_START) || s.strip_prefix('\'').is_some_and(needs_quote)
}

/// A text cell a spreadsheet will show rather than run: a leading `'` before `=`, `+`, `-`,
/// `@`, a tab or a carriage return (`=HYPERLINK(…)` → `'=HYPERLINK(…)`). [`unquote_cell`]
/// gives the text back.
pub fn quote_cell(s: &str) -> Cow<'_, str> {
    if needs_quote(s) {
        Cow::Owned(format!("'{s}"))
    } else {
        Cow::Borrowed(s)
    }
}

/// The text of a cell [`quote_cell`] wrote (the class file's own cells are read through it
/// too, so a results.csv graded again reads `-m g l cos θ` as typed).
pub fn unquote_cell(s: &str) -> &str {
    match s.strip_prefix('\'') {
        Some(rest) if needs_quote(rest) => rest,
        _ => s,
    }
}

/// A CSV document built in memory.
fn csv_bytes(
    header: &[&str],
    rows: impl IntoIterator<Item = Vec<String>>,
) -> anyhow::Result<Vec<u8>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record(header)?;
    for r in rows {
        w.write_record(&r)?;
    }
    w.into_inner().map_err(|e| anyhow::anyhow!("{e}"))
}

/// The rows formatted at once (in parallel), then written in order: memory stays bounded by
/// a batch, whatever the number of rows.
const BATCH: usize = 16 * 1024;

/// results.csv, streamed into `out`: every input answer, in input order, each row with the
/// run's id. Text cells are neutralised ([`quote_cell`]). Rows are formatted in parallel
/// batches; the bytes do not depend on the thread count.
pub fn results(
    out: &mut dyn Write,
    table: &Table,
    judged: &Judged,
    run: &str,
) -> std::io::Result<()> {
    let header = [
        "row", "student", "problem", "part", "answer", "status", "score", "codes", "message", "run",
    ];
    out.write_all(&csv_bytes(&header, std::iter::empty()).map_err(std::io::Error::other)?)?;
    // What an outcome writes, formatted once: score, codes, message.
    let shown: Vec<[String; 3]> = judged
        .outcomes
        .iter()
        .map(|o| {
            [
                num(o.score),
                o.codes.join(";"),
                quote_cell(&o.message).into_owned(),
            ]
        })
        .collect();
    let rows: Vec<(usize, &Row)> = table.rows.iter().enumerate().collect();
    for batch in rows.chunks(BATCH * rayon::current_num_threads().max(1)) {
        let parts: Vec<std::io::Result<Vec<u8>>> = batch
            .par_chunks(BATCH)
            .map(|chunk| {
                let mut w = csv::WriterBuilder::new()
                    .has_headers(false)
                    .from_writer(Vec::with_capacity(chunk.len() * 128));
                for &(i, r) in chunk {
                    let g = judged.rows[i];
                    let o = &judged.outcomes[g.outcome as usize];
                    let [score, codes, message] = &shown[g.outcome as usize];
                    let line = r.line.to_string();
                    w.write_record([
                        line.as_str(),
                        &quote_cell(table.student(r)),
                        &quote_cell(table.problem(r)),
                        &quote_cell(table.part(r)),
                        &quote_cell(table.answer(r)),
                        o.status.name(),
                        score,
                        codes,
                        message,
                        run,
                    ])?;
                }
                w.into_inner()
                    .map_err(|e| std::io::Error::other(e.to_string()))
            })
            .collect();
        for part in parts {
            out.write_all(&part?)?;
        }
    }
    Ok(())
}

/// The gradebook: students in order of first appearance, one column per part answered by
/// anyone (in bank order), the counted score of each, the total, the maximum and the percent.
pub struct Gradebook {
    /// `PROBLEM/PART` column titles.
    pub columns: Vec<String>,
    /// The points of each column.
    pub points: Vec<f64>,
    /// Student key and score per column (`None`: not answered).
    pub students: Vec<(String, Vec<Option<f64>>)>,
}

impl Gradebook {
    /// The maximum total.
    pub fn max(&self) -> f64 {
        self.points.iter().sum()
    }
}

/// Builds the gradebook from the rows that count. Its columns are `parts` (`--parts`, or the
/// wide format's part columns) when given, else every part some row names, in bank order;
/// every student's maximum is the sum of all columns, answered or not.
pub fn gradebook(
    table: &Table,
    judged: &Judged,
    bank: &Bank,
    parts: Option<&[(usize, usize)]>,
) -> Gradebook {
    let targets: Vec<(usize, usize)> = match parts {
        Some(p) => p.to_vec(),
        None => {
            let mut t: Vec<(usize, usize)> =
                (judged.outcomes.iter()).filter_map(|o| o.target).collect();
            t.sort_unstable();
            t.dedup();
            t
        }
    };
    let column: std::collections::HashMap<(usize, usize), usize> =
        targets.iter().enumerate().map(|(i, &t)| (t, i)).collect();
    let names = students(table);
    let mut scores = vec![vec![None; targets.len()]; names.len()];
    for (i, (r, g)) in table.rows.iter().zip(&judged.rows).enumerate() {
        let o = judged.outcome(i);
        if let (true, Some(t), Some(s)) = (g.counts, o.target, scores.get_mut(r.student as usize))
            && let Some(&c) = column.get(&t)
        {
            s[c] = Some(o.score);
        }
    }
    Gradebook {
        columns: targets
            .iter()
            .map(|&(p, q)| format!("{}/{}", bank.problems[p].id, bank.problems[p].parts[q].id))
            .collect(),
        points: targets
            .iter()
            .map(|&(p, q)| bank.problems[p].parts[q].points)
            .collect(),
        students: names.iter().map(|s| s.to_string()).zip(scores).collect(),
    }
}

/// A student's total.
fn total(scores: &[Option<f64>]) -> f64 {
    scores.iter().flatten().sum()
}

/// The percent of `max`, one decimal.
fn percent(total: f64, max: f64) -> String {
    if max > 0.0 {
        format!("{:.1}", 100.0 * total / max)
    } else {
        String::new()
    }
}

/// gradebook.csv.
pub fn gradebook_csv(book: &Gradebook) -> anyhow::Result<Vec<u8>> {
    let mut header: Vec<&str> = vec!["student"];
    header.extend(book.columns.iter().map(String::as_str));
    header.extend(["total", "max", "percent"]);
    let max = book.max();
    // A class has few distinct scores and totals: each is formatted once.
    let mut shown: rustc_hash::FxHashMap<u64, String> = rustc_hash::FxHashMap::default();
    let mut num = |x: f64| shown.entry(x.to_bits()).or_insert_with(|| num(x)).clone();
    let mut percents: rustc_hash::FxHashMap<u64, String> = rustc_hash::FxHashMap::default();
    let mut percent = |t: f64| {
        let p = percents.entry(t.to_bits());
        p.or_insert_with(|| percent(t, max)).clone()
    };
    let lines = book.students.iter().map(|(s, scores)| {
        let mut line = vec![quote_cell(s).into_owned()];
        line.extend(scores.iter().map(|x| x.map_or(String::new(), &mut num)));
        let t = total(scores);
        line.extend([num(t), num(max), percent(t)]);
        line
    });
    csv_bytes(&header, lines)
}

/// Whether every student key looks like an email address (Moodle then matches on email
/// rather than on an ID number).
fn emails(book: &Gradebook) -> bool {
    !book.students.is_empty() && book.students.iter().all(|(s, _)| s.contains('@'))
}

/// Moodle matches every row on one user field: student keys mixing email addresses and other
/// IDs cannot be imported. The error names the keys of the smaller kind (at most five).
pub fn moodle_keys(students: &[&str]) -> Result<(), String> {
    let (with, without): (Vec<&str>, Vec<&str>) = students.iter().partition(|s| s.contains('@'));
    if with.is_empty() || without.is_empty() {
        return Ok(());
    }
    let (few, kind) = if without.len() <= with.len() {
        (without, "without `@`")
    } else {
        (with, "with `@`")
    };
    let shown: Vec<String> = few
        .iter()
        .take(5)
        .map(|s| format!("`{}`", lagrange::expr::error::visible(s)))
        .collect();
    Err(format!(
        "--lms moodle: Moodle matches every row on one field (email address or ID number), \
         but {} student key(s) are {kind}: {}{}; make the keys one kind",
        few.len(),
        shown.join(", "),
        if few.len() > 5 { ", …" } else { "" }
    ))
}

/// The LMS import file's name and contents; `assignment` names the total column.
pub fn lms_file(lms: Lms, book: &Gradebook, assignment: &str) -> anyhow::Result<(String, Vec<u8>)> {
    let max = book.max();
    let totals = book
        .students
        .iter()
        .map(|(s, scores)| (quote_cell(s).into_owned(), num(total(scores))));
    let bytes = match lms {
        // Canvas matches a student on SIS Login ID (among its ID columns) and reads the
        // optional "Points Possible" row right under the header.
        Lms::Canvas => {
            let header = [
                "Student",
                "ID",
                "SIS User ID",
                "SIS Login ID",
                "Section",
                assignment,
            ];
            let points = vec![
                "    Points Possible".to_string(),
                String::new(),
                String::new(),
                String::new(),
                String::new(),
                num(max),
            ];
            let rows = totals
                .map(|(s, t)| vec![s.clone(), String::new(), String::new(), s, String::new(), t]);
            csv_bytes(&header, std::iter::once(points).chain(rows))?
        }
        // Moodle's CSV import maps one identifier column to a user field and each other
        // column to a grade item, chosen in its import form.
        Lms::Moodle => {
            let id = if emails(book) {
                "Email address"
            } else {
                "ID number"
            };
            csv_bytes(&[id, assignment], totals.map(|(s, t)| vec![s, t]))?
        }
        // Gradescope's score upload matches on SID or Email, with the score and its maximum.
        // Each row on its own key: an email address in Email, anything else in SID.
        Lms::Gradescope => {
            let rows = totals.map(|(s, t)| {
                let (sid, email) = if s.contains('@') {
                    (String::new(), s)
                } else {
                    (s, String::new())
                };
                vec![sid, email, t, num(max)]
            });
            csv_bytes(&["SID", "Email", "Score", "Max Points"], rows)?
        }
    };
    let name = match lms {
        Lms::Canvas => "canvas.csv",
        Lms::Moodle => "moodle.csv",
        Lms::Gradescope => "gradescope.csv",
    };
    Ok((name.to_string(), bytes))
}

/// summary.json, pretty, ending in a newline.
pub fn summary_json(s: &Summary) -> anyhow::Result<String> {
    Ok(serde_json::to_string_pretty(s)? + "\n")
}

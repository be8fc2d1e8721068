//! The files `lagrange grade` writes: results.csv (one row per answer), gradebook.csv (one
//! row per student), summary.md / summary.json, and an LMS import file, as bytes (written by
//! [`crate::face::outfile`]). Every text cell a spreadsheet would run as a formula is neutralised.

use std::io::Write;

use rayon::prelude::*;

use lagrange::bank::Bank;

use super::cell::needs_quote;
#[cfg(test)]
use super::cell::quote_cell;
use super::input::{Row, Table};
use super::judge::{Judged, Outcome};
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

/// Rows per chunk formatted by one worker; a round of chunks (two per thread) is formatted
/// while the previous round is written, so memory stays bounded by two rounds whatever the
/// number of rows (about 1 MB per thread with rows of all-different answers, which have no
/// shared tails).
const BATCH: usize = 1024;

/// Whether the csv crate's writer (`QuoteStyle::Necessary`, `\n` records) quotes a field: it
/// holds the delimiter, a quote or a line break.
fn csv_quotes(s: &str) -> bool {
    s.bytes().any(|c| matches!(c, b',' | b'"' | b'\n' | b'\r'))
}

/// Appends a field as the csv crate writes it, after a `'` when `formula` (see
/// [`quote_cell`]): quoted when needed, quotes doubled. Bytes equal to the csv writer's (a
/// unit test compares them), without its per-record cost.
fn push_csv(out: &mut Vec<u8>, s: &str, formula: bool) {
    let quoted = csv_quotes(s);
    if quoted {
        out.push(b'"');
    }
    if formula {
        out.push(b'\'');
    }
    if quoted {
        for part in s.split_inclusive('"') {
            out.extend_from_slice(part.as_bytes());
            if part.ends_with('"') {
                out.push(b'"');
            }
        }
        out.push(b'"');
    } else {
        out.extend_from_slice(s.as_bytes());
    }
}

/// Appends a text cell: neutralised ([`quote_cell`]), then as the csv writer writes it.
pub(super) fn push_cell(out: &mut Vec<u8>, s: &str) {
    push_csv(out, s, needs_quote(s));
}

/// Appends a field that is never neutralised (codes, numbers, the run id).
pub(super) fn push_plain(out: &mut Vec<u8>, s: &str) {
    push_csv(out, s, false);
}

/// Appends a number in decimal.
fn push_u32(out: &mut Vec<u8>, mut n: u32) {
    let mut digits = [0u8; 10];
    let mut i = digits.len();
    loop {
        i -= 1;
        digits[i] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    out.extend_from_slice(&digits[i..]);
}

/// results.csv, streamed into `out`: every input answer, in input order, each row with the
/// run's id. Text cells are neutralised ([`quote_cell`]). Rows are formatted in parallel
/// chunks while the chunks before them are written; the bytes do not depend on the thread
/// count.
pub fn results(
    out: &mut (dyn Write + Send),
    table: &Table,
    judged: &Judged,
    run: &str,
) -> std::io::Result<()> {
    let header = [
        "row", "student", "problem", "part", "answer", "status", "score", "codes", "message",
        "override", "run",
    ];
    out.write_all(&csv_bytes(&header, std::iter::empty()).map_err(std::io::Error::other)?)?;
    // What an outcome writes after the answer: status, score, codes, message, run and the
    // line's end. Formatted once per outcome when rows share outcomes; when nearly every row
    // has its own (all-different answers), formatted per row instead of kept.
    let tail = |o: &Outcome, t: &mut Vec<u8>| {
        t.push(b',');
        push_plain(t, o.status.name());
        t.push(b',');
        push_plain(t, &num(o.score));
        t.push(b',');
        let codes: Vec<&str> = o.codes.iter().map(|c| c.as_str()).collect();
        push_plain(t, &codes.join(";"));
        t.push(b',');
        push_cell(t, &judged.message(o));
        t.push(b',');
        push_plain(t, &super::review::override_cell(o));
        t.push(b',');
        push_plain(t, run);
        t.push(b'\n');
    };
    let shared = judged.outcome_count() * 4 <= table.rows.len();
    let tails: Vec<Vec<u8>> = if shared {
        (0..judged.outcome_count() as u32)
            .into_par_iter()
            .map(|k| {
                let o = judged.outcome_at(k);
                let mut t = Vec::with_capacity(judged.message(&o).len() + 48);
                tail(&o, &mut t);
                t
            })
            .collect()
    } else {
        Vec::new()
    };
    let format = |chunk: &[Row], first: usize| {
        let mut w = Vec::with_capacity(chunk.len() * 128);
        for (k, r) in chunk.iter().enumerate() {
            push_u32(&mut w, r.line);
            w.push(b',');
            push_cell(&mut w, table.student(r));
            w.push(b',');
            push_cell(&mut w, table.problem(r));
            w.push(b',');
            push_cell(&mut w, table.part(r));
            w.push(b',');
            push_cell(&mut w, table.answer(r));
            let o = judged.rows[first + k].outcome;
            match tails.get(o as usize) {
                Some(t) => w.extend_from_slice(t),
                None => tail(&judged.outcome_at(o), &mut w),
            }
        }
        w
    };
    let round = BATCH * 2 * rayon::current_num_threads().max(1);
    let mut written: Vec<Vec<u8>> = Vec::new();
    for (n, rows) in table.rows.chunks(round).enumerate() {
        let start = n * round;
        let (done, next) = rayon::join(
            || written.iter().try_for_each(|w| out.write_all(w)),
            || {
                (rows.par_chunks(BATCH).enumerate())
                    .map(|(k, chunk)| format(chunk, start + k * BATCH))
                    .collect::<Vec<Vec<u8>>>()
            },
        );
        done?;
        written = next;
    }
    written.iter().try_for_each(|w| out.write_all(w))
}

/// The gradebook: students in order of first appearance, one column per part answered by
/// anyone (in bank order), the counted score of each, the total, the maximum and the percent.
pub struct Gradebook<'t> {
    /// `PROBLEM/PART` column titles.
    pub columns: Vec<String>,
    /// The points of each column.
    pub points: Vec<f64>,
    /// The student keys, in order of first appearance.
    names: Vec<&'t str>,
    /// Every student's score per column, one student after the other (`None`: not
    /// answered): one list, not one per student (a class may have a million students).
    scores: Vec<Option<f64>>,
}

impl Gradebook<'_> {
    /// The maximum total.
    pub fn max(&self) -> f64 {
        self.points.iter().sum()
    }

    /// Student `i`'s scores, one per column (empty past the last student).
    pub fn scores(&self, i: usize) -> &[Option<f64>] {
        let w = self.columns.len();
        self.scores.get(i * w..(i + 1) * w).unwrap_or(&[])
    }

    /// The students' keys and scores, in order.
    fn students(&self) -> impl Iterator<Item = (&str, &[Option<f64>])> + '_ {
        (self.names.iter().enumerate()).map(|(i, &s)| (s, self.scores(i)))
    }
}

/// Builds the gradebook from the rows that count. Its columns are `parts` (`--parts`, or the
/// wide format's part columns) when given, else every part some row names, in bank order;
/// every student's maximum is the sum of all columns, answered or not.
pub fn gradebook<'t>(
    table: &'t Table,
    judged: &Judged,
    bank: &Bank,
    parts: Option<&[(usize, usize)]>,
) -> Gradebook<'t> {
    let targets: Vec<(usize, usize)> = match parts {
        Some(p) => p.to_vec(),
        None => {
            let mut t: Vec<(usize, usize)> = (judged.briefs()).filter_map(|o| o.target).collect();
            t.sort_unstable();
            t.dedup();
            t
        }
    };
    let column: rustc_hash::FxHashMap<(usize, usize), u32> = (targets.iter().enumerate())
        .map(|(i, &t)| (t, i as u32))
        .collect();
    // Each outcome's column, looked up once (`u32::MAX`: none).
    let columns: Vec<u32> = (judged.briefs())
        .map(|o| {
            o.target
                .and_then(|t| column.get(&t).copied())
                .unwrap_or(u32::MAX)
        })
        .collect();
    let names = students(table);
    let w = targets.len();
    let mut scores = vec![None; names.len() * w];
    for (i, (r, g)) in table.rows.iter().zip(&judged.rows).enumerate() {
        let c = columns[g.outcome as usize] as usize;
        let at = (r.student as usize).saturating_mul(w).saturating_add(c);
        if let (true, true, Some(s)) = (g.counts, c < w, scores.get_mut(at)) {
            *s = Some(judged.counted_score(i));
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
        names,
        scores,
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

/// A number as [`num`] writes it, formatted once per value (a class has few distinct scores
/// and totals).
#[derive(Default)]
struct Numbers(rustc_hash::FxHashMap<u64, String>);

impl Numbers {
    fn get(&mut self, x: f64, show: impl FnOnce(f64) -> String) -> &str {
        self.0.entry(x.to_bits()).or_insert_with(|| show(x))
    }
}

/// Students per chunk of an output formatted by one worker.
const STUDENTS: usize = 4 * 1024;

/// A file as the pieces it is written from, in order (never joined: a class of a million
/// students would hold its gradebook twice while joining it).
pub type Pieces = Vec<Vec<u8>>;

/// `out` (the lines before the students'), then `line(student, scores, out)` for every
/// student, formatted in parallel chunks, in order.
fn per_student(
    out: Vec<u8>,
    book: &Gradebook,
    line: impl Fn(&str, &[Option<f64>], &mut Numbers, &mut Vec<u8>) + Sync,
) -> anyhow::Result<Pieces> {
    let chunks: Vec<Vec<u8>> = (book.names.par_chunks(STUDENTS).enumerate())
        .map(|(k, chunk)| {
            let (mut w, mut numbers) = (Vec::with_capacity(chunk.len() * 64), Numbers::default());
            for (i, s) in chunk.iter().enumerate() {
                line(s, book.scores(k * STUDENTS + i), &mut numbers, &mut w);
            }
            w
        })
        .collect();
    Ok(std::iter::once(out).chain(chunks).collect())
}

/// gradebook.csv.
pub fn gradebook_csv(book: &Gradebook) -> anyhow::Result<Pieces> {
    let mut header: Vec<&str> = vec!["student"];
    header.extend(book.columns.iter().map(String::as_str));
    header.extend(["total", "max", "percent"]);
    let max = book.max();
    per_student(
        csv_bytes(&header, std::iter::empty())?,
        book,
        |s, scores, numbers, w| {
            push_cell(w, s);
            for x in scores {
                w.push(b',');
                if let Some(x) = x {
                    push_plain(w, numbers.get(*x, num));
                }
            }
            let t = total(scores);
            w.push(b',');
            push_plain(w, numbers.get(t, num));
            w.push(b',');
            push_plain(w, numbers.get(max, num));
            w.push(b',');
            // Percents keyed apart from scores: the same value shows differently.
            push_plain(w, &percent(t, max));
            w.push(b'\n');
        },
    )
}

/// Whether every student key looks like an email address (Moodle then matches on email
/// rather than on an ID number).
fn emails(book: &Gradebook) -> bool {
    !book.names.is_empty() && book.students().all(|(s, _)| s.contains('@'))
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
pub fn lms_file(lms: Lms, book: &Gradebook, assignment: &str) -> anyhow::Result<(String, Pieces)> {
    let max = book.max();
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
            let out = csv_bytes(&header, std::iter::once(points))?;
            per_student(out, book, |s, scores, numbers, w| {
                push_cell(w, s);
                w.extend_from_slice(b",,,");
                push_cell(w, s);
                w.extend_from_slice(b",,");
                push_plain(w, numbers.get(total(scores), num));
                w.push(b'\n');
            })?
        }
        // Moodle's CSV import maps one identifier column to a user field and each other
        // column to a grade item, chosen in its import form.
        Lms::Moodle => {
            let id = if emails(book) {
                "Email address"
            } else {
                "ID number"
            };
            per_student(
                csv_bytes(&[id, assignment], std::iter::empty())?,
                book,
                |s, scores, numbers, w| {
                    push_cell(w, s);
                    w.push(b',');
                    push_plain(w, numbers.get(total(scores), num));
                    w.push(b'\n');
                },
            )?
        }
        // Gradescope's score upload matches on SID or Email, with the score and its maximum.
        // Each row on its own key: an email address in Email, anything else in SID.
        Lms::Gradescope => {
            let header = ["SID", "Email", "Score", "Max Points"];
            per_student(
                csv_bytes(&header, std::iter::empty())?,
                book,
                |s, scores, numbers, w| {
                    if s.contains('@') {
                        w.push(b',');
                        push_cell(w, s);
                    } else {
                        push_cell(w, s);
                        w.push(b',');
                    }
                    w.push(b',');
                    push_plain(w, numbers.get(total(scores), num));
                    w.push(b',');
                    push_plain(w, numbers.get(max, num));
                    w.push(b'\n');
                },
            )?
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The csv crate's bytes for one record.
    fn csv_record(fields: &[&str]) -> Vec<u8> {
        let mut w = csv::WriterBuilder::new()
            .has_headers(false)
            .from_writer(Vec::new());
        w.write_record(fields).unwrap_or_else(|e| panic!("{e}"));
        w.into_inner().unwrap_or_else(|e| panic!("{e}"))
    }

    /// The writers append fields themselves: the bytes must be the csv crate's, with the
    /// formula `'` where `quote_cell` puts it, for every kind of text a class file holds.
    #[test]
    fn fields_are_written_as_the_csv_crate_writes_them() {
        let texts = [
            "",
            " ",
            "x",
            "-m g l cos θ",
            "=HYPERLINK(\"x\")",
            "'=1",
            "''-a",
            "a,b",
            "a;b",
            "say \"hi\"",
            "\"",
            "\"\"",
            "line\nbreak",
            "cr\rhere",
            "\tstart",
            "\rstart",
            "+1",
            "@me",
            "#comment",
            "a\u{0}b",
            "ünïcödé, \"quoted\"\r\n",
            " lead",
            "trail ",
        ];
        for a in texts {
            for b in texts {
                let (qa, qb) = (quote_cell(a), quote_cell(b));
                let want = csv_record(&[&qa, b, &qb]);
                let mut got = Vec::new();
                push_cell(&mut got, a);
                got.push(b',');
                push_plain(&mut got, b);
                got.push(b',');
                push_cell(&mut got, b);
                got.push(b'\n');
                assert_eq!(
                    String::from_utf8_lossy(&got),
                    String::from_utf8_lossy(&want),
                    "{a:?} {b:?}"
                );
            }
        }
    }

    #[test]
    fn numbers_are_written_in_decimal() {
        for n in [0, 7, 10, 99, 12_345, u32::MAX] {
            let mut w = Vec::new();
            push_u32(&mut w, n);
            assert_eq!(w, n.to_string().into_bytes());
        }
    }
}

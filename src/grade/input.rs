//! A class file (CSV) → one [`Row`] per answer. The header decides the format: long
//! (`student,problem,part,answer`, one answer a line) or wide (`student` plus one column per
//! `PROBLEM/PART`, one answer a non-empty cell). Nothing here judges an answer; a line that
//! cannot be used still becomes a row, carrying the reason, so rows in = rows out.

use std::borrow::Cow;

use super::output::unquote_cell;

/// The two layouts a class file may have.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// `student,problem,part,answer`: one answer per line.
    Long,
    /// `student` plus `PROBLEM/PART` columns: one answer per non-empty cell.
    Wide,
}

/// One answer of the class file (or one unusable line).
#[derive(Clone, Debug, Default)]
pub struct Row {
    /// The input line number the record starts on (the header is line 1).
    pub line: u64,
    /// The student key (trimmed; a key differing only in case from an earlier one takes the
    /// earlier spelling), as the LMS knows the student.
    pub student: String,
    /// The problem id (trimmed; in the wide format, from the column name).
    pub problem: String,
    /// The part id (trimmed; in the wide format, from the column name).
    pub part: String,
    /// The answer exactly as typed.
    pub answer: String,
    /// Why the row cannot be graded, already phrased for results.csv.
    pub error: Option<String>,
}

/// The rows of a class file and its layout.
#[derive(Debug)]
pub struct Table {
    /// The layout the header chose.
    pub format: Format,
    /// One row per answer, in input order.
    pub rows: Vec<Row>,
    /// The wide format's part columns, `(problem, part)` in header order (empty when long).
    pub columns: Vec<(String, String)>,
    /// Student keys read as one because they differ only in case: (kept, merged into it).
    pub merged: Vec<(String, String)>,
}

/// Why a class file cannot be read at all (exit 2).
#[derive(Debug)]
pub struct BadFile(
    /// The one-line reason.
    pub String,
);

/// The columns the header must have, for the error message.
const EXPECTED: &str = "expected the columns `student,problem,part,answer` (long format) or \
                        `student` plus one `PROBLEM/PART` column per part (wide format)";

/// Where each needed column is in a header.
enum Layout {
    Long {
        student: usize,
        problem: usize,
        part: usize,
        answer: usize,
    },
    /// The student column and each part column with its problem and part ids.
    Wide {
        student: usize,
        parts: Vec<(usize, String, String)>,
    },
}

/// Parses a whole class file. Only an unusable header (or none) is an error; every other
/// problem is recorded on the row it concerns.
pub fn parse(bytes: &[u8]) -> Result<Table, BadFile> {
    let decoded = super::decode::decode(bytes).map_err(BadFile)?;
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .delimiter(decoded.delimiter)
        .from_reader(&*decoded.text);
    let mut records = reader.byte_records();
    let header = match records.next() {
        Some(Ok(h)) => h,
        Some(Err(e)) => return Err(BadFile(format!("cannot read the header: {e}"))),
        None => return Err(BadFile(format!("the file is empty: {EXPECTED}"))),
    };
    let names: Vec<String> = header.iter().map(header_name).collect();
    let layout = layout(&names)?;
    let width = header.len();
    let mut rows = Vec::new();
    for record in records {
        let record = match record {
            Ok(r) => r,
            // The csv reader only fails on I/O, impossible on a byte slice; stop rather than
            // loop, and keep what was read.
            Err(e) => return Err(BadFile(format!("cannot read the file: {e}"))),
        };
        // The file's own line (the reader's count misses CR-only and CRLF endings).
        let line = record
            .position()
            .map_or(0, |p| decoded.record_line(p.byte() as usize));
        push_rows(&layout, width, line, &record, &mut rows);
    }
    let merged = merge_students(&mut rows);
    let (format, columns) = match layout {
        Layout::Long { .. } => (Format::Long, Vec::new()),
        Layout::Wide { parts, .. } => (
            Format::Wide,
            parts.into_iter().map(|(_, p, q)| (p, q)).collect(),
        ),
    };
    Ok(Table {
        format,
        rows,
        columns,
        merged,
    })
}

/// Student keys that differ only in case or surrounding spaces are one student: every row
/// takes the first spelling of its key. The keys merged, as (first spelling, other spelling).
fn merge_students(rows: &mut [Row]) -> Vec<(String, String)> {
    let mut first: std::collections::HashMap<String, String> = std::collections::HashMap::new();
    let mut merged = Vec::new();
    for row in rows.iter_mut().filter(|r| !r.student.is_empty()) {
        let key = row.student.to_lowercase();
        let spelling = first.entry(key).or_insert_with(|| row.student.clone());
        if *spelling != row.student {
            let pair = (
                spelling.clone(),
                std::mem::replace(&mut row.student, spelling.clone()),
            );
            if !merged.contains(&pair) {
                merged.push(pair);
            }
        }
    }
    merged
}

/// A header cell as compared: trimmed, lower-case, without a byte-order mark.
fn header_name(field: &[u8]) -> String {
    let text = String::from_utf8_lossy(field);
    text.trim_start_matches('\u{feff}').trim().to_lowercase()
}

/// The layout a header describes, or the error naming the expected columns.
fn layout(names: &[String]) -> Result<Layout, BadFile> {
    let find = |n: &str| names.iter().position(|h| h == n);
    let found = || {
        // Control characters shown escaped, and a binary file's "header" cut short.
        let shown: String = lagrange::expr::error::visible(&names.join(","))
            .chars()
            .take(200)
            .collect();
        format!("found `{shown}`")
    };
    let Some(student) = find("student") else {
        return Err(BadFile(format!("bad header: {EXPECTED}; {}", found())));
    };
    if let (Some(problem), Some(part), Some(answer)) =
        (find("problem"), find("part"), find("answer"))
    {
        return Ok(Layout::Long {
            student,
            problem,
            part,
            answer,
        });
    }
    let parts: Vec<(usize, String, String)> = names
        .iter()
        .enumerate()
        .filter_map(|(i, n)| {
            let (problem, part) = n.split_once('/')?;
            let (problem, part) = (problem.trim(), part.trim());
            (!problem.is_empty() && !part.is_empty())
                .then(|| (i, problem.to_string(), part.to_string()))
        })
        .collect();
    if parts.is_empty() {
        return Err(BadFile(format!("bad header: {EXPECTED}; {}", found())));
    }
    Ok(Layout::Wide { student, parts })
}

/// A field decoded lossily, and whether it had to be.
/// A cell lagrange neutralised for spreadsheets (`'=…`) reads as its text again.
fn text(record: &csv::ByteRecord, i: usize) -> (String, bool) {
    match record.get(i).map(String::from_utf8_lossy) {
        Some(Cow::Borrowed(s)) => (unquote_cell(s).to_string(), false),
        Some(Cow::Owned(s)) => (unquote_cell(&s).to_string(), true),
        None => (String::new(), false),
    }
}

/// The rows of one record: one in the long format, one per non-empty part cell in the wide
/// format (one error row when the record cannot be split into cells).
fn push_rows(
    layout: &Layout,
    width: usize,
    line: u64,
    record: &csv::ByteRecord,
    rows: &mut Vec<Row>,
) {
    let count_error = (record.len() != width).then(|| {
        format!(
            "line {line}: {} fields, the header has {width}; the row is not graded",
            record.len()
        )
    });
    match layout {
        Layout::Long {
            student,
            problem,
            part,
            answer,
        } => {
            let fields = [*student, *problem, *part, *answer].map(|i| text(record, i));
            let lossy = fields.iter().any(|f| f.1);
            let [student, problem, part, answer] = fields.map(|f| f.0);
            let mut row = Row {
                line,
                student: student.trim().to_string(),
                problem: problem.trim().to_string(),
                part: part.trim().to_string(),
                answer,
                error: count_error,
            };
            if row.error.is_none() {
                row.error = row_error(&row, lossy);
            }
            rows.push(row);
        }
        Layout::Wide { student, parts } => {
            let (student, student_lossy) = text(record, *student);
            let student = student.trim().to_string();
            if let Some(error) = count_error {
                rows.push(Row {
                    line,
                    student,
                    error: Some(error),
                    ..Row::default()
                });
                return;
            }
            for (i, problem, part) in parts {
                let (answer, lossy) = text(record, *i);
                if answer.trim().is_empty() {
                    continue;
                }
                let mut row = Row {
                    line,
                    student: student.clone(),
                    problem: problem.clone(),
                    part: part.clone(),
                    answer,
                    error: None,
                };
                row.error = row_error(&row, lossy || student_lossy);
                rows.push(row);
            }
        }
    }
}

/// What is wrong with a row before any problem is looked up.
fn row_error(row: &Row, lossy: bool) -> Option<String> {
    let line = row.line;
    if lossy {
        return Some(format!(
            "line {line}: not valid UTF-8 (shown decoded lossily, with U+FFFD for the bad \
             bytes); save the file as UTF-8"
        ));
    }
    if row.student.is_empty() {
        return Some(format!("line {line}: no student"));
    }
    if row.problem.is_empty() || row.part.is_empty() {
        return Some(format!("line {line}: no problem or part"));
    }
    if row.answer.trim().is_empty() {
        return Some(format!("line {line}: empty answer"));
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn headers_ignore_case_spaces_and_a_byte_order_mark() {
        let t = parse("\u{feff} Student ,PROBLEM, Part,Answer,extra\na,p,q,x,y\n".as_bytes());
        let t = t.map_err(|e| e.0).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(t.format, Format::Long);
        assert_eq!(t.rows[0].line, 2);
        assert_eq!(t.rows[0].answer, "x");
        assert!(t.rows[0].error.is_none());
    }

    #[test]
    fn wide_rows_are_the_non_empty_cells() {
        let t = parse(b"student,a/b,c/d\ns1,x,\ns2,,y\n").map_err(|e| e.0);
        let t = t.unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(t.format, Format::Wide);
        let got: Vec<(u64, &str, &str)> = t
            .rows
            .iter()
            .map(|r| (r.line, r.student.as_str(), r.part.as_str()))
            .collect();
        assert_eq!(got, [(2, "s1", "b"), (3, "s2", "d")]);
    }

    #[test]
    fn a_header_of_neither_format_names_the_expected_columns() {
        let e = parse(b"name,score\n")
            .err()
            .map(|e| e.0)
            .unwrap_or_default();
        assert!(e.contains("student,problem,part,answer"), "{e}");
    }
}

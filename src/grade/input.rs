//! A class file (CSV) → one [`Row`] per answer. The header decides the format: long
//! (`student,problem,part,answer`, one answer a line) or wide (`student` plus one column per
//! `PROBLEM/PART`, one answer a non-empty cell). Nothing here judges an answer; a line that
//! cannot be used still becomes a row, carrying the reason, so rows in = rows out.

use std::borrow::Cow;

use hashbrown::HashTable;
use rayon::prelude::*;
use rustc_hash::{FxBuildHasher, FxHashMap};
use std::hash::BuildHasher as _;

use super::cell::unquote_cell;
use super::decode::Decoded;
use super::header::{EXPECTED, Layout, header_name, layout};
use super::intern::Interner;

/// The two layouts a class file may have.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// `student,problem,part,answer`: one answer per line.
    Long,
    /// `student` plus `PROBLEM/PART` columns: one answer per non-empty cell.
    Wide,
}

/// The index a row holds where it has nothing (no student, no error).
pub const NONE: u32 = u32::MAX;

/// One answer of the class file (or one unusable line), its text held as indices into the
/// [`Table`]'s interned strings.
#[derive(Clone, Copy, Debug, Default)]
pub struct Row {
    /// The input line number the record starts on (the header is line 1).
    pub line: u32,
    /// The student ([`Table::students`]; [`NONE`]: no key).
    pub student: u32,
    /// The problem id as typed, trimmed ([`Table::names`]; in the wide format, the column's).
    pub problem: u32,
    /// The part id as typed, trimmed ([`Table::names`]).
    pub part: u32,
    /// The answer exactly as typed ([`Table::answers`]).
    pub answer: u32,
    /// Why the row cannot be graded, already phrased for results.csv ([`Table::errors`];
    /// [`NONE`]: it can).
    pub error: u32,
}

/// The rows of a class file, its layout and its interned text.
pub struct Table {
    /// The layout the header chose.
    pub format: Format,
    /// One row per answer, in input order.
    pub rows: Vec<Row>,
    /// The wide format's part columns, `(problem, part)` in header order (empty when long).
    pub columns: Vec<(String, String)>,
    /// Student keys read as one because they differ only in case: (kept, merged into it).
    pub merged: Vec<(String, String)>,
    /// The distinct non-empty student keys (trimmed; a key differing only in case from an
    /// earlier one takes the earlier spelling), in order of first appearance.
    pub students: Vec<String>,
    /// Problem and part ids as typed.
    pub names: Interner,
    /// Answers as typed.
    pub answers: Interner,
    /// The rows' error messages.
    pub errors: Vec<String>,
}

impl Table {
    /// A row's student key (empty: none).
    pub fn student(&self, row: &Row) -> &str {
        self.students
            .get(row.student as usize)
            .map_or("", String::as_str)
    }

    /// A row's problem id as typed.
    pub fn problem(&self, row: &Row) -> &str {
        self.names.get(row.problem)
    }

    /// A row's part id as typed.
    pub fn part(&self, row: &Row) -> &str {
        self.names.get(row.part)
    }

    /// A row's answer as typed.
    pub fn answer(&self, row: &Row) -> &str {
        self.answers.get(row.answer)
    }

    /// Why a row cannot be graded, if it cannot.
    pub fn error(&self, row: &Row) -> Option<&str> {
        self.errors.get(row.error as usize).map(String::as_str)
    }
}

/// Builds a [`Table`]'s rows and text while the records are read: the whole table, or one
/// piece of the file read on its own (`piece`: student keys only by exact spelling, in order
/// of first appearance, each with its lower case; [`Builder::absorb`] folds them into the
/// table in order).
#[derive(Default)]
struct Builder {
    rows: Vec<Row>,
    /// A piece's student keys by exact spelling, in order of first appearance.
    keys: Interner,
    /// A piece's student keys whose lower case differs from them, with it (by index in
    /// `keys`, ascending), made beside the reading so that joining the pieces does not lower
    /// every key again; the others are their own lower case.
    lowered: Vec<(u32, String)>,
    /// The table's students, each under its first spelling.
    students: Vec<String>,
    /// The table's students by their own spelling, and by every other spelling (one that
    /// differs only in case) in `spellings`.
    exact: HashTable<u32>,
    spellings: FxHashMap<String, u32>,
    /// The table's students by their lower case: `folded_of` holds it where it differs from
    /// the key itself. No key is held twice: a class of a million students would otherwise
    /// keep three copies of every key while its pieces are joined.
    folded: HashTable<u32>,
    folded_of: FxHashMap<u32, String>,
    /// The last key looked up and its index: a class file usually lists one student's
    /// answers together.
    last: Option<(String, u32)>,
    merged: Vec<(String, String)>,
    names: Interner,
    answers: Interner,
    errors: Vec<String>,
}

/// The hash of a key, as the tables of student keys take it.
fn key_hash(key: &str) -> u64 {
    FxBuildHasher.hash_one(key)
}

/// Student `i`'s key in lower case.
fn folded<'a>(students: &'a [String], folded_of: &'a FxHashMap<u32, String>, i: u32) -> &'a str {
    folded_of
        .get(&i)
        .map_or(students[i as usize].as_str(), String::as_str)
}

impl Builder {
    /// The index of a (trimmed) student key in a piece, by exact spelling.
    fn student(&mut self, key: &str) -> u32 {
        if key.is_empty() {
            return NONE;
        }
        if let Some((k, i)) = &self.last
            && k == key
        {
            return *i;
        }
        let known = self.keys.len();
        let i = self.keys.intern(key);
        if i as usize == known {
            let lower = key.to_lowercase();
            if lower != key {
                self.lowered.push((i, lower));
            }
        }
        match &mut self.last {
            Some((k, j)) => {
                k.clear();
                k.push_str(key);
                *j = i;
            }
            None => self.last = Some((key.to_string(), i)),
        }
        i
    }

    /// The table's index of a piece's student key (`lower`: its lower case, `None` when the
    /// same): keys that differ only in case are one student, under the first spelling (the
    /// merge noted once per other spelling).
    fn table_student(&mut self, key: &str, lower: Option<&str>) -> u32 {
        let students = &self.students;
        let hash = key_hash(key);
        if let Some(&i) = self.exact.find(hash, |&i| students[i as usize] == key) {
            return i;
        }
        if let Some(&i) = self.spellings.get(key) {
            return i;
        }
        let lowered = lower.unwrap_or(key);
        let folded_hash = key_hash(lowered);
        let found = (self.folded)
            .find(folded_hash, |&i| {
                folded(students, &self.folded_of, i) == lowered
            })
            .copied();
        if let Some(i) = found {
            self.merged
                .push((self.students[i as usize].clone(), key.to_string()));
            self.spellings.insert(key.to_string(), i);
            return i;
        }
        let i = self.students.len() as u32;
        self.students.push(key.to_string());
        if let Some(l) = lower {
            self.folded_of.insert(i, l.to_string());
        }
        let (students, folded_of) = (&self.students, &self.folded_of);
        self.exact
            .insert_unique(hash, i, |&j| key_hash(&students[j as usize]));
        (self.folded).insert_unique(folded_hash, i, |&j| {
            key_hash(folded(students, folded_of, j))
        });
        i
    }

    /// Joins the pieces, read in file order: their text interned here in its order of first
    /// appearance, so the indices are those a single pass would have given. The text is
    /// joined in order (a small part of the work); the rows, renumbered, in parallel.
    fn absorb(&mut self, pieces: Vec<Builder>, phases: &mut super::phases::Phases) {
        let keys: usize = pieces.iter().map(|p| p.keys.len()).sum();
        let answers: usize = pieces.iter().map(|p| p.answers.len()).sum();
        let text: usize = pieces.iter().map(|p| p.answers.bytes()).sum();
        self.answers.reserve(answers, text);
        self.students.reserve(keys);
        let (students, folded_of) = (&self.students, &self.folded_of);
        (self.exact).reserve(keys, |&j| key_hash(&students[j as usize]));
        (self.folded).reserve(keys, |&j| key_hash(folded(students, folded_of, j)));
        let mut maps = Vec::with_capacity(pieces.len());
        let mut piece_rows = Vec::with_capacity(pieces.len());
        // A class of mostly different answers joins as much text as it read: the pieces'
        // memory, freed as each is joined, is given back now and then, else it would still be
        // counted (in the workers' heaps) when the joined text is whole.
        let rows: usize = pieces.iter().map(|p| p.rows.len()).sum();
        let give_back = answers >= super::memory::MANY && answers * 4 > rows;
        for (k, p) in pieces.into_iter().enumerate() {
            if give_back && k % 8 == 7 {
                super::memory::give_back();
            }
            let mut lowered = p.lowered.iter().peekable();
            let students: Vec<u32> = (0..p.keys.len() as u32)
                .map(|i| {
                    let lower = lowered.next_if(|(j, _)| *j == i).map(|(_, l)| l.as_str());
                    self.table_student(p.keys.get(i), lower)
                })
                .collect();
            let names: Vec<u32> = (0..p.names.len() as u32)
                .map(|i| self.names.intern(p.names.get(i)))
                .collect();
            let answers: Vec<u32> = (0..p.answers.len() as u32)
                .map(|i| self.answers.intern(p.answers.get(i)))
                .collect();
            let first_error = self.errors.len() as u32;
            self.errors.extend(p.errors);
            maps.push((students, names, answers, first_error));
            piece_rows.push(p.rows);
        }
        phases.end("join text");
        let shift = |i: u32, to: &[u32]| to.get(i as usize).copied().unwrap_or(NONE);
        // Every row renumbered into its place in the table, in parallel (each finds its piece
        // among the pieces' first rows).
        let mut firsts = Vec::with_capacity(piece_rows.len());
        let mut total = 0;
        for rows in &piece_rows {
            firsts.push(total);
            total += rows.len();
        }
        // A worker goes through consecutive rows: it looks its piece up again only when it
        // starts or leaves one.
        let renumbered = (0..total).into_par_iter().map_init(
            || usize::MAX,
            |k, i| {
                if *k >= firsts.len() || i < firsts[*k] || i - firsts[*k] >= piece_rows[*k].len() {
                    *k = firsts.partition_point(|&f| f <= i) - 1;
                }
                let k = *k;
                let r = &piece_rows[k][i - firsts[k]];
                let (students, names, answers, first_error) = &maps[k];
                Row {
                    line: r.line,
                    student: shift(r.student, students),
                    problem: shift(r.problem, names),
                    part: shift(r.part, names),
                    answer: shift(r.answer, answers),
                    error: if r.error == NONE {
                        NONE
                    } else {
                        first_error + r.error
                    },
                }
            },
        );
        if self.rows.is_empty() {
            renumbered.collect_into_vec(&mut self.rows);
        } else {
            self.rows.par_extend(renumbered);
        }
    }

    /// Adds a row; `error` is why it cannot be graded.
    fn push(&mut self, line: u32, student: u32, ids: [&str; 3], error: Option<String>) {
        let error = error.map_or(NONE, |e| {
            self.errors.push(e);
            self.errors.len() as u32 - 1
        });
        let row = Row {
            line,
            student,
            problem: self.names.intern(ids[0]),
            part: self.names.intern(ids[1]),
            answer: self.answers.intern(ids[2]),
            error,
        };
        self.rows.push(row);
    }
}

/// Why a class file cannot be read at all (exit 2).
#[derive(Debug)]
pub struct BadFile(
    /// The one-line reason.
    pub String,
);

/// Parses a whole class file. Only an unusable header (or none) is an error; every other
/// problem is recorded on the row it concerns.
#[cfg(test)]
pub fn parse(bytes: &[u8], phases: &mut super::phases::Phases) -> Result<Table, BadFile> {
    parse_cut(bytes.to_vec(), super::decode::CUT_BYTES, phases, |_| ()).map(|(t, ())| t)
}

/// [`parse`] of a class file it takes and frees as soon as its pieces are read (before
/// they are joined, where a class of all-different answers needs its memory), running
/// `beside(bytes)` while it is decoded.
pub fn parse_beside<R: Send>(
    bytes: Vec<u8>,
    phases: &mut super::phases::Phases,
    beside: impl FnOnce(&[u8]) -> R + Send,
) -> Result<(Table, R), BadFile> {
    parse_cut(bytes, super::decode::CUT_BYTES, phases, beside)
}

/// [`parse_beside`], the file read in pieces of about `cut` bytes (small in tests, to cut
/// often).
fn parse_cut<R: Send>(
    bytes: Vec<u8>,
    cut: usize,
    phases: &mut super::phases::Phases,
    beside: impl FnOnce(&[u8]) -> R + Send,
) -> Result<(Table, R), BadFile> {
    let (decoded, besides) =
        rayon::join(|| super::decode::decode_cut(&bytes, cut), || beside(&bytes));
    let decoded = decoded.map_err(BadFile)?;
    phases.end("decode");
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .delimiter(decoded.delimiter)
        .from_reader(&*decoded.text);
    let mut record = csv::ByteRecord::new();
    let header = match reader.read_byte_record(&mut record) {
        Ok(true) => record.clone(),
        Ok(false) => return Err(BadFile(format!("the file is empty: {EXPECTED}"))),
        Err(e) => return Err(BadFile(format!("cannot read the header: {e}"))),
    };
    let names: Vec<String> = header.iter().map(header_name).collect();
    let layout = layout(&names).map_err(BadFile)?;
    let width = header.len();
    // The body in pieces that start at record starts (found by the quote check), read in
    // parallel, then joined in file order.
    let body = reader.position().byte() as usize;
    let mut bounds = vec![(body, decoded.line(body))];
    bounds.extend(decoded.cuts.iter().copied().filter(|&(c, _)| c > body));
    bounds.push((decoded.text.len().max(body), 0));
    let pieces = bounds
        .par_windows(2)
        .map(|w| read_piece(&decoded, w[0], w[1].0, &layout, width))
        .collect::<Result<Vec<Builder>, BadFile>>()?;
    phases.end("pieces");
    drop(reader);
    drop(decoded);
    drop(bytes);
    let mut b = Builder::default();
    b.absorb(pieces, phases);
    // Grading looks answers up by number from here on.
    b.answers.seal();
    let (format, columns) = match layout {
        Layout::Long { .. } => (Format::Long, Vec::new()),
        Layout::Wide { parts, .. } => (
            Format::Wide,
            parts.into_iter().map(|(_, p, q)| (p, q)).collect(),
        ),
    };
    let table = Table {
        format,
        rows: b.rows,
        columns,
        merged: b.merged,
        students: b.students,
        names: b.names,
        answers: b.answers,
        errors: b.errors,
    };
    Ok((table, besides))
}

/// The rows of the records in `text[start..end]` (which starts at a record, on line
/// `line`), with their lines in the whole file.
fn read_piece(
    decoded: &Decoded,
    (start, line): (usize, u64),
    end: usize,
    layout: &Layout,
    width: usize,
) -> Result<Builder, BadFile> {
    let mut lines = super::decode::Lines::new(&decoded.text, (start, line));
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .delimiter(decoded.delimiter)
        .from_reader(&decoded.text[start..end]);
    let mut record = csv::ByteRecord::new();
    let mut b = Builder::default();
    loop {
        match reader.read_byte_record(&mut record) {
            Ok(true) => {}
            Ok(false) => break,
            // The csv reader only fails on I/O, impossible on a byte slice; stop rather than
            // loop, and keep what was read.
            Err(e) => return Err(BadFile(format!("cannot read the file: {e}"))),
        }
        // The file's own line (the reader's count misses CR-only and CRLF endings).
        let line = record
            .position()
            .map_or(0, |p| lines.record(start + p.byte() as usize));
        push_rows(layout, width, line as u32, &record, &mut b);
    }
    Ok(b)
}

/// A field's text, and whether it had to be decoded lossily. A cell lagrange neutralised for
/// spreadsheets (`'=…`) reads as its text again.
fn text(record: &csv::ByteRecord, i: usize) -> (Cow<'_, str>, bool) {
    match record.get(i).map(String::from_utf8_lossy) {
        Some(Cow::Borrowed(s)) => (Cow::Borrowed(unquote_cell(s)), false),
        Some(Cow::Owned(s)) => (Cow::Owned(unquote_cell(&s).to_string()), true),
        None => (Cow::Borrowed(""), false),
    }
}

/// The rows of one record: one in the long format, one per non-empty part cell in the wide
/// format (one error row when the record cannot be split into cells).
fn push_rows(layout: &Layout, width: usize, line: u32, record: &csv::ByteRecord, b: &mut Builder) {
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
            let (student, problem, part) = (student.trim(), problem.trim(), part.trim());
            let error =
                count_error.or_else(|| row_error(line, [student, problem, part, &answer], lossy));
            let id = b.student(student);
            b.push(line, id, [problem, part, &answer], error);
        }
        Layout::Wide { student, parts } => {
            let (student, student_lossy) = text(record, *student);
            let id = b.student(student.trim());
            if let Some(error) = count_error {
                b.push(line, id, ["", "", ""], Some(error));
                return;
            }
            for (i, problem, part) in parts {
                let (answer, lossy) = text(record, *i);
                if answer.trim().is_empty() {
                    continue;
                }
                let fields = [student.trim(), problem, part, &answer];
                let error = row_error(line, fields, lossy || student_lossy);
                b.push(line, id, [problem, part, &answer], error);
            }
        }
    }
}

/// What is wrong with a row (student, problem, part, answer) before any problem is looked up.
fn row_error(
    line: u32,
    [student, problem, part, answer]: [&str; 4],
    lossy: bool,
) -> Option<String> {
    if lossy {
        return Some(format!(
            "line {line}: not valid UTF-8 (shown decoded lossily, with U+FFFD for the bad \
             bytes); save the file as UTF-8"
        ));
    }
    if student.is_empty() {
        return Some(format!("line {line}: no student"));
    }
    if problem.is_empty() || part.is_empty() {
        return Some(format!("line {line}: no problem or part"));
    }
    if answer.trim().is_empty() {
        return Some(format!("line {line}: empty answer"));
    }
    None
}

#[cfg(test)]
#[path = "input_tests.rs"]
mod tests;

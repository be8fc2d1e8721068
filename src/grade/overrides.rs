//! `grade --overrides FILE`: the instructor's decisions on answers the checker could not
//! settle, read from a review queue they filled in (review.csv, or any CSV with the columns
//! `problem`, `part`, `answer` and `decision`, and `variant` where the numbers vary), applied
//! to every row with that exact text on that part and variant — visibly: the row's `override` column names the decision and its message says
//! what the checker had said.

use rustc_hash::FxHashMap;

use lagrange::bank::Bank;
use lagrange::expr::error::visible;
use lagrange::policy::Decision;

use super::cell::unquote_cell;
use super::input::Table;
use super::judge::{Judged, Override, Status};
use super::variants::Variants;

/// The largest overrides file read.
const MAX_BYTES: u64 = 64 * 1024 * 1024;

/// One decision of the file.
#[derive(Clone, Debug)]
pub struct Entry {
    /// The problem id, as in the class file.
    pub problem: String,
    /// The part id.
    pub part: String,
    /// The student's numbers the decision is about, as review.csv's `variant` column writes
    /// them (empty: a problem without variants, or a file without the column).
    pub variant: String,
    /// The answer, exactly as typed.
    pub answer: String,
    /// The decision.
    pub decision: Decision,
    /// The decision cell as written (carried into the next review queue).
    pub written: String,
    /// The file's line it is on (1-based; the header is line 1).
    pub line: usize,
}

/// The decisions of an overrides file.
#[derive(Clone, Debug, Default)]
pub struct Overrides {
    /// Every decided row of the file, in file order (a later one for the same answer wins).
    pub entries: Vec<Entry>,
}

/// The `(problem, part, variant, answer)` an entry is about.
pub type Key<'a> = (&'a str, &'a str, &'a str, &'a str);

impl Overrides {
    /// Reads an overrides file; the error is one line with the file's line number.
    pub fn read(path: &std::path::Path) -> Result<Overrides, String> {
        let shown = visible(&path.display().to_string());
        let meta = std::fs::metadata(path).map_err(|e| format!("cannot read {shown}: {e}"))?;
        if !meta.is_file() {
            return Err(format!("--overrides {shown} is not a regular file"));
        }
        if meta.len() > MAX_BYTES {
            return Err(format!("--overrides {shown} is over 64 MB"));
        }
        let bytes = std::fs::read(path).map_err(|e| format!("cannot read {shown}: {e}"))?;
        Overrides::parse(&bytes).map_err(|e| format!("{shown}: {e}"))
    }

    /// Reads the decisions from a CSV document (UTF-8, `,` or `;` separated, a header naming
    /// `problem`, `part`, `answer` and `decision` in any order and case). Rows with an empty
    /// decision are not decided yet and are skipped.
    pub fn parse(bytes: &[u8]) -> Result<Overrides, String> {
        let bytes = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes);
        let text = std::str::from_utf8(bytes).map_err(|e| {
            let line = bytes[..e.valid_up_to()]
                .iter()
                .filter(|&&b| b == b'\n')
                .count()
                + 1;
            format!("line {line} is not UTF-8; save the file as CSV UTF-8")
        })?;
        let first = text.lines().next().unwrap_or("");
        let delimiter = if first.matches(';').count() > first.matches(',').count() {
            b';'
        } else {
            b','
        };
        let mut reader = csv::ReaderBuilder::new()
            .delimiter(delimiter)
            .flexible(true)
            .has_headers(false)
            .from_reader(text.as_bytes());
        let mut records = reader.records();
        let header = match records.next() {
            Some(Ok(h)) => h,
            Some(Err(e)) => return Err(format!("line 1: {e}")),
            None => return Err("the file is empty; expected a header".to_string()),
        };
        let names: Vec<String> = header.iter().map(|h| h.trim().to_lowercase()).collect();
        let column = |n: &str| names.iter().position(|h| h == n);
        let (Some(problem), Some(part), Some(answer), Some(decision)) = (
            column("problem"),
            column("part"),
            column("answer"),
            column("decision"),
        ) else {
            return Err(
                "line 1: expected the columns `problem`, `part`, `answer` and `decision` \
                 (the review queue, review.csv, has them)"
                    .to_string(),
            );
        };
        let variant = column("variant");
        let mut entries = Vec::new();
        for record in records {
            let record = record.map_err(|e| {
                let line = e.position().map_or(0, |p| p.line());
                format!("line {line}: {e}")
            })?;
            let line = record.position().map_or(0, |p| p.line() as usize);
            let cell = |i: usize| unquote_cell(record.get(i).unwrap_or(""));
            let written = cell(decision).trim().to_string();
            let Some(d) = Decision::parse(&written).map_err(|e| format!("line {line}: {e}"))?
            else {
                continue;
            };
            entries.push(Entry {
                problem: cell(problem).trim().to_string(),
                part: cell(part).trim().to_string(),
                variant: variant.map_or(String::new(), |v| cell(v).trim().to_string()),
                answer: cell(answer).to_string(),
                decision: d,
                written,
                line,
            });
        }
        Ok(Overrides { entries })
    }

    /// The entry deciding each `(problem, part, variant, answer)`: the last of the file.
    pub fn by_key(&self) -> FxHashMap<Key<'_>, usize> {
        (self.entries.iter().enumerate())
            .map(|(i, e)| (e.key(), i))
            .collect()
    }
}

impl Override for Overrides {
    /// Applies the decisions: every graded row (not an error) whose part and exact answer an
    /// entry names gets the decision's status and score, the entry in its `override` column
    /// and a message saying what the checker had said. Rows sharing an outcome share the new
    /// one. The number of rows each entry changed, in entry order.
    /// A decision about an answer on a problem with variants holds for that variant only.
    fn apply(
        &self,
        table: &Table,
        judged: &mut Judged,
        bank: &Bank,
        variants: &Variants,
    ) -> Vec<usize> {
        let mut used = vec![0usize; self.entries.len()];
        if self.entries.is_empty() {
            return used;
        }
        let by_key = self.by_key();
        // One new outcome per (entry, outcome replaced).
        let mut made: FxHashMap<(usize, u32), u32> = FxHashMap::default();
        for (i, row) in table.rows.iter().enumerate() {
            let old = judged.rows[i].outcome;
            let o = judged.outcome_at(old).into_owned();
            let Some((p, q)) = o.target else { continue };
            if o.status == Status::Error {
                continue;
            }
            let problem = &bank.problems[p];
            let part = &problem.parts[q];
            let key = (
                problem.id.as_str(),
                part.id.as_str(),
                variants.label(judged.judged_with(&o).unwrap_or(p)),
                table.answer(row),
            );
            let Some(&e) = by_key.get(&key) else {
                continue;
            };
            used[e] += 1;
            let new = match made.get(&(e, old)) {
                Some(&n) => n,
                None => {
                    let d = self.entries[e].decision;
                    let mut g = o.clone();
                    let said = judged.message(&o).to_string();
                    g.status = match d {
                        Decision::Correct => Status::Correct,
                        _ => Status::Incorrect,
                    };
                    g.score = d.fraction() * part.points;
                    g.decision = Some(d);
                    let was = if said.is_empty() {
                        format!("the checker said {}", o.status.name())
                    } else {
                        format!("the checker said {}: {said}", o.status.name())
                    };
                    g.message = Some(format!("instructor's decision: {d} ({was})"));
                    let n = judged.add(g);
                    made.insert((e, old), n);
                    n
                }
            };
            judged.rows[i].outcome = new;
        }
        used
    }
}

impl Entry {
    /// What the entry is about.
    fn key(&self) -> Key<'_> {
        (
            self.problem.as_str(),
            self.part.as_str(),
            self.variant.as_str(),
            self.answer.as_str(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decisions_are_read_by_column_name_in_any_order_and_separator() {
        let file = "decision;answer;part;problem;students\n\
                    correct;mgl;potential;simple-pendulum;3\n\
                    ;x;eom;simple-pendulum;1\n\
                    0.5;'-m g l;potential;simple-pendulum;1\n";
        let o = Overrides::parse(file.as_bytes()).unwrap();
        assert_eq!(o.entries.len(), 2);
        assert_eq!(o.entries[0].decision, Decision::Correct);
        assert_eq!(o.entries[0].line, 2);
        // A cell neutralised against spreadsheet formulas reads as typed.
        assert_eq!(o.entries[1].answer, "-m g l");
        assert_eq!(o.entries[1].line, 4);
        let bad = Overrides::parse(b"problem,part,answer,decision\np,q,a,perhaps\n").unwrap_err();
        assert!(bad.starts_with("line 2: "), "{bad}");
        assert!(Overrides::parse(b"problem,part,answer\n").is_err());
    }
}

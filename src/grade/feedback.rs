//! `grade --feedback`: one file per student, Markdown and HTML, under `OUT/feedback/`, with
//! every answer they gave, how it was read, the verdict, the diagnosis and the hint a tutor
//! would give next — ready to upload or mail.
//!
//! A file is named from the student key: `[A-Za-z0-9._@-]` kept, every other byte
//! percent-encoded (`%2F` for `/`, `%25` for `%`), a leading `.` too (`%2E`), so a name is
//! never hidden, never a path and never `..`; a key of over 180 such bytes is cut and ends
//! with a hash of the whole key. Two keys mapping to one name (compared ignoring case, as some
//! file systems do) are an error before anything is graded. Every text is escaped: HTML
//! entities in the HTML file, code spans and backslashes in the Markdown one.

use std::fmt::Write as _;
use std::path::Path;

use lagrange::bank::Bank;
use lagrange::expr::error::visible;
use lagrange::tutor::first_hint;

use super::input::{NONE, Table};
use super::judge::{Judged, Status};
use super::output::Gradebook;
use super::summary::{cell, num};
use super::variants::Variants;

/// The longest name kept whole (bytes, before the extension).
const LONGEST: usize = 180;

/// Students whose files are written, then renamed into place, at a time (each staged file
/// holds an open file until its rename).
const BATCH: usize = 64;

/// The file name (without extension) for a student key.
pub fn file_name(key: &str) -> String {
    let mut name = String::with_capacity(key.len());
    for (i, b) in key.bytes().enumerate() {
        let keep = b.is_ascii_alphanumeric() || matches!(b, b'.' | b'_' | b'@' | b'-');
        if keep && !(i == 0 && b == b'.') {
            name.push(b as char);
        } else {
            let _ = write!(name, "%{b:02X}");
        }
    }
    if name.len() > LONGEST {
        let mut cut = LONGEST;
        // Not inside a `%XX`.
        while let Some(p) = name[..cut].rfind('%').filter(|&p| p + 3 > cut) {
            cut = p;
        }
        let mut h: u64 = 0xcbf2_9ce4_8422_2325;
        for b in key.bytes() {
            h = (h ^ u64::from(b)).wrapping_mul(0x0100_0000_01b3);
        }
        name.truncate(cut);
        let _ = write!(name, "--{h:016x}");
    }
    name
}

/// Every student's file name, in student order; two keys with one name (ignoring case) are an
/// error naming both.
pub fn names(students: &[String]) -> Result<Vec<String>, String> {
    let names: Vec<String> = students.iter().map(|s| file_name(s)).collect();
    let mut seen: rustc_hash::FxHashMap<String, usize> = rustc_hash::FxHashMap::default();
    for (i, n) in names.iter().enumerate() {
        if let Some(&j) = seen.get(&n.to_lowercase()) {
            return Err(format!(
                "--feedback: the student keys `{}` and `{}` would both be written to \
                 feedback/{n}.md; rename one of them in the class file",
                visible(&students[j]),
                visible(&students[i])
            ));
        }
        seen.insert(n.to_lowercase(), i);
    }
    Ok(names)
}

/// Checks, before grading, that `OUT/feedback` can be written: free, or a folder (not a link).
pub fn check_dir(dir: &Path) -> Result<(), String> {
    match std::fs::symlink_metadata(dir) {
        Err(_) => Ok(()),
        Ok(m) if m.is_dir() => Ok(()),
        Ok(_) => Err(format!(
            "{} is not a folder (a link or a file); grade writes the feedback files into a \
             folder it makes there (remove it, or choose another --out)",
            visible(&dir.display().to_string())
        )),
    }
}

/// One answer as the files show it.
struct Shown {
    part: String,
    attempt: usize,
    attempts: usize,
    counts: bool,
    answer: String,
    /// The student's numbers the answer was judged with (empty: the same for everyone).
    numbers: String,
    read_as: String,
    status: Status,
    score: String,
    counted: Option<String>,
    points: String,
    codes: String,
    message: String,
    hint: Option<String>,
}

/// Writes `feedback/NAME.md` and `feedback/NAME.html` for every student into `dir` (through
/// the safe writer: whole files renamed into place, links refused); the number of students.
pub fn write(
    dir: &Path,
    table: &Table,
    judged: &Judged,
    bank: &Bank,
    book: &Gradebook<'_>,
    variants: &Variants,
) -> Result<usize, String> {
    let names = names(&table.students)?;
    let files: Vec<String> = (names.iter())
        .flat_map(|n| [format!("{n}.md"), format!("{n}.html")])
        .collect();
    let refs: Vec<&str> = files.iter().map(String::as_str).collect();
    let folder = crate::face::outfile::Folder::open(dir, &refs)?;
    // Each student's rows: by part (bank order), then in file order; rows naming no part last.
    let mut order: Vec<u32> = (0..table.rows.len() as u32)
        .filter(|&i| table.rows[i as usize].student != NONE)
        .collect();
    let key = |i: u32| {
        let r = &table.rows[i as usize];
        let t = judged.brief(i as usize).target.unwrap_or((usize::MAX, 0));
        (r.student, t, i)
    };
    order.sort_unstable_by_key(|&i| key(i));
    let mut hints: rustc_hash::FxHashMap<(usize, usize), Option<String>> = Default::default();
    let mut start = 0;
    let mut staged = Vec::new();
    for (s, name) in names.iter().enumerate() {
        let mut end = start;
        while end < order.len() && table.rows[order[end] as usize].student as usize == s {
            end += 1;
        }
        let rows = &order[start..end];
        start = end;
        let shown = shown(rows, (table, judged, bank, variants), &mut hints);
        let scores = book.scores(s);
        let head = Head {
            key: &table.students[s],
            total: scores.iter().flatten().sum(),
            max: book.max(),
            // The parts set that no answer of this student counts for.
            missing: (book.columns.iter().zip(scores))
                .filter(|(_, sc)| sc.is_none())
                .map(|(c, _)| c.as_str())
                .collect(),
        };
        staged.push(folder.stage(&format!("{name}.md"), markdown(&head, &shown).as_bytes())?);
        staged.push(folder.stage(&format!("{name}.html"), html(&head, &shown).as_bytes())?);
        if staged.len() >= 2 * BATCH {
            sound(judged)?;
            crate::face::outfile::commit(std::mem::take(&mut staged))?;
        }
    }
    sound(judged)?;
    crate::face::outfile::commit(staged)?;
    Ok(names.len())
}

/// Whether every word the files were made from was read back (else none of them is put in
/// place: a batch is checked before it is renamed).
fn sound(judged: &Judged) -> Result<(), String> {
    judged.lost().map_or(Ok(()), |m| {
        Err(format!("{m}; no more feedback was written"))
    })
}

/// A student's answers as shown.
fn shown(
    rows: &[u32],
    (table, judged, bank, variants): (&Table, &Judged, &Bank, &Variants),
    hints: &mut rustc_hash::FxHashMap<(usize, usize), Option<String>>,
) -> Vec<Shown> {
    let mut out: Vec<Shown> = Vec::with_capacity(rows.len());
    let mut k = 0;
    while k < rows.len() {
        let target = judged.brief(rows[k] as usize).target;
        let mut end = k + 1;
        while target.is_some()
            && end < rows.len()
            && judged.brief(rows[end] as usize).target == target
        {
            end += 1;
        }
        for (n, &i) in rows[k..end].iter().enumerate() {
            let i = i as usize;
            let row = &table.rows[i];
            let o = judged.outcome(i);
            let part = match target {
                Some((p, q)) => format!("{}/{}", bank.problems[p].id, bank.problems[p].parts[q].id),
                None => format!("{}/{}", table.problem(row), table.part(row)),
            };
            let points = target.map_or(0.0, |(p, q)| bank.problems[p].parts[q].points);
            let read_as = o
                .rep
                .map_or(String::new(), |r| judged.reading(r).to_string());
            let hint = match (o.status, target) {
                (Status::Incorrect | Status::Invalid, Some((p, q))) => hints
                    .entry((p, q))
                    .or_insert_with(|| first_hint(&bank.problems[p], &bank.problems[p].parts[q]))
                    .clone(),
                _ => None,
            };
            let counts = judged.rows[i].counts;
            let counted = judged.counted_score(i);
            out.push(Shown {
                part,
                attempt: n + 1,
                attempts: end - k,
                counts,
                answer: table.answer(row).to_string(),
                numbers: target.map_or(String::new(), |(p, _)| {
                    variants
                        .label(judged.judged_with(&o).unwrap_or(p))
                        .to_string()
                }),
                read_as,
                status: o.status,
                score: num(o.score),
                counted: (counts && counted != o.score).then(|| num(counted)),
                points: num(points),
                codes: (o.codes.iter().map(|c| c.as_str()))
                    .collect::<Vec<_>>()
                    .join(", "),
                message: judged.message(&o).to_string(),
                hint,
            });
        }
        k = end;
    }
    out
}

/// "1 point" or "2 points".
fn points(p: &str) -> String {
    if p == "1" {
        "1 point".to_string()
    } else {
        format!("{p} points")
    }
}

/// The percent of `max`, one decimal (empty when `max` is 0).
fn percent(total: f64, max: f64) -> String {
    if max > 0.0 {
        format!(" ({:.1} %)", 100.0 * total / max)
    } else {
        String::new()
    }
}

/// A Markdown code span of a student's text (control characters shown escaped; fenced by more
/// backticks than the text holds in a row, so nothing in it is interpreted).
fn code(s: &str) -> String {
    let s = visible(s);
    let longest = s.split(|c| c != '`').map(str::len).max().unwrap_or(0);
    let fence = "`".repeat(longest + 1);
    if longest == 0 {
        format!("`{s}`")
    } else {
        format!("{fence} {s} {fence}")
    }
}

/// The headline of one answer: which part, which attempt, whether it counts.
fn title(a: &Shown) -> String {
    let mut t = a.part.clone();
    if a.attempts > 1 {
        let _ = write!(t, ", attempt {} of {}", a.attempt, a.attempts);
    }
    if a.counts && a.attempts > 1 {
        t.push_str(" (counts)");
    }
    t
}

/// The verdict line: status and score.
fn verdict(a: &Shown) -> String {
    let mut v = match a.status {
        Status::Error => "not graded".to_string(),
        s => format!("{}, {} of {}", s.name(), a.score, points(&a.points)),
    };
    if let Some(c) = &a.counted {
        let _ = write!(v, "; counts for {c} after the penalty for extra attempts");
    }
    v
}

/// What heads a student's file: the key, the total of the parts set and those not answered.
struct Head<'b> {
    key: &'b str,
    total: f64,
    max: f64,
    missing: Vec<&'b str>,
}

/// The Markdown file.
fn markdown(head: &Head, answers: &[Shown]) -> String {
    let (total, max) = (head.total, head.max);
    let mut out = format!("# Feedback for {}\n\n", cell(head.key));
    let _ = writeln!(
        out,
        "Total: {} of {}{}.\n",
        num(total),
        points(&num(max)),
        percent(total, max)
    );
    if !head.missing.is_empty() {
        let _ = writeln!(out, "Not answered: {}.\n", cell(&head.missing.join(", ")));
    }
    for a in answers {
        let _ = writeln!(out, "## {}\n", cell(&title(a)));
        if !a.numbers.is_empty() {
            let _ = writeln!(out, "- Your numbers: {}", cell(&a.numbers));
        }
        let _ = writeln!(out, "- Your answer: {}", code(&a.answer));
        if !a.read_as.is_empty() {
            let _ = writeln!(out, "- Read as: {}", code(&a.read_as));
        }
        let _ = writeln!(out, "- Verdict: {}", cell(&verdict(a)));
        if !a.message.is_empty() {
            let codes = if a.codes.is_empty() {
                String::new()
            } else {
                format!(" ({})", cell(&a.codes))
            };
            let _ = writeln!(out, "- Diagnosis: {}{codes}", cell(&a.message));
        }
        if let Some(h) = &a.hint {
            let _ = writeln!(out, "- Next hint: {}", cell(h));
        }
        out.push('\n');
    }
    out
}

/// Text escaped for HTML (control characters shown escaped first).
fn esc(s: &str) -> String {
    let s = visible(s);
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&#39;"),
            _ => out.push(c),
        }
    }
    out
}

/// The HTML file: a page of its own, no script, no outside resource.
fn html(head: &Head, answers: &[Shown]) -> String {
    let (total, max) = (head.total, head.max);
    let key = esc(head.key);
    let mut out = format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>Feedback for {key}</title>\n\
         <style>body{{font-family:sans-serif;max-width:50em;margin:1em auto}}\
         code{{background:#f3f3f3;padding:0 .2em}}</style>\n</head>\n<body>\n\
         <h1>Feedback for {key}</h1>\n"
    );
    let _ = writeln!(
        out,
        "<p>Total: {} of {}{}.</p>",
        num(total),
        points(&num(max)),
        esc(&percent(total, max))
    );
    if !head.missing.is_empty() {
        let _ = writeln!(
            out,
            "<p>Not answered: {}.</p>",
            esc(&head.missing.join(", "))
        );
    }
    for a in answers {
        let _ = writeln!(out, "<h2>{}</h2>\n<ul>", esc(&title(a)));
        if !a.numbers.is_empty() {
            let _ = writeln!(out, "<li>Your numbers: {}</li>", esc(&a.numbers));
        }
        let _ = writeln!(out, "<li>Your answer: <code>{}</code></li>", esc(&a.answer));
        if !a.read_as.is_empty() {
            let _ = writeln!(out, "<li>Read as: <code>{}</code></li>", esc(&a.read_as));
        }
        let _ = writeln!(out, "<li>Verdict: {}</li>", esc(&verdict(a)));
        if !a.message.is_empty() {
            let codes = if a.codes.is_empty() {
                String::new()
            } else {
                format!(" ({})", esc(&a.codes))
            };
            let _ = writeln!(out, "<li>Diagnosis: {}{codes}</li>", esc(&a.message));
        }
        if let Some(h) = &a.hint {
            let _ = writeln!(out, "<li>Next hint: {}</li>", esc(h));
        }
        out.push_str("</ul>\n");
    }
    out.push_str("</body>\n</html>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_keep_safe_bytes_and_encode_the_rest() {
        assert_eq!(file_name("ada@uni.example"), "ada@uni.example");
        assert_eq!(file_name("../../x"), "%2E.%2F..%2Fx");
        assert_eq!(file_name(".hidden"), "%2Ehidden");
        assert_eq!(file_name("a b%"), "a%20b%25");
        assert_eq!(file_name("é"), "%C3%A9");
        let long = file_name(&"é".repeat(100));
        assert!(long.len() <= LONGEST + 18, "{long}");
        assert!(!long.contains("%C--") && long.contains("--"), "{long}");
        assert_ne!(long, file_name(&"é".repeat(101)));
    }

    #[test]
    fn two_keys_with_one_name_are_an_error() {
        let keys = vec!["Ab".to_string(), "ab".to_string()];
        let e = names(&keys).unwrap_err();
        assert!(e.contains("`Ab`") && e.contains("`ab`"), "{e}");
        assert!(names(&["a".to_string(), "b".to_string()]).is_ok());
    }

    #[test]
    fn html_escapes_everything_a_student_typed() {
        assert_eq!(esc("<script>&\"'"), "&lt;script&gt;&amp;&quot;&#39;");
    }
}

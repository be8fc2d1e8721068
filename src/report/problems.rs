//! Reports on the problem bank: [`ProblemList`] (`problems list`), [`ProblemSheet`]
//! (`problems show`: a problem for a terminal) and [`Verification`] (`problems verify`: every
//! stated answer proved against the physics).

use std::fmt::{self, Write as _};

use serde::Serialize;

use super::{Paint, text};
use crate::bank::{Bank, Problem, verify::verify};
use crate::expr::error::{visible, visible_lines};
use crate::expr::names;
use crate::problem::variant::fill;

/// One line per problem of a bank, and the files that failed to load.
#[derive(Clone, Debug, Serialize)]
pub struct ProblemList {
    /// The problems, in bank order.
    pub(crate) problems: Vec<ListedProblem>,
    /// Why each broken file failed to load.
    pub(crate) failures: Vec<String>,
}

/// A problem as listed.
#[derive(Clone, Debug, Serialize)]
pub struct ListedProblem {
    /// Its id.
    pub(crate) id: String,
    /// Its title.
    pub(crate) title: String,
    /// The ids of its parts.
    pub(crate) parts: Vec<String>,
}

/// The list of `bank`.
pub fn problem_list(bank: &Bank) -> ProblemList {
    ProblemList {
        problems: bank
            .problems
            .iter()
            .map(|p| ListedProblem {
                id: p.id.clone(),
                title: p.title.clone(),
                parts: p.parts.iter().map(|x| x.id.clone()).collect(),
            })
            .collect(),
        failures: failures(bank),
    }
}

fn failures(bank: &Bank) -> Vec<String> {
    bank.failures.iter().map(ToString::to_string).collect()
}

fn render_failures(failures: &[String], paint: &dyn Paint, o: &mut String) -> fmt::Result {
    for f in failures {
        writeln!(o, "{} {f}", paint.bad("✗"))?;
    }
    Ok(())
}

impl ProblemList {
    /// Two lines per problem (id and title; part ids), then the failures.
    pub fn render(&self, paint: &dyn Paint) -> String {
        text(|o| self.write_text(paint, o))
    }

    fn write_text(&self, paint: &dyn Paint, o: &mut String) -> fmt::Result {
        let w = self.problems.iter().map(|p| p.id.len()).max().unwrap_or(0);
        // Ids are checked on loading; titles are the file's text, shown made visible.
        for p in &self.problems {
            // Padded before painting, so that escape codes do not count towards the width.
            writeln!(
                o,
                "{}  {}\n{:w$}  parts: {}",
                paint.heading(&format!("{:w$}", p.id)),
                visible(&p.title),
                "",
                p.parts.join(", ")
            )?;
        }
        render_failures(&self.failures, paint, o)
    }
}

/// A problem as a student reads it, with the reference answers for an instructor.
#[derive(Clone, Debug, Serialize)]
pub struct ProblemSheet {
    /// Its id.
    pub id: String,
    /// Its title.
    pub(crate) title: String,
    /// Where it comes from (empty: not given).
    pub(crate) source: String,
    /// The statement, with inline math made readable on a terminal.
    pub statement: String,
    /// The coordinates, in Unicode.
    pub(crate) coordinates: Vec<String>,
    /// The parameters in Unicode, with their dimensions when known.
    pub(crate) parameters: Vec<String>,
    /// The stated assumptions.
    pub(crate) assumptions: Vec<String>,
    /// The named quantities the problem defines, each `θ₀ = acos(g/(R·ω²))` in Unicode.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(crate) definitions: Vec<String>,
    /// The parts.
    pub(crate) parts: Vec<SheetPart>,
    /// The parameters that vary from student to student (empty: none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(crate) varies: Vec<String>,
    /// The student this sheet is for (`--student`), with their numbers.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) student: Option<String>,
    /// The student's numbers, each `m = 1.5 kg`.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub numbers: Vec<String>,
    /// The course seed the student's numbers come from (`--seed`; only when the problem's
    /// numbers vary), which the sheet's `lagrange check` line repeats.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) seed: Option<u64>,
}

/// A part of a problem sheet.
#[derive(Clone, Debug, Serialize)]
pub struct SheetPart {
    /// Its id.
    pub(crate) id: String,
    /// What kind of answer it asks for.
    pub(crate) kind: String,
    /// Its weight.
    pub(crate) points: f64,
    /// The question, with inline math made readable on a terminal.
    pub(crate) prompt: String,
    /// The reference answers, when asked for.
    pub(crate) answers: Option<Vec<String>>,
    /// The answer may use the student's numbers.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub(crate) numbers: bool,
}

/// A part's prompt followed by how its answer is written, where that is not plain (a numeric
/// part's units, a growth-rates part's λ): every sheet shows the same words.
pub(crate) fn with_answer_form(part: &crate::problem::Part, prompt: String) -> String {
    match crate::check::units::answer_form(part) {
        Some(form) => format!("{prompt} ({form})"),
        None => prompt,
    }
}

/// The sheet of `p`; with `answers`, the reference answers too.
pub fn problem_sheet(p: &Problem, answers: bool) -> ProblemSheet {
    let mut pool = p.system.pool.clone();
    let coordinates = p
        .system
        .coordinates
        .iter()
        .map(|c| {
            let v = pool.var(c.sym, 0);
            pool.unicode(v)
        })
        .collect();
    let parameters = p
        .system
        .parameters
        .iter()
        .map(|q| {
            let v = pool.var(q.sym, 0);
            match q.dimension {
                Some(d) => format!("{} [{d}]", pool.unicode(v)),
                None => pool.unicode(v),
            }
        })
        .collect();
    let definitions = p
        .system
        .definitions
        .iter()
        .map(|(name, value)| {
            let named = pool.symbol(name);
            let named = pool.var(named, 0);
            format!("{} = {}", pool.unicode(named), pool.unicode(*value))
        })
        .collect();
    ProblemSheet {
        definitions,
        id: p.id.clone(),
        title: p.title.clone(),
        source: p.source.clone(),
        statement: terminal_math(&fill(p.statement.trim(), &p.variants, None)),
        coordinates,
        parameters,
        // In Unicode, as everything else on the sheet (R ω² > g, not R*omega^2 > g).
        assumptions: p
            .assumptions
            .iter()
            .map(|a| {
                let or_equal = a.text.contains(['=', '≥', '≤']);
                let op = match (a.greater, or_equal) {
                    (true, false) => ">",
                    (true, true) => "≥",
                    (false, false) => "<",
                    (false, true) => "≤",
                };
                format!("{} {op} {}", pool.unicode(a.lhs), pool.unicode(a.rhs))
            })
            .collect(),
        parts: p
            .parts
            .iter()
            .map(|part| SheetPart {
                id: part.id.clone(),
                kind: part.kind.name().to_string(),
                points: part.points,
                prompt: with_answer_form(
                    part,
                    terminal_math(&fill(&part.prompt, &p.variants, None)),
                ),
                answers: answers.then(|| part.reference_items()),
                numbers: part.numbers,
            })
            .collect(),
        varies: p.variants.iter().map(|v| v.name.clone()).collect(),
        student: None,
        numbers: Vec::new(),
        seed: None,
    }
}

impl ProblemSheet {
    /// The statement, symbols, assumptions and parts, and how to answer.
    pub fn render(&self, paint: &dyn Paint) -> String {
        text(|o| self.write_text(paint, o))
    }

    fn write_text(&self, paint: &dyn Paint, o: &mut String) -> fmt::Result {
        let h = |t: &str| paint.heading(t);
        // The file's text is shown with control and invisible characters made visible, so a
        // problem file cannot drive the terminal (colours come from `paint`, after this).
        writeln!(o, "{}  ({})", h(&visible(&self.title)), visible(&self.id))?;
        if !self.source.is_empty() {
            writeln!(o, "{}", paint.dim(&visible(&self.source)))?;
        }
        writeln!(o, "\n{}", visible_lines(&self.statement))?;
        writeln!(o, "\n{} {}", h("coordinates:"), self.coordinates.join(", "))?;
        writeln!(o, "{} {}", h("parameters: "), self.parameters.join(", "))?;
        if !self.assumptions.is_empty() {
            let shown = visible(&self.assumptions.join(", "));
            writeln!(o, "{} {shown}", h("assuming:   "))?;
        }
        if !self.definitions.is_empty() {
            writeln!(o, "{} {}", h("defined:    "), self.definitions.join(", "))?;
        }
        write_numbers(self, paint, o)?;
        for (i, part) in self.parts.iter().enumerate() {
            writeln!(
                o,
                "\n{} {} ({}, {} point{})",
                h(&format!("{}.", i + 1)),
                h(&visible(&part.id)),
                part.kind,
                part.points,
                if part.points == 1.0 { "" } else { "s" }
            )?;
            writeln!(o, "   {}", visible_lines(&part.prompt))?;
            if part.numbers {
                writeln!(o, "   {}", paint.dim("(in symbols, or with your numbers)"))?;
            }
            if let Some(answers) = &part.answers {
                let shown = visible(&answers.join("; "));
                writeln!(o, "   {} {shown}", paint.dim("answer:"))?;
            }
        }
        // The student's numbers depend on the seed too: a check without it judges others.
        let student = self.student.as_deref().map_or(String::new(), |k| {
            format!(" --student {}", shell_word(&visible(k)))
        });
        let seed = self.seed.map_or(String::new(), |s| format!(" --seed {s}"));
        writeln!(
            o,
            "\nAnswer with `lagrange check {} <part> \"<answer>\"{student}{seed}`.",
            visible(&self.id)
        )
    }
}

/// The `varies:` line of a sheet for no student, or the student and their numbers.
fn write_numbers(s: &ProblemSheet, paint: &dyn Paint, o: &mut String) -> fmt::Result {
    let h = |t: &str| paint.heading(t);
    if let Some(student) = &s.student {
        writeln!(o, "{} {}", h("student:    "), visible(student))?;
    }
    if !s.numbers.is_empty() {
        writeln!(
            o,
            "{} {}",
            h("numbers:    "),
            visible(&s.numbers.join(", "))
        )?;
    } else if !s.varies.is_empty() && s.student.is_none() {
        writeln!(
            o,
            "{} {} (each student's own numbers: --student KEY; :variant to practise)",
            h("varies:     "),
            s.varies.join(", ")
        )?;
    }
    Ok(())
}

/// `s` quoted for a POSIX shell when it holds anything but safe characters.
pub(super) fn shell_word(s: &str) -> String {
    if !s.is_empty()
        && s.chars()
            .all(|c| c.is_ascii_alphanumeric() || "@._-+".contains(c))
    {
        s.to_string()
    } else {
        format!("'{}'", s.replace('\'', "'\\''"))
    }
}

/// LaTeX-ish inline math for a terminal: `$\theta_1$` → θ₁, `$m^2$` → m².
/// `\sqrt{k/m}` → √(k/m), `\frac{a}{b}` → a/b, `_{12}` → ₁₂ likewise.
pub fn terminal_math(text: &str) -> String {
    let mut s = braces(&text.replace('$', ""));
    for (c, name) in names::GREEK {
        s = s.replace(&format!("\\{name}"), &c.to_string());
    }
    for (from, to) in [
        ("\\varphi", "φ"),
        ("\\pi", "π"),
        ("\\cdot", "·"),
        ("\\,", " "),
    ] {
        s = s.replace(from, to);
    }
    let mut out = String::with_capacity(s.len());
    let mut chars = s.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '_' | '^' if chars.peek().is_some_and(|d| d.is_ascii_digit()) => {
                let mut digits = String::new();
                while let Some(d) = chars.peek().filter(|d| d.is_ascii_digit()) {
                    digits.push(*d);
                    chars.next();
                }
                if c == '_' {
                    out.push_str(&names::subscript(&digits));
                } else {
                    out.push_str(&names::superscript(digits.parse().unwrap_or(0)));
                }
            }
            _ => out.push(c),
        }
    }
    out
}

/// `\sqrt{…}` and `\frac{…}{…}` as √ and /, with brackets round a group of more than one
/// symbol; the braces of `_{…}` and `^{…}` dropped (their digits become scripts afterwards).
fn braces(text: &str) -> String {
    // The group that starts at `s` (just after its `{`) and the text after its `}`.
    fn group(s: &str) -> (&str, &str) {
        let mut depth = 1;
        for (i, c) in s.char_indices() {
            match c {
                '{' => depth += 1,
                '}' => {
                    depth -= 1;
                    if depth == 0 {
                        return (&s[..i], &s[i + 1..]);
                    }
                }
                _ => {}
            }
        }
        (s, "")
    }
    fn atom(s: &str) -> String {
        let s = braces(s);
        if s.chars().count() <= 1 || s.chars().all(char::is_alphanumeric) {
            s
        } else {
            format!("({s})")
        }
    }
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(i) = rest.find(['\\', '_', '^']) {
        out.push_str(&rest[..i]);
        let tail = &rest[i..];
        if let Some(t) = tail.strip_prefix("\\sqrt{") {
            let (inner, after) = group(t);
            out.push('√');
            out.push_str(&atom(inner));
            rest = after;
        } else if let Some(t) = tail.strip_prefix("\\frac{") {
            let (num, after) = group(t);
            let (den, after) = match after.strip_prefix('{') {
                Some(a) => group(a),
                None => ("", after),
            };
            out.push_str(&format!("{}/{}", atom(num), atom(den)));
            rest = after;
        } else if let Some(t) = tail.get(1..).and_then(|t| t.strip_prefix('{')) {
            let (inner, after) = group(t);
            out.push_str(&tail[..1]);
            out.push_str(&braces(inner));
            rest = after;
        } else {
            let n = tail.chars().next().map_or(1, char::len_utf8);
            out.push_str(&tail[..n]);
            rest = &tail[n..];
        }
    }
    out.push_str(rest);
    out
}

/// Every problem of a bank checked against the physics, and the files that failed to load.
#[derive(Clone, Debug, Serialize)]
#[non_exhaustive]
pub struct Verification {
    /// One entry per loaded problem, in bank order.
    pub(crate) problems: Vec<VerifiedProblem>,
    /// Why each broken file failed to load.
    pub(crate) failures: Vec<String>,
}

/// One problem's verification.
#[derive(Clone, Debug, Serialize)]
pub struct VerifiedProblem {
    /// Its id.
    pub(crate) id: String,
    /// How many parts it has.
    pub(crate) parts: usize,
    /// What is wrong with it (empty: every part proved).
    pub(crate) findings: Vec<String>,
    /// What verification could not decide and so did not check (not failures).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub(crate) notes: Vec<String>,
}

/// Verifies every problem of `bank`.
/// Two problems with one id (from files of different names, or from several folders) are a
/// finding on the second: `check` would reach only the first.
pub fn verification(bank: &Bank) -> Verification {
    Verification {
        problems: bank
            .problems
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let mut findings: Vec<String> = Vec::new();
                if let Some(first) = bank.problems[..i].iter().find(|q| q.id == p.id) {
                    let f = crate::bank::Finding {
                        file: p.file.clone(),
                        problem: Some(p.id.clone()),
                        part: None,
                        line: 1,
                        code: crate::bank::FindingCode::DuplicateId,
                        message: format!("{} already defines the problem `{}`", first.file, p.id),
                    };
                    findings.push(f.to_string());
                }
                findings.extend(verify(p).iter().map(ToString::to_string));
                VerifiedProblem {
                    id: p.id.clone(),
                    parts: p.parts.len(),
                    findings,
                    notes: undecided_dimensions(p)
                        .into_iter()
                        .chain(crate::bank::verify_variants::coverage(p))
                        .collect(),
                }
            })
            .collect(),
        failures: failures(bank),
    }
}

/// The problem's Lagrangian has a dimension that cannot be decided (a power with a symbolic
/// exponent, `k·r^n`): said, since the dimension check then proves nothing about it.
fn undecided_dimensions(p: &crate::problem::Problem) -> Vec<String> {
    let declared = p
        .system
        .coordinates
        .iter()
        .map(|c| c.name.as_str())
        .chain(p.system.parameters.iter().map(|q| q.name.as_str()))
        .all(|n| p.dims.get(n).is_some());
    match p.system.pool.dimension(p.system.lagrangian, &p.dims) {
        Ok(None) if declared => vec![
            "the dimension of L cannot be decided (a power with a symbolic exponent has one that depends on the exponent's value): it was not checked".into(),
        ],
        _ => Vec::new(),
    }
}

impl Verification {
    /// How many problems fail: broken files and problems with findings.
    pub fn failing(&self) -> usize {
        self.failures.len()
            + self
                .problems
                .iter()
                .filter(|p| !p.findings.is_empty())
                .count()
    }

    /// A ✓ or ✗ line per problem with its findings, the load failures, and a count.
    pub fn render(&self, paint: &dyn Paint) -> String {
        text(|o| self.write_text(paint, o))
    }

    fn write_text(&self, paint: &dyn Paint, o: &mut String) -> fmt::Result {
        for p in &self.problems {
            if p.findings.is_empty() {
                writeln!(
                    o,
                    "{} {} ({} parts proved)",
                    paint.good("✓"),
                    visible(&p.id),
                    p.parts
                )?;
                for n in &p.notes {
                    writeln!(o, "  note: {n}")?;
                }
            } else {
                writeln!(o, "{} {}", paint.bad("✗"), visible(&p.id))?;
                for f in &p.findings {
                    writeln!(o, "  {f}")?;
                }
            }
        }
        render_failures(&self.failures, paint, o)?;
        writeln!(
            o,
            "{} problems, {} failing",
            self.problems.len() + self.failures.len(),
            self.failing()
        )
    }
}

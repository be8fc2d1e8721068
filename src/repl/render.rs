//! Text for every [`Response`] of a tutor session: the verdict with its reading, diagnoses
//! and score, statements, hints, lists, help, analyses and errors. Colour comes through a
//! [`Paint`] (the terminal's, or none); no mathematics here.

use std::fmt::Write as _;

use lagrange::check::{Status, Verdict};
use lagrange::diagnostic::render_parse_error;
use lagrange::expr::Style;
use lagrange::report::Paint;
use lagrange::tutor::Response;
use lagrange::tutor::response::{
    AnalysisReply, AnalysisReport, ErrorReply, HintReply, PartsReply, ProblemEntry, SolutionReply,
    StepPrompt,
};

/// How `:read` asks for dimensions in the REPL (the CLI says `--dims`).
const GIVE_DIMENSIONS: &str = "dimensions come from the open problem";

/// The width of `:help`'s usage column.
const HELP_COLUMN: usize = 18;

/// The text of one response to `line`, ending in a newline (empty for `Quit`).
pub fn response(r: &Response, line: &str, paint: &dyn Paint, color: bool) -> String {
    let mut o = String::new();
    write_response(&mut o, r, line, paint, color).expect("writing into a String cannot fail");
    o
}

fn write_response(
    o: &mut String,
    r: &Response,
    line: &str,
    paint: &dyn Paint,
    color: bool,
) -> std::fmt::Result {
    match r {
        Response::Verdict(v) => verdict(o, &v.verdict, v.attempts, line, paint, color),
        Response::Step(st) => step(o, st, paint),
        Response::StepVerdict(v) => {
            verdict(o, &v.verdict, v.attempts, line, paint, color)?;
            match &v.next {
                Some(next) => next_step(o, next.as_ref(), paint),
                None => Ok(()),
            }
        }
        Response::StepSolution(s) => {
            writeln!(
                o,
                "{} {}",
                paint.heading(&format!("step {} of {} ({}):", s.number, s.total, s.step)),
                s.answer
            )?;
            if !s.unicode.is_empty() {
                writeln!(o, "{} {}", paint.dim("read as:"), s.unicode)?;
            }
            next_step(o, s.next.as_ref(), paint)
        }
        Response::Statement(s) => {
            let text = s.sheet.render(paint);
            // The sheet ends with how to answer on the command line; in the REPL one types.
            let text = text
                .rsplit_once("\nAnswer with `lagrange check")
                .map_or(text.as_str(), |(head, _)| head);
            writeln!(o, "{}", text.trim_end())
        }
        Response::Part(p) => {
            let state = if p.solved { " (solved)" } else { "" };
            writeln!(
                o,
                "{} {}{state}\n   {}",
                paint.heading(&format!("part {}: {}", p.number, p.part)),
                paint.dim(&format!("({})", p.part_kind)),
                p.prompt
            )
        }
        Response::Done(d) => writeln!(
            o,
            "{} every part of {} is solved ({} of {}). `:problems` for the next one.",
            paint.good("done:"),
            d.problem,
            d.parts,
            d.parts
        ),
        Response::Hint(h) => hint(o, h, paint),
        Response::Solution(s) => solution(o, s, paint),
        Response::Problems(p) => problems(o, &p.problems, paint),
        Response::Progress(p) => {
            problems(o, &p.problems, paint)?;
            writeln!(
                o,
                "{} {} of {} parts solved",
                paint.heading("total:"),
                p.solved,
                p.parts
            )
        }
        Response::Parts(p) => parts(o, p, paint),
        Response::Help(h) => {
            // Padded before painting (colour codes take no column); a usage longer than the
            // column puts its summary on the next line, under the others.
            for c in &h.commands {
                let usage = paint.heading(&c.usage);
                match HELP_COLUMN.checked_sub(c.usage.chars().count()) {
                    Some(pad) => writeln!(o, "  {usage}{} {}", " ".repeat(pad), c.summary)?,
                    None => writeln!(o, "  {usage}\n  {} {}", " ".repeat(HELP_COLUMN), c.summary)?,
                }
            }
            Ok(())
        }
        Response::Analysis(a) => analysis(o, a, paint),
        Response::Error(e) => error(o, e, paint),
        Response::Quit => Ok(()),
    }
}

/// The reference answer, after its worked derivation.
fn solution(o: &mut String, s: &SolutionReply, paint: &dyn Paint) -> std::fmt::Result {
    if !s.derivation.is_empty() {
        writeln!(o, "{}", paint.heading("worked derivation:"))?;
        for (i, w) in s.derivation.iter().enumerate() {
            writeln!(o, "  {}. {}", i + 1, paint.dim(&w.prompt))?;
            let shown = if w.unicode.is_empty() {
                &w.answer
            } else {
                &w.unicode
            };
            writeln!(o, "     {shown}")?;
        }
    }
    writeln!(o, "{} {}", paint.heading("answer:"), s.answer)?;
    if !s.unicode.is_empty() {
        writeln!(o, "{} {}", paint.dim("read as:"), s.unicode)?;
    }
    Ok(())
}

/// The step asked next, or the end of the derivation.
fn next_step(o: &mut String, next: Option<&StepPrompt>, paint: &dyn Paint) -> std::fmt::Result {
    match next {
        Some(next) => step(o, next, paint),
        None => writeln!(
            o,
            "{} every step of the derivation is done",
            paint.good("tutor:")
        ),
    }
}

/// A tutor step: its number, id and question.
fn step(o: &mut String, s: &StepPrompt, paint: &dyn Paint) -> std::fmt::Result {
    writeln!(
        o,
        "{} {}",
        paint.heading(&format!("step {} of {} ({}):", s.number, s.total, s.step)),
        s.prompt
    )?;
    if let Some(n) = &s.note {
        writeln!(o, "   {}", paint.dim(n))?;
    }
    Ok(())
}

fn verdict(
    o: &mut String,
    v: &Verdict,
    attempts: u32,
    line: &str,
    paint: &dyn Paint,
    color: bool,
) -> std::fmt::Result {
    if !v.reading.unicode.is_empty() {
        writeln!(o, "{} {}", paint.heading("read as:"), v.reading.unicode)?;
        if let Some(n) = &v.reading.note {
            writeln!(o, "         ({n})")?;
        }
    }
    if let Some(e) = &v.parse_error {
        o.push_str(&render_parse_error("answer", line.trim(), e, color));
    }
    let status = match v.status {
        Status::Correct => paint.good("correct"),
        Status::Incorrect => paint.bad("incorrect"),
        Status::Invalid => paint.warn("cannot check this answer (not counted as an attempt)"),
    };
    match v.status {
        Status::Invalid => writeln!(o, "{status}")?,
        _ => writeln!(
            o,
            "{status}  score {:.0}%  {}",
            v.score * 100.0,
            paint.dim(&format!("(attempt {attempts})"))
        )?,
    }
    // The caret box above already says what a one-line parse diagnosis would repeat.
    let repeats = |d: &&lagrange::check::Diagnosis| {
        v.parse_error
            .as_ref()
            .is_some_and(|e| d.message.starts_with(&e.kind.to_string()))
    };
    for d in v.diagnoses.iter().filter(|d| !repeats(d)) {
        writeln!(o, "  {} {}", paint.dim(&format!("[{}]", d.code)), d.message)?;
    }
    Ok(())
}

fn hint(o: &mut String, h: &HintReply, paint: &dyn Paint) -> std::fmt::Result {
    let total = h.number + h.remaining;
    match &h.hint {
        Some(text) => writeln!(
            o,
            "{} {text}",
            paint.heading(&format!("hint ({} of {total}):", h.number))
        ),
        None => writeln!(
            o,
            "{} all {} hints given; `{}` shows the answer",
            paint.heading("hint:"),
            h.number,
            h.reveal
        ),
    }
}

fn problems(o: &mut String, list: &[ProblemEntry], paint: &dyn Paint) -> std::fmt::Result {
    for p in list {
        let mark = if p.parts > 0 && p.solved == p.parts {
            paint.good("✓")
        } else {
            " ".to_string()
        };
        writeln!(
            o,
            "{mark} {:<28} {}/{}  {}",
            p.id, p.solved, p.parts, p.title
        )?;
    }
    Ok(())
}

fn parts(o: &mut String, p: &PartsReply, paint: &dyn Paint) -> std::fmt::Result {
    writeln!(o, "{}", paint.heading(&p.problem))?;
    // Columns as wide as their longest entry (so the table fits 80 columns), padded before
    // painting; attempts and hints are dropped where there are none.
    let id_w = p
        .parts
        .iter()
        .map(|e| e.id.chars().count())
        .max()
        .unwrap_or(0);
    let kind_w = p.parts.iter().map(|e| e.part_kind.chars().count()).max();
    let kind_w = kind_w.unwrap_or(0);
    let num_w = p.parts.len().to_string().len();
    for e in &p.parts {
        let cur = if e.current { ">" } else { " " };
        let (word, pad) = if e.solved {
            (paint.good("solved"), 2)
        } else if e.revealed {
            (paint.warn("revealed"), 0)
        } else {
            (paint.dim("open"), 4)
        };
        let mut line = format!(
            "{cur} {:>num_w$}. {:<id_w$}  {:<kind_w$}  {word}",
            e.number, e.id, e.part_kind
        );
        if e.attempts > 0 || e.hints_used > 0 {
            let _ = write!(
                line,
                "{}  attempts {}, hints {}",
                " ".repeat(pad),
                e.attempts,
                e.hints_used
            );
        }
        writeln!(o, "{line}")?;
    }
    Ok(())
}

fn analysis(o: &mut String, a: &AnalysisReply, paint: &dyn Paint) -> std::fmt::Result {
    if let Some(n) = &a.note {
        writeln!(o, "{}", paint.dim(n))?;
    }
    let text = match &a.report {
        AnalysisReport::Read(r) => r.render(paint, GIVE_DIMENSIONS),
        AnalysisReport::Derive(r) => r.render(Style::Unicode, paint),
        AnalysisReport::Modes(r) => r.render(Style::Unicode, paint),
        // The summary first, then the chart, as `lagrange simulate --plot -` prints them.
        AnalysisReport::Simulate(r) => {
            r.render_unicode(paint) + &crate::face::plot::terminal_chart(r)
        }
    };
    o.push_str(&text);
    if !text.ends_with('\n') {
        o.push('\n');
    }
    Ok(())
}

fn error(o: &mut String, e: &ErrorReply, paint: &dyn Paint) -> std::fmt::Result {
    writeln!(
        o,
        "{} {}",
        paint.bad(&format!("error[{}]:", e.code)),
        e.message
    )?;
    if let Some(s) = &e.suggestion {
        writeln!(o, "  {} did you mean `{s}`?", paint.dim("help:"))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use lagrange::report::Plain;

    #[test]
    fn error_with_suggestion() {
        let r = Response::error("unknown-command", "no command `:hnt`", Some(":hint".into()));
        let t = response(&r, ":hnt", &Plain, false);
        assert_eq!(
            t,
            "error[unknown-command]: no command `:hnt`\n  help: did you mean `:hint`?\n"
        );
        assert_eq!(response(&Response::Quit, "", &Plain, false), "");
    }

    /// Paints headings as the terminal does, with escape codes.
    struct Bold;
    impl Paint for Bold {
        fn heading(&self, s: &str) -> String {
            format!("\x1b[1m{s}\x1b[0m")
        }
    }

    #[test]
    fn help_columns_align_with_colour() {
        let mut s = lagrange::tutor::Session::new(
            lagrange::embedded::bank(),
            lagrange::tutor::Progress::new(),
        );
        let help = s.handle(":help");
        let t = response(&help[0], ":help", &Bold, true);
        let plain = crate::repl::wrap::strip(&t);
        // Every summary starts in one column (a usage too long for its column stands alone).
        for l in plain.lines() {
            let c: Vec<char> = l.chars().collect();
            let alone = c.len() > 2 + HELP_COLUMN && !c[2..].contains(&' ') || c.len() <= 21;
            let aligned = c.len() > 21 && c[20] == ' ' && c[21] != ' ';
            assert!(
                alone || aligned || l.starts_with("  :simulate"),
                "{l:?} in\n{plain}"
            );
        }
        s.handle(":open double-pendulum");
        let parts = s.handle(":parts");
        let t = response(&parts[0], ":parts", &Bold, true);
        assert!(
            t.lines().all(|l| crate::repl::wrap::columns(l) <= 80),
            "{t}"
        );
    }
}

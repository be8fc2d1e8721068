//! `lagrange check PROBLEM PART "ANSWER"`: one verdict, for a student or a script.

use std::fmt::Write as _;
use std::path::Path;
use std::process::ExitCode;

use clap::Args;
use colored::Colorize;

use lagrange::check::{CheckError, Checker, Status};
use lagrange::diagnostic::{Diagnostic, render_parse_error, render_plain};

#[derive(Args, Debug)]
pub struct CheckArgs {
    /// The problem id (`lagrange problems list`).
    problem: String,
    /// The part id (`lagrange problems show PROBLEM`).
    part: String,
    /// The answer, e.g. "m*l^2*theta'' + m*g*l*sin(theta) = 0".
    #[arg(allow_hyphen_values = true)]
    answer: String,
    /// One JSON object instead of text.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    student: super::sheets::StudentArgs,
}

pub fn run(
    args: &CheckArgs,
    problems: Option<&Path>,
    color: bool,
    out: &mut String,
) -> anyhow::Result<ExitCode> {
    // Only the problem asked for is built, from the embedded bank or a folder.
    let found = crate::face::find_problem(problems, &args.problem).map_err(anyhow::Error::msg)?;
    let Some(problem) = found.as_ref() else {
        eprintln!(
            "error: no problem `{}`\n  help: `lagrange problems list` shows the ids",
            lagrange::expr::error::visible(&args.problem)
        );
        return Ok(ExitCode::from(2));
    };
    // A part that accepts numbers is judged against the student's own numbers.
    let variant = (args.student.student.as_deref())
        .and_then(|k| lagrange::problem::variant::pick(problem, args.student.seed, k));
    let numbers = problem.part(&args.part).is_some_and(|p| p.numbers);
    let pinned = variant
        .as_ref()
        .filter(|_| numbers)
        .map(|v| problem.pinned(v));
    let mut checker = Checker::new(pinned.as_ref().unwrap_or(problem));
    let v = match checker.check(&args.part, &args.answer) {
        Ok(v) => v,
        Err(e) => {
            let mut d = Diagnostic::from(&e);
            // Only an unknown part id is helped by the list of parts; a part that fails to
            // prepare keeps its own help.
            if matches!(e, CheckError::UnknownPart { .. }) {
                let parts: Vec<&str> = problem.parts.iter().map(|p| p.id.as_str()).collect();
                d = d.with_help(format!("the parts are {}", parts.join(", ")));
            }
            eprint!("{}", render_plain(&d));
            return Ok(ExitCode::from(2));
        }
    };
    if args.json {
        writeln!(out, "{}", serde_json::to_string_pretty(&v)?)?;
    } else {
        if let Some(variant) = variant.as_ref().filter(|_| numbers) {
            let shown = lagrange::report::sheets::numbers_of(problem, variant).join(", ");
            writeln!(out, "{} {shown}", "numbers:".bold())?;
        }
        if !v.reading.unicode.is_empty() {
            writeln!(out, "{} {}", "read as:".bold(), v.reading.unicode)?;
            if let Some(n) = &v.reading.note {
                writeln!(out, "         ({n})")?;
            }
        }
        // A parse error is shown once, on stdout with the verdict it explains: the caret box
        // replaces the one-line summary of the same error (a script reading stdout still
        // sees the code, in the box's first line).
        if let Some(e) = &v.parse_error {
            out.push_str(&render_parse_error("answer", &args.answer, e, color));
        }
        let status = match v.status {
            Status::Correct => "correct".green().bold(),
            Status::Incorrect => "incorrect".red().bold(),
            Status::Invalid => "cannot check this answer".yellow().bold(),
        };
        if v.score > 0.0 && v.score < 1.0 {
            writeln!(out, "{status} (partial credit {:.0}%)", v.score * 100.0)?;
        } else {
            writeln!(out, "{status}")?;
        }
        for d in v.diagnoses.iter().filter(|d| !repeats_parse_error(&v, d)) {
            writeln!(out, "  {} {}", format!("[{}]", d.code).dimmed(), d.message)?;
        }
    }
    if numbers && pinned.is_none() && v.status != Status::Correct && !problem.variants.is_empty() {
        eprintln!(
            "note: this part takes each student's own numbers; give `--student KEY` to be judged with yours"
        );
    }
    Ok(if v.status == Status::Correct {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// Whether `d` only restates the parse error whose caret box is already shown.
pub(crate) fn repeats_parse_error(
    v: &lagrange::check::Verdict,
    d: &lagrange::check::Diagnosis,
) -> bool {
    v.parse_error
        .as_ref()
        .is_some_and(|e| d.message.starts_with(&e.kind.to_string()))
}

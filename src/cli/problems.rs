//! `lagrange problems list|show|verify`: the bank, for students and instructors.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::Subcommand;
use colored::Colorize;

use lagrange::bank::{Bank, Problem, embedded, load_dir, load_str, verify::verify};

#[derive(Subcommand, Debug)]
pub enum ProblemsCommand {
    /// One line per problem: id, title and part ids.
    List,
    /// A problem's statement and parts, for the terminal.
    Show {
        /// The problem id.
        id: String,
        /// Also print the reference answers (for instructors).
        #[arg(long)]
        answers: bool,
    },
    /// Prove every stated answer against the physics. With no PATH, the bank in use.
    Verify {
        /// Problem files or folders of them.
        paths: Vec<PathBuf>,
    },
}

/// The bank from `dir`, or the embedded one.
pub fn load_bank(dir: Option<&Path>) -> Result<Bank, String> {
    match dir {
        Some(d) => load_dir(d),
        None => Ok(embedded::bank()),
    }
}

pub fn run(
    cmd: &ProblemsCommand,
    dir: Option<&Path>,
    out: &mut String,
) -> anyhow::Result<ExitCode> {
    match cmd {
        ProblemsCommand::List => {
            let bank = load_bank(dir).map_err(anyhow::Error::msg)?;
            let w = bank.problems.iter().map(|p| p.id.len()).max().unwrap_or(0);
            for p in &bank.problems {
                let parts: Vec<&str> = p.parts.iter().map(|x| x.id.as_str()).collect();
                writeln!(
                    out,
                    "{:w$}  {}\n{:w$}  parts: {}",
                    p.id.bold(),
                    p.title,
                    "",
                    parts.join(", ")
                )?;
            }
            report_failures(&bank, out)?;
            Ok(ExitCode::SUCCESS)
        }
        ProblemsCommand::Show { id, answers } => {
            let bank = load_bank(dir).map_err(anyhow::Error::msg)?;
            let Some(p) = bank.problem(id) else {
                eprintln!(
                    "error: no problem `{id}`\n  help: `lagrange problems list` shows the ids"
                );
                return Ok(ExitCode::from(2));
            };
            show(p, *answers, out)?;
            Ok(ExitCode::SUCCESS)
        }
        ProblemsCommand::Verify { paths } => {
            let bank = if paths.is_empty() {
                load_bank(dir).map_err(anyhow::Error::msg)?
            } else {
                let mut b = Bank::default();
                for path in paths {
                    if path.is_dir() {
                        let sub = load_dir(path).map_err(anyhow::Error::msg)?;
                        b.problems.extend(sub.problems);
                        b.failures.extend(sub.failures);
                    } else {
                        let name = path.display().to_string();
                        match std::fs::read_to_string(path) {
                            Ok(text) => match load_str(&name, &text) {
                                Ok(p) => b.problems.push(p),
                                Err(f) => b.failures.push(f),
                            },
                            Err(e) => {
                                eprintln!("error: cannot read {name}: {e}");
                                return Ok(ExitCode::from(2));
                            }
                        }
                    }
                }
                b
            };
            let mut failing = bank.failures.len();
            for p in &bank.problems {
                let findings = verify(p);
                if findings.is_empty() {
                    writeln!(
                        out,
                        "{} {} ({} parts proved)",
                        "✓".green(),
                        p.id,
                        p.parts.len()
                    )?;
                } else {
                    failing += 1;
                    writeln!(out, "{} {}", "✗".red(), p.id)?;
                    for f in findings {
                        writeln!(out, "  {f}")?;
                    }
                }
            }
            report_failures(&bank, out)?;
            writeln!(
                out,
                "{} problems, {failing} failing",
                bank.problems.len() + bank.failures.len()
            )?;
            Ok(if failing > 0 {
                ExitCode::from(1)
            } else {
                ExitCode::SUCCESS
            })
        }
    }
}

fn report_failures(bank: &Bank, out: &mut String) -> std::fmt::Result {
    for f in &bank.failures {
        writeln!(out, "{} {f}", "✗".red())?;
    }
    Ok(())
}

/// LaTeX-ish inline math for a terminal: `$\theta_1$` → θ₁, `$m^2$` → m².
pub fn terminal_math(text: &str) -> String {
    let mut s = text.replace('$', "");
    for (c, name) in lagrange::expr::names::GREEK {
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
                    out.push_str(&lagrange::expr::names::subscript(&digits));
                } else {
                    out.push_str(&lagrange::expr::names::superscript(
                        digits.parse().unwrap_or(0),
                    ));
                }
            }
            _ => out.push(c),
        }
    }
    out
}

fn show(p: &Problem, answers: bool, out: &mut String) -> std::fmt::Result {
    writeln!(out, "{}  ({})", p.title.bold(), p.id)?;
    if !p.source.is_empty() {
        writeln!(out, "{}", p.source.dimmed())?;
    }
    writeln!(out, "\n{}", terminal_math(p.statement.trim()))?;
    let mut pool = p.system.pool.clone();
    let coords: Vec<String> = p
        .system
        .coordinates
        .iter()
        .map(|c| {
            let v = pool.var(c.sym, 0);
            pool.unicode(v)
        })
        .collect();
    writeln!(out, "\n{} {}", "coordinates:".bold(), coords.join(", "))?;
    let params: Vec<String> = p
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
    writeln!(out, "{} {}", "parameters: ".bold(), params.join(", "))?;
    if !p.assumptions.is_empty() {
        let a: Vec<&str> = p.assumptions.iter().map(|a| a.text.as_str()).collect();
        writeln!(out, "{} {}", "assuming:   ".bold(), a.join(", "))?;
    }
    for (i, part) in p.parts.iter().enumerate() {
        writeln!(
            out,
            "\n{} {} ({}, {} point{})",
            format!("{}.", i + 1).bold(),
            part.id.bold(),
            part.kind.name(),
            part.points,
            if part.points == 1.0 { "" } else { "s" }
        )?;
        writeln!(out, "   {}", terminal_math(&part.prompt))?;
        if answers {
            writeln!(out, "   {} {}", "answer:".dimmed(), part.answers.join("; "))?;
        }
    }
    writeln!(
        out,
        "\nAnswer with `lagrange check {} <part> \"<answer>\"`.",
        p.id
    )
}

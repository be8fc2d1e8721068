//! One student's sheets: a problem with the student's numbers (`problems show ID --student
//! KEY`), and the sheets of a whole class as Markdown and LaTeX (`problems export-sheets`).
//! A statement or prompt names a varied parameter by its symbol (`$m$`), or shows its value
//! where it writes `{{m}}`; the sheet lists every number with its unit.

use std::fmt::Write as _;

use super::problems::{ProblemSheet, problem_sheet, shell_word, terminal_math, with_answer_form};
use super::text;
use crate::expr::error::visible;
use crate::problem::Problem;
use crate::problem::variant::{Variant, fill, pick};

/// The numbers of `variant` as a sheet lists them (`m = 1.5 kg`), in declaration order.
pub fn numbers_of(p: &Problem, variant: &Variant) -> Vec<String> {
    p.variants
        .iter()
        .filter_map(|v| {
            variant
                .get(&v.name)
                .map(|x| format!("{} = {}", v.name, v.show(x)))
        })
        .collect()
}

/// The sheet of `p` for the student `key` under the course `seed`: the statement and prompts
/// with the student's values where they write `{{name}}`, and the student's numbers listed.
/// A problem without variants gives the plain sheet, with the student named.
pub fn student_sheet(p: &Problem, answers: bool, key: &str, seed: u64) -> ProblemSheet {
    let mut sheet = match pick(p, seed, key) {
        Some(variant) => variant_sheet(p, answers, &variant),
        None => problem_sheet(p, answers),
    };
    sheet.student = Some(key.trim().to_string());
    sheet.seed = (!p.variants.is_empty()).then_some(seed);
    sheet
}

/// The sheet of `p` with the numbers of `variant`: where the statement and prompts write
/// `{{name}}`, the value and unit; the numbers listed.
pub fn variant_sheet(p: &Problem, answers: bool, variant: &Variant) -> ProblemSheet {
    let mut sheet = problem_sheet(p, answers);
    sheet.statement = terminal_math(&fill(p.statement.trim(), &p.variants, Some(variant)));
    for (s, part) in sheet.parts.iter_mut().zip(&p.parts) {
        s.prompt = with_answer_form(
            part,
            terminal_math(&fill(&part.prompt, &p.variants, Some(variant))),
        );
    }
    sheet.numbers = numbers_of(p, variant);
    sheet
}

/// The sheets of `problems` for one student as Markdown: a heading per problem, the
/// statement (its `$…$` math kept for a renderer), the student's numbers, and the parts.
pub fn markdown(problems: &[&Problem], key: &str, seed: u64) -> String {
    text(|o| {
        writeln!(o, "# Problems for {}\n", one_line(key))?;
        for p in problems {
            let variant = pick(p, seed, key);
            writeln!(o, "## {}\n", one_line(&p.title))?;
            writeln!(
                o,
                "{}\n",
                fill(p.statement.trim(), &p.variants, variant.as_ref())
            )?;
            if let Some(v) = &variant {
                writeln!(o, "**Your numbers:** {}.\n", numbers_of(p, v).join(", "))?;
            }
            for (i, part) in p.parts.iter().enumerate() {
                let prompt =
                    with_answer_form(part, fill(&part.prompt, &p.variants, variant.as_ref()));
                let how = if part.numbers && variant.is_some() {
                    " (in symbols, or with your numbers)"
                } else {
                    ""
                };
                writeln!(
                    o,
                    "{}. **{}** ({} point{}): {}{how}\n",
                    i + 1,
                    part.id,
                    part.points,
                    if part.points == 1.0 { "" } else { "s" },
                    one_line(&prompt)
                )?;
            }
            // The seed is named whenever the numbers depend on it, 0 included: without it
            // `check` cannot find the student's numbers.
            let seeded = if p.variants.is_empty() {
                String::new()
            } else {
                format!(" --seed {seed}")
            };
            writeln!(
                o,
                "Answer with `lagrange check {} <part> \"<answer>\" --student {}{seeded}`.\n",
                p.id,
                shell_word(key.trim())
            )?;
        }
        Ok(())
    })
}

/// The sheets of `problems` for one student as a LaTeX document (Unicode: compile with
/// LuaLaTeX or XeLaTeX). Text outside `$…$` has LaTeX's special characters escaped.
pub fn latex(problems: &[&Problem], key: &str, seed: u64) -> String {
    text(|o| {
        writeln!(
            o,
            "% lagrange problem sheets; compile with lualatex or xelatex"
        )?;
        writeln!(o, "\\documentclass{{article}}")?;
        writeln!(o, "\\usepackage{{fontspec}}")?;
        writeln!(o, "\\begin{{document}}")?;
        writeln!(o, "\\section*{{Problems for {}}}", escape(&one_line(key)))?;
        for p in problems {
            let variant = pick(p, seed, key);
            writeln!(o, "\n\\subsection*{{{}}}", escape(&one_line(&p.title)))?;
            let statement = fill(p.statement.trim(), &p.variants, variant.as_ref());
            writeln!(o, "{}\n", escape_outside_math(&statement))?;
            if let Some(v) = &variant {
                let numbers = numbers_of(p, v).join(", ");
                writeln!(o, "\\textbf{{Your numbers:}} {}.\n", escape(&numbers))?;
            }
            writeln!(o, "\\begin{{enumerate}}")?;
            for part in &p.parts {
                let prompt =
                    with_answer_form(part, fill(&part.prompt, &p.variants, variant.as_ref()));
                let how = if part.numbers && variant.is_some() {
                    " (in symbols, or with your numbers)"
                } else {
                    ""
                };
                writeln!(
                    o,
                    "  \\item \\textbf{{{}}} {}{how}",
                    escape(&part.id),
                    escape_outside_math(&one_line(&prompt))
                )?;
            }
            writeln!(o, "\\end{{enumerate}}")?;
        }
        writeln!(o, "\\end{{document}}")
    })
}

/// `s` on one line (a key or title with a newline would break a heading), made visible.
fn one_line(s: &str) -> String {
    visible(&s.split_whitespace().collect::<Vec<_>>().join(" "))
}

/// LaTeX's special characters escaped, for text mode.
fn escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '\\' => out.push_str("\\textbackslash{}"),
            '&' | '%' | '$' | '#' | '_' | '{' | '}' => {
                out.push('\\');
                out.push(c);
            }
            '~' => out.push_str("\\textasciitilde{}"),
            '^' => out.push_str("\\textasciicircum{}"),
            _ => out.push(c),
        }
    }
    out
}

/// Text whose `$…$` spans are LaTeX math already (kept) and whose other text is escaped.
fn escape_outside_math(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for (i, piece) in s.split('$').enumerate() {
        if i % 2 == 1 {
            // A problem file doubles its backslashes in TOML; the text holds single ones.
            out.push('$');
            out.push_str(piece);
            out.push('$');
        } else {
            out.push_str(&escape(piece));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn latex_keeps_math_and_escapes_text() {
        assert_eq!(
            escape_outside_math("50% of $\\theta_1$ & more"),
            "50\\% of $\\theta_1$ \\& more"
        );
        assert_eq!(shell_word("ada@uni.example"), "ada@uni.example");
        assert_eq!(shell_word("o'neil x"), "'o'\\''neil x'");
    }
}

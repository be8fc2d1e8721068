//! `lagrange grade CLASS.csv`: the clap arguments of the grading face (`src/grade/`).

use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, ValueEnum};

use crate::grade::{Lms, Options};

/// `lagrange grade SUBMISSIONS.csv [--out DIR] [--lms …] [--follow-through] [--best] [--json]`.
#[derive(Args, Debug)]
#[command(after_help = "\
Input: a CSV file with a header, either long (student,problem,part,answer: one answer a line)
or wide (student plus one PROBLEM/PART column per part: one answer a cell). Column names are
case-insensitive; other columns are ignored.

Outputs in DIR: results.csv (one row per answer, in input order), gradebook.csv, summary.md,
summary.json, and with --lms canvas.csv, moodle.csv or gradescope.csv. See docs/grading.md.

Exit codes:
  0  graded (rows with errors are in results.csv; stderr says how many)
  2  the file cannot be read, is over 512 MB, its header is neither format, or an option is bad")]
pub struct GradeArgs {
    /// The class file (CSV), or `-` for standard input.
    input: PathBuf,
    /// The folder for the outputs (default: `grades/` beside the input file).
    #[arg(long, value_name = "DIR")]
    out: Option<PathBuf>,
    /// Also write an import file for this learning-management system.
    #[arg(long, value_enum)]
    lms: Option<LmsArg>,
    /// Credit a wrong answer that follows from the same student's own wrong earlier answer.
    #[arg(long)]
    follow_through: bool,
    /// The credit for such an answer, as a fraction of the part's points (implies
    /// --follow-through).
    #[arg(long, value_name = "F")]
    follow_through_credit: Option<f64>,
    /// The best attempt at a part counts (default: the last).
    #[arg(long)]
    best: bool,
    /// Print the summary as JSON instead of the table.
    #[arg(long)]
    json: bool,
    /// The parts the instructor set, comma-separated PROBLEM/PART: the gradebook's columns and
    /// every student's maximum (default: every part column of a wide file, every part some row
    /// of a long file names).
    #[arg(long, value_name = "LIST", value_delimiter = ',')]
    parts: Option<Vec<String>>,
    /// The course seed: with each student's key it picks the student's numbers, against
    /// which the parts that accept numbers are judged.
    #[arg(long, value_name = "S", default_value_t = 0)]
    seed: u64,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum LmsArg {
    Canvas,
    Moodle,
    Gradescope,
}

/// Runs `lagrange grade`.
pub fn run(args: &GradeArgs, problems: Option<&Path>) -> anyhow::Result<ExitCode> {
    let follow_through = match (args.follow_through, args.follow_through_credit) {
        (_, Some(c)) => Some(c),
        (true, None) => Some(0.5),
        (false, None) => None,
    };
    crate::grade::run(&Options {
        input: args.input.clone(),
        out: args.out.clone(),
        problems: problems.map(Path::to_path_buf),
        lms: args.lms.map(|l| match l {
            LmsArg::Canvas => Lms::Canvas,
            LmsArg::Moodle => Lms::Moodle,
            LmsArg::Gradescope => Lms::Gradescope,
        }),
        follow_through,
        best: args.best,
        json: args.json,
        parts: args.parts.clone(),
        seed: args.seed,
    })
}

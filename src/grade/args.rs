//! `lagrange grade CLASS.csv`: the clap arguments of the grading face, turned into its
//! [`Options`].

use std::path::{Path, PathBuf};

use clap::{Args, ValueEnum};

use super::{Lms, Options};

/// `lagrange grade SUBMISSIONS.csv [--out DIR] [--lms …] [--follow-through] [--best] [--json]`.
#[derive(Args, Debug)]
#[command(after_help = "\
Input: a CSV file with a header, either long (student,problem,part,answer: one answer a line)
or wide (student plus one PROBLEM/PART column per part: one answer a cell). Column names are
case-insensitive; other columns are ignored.

Outputs in DIR: results.csv (one row per answer, in input order), gradebook.csv, summary.md,
summary.json, review.csv (the answers needing a human), with --lms canvas.csv, moodle.csv or
gradescope.csv, with --feedback one file per student in feedback/. See docs/grading.md.

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
    /// The assignment file (TOML): its problems, parts, points, course seed and grading policy
    /// (credit per diagnosis code, penalty per extra attempt, best or last, follow-through).
    /// The options above take precedence over it.
    #[arg(long, value_name = "FILE")]
    assignment: Option<PathBuf>,
    /// The instructor's decisions on answers: a review.csv with its `decision` column filled
    /// in (correct, incorrect or a fraction of the points).
    #[arg(long, value_name = "FILE")]
    overrides: Option<PathBuf>,
    /// Also write one Markdown and one HTML file per student under DIR/feedback/.
    #[arg(long)]
    feedback: bool,
    /// The course seed: with each student's key it picks the student's numbers, against
    /// which the parts that accept numbers are judged.
    /// Without it, the assignment file's seed, else 0.
    #[arg(long, value_name = "S")]
    seed: Option<u64>,
}

#[derive(Clone, Copy, Debug, ValueEnum)]
enum LmsArg {
    Canvas,
    Moodle,
    Gradescope,
}

impl GradeArgs {
    /// The options of a grading run: these arguments, with the bank folder of `--problems`.
    pub fn options(&self, problems: Option<&Path>) -> Options {
        let follow_through = match (self.follow_through, self.follow_through_credit) {
            (_, Some(c)) => Some(c),
            (true, None) => Some(0.5),
            (false, None) => None,
        };
        Options {
            input: self.input.clone(),
            out: self.out.clone(),
            problems: problems.map(Path::to_path_buf),
            lms: self.lms.map(|l| match l {
                LmsArg::Canvas => Lms::Canvas,
                LmsArg::Moodle => Lms::Moodle,
                LmsArg::Gradescope => Lms::Gradescope,
            }),
            follow_through,
            best: self.best,
            json: self.json,
            parts: self.parts.clone(),
            assignment: self.assignment.clone(),
            overrides: self.overrides.clone(),
            feedback: self.feedback,
            seed: self.seed,
        }
    }
}

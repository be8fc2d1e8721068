//! `lagrange grade`: a whole class from a CSV file to results, a gradebook, a summary of
//! what the class got wrong and, optionally, an LMS import file. A face over the checker
//! (`lagrange::check`) and follow-through (`lagrange::tutor::follow`): reading the file
//! ([`input`]), judging every answer once per canonical form in parallel ([`judge`]),
//! summarising ([`summary`]) and writing ([`output`]). No mathematics here.
//!
//! Exit codes: 0 graded (even when rows are wrong or errors: they are in results.csv), 2 the
//! file cannot be read at all, its header is neither format, or an option is bad.

mod input;
mod judge;
mod output;
mod summary;

use std::io::{IsTerminal, Read};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use anyhow::Context as _;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

pub use output::Lms;

/// The largest class file read (a larger one is refused with exit 2).
pub const MAX_FILE_BYTES: u64 = 512 * 1024 * 1024;
/// Fewer distinct answers than this are checked without a progress bar (it would flash).
const PROGRESS_FROM: usize = 2_000;

/// How `lagrange grade` was asked to run.
pub struct Options {
    /// The class file, or `-` for standard input.
    pub input: PathBuf,
    /// The output folder (default: `grades/` beside the input).
    pub out: Option<PathBuf>,
    /// The folder of problem files (`--problems`), else the embedded bank.
    pub problems: Option<PathBuf>,
    /// Also write an import file for this LMS.
    pub lms: Option<Lms>,
    /// Follow-through credit as a fraction of the part's points (`None`: off).
    pub follow_through: Option<f64>,
    /// The best attempt counts instead of the last.
    pub best: bool,
    /// Print the summary JSON instead of the table.
    pub json: bool,
}

/// Grades a class file; see the module docs for the exit codes.
pub fn run(opts: &Options) -> anyhow::Result<ExitCode> {
    if let Some(c) = opts.follow_through
        && !(0.0..=1.0).contains(&c)
    {
        eprintln!("error: --follow-through-credit must be between 0 and 1, not {c}");
        return Ok(ExitCode::from(2));
    }
    let bytes = match read_input(&opts.input) {
        Ok(b) => b,
        Err(message) => {
            eprintln!("error: {message}");
            return Ok(ExitCode::from(2));
        }
    };
    let table = match input::parse(&bytes) {
        Ok(t) => t,
        Err(input::BadFile(message)) => {
            eprintln!("error: {}: {message}", shown(&opts.input));
            return Ok(ExitCode::from(2));
        }
    };
    drop(bytes);
    let bank =
        crate::cli::problems::load_bank(opts.problems.as_deref()).map_err(anyhow::Error::msg)?;
    let settings = judge::Settings {
        follow_through: opts.follow_through,
        best: opts.best,
    };
    let judged = judge::judge(&table.rows, &bank, settings, &progress_bar);
    let summary = summary::summarise(&table.rows, &judged, &bank);
    let dir = out_dir(opts);
    std::fs::create_dir_all(&dir).with_context(|| format!("cannot create {}", dir.display()))?;
    let book = output::gradebook(&table.rows, &judged, &bank);
    let mut written = vec![
        output::write_atomic(&dir, "results.csv", &output::results(&table.rows, &judged)?)?,
        output::write_atomic(&dir, "gradebook.csv", &output::gradebook_csv(&book)?)?,
        output::write_atomic(&dir, "summary.md", summary::markdown(&summary).as_bytes())?,
        output::write_atomic(
            &dir,
            "summary.json",
            output::summary_json(&summary)?.as_bytes(),
        )?,
    ];
    if let Some(lms) = opts.lms {
        let (name, bytes) = output::lms_file(lms, &book, &assignment(&opts.input))?;
        written.push(output::write_atomic(&dir, &name, &bytes)?);
    }
    let text = if opts.json {
        output::summary_json(&summary)?
    } else {
        table_text(&summary, table.format, &written)
    };
    crate::cli::emit(&text)?;
    let errors = summary.status.get("error").copied().unwrap_or(0);
    if errors > 0 {
        let what = if errors == 1 {
            "1 row had an error".to_string()
        } else {
            format!("{errors} rows had errors")
        };
        eprintln!("{what}, see {}", shown(&dir.join("results.csv")));
    }
    Ok(ExitCode::SUCCESS)
}

/// A path as shown to the user (`-` is standard input).
fn shown(p: &Path) -> String {
    if p == Path::new("-") {
        "standard input".to_string()
    } else {
        p.display().to_string()
    }
}

/// The whole class file, refusing one over [`MAX_FILE_BYTES`]; the error is one line.
fn read_input(path: &Path) -> Result<Vec<u8>, String> {
    let too_large = || format!("{} is over 512 MB; split the class file", shown(path));
    let mut bytes = Vec::new();
    if path == Path::new("-") {
        let stdin = std::io::stdin().lock();
        stdin
            .take(MAX_FILE_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(|e| format!("cannot read standard input: {e}"))?;
    } else {
        let cannot = |e: std::io::Error| format!("cannot read {}: {e}", path.display());
        let meta = std::fs::metadata(path).map_err(cannot)?;
        if meta.is_dir() {
            return Err(format!("{} is a folder, not a class file", path.display()));
        }
        if meta.len() > MAX_FILE_BYTES {
            return Err(too_large());
        }
        let file = std::fs::File::open(path).map_err(cannot)?;
        file.take(MAX_FILE_BYTES + 1)
            .read_to_end(&mut bytes)
            .map_err(cannot)?;
    }
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(too_large());
    }
    Ok(bytes)
}

/// `--out`, else `grades/` beside the input (in the current folder for standard input).
fn out_dir(opts: &Options) -> PathBuf {
    if let Some(o) = &opts.out {
        return o.clone();
    }
    if opts.input == Path::new("-") {
        return PathBuf::from("grades");
    }
    match opts.input.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.join("grades"),
        _ => PathBuf::from("grades"),
    }
}

/// The name of the LMS assignment column: the class file's stem.
fn assignment(input: &Path) -> String {
    match input.file_stem().and_then(|s| s.to_str()) {
        Some(s) if input != Path::new("-") => format!("lagrange {s}"),
        _ => "lagrange".to_string(),
    }
}

/// A bar on stderr for a long job on a terminal; hidden otherwise (pipes and tests never see
/// it).
fn progress_bar(distinct: usize) -> ProgressBar {
    if distinct < PROGRESS_FROM || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(distinct as u64), ProgressDrawTarget::stderr());
    if let Ok(style) = ProgressStyle::with_template("{msg:9} {bar:40} {pos}/{len} distinct answers")
    {
        bar.set_style(style);
    }
    bar
}

/// The short table printed on stdout.
fn table_text(s: &summary::Summary, format: input::Format, written: &[PathBuf]) -> String {
    use std::fmt::Write as _;
    let mut out = String::new();
    let format = match format {
        input::Format::Long => "long",
        input::Format::Wide => "wide",
    };
    let _ = writeln!(
        out,
        "{} students, {} answers ({format} format)",
        s.students, s.rows
    );
    let width = s
        .parts
        .keys()
        .map(|k| k.chars().count())
        .max()
        .unwrap_or(4)
        .max(4);
    let _ = writeln!(out, "{:width$}  answers  correct", "part");
    for (key, p) in &s.parts {
        let rate = if p.answers == 0 {
            0.0
        } else {
            100.0 * p.correct as f64 / p.answers as f64
        };
        let _ = writeln!(out, "{key:width$}  {:>7}  {rate:>6.1}%", p.answers);
    }
    out.push_str("wrote:\n");
    for w in written {
        let _ = writeln!(out, "  {}", w.display());
    }
    out
}

//! `lagrange grade`: a whole class from a CSV file to results, a gradebook, a summary of
//! what the class got wrong and, optionally, an LMS import file. A face over the checker
//! (`lagrange::check`) and follow-through (`lagrange::tutor::follow`): reading the file
//! ([`input`]), judging every answer once per canonical form in parallel ([`judge`]),
//! summarising ([`summary`]) and writing ([`output`]). No mathematics here.
//!
//! Exit codes: 0 graded (even when rows are wrong or errors: they are in results.csv), 2 the
//! file cannot be read at all, its header is neither format, or an option is bad.

mod args;
mod assignment;
mod cell;
mod decode;
mod feedback;
mod header;
mod input;
mod intern;
mod judge;
mod memory;
mod output;
mod overrides;
mod phases;
mod review;
mod run_id;
mod summary;
mod variants;

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

pub use args::GradeArgs;
pub use output::Lms;

/// The largest class file read (a larger one is refused with exit 2).
pub const MAX_FILE_BYTES: u64 = 512 * 1024 * 1024;

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
    /// The parts the instructor set (`PROBLEM/PART`), the gradebook's columns (`--parts`).
    pub parts: Option<Vec<String>>,
    /// The assignment file (`--assignment`): problems, parts, points, seed and policy; the
    /// options above, when given, take precedence over it.
    pub assignment: Option<PathBuf>,
    /// The instructor's decisions on answers (`--overrides`, a filled-in review.csv).
    pub overrides: Option<PathBuf>,
    /// Also write one feedback file per student under `OUT/feedback/` (`--feedback`).
    pub feedback: bool,
    /// The course seed (`--seed`) that, with each student's key, picks the student's
    /// numbers; without it, the assignment file's seed, else 0.
    pub seed: Option<u64>,
}

/// Grades a class file; see the module docs for the exit codes.
pub fn run(opts: &Options) -> anyhow::Result<ExitCode> {
    if let Some(c) = opts.follow_through
        && !(0.0..=1.0).contains(&c)
    {
        eprintln!("error: --follow-through-credit must be between 0 and 1, not {c}");
        return Ok(ExitCode::from(2));
    }
    let (assignment, policy) = match assignment::read(opts) {
        Ok(a) => a,
        Err(message) => {
            eprintln!("error: {message}");
            return Ok(ExitCode::from(2));
        }
    };
    let decisions = match opts.overrides.as_deref().map(overrides::Overrides::read) {
        Some(Err(message)) => {
            eprintln!("error: --overrides {message}");
            return Ok(ExitCode::from(2));
        }
        Some(Ok(o)) => Some(o),
        None => None,
    };
    let dir = out_dir(opts);
    let names = output_names(opts.lms);
    if opts.feedback
        && let Err(message) = feedback::check_dir(&dir.join("feedback"))
    {
        eprintln!("error: {message}");
        return Ok(ExitCode::from(2));
    }
    // Before any work: every output name must be free or a regular file, and none the input.
    if let Err(message) = check_outputs(&dir, &names, &opts.input) {
        eprintln!("error: {message}");
        return Ok(ExitCode::from(2));
    }
    memory::map_large_blocks();
    let mut phases = phases::Phases::from_env();
    let bytes = match read_input(&opts.input) {
        Ok(b) => b,
        Err(message) => {
            eprintln!("error: {message}");
            return Ok(ExitCode::from(2));
        }
    };
    phases.end("read");
    // The file's hash (one serial pass) beside its decoding; the bytes are freed once read.
    // The bank is loaded meanwhile (on the other core when there is one); a bad file is
    // still what is reported first.
    let (parsed, bank) = rayon::join(
        || input::parse_beside(bytes, &mut phases, run_id::file_hash),
        || crate::face::load_bank(opts.problems.as_deref()),
    );
    let (table, hash) = match parsed {
        Ok(t) => t,
        Err(input::BadFile(message)) => {
            eprintln!("error: {}: {message}", shown(&opts.input));
            return Ok(ExitCode::from(2));
        }
    };
    phases.end("renumber");
    let mut bank = bank.map_err(anyhow::Error::msg)?;
    let set = match assignment::apply(assignment.as_ref(), opts, &mut bank) {
        Ok(set) => set,
        Err(message) => {
            eprintln!("error: {message}");
            return Ok(ExitCode::from(2));
        }
    };
    let columns = match set_parts(opts.parts.as_deref(), &table, &bank) {
        Ok(_) if opts.parts.is_none() && set.is_some() => set,
        Ok(c) => c,
        Err(message) => {
            eprintln!("error: {message}");
            return Ok(ExitCode::from(2));
        }
    };
    if opts.feedback
        && let Err(message) = feedback::names(&table.students)
    {
        eprintln!("error: {message}");
        return Ok(ExitCode::from(2));
    }
    if opts.lms == Some(Lms::Moodle)
        && let Err(message) = output::moodle_keys(&summary::students(&table))
    {
        eprintln!("error: {message}");
        return Ok(ExitCode::from(2));
    }
    for (kept, other) in &table.merged {
        eprintln!(
            "note: the student keys `{}` and `{}` differ only in case: graded as one student, `{}`",
            lagrange::expr::error::visible(kept),
            lagrange::expr::error::visible(other),
            lagrange::expr::error::visible(kept),
        );
    }
    let extra = assignment::run_key(&policy, assignment.as_ref(), decisions.as_ref());
    let seed = (opts.seed).or(assignment.as_ref().and_then(|a| a.seed));
    // Without a course seed every student's numbers would silently be seed 0's: refuse.
    let varied = variants::answered_with_variants(&bank, &table);
    let seed = match (seed, varied.is_empty()) {
        (Some(s), _) => s,
        (None, true) => 0,
        (None, false) => {
            eprintln!(
                "error: {} give{} each student their own numbers from the course seed, and no seed was given\n  help: add `--seed S` (the seed the students' sheets were made with) or `seed = S` in the assignment file",
                varied.join(", "),
                if varied.len() == 1 { "s" } else { "" }
            );
            return Ok(ExitCode::from(2));
        }
    };
    let run = run_id::run_id(hash, opts, &bank, &extra, seed);
    let mut bank = bank;
    let variants = variants::extend(&mut bank, &table, seed);
    let settings = judge::Settings {
        policy: &policy,
        overrides: decisions.as_ref().map(|d| d as &dyn judge::Override),
        variants: &variants,
        scratch: &scratch_dir(&dir),
    };
    let mut bar = crate::face::bar::Bar::new("{bar:40} {pos}/{len} distinct answers", true);
    phases.end("bank");
    let judged = judge::judge(&table, &bank, settings, &mut bar, &mut phases);
    bar.finish();
    let judged = judged?;
    if let Some(message) = judged.lost() {
        eprintln!("error: {message}; nothing was written");
        return Ok(ExitCode::from(2));
    }
    if opts.feedback {
        let book = output::gradebook(&table, &judged, &bank, columns.as_deref());
        if let Err(message) = feedback::write(
            &dir.join("feedback"),
            &table,
            &judged,
            &bank,
            &book,
            &variants,
        ) {
            eprintln!("error: {message}");
            return Ok(ExitCode::from(2));
        }
    }
    let results = |w: &mut (dyn std::io::Write + Send)| output::results(w, &table, &judged, &run);
    // The summary, the gradebook and the small files are made while results.csv is
    // formatted and written (on another core when there is one).
    let others = || -> anyhow::Result<(summary::Summary, Files)> {
        let mut summary = summary::summarise(&table, &judged, &bank);
        summary.run = run.clone();
        let book = output::gradebook(&table, &judged, &bank, columns.as_deref());
        let mut files = vec![("gradebook.csv", output::gradebook_csv(&book)?)];
        if let Some(lms) = opts.lms {
            let title = assignment::title(assignment.as_ref(), &opts.input);
            let (_, bytes) = output::lms_file(lms, &book, &title)?;
            files.push((lms_name(lms), bytes));
        }
        let (queue, unmatched) =
            review::review_csv(&table, &judged, &bank, &variants, decisions.as_ref());
        files.push(("review.csv", vec![queue]));
        if let Some(d) = &decisions {
            assignment::unmatched_notes(d, &unmatched);
        }
        files.push(("summary.md", vec![summary::markdown(&summary).into_bytes()]));
        files.push((
            "summary.json",
            vec![output::summary_json(&summary)?.into_bytes()],
        ));
        Ok((summary, files))
    };
    // With about as many verdicts as rows (all-different answers), the summary's working
    // memory is a verdict's worth per row; with about as many students as rows, the gradebook
    // and the LMS file are about as long as the results. Then they are made and written
    // before results.csv rather than beside it, so the two never add up (issue 20 §5). The
    // bytes are the same either way.
    let many = |n: usize| n * 4 > table.rows.len();
    let one_at_a_time = many(judged.outcome_count()) || many(table.students.len());
    let lost = || judged.lost();
    let made = write_outputs(&dir, &names, results, others, one_at_a_time, lost)?;
    let (summary, written) = match made {
        Ok(done) => done,
        Err(message) => {
            eprintln!("error: {message}");
            return Ok(ExitCode::from(2));
        }
    };
    phases.end("outputs");
    phases.threads();
    let text = if opts.json {
        output::summary_json(&summary)?
    } else {
        table_text(&summary, table.format, &written)
    };
    crate::face::emit(&text)?;
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

/// The gradebook's columns: `--parts` (each `PROBLEM/PART` of the bank, else an error), else
/// the wide format's part columns that name a bank part, else `None` (every part some row
/// names).
fn set_parts(
    asked: Option<&[String]>,
    table: &input::Table,
    bank: &lagrange::bank::Bank,
) -> Result<Option<Vec<(usize, usize)>>, String> {
    let find = |problem: &str, part: &str| {
        let p = bank.problems.iter().position(|x| x.id == problem)?;
        let q = bank.problems[p].parts.iter().position(|x| x.id == part)?;
        Some((p, q))
    };
    let mut out: Vec<(usize, usize)> = Vec::new();
    if let Some(asked) = asked {
        for item in asked {
            let found = item
                .split_once('/')
                .and_then(|(p, q)| find(p.trim(), q.trim()));
            let Some(t) = found else {
                return Err(format!(
                    "--parts: `{}` is not a PROBLEM/PART of the bank (see `lagrange problems list`)",
                    lagrange::expr::error::visible(item)
                ));
            };
            if !out.contains(&t) {
                out.push(t);
            }
        }
        return Ok(Some(out));
    }
    if table.format == input::Format::Wide {
        for (p, q) in &table.columns {
            if let Some(t) = find(p, q)
                && !out.contains(&t)
            {
                out.push(t);
            }
        }
        out.sort_unstable();
        return Ok(Some(out));
    }
    Ok(None)
}

/// A path as shown to the user (`-` is standard input; control characters escaped).
fn shown(p: &Path) -> String {
    if p == Path::new("-") {
        "standard input".to_string()
    } else {
        lagrange::expr::error::visible(&p.display().to_string())
    }
}

/// The names of the files this run writes, in the order they are renamed into place:
/// summary.json last, so when its `run` equals results.csv's, the set is whole.
fn output_names(lms: Option<Lms>) -> Vec<&'static str> {
    let mut names = vec!["results.csv", "gradebook.csv"];
    if let Some(lms) = lms {
        names.push(lms_name(lms));
    }
    names.push("review.csv");
    names.extend(["summary.md", "summary.json"]);
    names
}

/// The LMS file's name (as [`output::lms_file`] names it).
fn lms_name(lms: Lms) -> &'static str {
    match lms {
        Lms::Canvas => "canvas.csv",
        Lms::Moodle => "moodle.csv",
        Lms::Gradescope => "gradescope.csv",
    }
}

/// Refuses, before any work, an output name holding a link, a device, a FIFO or a folder,
/// and an input file that is one of the outputs (it would be replaced by its own results).
fn check_outputs(dir: &Path, names: &[&str], input: &Path) -> Result<(), String> {
    // `--out` follows a link to a folder; anything else that exists there is not a folder.
    if dir.exists() && !dir.is_dir() {
        return Err(format!(
            "--out {} is not a folder; grade writes its files into a folder",
            shown(dir)
        ));
    }
    let input_id = (input != Path::new("-"))
        .then(|| std::fs::metadata(input).ok())
        .flatten();
    for name in names {
        let path = dir.join(name);
        crate::face::outfile::check(&path, false).map_err(|e| {
            format!("{e}; grade writes only regular files it names (choose another --out)")
        })?;
        if let (Some(a), Ok(b)) = (&input_id, std::fs::metadata(&path))
            && same_file(a, &b)
        {
            return Err(format!(
                "the class file {} is one of grade's outputs and would be replaced; \
                 choose another --out",
                shown(input)
            ));
        }
    }
    Ok(())
}

/// Whether two metadata describe one file (device and inode on Unix).
fn same_file(a: &std::fs::Metadata, b: &std::fs::Metadata) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt as _;
        a.dev() == b.dev() && a.ino() == b.ino()
    }
    #[cfg(not(unix))]
    {
        let _ = (a, b);
        false
    }
}

/// The outputs other than results.csv, by name, each as the pieces it is written from.
type Files<'n> = Vec<(&'n str, output::Pieces)>;

/// Writes every output whole under a temporary name — results.csv streamed by `results`
/// while `others` makes the summary and the other files — and renames them all into place
/// (the folder locked meanwhile; stale temporary files of a killed run removed): the summary
/// and the paths written, or why they could not be written. `one_at_a_time`: `others` first,
/// then results.csv, instead of both at once (less memory, a little more time). `lost`: why
/// what the files were made from cannot be trusted (then none is renamed into place).
fn write_outputs<'n>(
    dir: &Path,
    names: &[&str],
    mut results: impl FnMut(&mut (dyn std::io::Write + Send)) -> std::io::Result<()> + Send,
    others: impl FnOnce() -> anyhow::Result<(summary::Summary, Files<'n>)> + Send,
    one_at_a_time: bool,
    lost: impl Fn() -> Option<String>,
) -> anyhow::Result<Result<(summary::Summary, Vec<PathBuf>), String>> {
    let folder = match crate::face::outfile::Folder::open(dir, names) {
        Ok(f) => f,
        Err(e) => return Ok(Err(e)),
    };
    let stage = |(name, pieces): (&str, output::Pieces)| {
        folder.stage_with(name, &mut |w| {
            pieces.iter().try_for_each(|p| w.write_all(p))
        })
    };
    // One at a time, the other files are written (and their bytes freed) before results.csv
    // is made; else results.csv is made beside them and they are written after.
    let (summary, staged) = if one_at_a_time {
        let (summary, files) = others()?;
        let files: Vec<_> = files.into_iter().map(stage).collect();
        let results = folder.stage_with("results.csv", &mut results);
        (
            summary,
            std::iter::once(results).chain(files).collect::<Vec<_>>(),
        )
    } else {
        let (results, made) =
            rayon::join(|| folder.stage_with("results.csv", &mut results), others);
        let (summary, files) = made?;
        let files = files.into_iter().map(stage);
        (summary, std::iter::once(results).chain(files).collect())
    };
    let written = (|| {
        let staged = staged.into_iter().collect::<Result<Vec<_>, String>>()?;
        if let Some(message) = lost() {
            return Err(format!("{message}; nothing was written"));
        }
        crate::face::outfile::commit(staged)
    })();
    Ok(written.map(|w| (summary, w)))
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
        // A FIFO or a device would be read until it ends, perhaps never: pipe it in with `-`.
        if !meta.is_file() {
            return Err(format!(
                "{} is not a regular file (a FIFO or a device); give a file, or pipe it in: \
                 `lagrange grade - < …`",
                shown(path)
            ));
        }
        if meta.len() > MAX_FILE_BYTES {
            return Err(too_large());
        }
        let file = std::fs::File::open(path).map_err(cannot)?;
        bytes = read_whole(&file, meta.len()).map_err(cannot)?;
    }
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(too_large());
    }
    Ok(bytes)
}

/// A file of about `len` bytes read whole (more if it grew since, up to one byte past
/// [`MAX_FILE_BYTES`]): in parallel blocks into room made at once, where the system reads at
/// an offset, rather than one read into a list that doubles (each time copying the last).
fn read_whole(file: &std::fs::File, len: u64) -> std::io::Result<Vec<u8>> {
    #[cfg(unix)]
    let mut bytes = {
        use rayon::prelude::*;
        use std::os::unix::fs::FileExt as _;
        const BLOCK: usize = 4 << 20;
        // Zeroed room comes as fresh pages: filled by the reads, not written twice.
        let mut bytes = vec![0; len as usize];
        (bytes.par_chunks_mut(BLOCK).enumerate())
            .try_for_each(|(i, block)| file.read_exact_at(block, (i * BLOCK) as u64))?;
        bytes
    };
    #[cfg(not(unix))]
    let mut bytes = {
        let _ = len;
        Vec::new()
    };
    // What is left (all of it where reading at an offset is not available), up to the limit.
    let mut rest = file;
    #[cfg(unix)]
    std::io::Seek::seek(&mut rest, std::io::SeekFrom::Start(len))?;
    rest.take(MAX_FILE_BYTES + 1 - bytes.len() as u64)
        .read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// Where grading keeps its nameless temporary file (`judge::Settings::scratch`): the output
/// folder, else (not made yet) the nearest folder that holds it, on the disk the outputs go
/// to; else the system's temporary folder.
fn scratch_dir(out: &Path) -> PathBuf {
    let out = std::path::absolute(out).unwrap_or_else(|_| out.to_path_buf());
    (out.ancestors().find(|a| a.is_dir())).map_or_else(std::env::temp_dir, Path::to_path_buf)
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
fn lms_title(input: &Path) -> String {
    match input.file_stem().and_then(|s| s.to_str()) {
        Some(s) if input != Path::new("-") => format!("lagrange {s}"),
        _ => "lagrange".to_string(),
    }
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
        let _ = writeln!(out, "  {}", shown(w));
    }
    out
}

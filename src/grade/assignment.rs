//! `grade --assignment FILE`: reads the assignment file (the library's
//! `lagrange::policy::Assignment` parses and checks it) and merges it with the command line,
//! whose options are shorthands that take precedence: `--best`, `--follow-through[-credit]`,
//! `--parts`.

use std::path::Path;

use lagrange::bank::Bank;
use lagrange::expr::error::visible;
use lagrange::policy::{Assignment, Attempts, Policy};

use super::Options;
use super::overrides::Overrides;

/// The largest assignment file read.
const MAX_BYTES: u64 = 1 << 20;

/// The assignment (if any) and the policy the run grades by: the file's, with the command
/// line's options over it. The error is one line (two with its help) naming the file, line
/// and column.
pub fn read(opts: &Options) -> Result<(Option<Assignment>, Policy), String> {
    let assignment = match &opts.assignment {
        Some(path) => Some(parse(path)?),
        None => None,
    };
    let mut policy = assignment
        .as_ref()
        .map_or_else(Policy::default, |a| a.policy.clone());
    if let Some(c) = opts.follow_through {
        policy.follow_through = Some(c);
    }
    if opts.best {
        policy.attempts = Attempts::Best;
    }
    Ok((assignment, policy))
}

/// Reads and parses one assignment file.
fn parse(path: &Path) -> Result<Assignment, String> {
    let shown = visible(&path.display().to_string());
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot read {shown}: {e}"))?;
    if !meta.is_file() {
        return Err(format!("--assignment {shown} is not a regular file"));
    }
    if meta.len() > MAX_BYTES {
        return Err(format!("--assignment {shown} is over 1 MB"));
    }
    let bytes = std::fs::read(path).map_err(|e| format!("cannot read {shown}: {e}"))?;
    let text = String::from_utf8(bytes)
        .map_err(|_| format!("{shown} is not UTF-8; save the assignment file as UTF-8"))?;
    Assignment::parse(&text).map_err(|e| format!("{shown}:{e}\n  help: {}", e.help))
}

/// Sets the assignment's points in the bank and gives its parts (indices into the bank), or
/// `None` without an assignment or one naming no problem.
pub fn apply(
    assignment: Option<&Assignment>,
    opts: &Options,
    bank: &mut Bank,
) -> Result<Option<Vec<(usize, usize)>>, String> {
    let Some(a) = assignment else {
        return Ok(None);
    };
    a.apply(bank).map_err(|e| {
        let shown = (opts.assignment.as_deref())
            .map_or(String::new(), |p| visible(&p.display().to_string()));
        format!("{shown}:{e}\n  help: {}", e.help)
    })
}

/// What the run id adds for an assignment and overrides: the policy, the seed and every
/// decision (empty without either, so ids of runs without them do not change).
pub fn run_key(
    policy: &Policy,
    assignment: Option<&Assignment>,
    decisions: Option<&Overrides>,
) -> String {
    let mut key = String::new();
    if let Some(a) = assignment {
        key.push_str(&format!(
            "|assignment {} seed={:?} title={:?}",
            policy.describe(),
            a.seed,
            a.title
        ));
    }
    if let Some(d) = decisions {
        for e in &d.entries {
            key.push_str(&format!(
                "|override {:?} {:?} {:?} {}",
                e.problem, e.part, e.answer, e.decision
            ));
        }
    }
    key
}

/// The LMS column's title: the assignment's, else from the class file's name.
pub fn title(assignment: Option<&Assignment>, input: &Path) -> String {
    match assignment.and_then(|a| a.title.as_deref()) {
        Some(t) => t.to_string(),
        None => super::lms_title(input),
    }
}

/// A note on stderr for each decision that matched no answer (it is kept in review.csv).
pub fn unmatched_notes(decisions: &Overrides, unmatched: &[usize]) {
    for &e in unmatched {
        let e = &decisions.entries[e];
        eprintln!(
            "note: --overrides line {}: no answer `{}` to {}/{} in this class; the decision is \
             kept in review.csv",
            e.line,
            visible(&e.answer),
            visible(&e.problem),
            visible(&e.part)
        );
    }
}

//! The assignment file (TOML): its problems and parts, points, the course seed for
//! per-student variants and the grading [`Policy`]. Read from text (the face reads the file);
//! every error names its line and column and says in one line how to fix it.
//!
//! ```toml
//! title = "Problem set 3"          # the LMS column (default: from the class file's name)
//! seed = 20261126                  # the course seed for per-student variants
//!
//! [policy]
//! attempts = "best"                # or "last" (the default)
//! penalty = 0.1                    # of the part's points, per attempt after the first
//! follow-through = 0.5             # a fraction, true (0.5) or false (the default)
//! credit = { sign-error = 0.5, constant-factor = 0.25 }
//!
//! [[problems]]
//! id = "simple-pendulum"
//! parts = ["lagrangian", "eom"]    # default: every part of the problem
//! points = { eom = 2 }             # default: the bank's points
//! ```

use std::collections::BTreeMap;
use std::fmt;

use serde::Deserialize;
use toml::Spanned;

use crate::bank::Bank;
use crate::check::Code;
use crate::diagnostic::did_you_mean;
use crate::expr::error::visible;

use super::{Attempts, Policy};

/// The largest assignment file read.
const MAX_BYTES: usize = 1 << 20;

/// An assignment, as its file states it.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Assignment {
    /// Its title (the LMS column), if given.
    pub title: Option<String>,
    /// The course seed for per-student variants, if given.
    pub seed: Option<u64>,
    /// How answers are scored and which attempt counts.
    pub policy: Policy,
    /// The problems set, in file order.
    pub(crate) problems: Vec<ProblemEntry>,
}

/// One problem of an assignment.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ProblemEntry {
    /// The problem's id in the bank.
    pub id: String,
    /// The parts set (`None`: every part of the problem).
    pub parts: Option<Vec<String>>,
    /// Points per part that replace the bank's.
    pub(crate) points: Vec<(String, f64)>,
    /// Where the entry is (1-based line and column), for errors found against the bank.
    pub(crate) line: usize,
    /// The column of [`ProblemEntry::line`].
    pub(crate) column: usize,
}

/// Why an assignment file is refused: where (1-based line and column), what, and how to fix it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct AssignmentError {
    /// 1-based line.
    pub(crate) line: usize,
    /// 1-based column (in characters).
    pub(crate) column: usize,
    /// A stable code, e.g. `unknown-code`.
    pub(crate) code: &'static str,
    /// What is wrong.
    pub(crate) message: String,
    /// How to fix it, in one line.
    pub help: String,
}

impl fmt::Display for AssignmentError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{}:{}: {} [{}]",
            self.line,
            self.column,
            visible(&self.message),
            self.code
        )
    }
}

impl std::error::Error for AssignmentError {}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct File {
    title: Option<Spanned<String>>,
    seed: Option<Spanned<i64>>,
    policy: Option<PolicyFile>,
    #[serde(default)]
    problems: Vec<Spanned<ProblemFile>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct PolicyFile {
    attempts: Option<Spanned<String>>,
    penalty: Option<Spanned<f64>>,
    #[serde(rename = "follow-through")]
    follow_through: Option<Spanned<FollowThrough>>,
    #[serde(default)]
    credit: BTreeMap<String, Spanned<f64>>,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum FollowThrough {
    On(bool),
    Credit(f64),
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct ProblemFile {
    id: String,
    parts: Option<Vec<String>>,
    #[serde(default)]
    points: BTreeMap<String, Spanned<f64>>,
}

/// The follow-through credit `follow-through = true` gives (as `grade --follow-through`).
pub const DEFAULT_FOLLOW_THROUGH: f64 = 0.5;

/// 1-based line and column (in characters) of byte `at` in `text`.
fn position(text: &str, at: usize) -> (usize, usize) {
    let mut at = at.min(text.len());
    while !text.is_char_boundary(at) {
        at -= 1;
    }
    let before = &text[..at];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[start..].chars().count() + 1)
}

impl Assignment {
    /// Reads an assignment from the text of its file.
    pub fn parse(text: &str) -> Result<Assignment, AssignmentError> {
        let fail = |at: usize, code: &'static str, message: String, help: &str| {
            let (line, column) = position(text, at);
            AssignmentError {
                line,
                column,
                code,
                message,
                help: help.to_string(),
            }
        };
        if text.len() > MAX_BYTES {
            return Err(fail(
                0,
                "too-large",
                format!(
                    "the file is {} bytes; at most {MAX_BYTES} are read",
                    text.len()
                ),
                "an assignment file names problems and a policy: it is small",
            ));
        }
        let file: File = toml::from_str(text).map_err(|e| {
            let at = e.span().map_or(0, |s| s.start);
            let message = e.message().trim().to_string();
            let (code, help) = if message.contains("unknown field") {
                (
                    "unknown-key",
                    "the keys are title, seed, [policy] and [[problems]]; see docs/grading.md",
                )
            } else if message.contains("missing field") {
                ("missing-key", "every [[problems]] entry needs an `id`")
            } else if message.contains("invalid type") || message.contains("did not match") {
                ("wrong-type", "see docs/grading.md for each key's type")
            } else {
                ("toml-syntax", "the file must be TOML (see docs/grading.md)")
            };
            fail(at, code, message, help)
        })?;
        let fraction = |v: &Spanned<f64>, what: &str| {
            let x = *v.get_ref();
            if (0.0..=1.0).contains(&x) {
                Ok(x)
            } else {
                Err(fail(
                    v.span().start,
                    "out-of-range",
                    format!("{what} is {x}; it must be between 0 and 1 (a fraction of the points)"),
                    "write a fraction such as 0.5",
                ))
            }
        };
        let mut policy = Policy::default();
        if let Some(p) = &file.policy {
            if let Some(a) = &p.attempts {
                policy.attempts = match a.get_ref().trim() {
                    "last" => Attempts::Last,
                    "best" => Attempts::Best,
                    other => {
                        return Err(fail(
                            a.span().start,
                            "unknown-attempts",
                            format!(
                                "attempts = `{}` is neither `last` nor `best`",
                                visible(other)
                            ),
                            "write attempts = \"last\" or attempts = \"best\"",
                        ));
                    }
                };
            }
            if let Some(v) = &p.penalty {
                policy.penalty = fraction(v, "the penalty")?;
            }
            if let Some(v) = &p.follow_through {
                policy.follow_through = match v.get_ref() {
                    FollowThrough::On(false) => None,
                    FollowThrough::On(true) => Some(DEFAULT_FOLLOW_THROUGH),
                    FollowThrough::Credit(x) => {
                        let s = Spanned::new(v.span(), *x);
                        Some(fraction(&s, "the follow-through credit")?)
                    }
                };
            }
            for (name, v) in &p.credit {
                let Some(code) = Code::ALL.iter().find(|c| c.as_str() == name.trim()) else {
                    let hint = did_you_mean(name, Code::ALL.iter().map(|c| c.as_str()))
                        .map_or(String::new(), |s| format!("; did you mean `{s}`?"));
                    return Err(fail(
                        v.span().start,
                        "unknown-code",
                        format!("`{}` is not a diagnosis code{hint}", visible(name)),
                        "the codes are listed in docs/checking.md (e.g. sign-error, constant-factor)",
                    ));
                };
                policy.credit.push((*code, fraction(v, "the credit")?));
            }
            policy.credit.sort_by_key(|(c, _)| *c);
        }
        let seed = match &file.seed {
            Some(s) => Some(u64::try_from(*s.get_ref()).map_err(|_| {
                fail(
                    s.span().start,
                    "out-of-range",
                    format!("the seed is {}; it must be 0 or more", s.get_ref()),
                    "any whole number from 0 up names the course's variants",
                )
            })?),
            None => None,
        };
        let mut problems = Vec::new();
        for p in &file.problems {
            let (line, column) = position(text, p.span().start);
            let body = p.get_ref();
            let mut points = Vec::new();
            for (part, v) in &body.points {
                let x = *v.get_ref();
                if !(x.is_finite() && x >= 0.0) {
                    return Err(fail(
                        v.span().start,
                        "out-of-range",
                        format!(
                            "the points of `{}` are {x}; they must be 0 or more",
                            visible(part)
                        ),
                        "write the part's points as a number, e.g. 2",
                    ));
                }
                points.push((part.clone(), x));
            }
            problems.push(ProblemEntry {
                id: body.id.clone(),
                parts: body.parts.clone(),
                points,
                line,
                column,
            });
        }
        Ok(Assignment {
            title: file.title.map(|t| t.into_inner()),
            seed,
            policy,
            problems,
        })
    }

    /// Checks the problems and parts against `bank`, sets the assignment's points in it, and
    /// gives the parts set as `(problem, part)` indices of the bank, in assignment order
    /// (`None` when the file names no problem: every part answered is graded). An unknown
    /// problem or part is an error at its entry, with the closest name.
    pub fn apply(&self, bank: &mut Bank) -> Result<Option<Vec<(usize, usize)>>, AssignmentError> {
        if self.problems.is_empty() {
            return Ok(None);
        }
        let mut set = Vec::new();
        for entry in &self.problems {
            let fail = |code: &'static str, message: String, help: String| AssignmentError {
                line: entry.line,
                column: entry.column,
                code,
                message,
                help,
            };
            let Some(p) = bank.problems.iter().position(|x| x.id == entry.id) else {
                let hint = did_you_mean(&entry.id, bank.problems.iter().map(|x| x.id.as_str()))
                    .map_or(String::new(), |s| format!("; did you mean `{s}`?"));
                return Err(fail(
                    "unknown-problem",
                    format!("no problem `{}` in the bank{hint}", visible(&entry.id)),
                    "`lagrange problems list` lists the problems; a problem of your own needs its folder: `--add-problems DIR`".to_string(),
                ));
            };
            let problem = &bank.problems[p];
            let ids: Vec<&str> = problem.parts.iter().map(|x| x.id.as_str()).collect();
            let find = |part: &str| {
                ids.iter().position(|x| *x == part).ok_or_else(|| {
                    let hint = did_you_mean(part, ids.iter().copied())
                        .map_or(String::new(), |s| format!("; did you mean `{s}`?"));
                    fail(
                        "unknown-part",
                        format!("`{}` has no part `{}`{hint}", problem.id, visible(part)),
                        format!("the parts of `{}` are {}", problem.id, ids.join(", ")),
                    )
                })
            };
            let parts: Vec<usize> = match &entry.parts {
                Some(list) => list.iter().map(|q| find(q)).collect::<Result<_, _>>()?,
                None => (0..ids.len()).collect(),
            };
            let points: Vec<(usize, f64)> = (entry.points.iter())
                .map(|(q, x)| Ok((find(q)?, *x)))
                .collect::<Result<_, AssignmentError>>()?;
            for q in parts {
                if !set.contains(&(p, q)) {
                    set.push((p, q));
                }
            }
            for (q, x) in points {
                bank.problems[p].parts[q].points = x;
            }
        }
        Ok(Some(set))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FILE: &str = r#"
title = "Set 3"
seed = 42

[policy]
attempts = "best"
penalty = 0.1
follow-through = true
credit = { sign-error = 0.5, constant-factor = 0.25 }

[[problems]]
id = "simple-pendulum"
parts = ["lagrangian", "eom"]
points = { eom = 2 }
"#;

    #[test]
    fn an_assignment_reads_its_policy_problems_and_seed() {
        let a = Assignment::parse(FILE).unwrap();
        assert_eq!(a.title.as_deref(), Some("Set 3"));
        assert_eq!(a.seed, Some(42));
        assert_eq!(a.policy.attempts, Attempts::Best);
        assert_eq!(a.policy.penalty, 0.1);
        assert_eq!(a.policy.follow_through, Some(0.5));
        assert_eq!(
            a.policy.credit,
            vec![(Code::SignError, 0.5), (Code::ConstantFactor, 0.25)]
        );
        let mut bank = crate::embedded::bank();
        let set = a.apply(&mut bank).unwrap().unwrap();
        assert_eq!(set.len(), 2);
        let (p, q) = set[1];
        assert_eq!(bank.problems[p].parts[q].id, "eom");
        assert_eq!(bank.problems[p].parts[q].points, 2.0);
    }

    #[test]
    fn errors_name_line_and_column() {
        let bad = FILE.replace("sign-error", "sign-eror");
        let e = Assignment::parse(&bad).unwrap_err();
        assert_eq!((e.code, e.line, e.column), ("unknown-code", 9, 24));
        assert!(e.message.contains("did you mean `sign-error`"), "{e}");
        let bad = FILE.replace("penalty = 0.1", "penalty = 3");
        let e = Assignment::parse(&bad).unwrap_err();
        assert_eq!((e.code, e.line, e.column), ("out-of-range", 7, 11));
        let bad = FILE.replace("seed = 42", "sede = 42");
        assert_eq!(Assignment::parse(&bad).unwrap_err().code, "unknown-key");
        let bad = FILE.replace("\"eom\"]", "\"eon\"]");
        let a = Assignment::parse(&bad).unwrap();
        let e = a.apply(&mut crate::embedded::bank()).unwrap_err();
        assert_eq!((e.code, e.line), ("unknown-part", 11));
        assert!(e.message.contains("did you mean `eom`"), "{e}");
        assert!(Assignment::parse("seed = -1").is_err());
        assert!(Assignment::parse("[policy]\nattempts = \"first\"").is_err());
        assert!(Assignment::parse("[[problems]]\nparts = []").is_err());
    }
}

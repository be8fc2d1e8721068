//! A student's progress as data: per problem and part, the attempts, whether it is solved,
//! the hints used, whether the answer was revealed, and the last answers given (which the
//! follow-through reads). Versioned JSON through serde; no file access here — the face reads
//! and writes the file and decides what to do with one that does not parse.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::problem::Problem;

/// The format version written by [`Progress::to_json`] and the only one read back.
pub const PROGRESS_VERSION: u32 = 1;

/// How many of a part's latest answers are kept (oldest dropped first).
pub const KEPT_ANSWERS: usize = 8;

/// Why a progress file's text could not be read.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ProgressError {
    /// The text is not JSON of the progress shape.
    #[error("the progress file is not valid (line {line}, column {column}): {message}")]
    Malformed {
        line: usize,
        column: usize,
        message: String,
    },
    /// The file was written by another version of the format.
    #[error(
        "the progress file has version {found}; this version of lagrange reads version {PROGRESS_VERSION}"
    )]
    Version { found: u32 },
}

/// One part's record.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default)]
pub struct PartProgress {
    /// Checked answers (correct or not; unreadable input never counts).
    pub attempts: u32,
    /// Answered correctly at least once.
    pub solved: bool,
    /// Hints shown.
    pub(crate) hints_used: u32,
    /// The reference answer was shown (`:solution`).
    pub revealed: bool,
    /// The latest checked answers as typed, oldest first (at most [`KEPT_ANSWERS`]).
    pub answers: Vec<String>,
}

impl PartProgress {
    /// The latest checked answer, if any.
    pub fn last_answer(&self) -> Option<&str> {
        self.answers.last().map(String::as_str)
    }
}

/// One problem's record: its parts by id.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default)]
pub struct ProblemProgress {
    /// The parts attempted, hinted or revealed, by id.
    pub(crate) parts: BTreeMap<String, PartProgress>,
    /// The seed of the numbers being practised (`:variant`), for a problem whose numbers
    /// vary; absent until the student asks for numbers.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub variant_seed: Option<u64>,
}

/// A student's progress over every problem, by problem id (ordered, so the JSON is stable).
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Progress {
    /// The format version ([`PROGRESS_VERSION`]).
    pub(crate) version: u32,
    /// A number drawn once for this learner's progress file (by the face that keeps it) and
    /// kept in it: where `:variant` starts each problem's sequence of numbers, so that two
    /// learners practise different numbers and one learner the same ones, given the file.
    /// Absent (older files, a progress never saved): the sequence starts from the problem id.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub learner_seed: Option<u64>,
    /// The problems touched, by id.
    #[serde(default)]
    pub problems: BTreeMap<String, ProblemProgress>,
}

impl Default for Progress {
    fn default() -> Self {
        Progress {
            version: PROGRESS_VERSION,
            learner_seed: None,
            problems: BTreeMap::new(),
        }
    }
}

impl Progress {
    /// A fresh, empty progress.
    pub fn new() -> Self {
        Progress::default()
    }

    /// The record of a part, if it was ever touched.
    pub fn part(&self, problem: &str, part: &str) -> Option<&PartProgress> {
        self.problems.get(problem)?.parts.get(part)
    }

    /// The record of a part, created empty when missing.
    pub fn part_mut(&mut self, problem: &str, part: &str) -> &mut PartProgress {
        self.problems
            .entry(problem.to_string())
            .or_default()
            .parts
            .entry(part.to_string())
            .or_default()
    }

    /// Whether the part is solved.
    pub fn is_solved(&self, problem: &str, part: &str) -> bool {
        self.part(problem, part).is_some_and(|p| p.solved)
    }

    /// Records a checked answer: one more attempt, the answer kept, solved when `correct`.
    pub fn record_attempt(&mut self, problem: &str, part: &str, answer: &str, correct: bool) {
        let rec = self.part_mut(problem, part);
        rec.attempts = rec.attempts.saturating_add(1);
        rec.solved |= correct;
        rec.answers.push(answer.to_string());
        if rec.answers.len() > KEPT_ANSWERS {
            let extra = rec.answers.len() - KEPT_ANSWERS;
            rec.answers.drain(..extra);
        }
    }

    /// How many of `problem`'s parts are solved (parts no longer in the problem are ignored).
    pub fn solved_parts(&self, problem: &Problem) -> usize {
        problem
            .parts
            .iter()
            .filter(|p| self.is_solved(&problem.id, &p.id))
            .count()
    }

    /// The progress as pretty JSON (`"version": 1` first).
    pub fn to_json(&self) -> String {
        // Maps with string keys, strings, numbers and booleans: serialising cannot fail.
        serde_json::to_string_pretty(self).unwrap_or_default()
    }

    /// Reads progress written by [`to_json`](Progress::to_json); a malformed text or another
    /// version is a typed error (the face moves such a file aside and starts afresh).
    pub fn from_json(text: &str) -> Result<Progress, ProgressError> {
        let value: serde_json::Value = serde_json::from_str(text).map_err(malformed)?;
        match value.get("version").and_then(serde_json::Value::as_u64) {
            Some(v) if v == u64::from(PROGRESS_VERSION) => {}
            Some(v) => {
                return Err(ProgressError::Version {
                    found: u32::try_from(v).unwrap_or(u32::MAX),
                });
            }
            None => {
                return Err(ProgressError::Malformed {
                    line: 1,
                    column: 1,
                    message: "no \"version\" number".to_string(),
                });
            }
        }
        serde_json::from_value(value).map_err(malformed)
    }
}

fn malformed(e: serde_json::Error) -> ProgressError {
    ProgressError::Malformed {
        line: e.line(),
        column: e.column(),
        message: e.to_string(),
    }
}

impl Progress {
    /// Two sessions' records as one: `disk` (what another session saved since) plus what
    /// `mine` added to `base` (the record `mine` started from). Attempts and hints add up,
    /// solved and revealed stay true once true, and the new answers follow the ones on disk
    /// (the latest [`KEPT_ANSWERS`] kept). The learner seed is drawn once per file: the one on
    /// disk stays, and `mine`'s is kept only where the file has none yet.
    pub fn merged(disk: &Progress, base: &Progress, mine: &Progress) -> Progress {
        let mut out = disk.clone();
        if out.learner_seed.is_none() {
            out.learner_seed = mine.learner_seed;
        }
        for (problem, pp) in &mine.problems {
            // The numbers practised last in this session win (a `:variant` here).
            let before = base.problems.get(problem).and_then(|b| b.variant_seed);
            if pp.variant_seed.is_some() && pp.variant_seed != before {
                out.problems
                    .entry(problem.clone())
                    .or_default()
                    .variant_seed = pp.variant_seed;
            }
            for (part, rec) in &pp.parts {
                let before = base.part(problem, part).cloned().unwrap_or_default();
                let new_attempts = rec.attempts.saturating_sub(before.attempts);
                let new_hints = rec.hints_used.saturating_sub(before.hints_used);
                let target = out.part_mut(problem, part);
                target.attempts = target.attempts.saturating_add(new_attempts);
                target.hints_used = target.hints_used.saturating_add(new_hints);
                target.solved |= rec.solved;
                target.revealed |= rec.revealed;
                let fresh = (new_attempts as usize).min(rec.answers.len());
                target
                    .answers
                    .extend(rec.answers[rec.answers.len() - fresh..].iter().cloned());
                if target.answers.len() > KEPT_ANSWERS {
                    let extra = target.answers.len() - KEPT_ANSWERS;
                    target.answers.drain(..extra);
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn attempts_keep_the_latest_answers() {
        let mut p = Progress::new();
        for i in 0..10 {
            p.record_attempt("a", "b", &format!("x{i}"), i == 3);
        }
        let rec = p.part("a", "b").cloned().unwrap_or_default();
        assert_eq!(rec.attempts, 10);
        assert!(rec.solved, "solved stays solved after later wrong answers");
        assert_eq!(rec.answers.len(), KEPT_ANSWERS);
        assert_eq!(rec.last_answer(), Some("x9"));
        assert_eq!(rec.answers.first().map(String::as_str), Some("x2"));
    }

    #[test]
    fn round_trip_and_errors() {
        let mut p = Progress::new();
        p.record_attempt("simple-pendulum", "kinetic", "1/2*m*l^2*theta'^2", true);
        p.part_mut("simple-pendulum", "eom").hints_used = 2;
        let json = p.to_json();
        assert!(json.contains("\"version\": 1"));
        assert_eq!(Progress::from_json(&json), Ok(p));
        assert!(matches!(
            Progress::from_json("{\"version\": 1, \"problems\": 3"),
            Err(ProgressError::Malformed { .. })
        ));
        assert_eq!(
            Progress::from_json("{\"version\": 7}"),
            Err(ProgressError::Version { found: 7 })
        );
        assert!(matches!(
            Progress::from_json("[]"),
            Err(ProgressError::Malformed { .. })
        ));
        assert_eq!(Progress::from_json("{\"version\": 1}"), Ok(Progress::new()));
    }

    #[test]
    fn merging_adds_what_each_session_did_since_it_started() {
        let base = Progress::new();
        let mut disk = base.clone();
        disk.record_attempt("simple-pendulum", "kinetic", "a", false);
        let mut mine = base.clone();
        mine.record_attempt("simple-pendulum", "kinetic", "b", true);
        mine.record_attempt("simple-pendulum", "eom", "c", false);
        let m = Progress::merged(&disk, &base, &mine);
        let kinetic = m
            .part("simple-pendulum", "kinetic")
            .cloned()
            .unwrap_or_default();
        assert_eq!(kinetic.attempts, 2);
        assert!(kinetic.solved, "solved in one session is solved");
        assert_eq!(kinetic.answers, ["a", "b"]);
        assert_eq!(
            m.part("simple-pendulum", "eom").map(|p| p.attempts),
            Some(1)
        );
        // A session that did nothing leaves the disk's record as it is.
        assert_eq!(Progress::merged(&disk, &base, &base), disk);
    }

    #[test]
    fn the_learner_seed_is_drawn_once_per_file() {
        let base = Progress::new();
        let mut mine = base.clone();
        mine.learner_seed = Some(7);
        // A file without a seed takes the session's.
        assert_eq!(Progress::merged(&base, &base, &mine).learner_seed, Some(7));
        // A file that has one keeps it: another session saved first.
        let mut disk = base.clone();
        disk.learner_seed = Some(3);
        assert_eq!(Progress::merged(&disk, &base, &mine).learner_seed, Some(3));
        // It is kept in the JSON, and an older file without it reads as none.
        let json = mine.to_json();
        assert!(json.contains("\"learner_seed\": 7"), "{json}");
        assert_eq!(Progress::from_json(&json), Ok(mine));
        assert_eq!(
            Progress::from_json("{\"version\": 1, \"problems\": {}}").map(|p| p.learner_seed),
            Ok(None)
        );
    }
}

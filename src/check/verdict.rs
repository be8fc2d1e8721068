//! The verdict on an answer: data only (rendering is the faces' business).

use serde::Serialize;

/// Correct, incorrect, or unreadable / not of the part's kind (never a wrong attempt).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Status {
    Correct,
    Incorrect,
    Invalid,
}

impl Status {
    /// "correct", "incorrect" or "invalid".
    pub fn name(self) -> &'static str {
        match self {
            Status::Correct => "correct",
            Status::Incorrect => "incorrect",
            Status::Invalid => "invalid",
        }
    }
}

/// How the input was read.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct ReadAs {
    pub plain: String,
    pub unicode: String,
    /// Anything the reader assumed, e.g. "read as … = 0".
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// One reason, with a stable code.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Diagnosis {
    pub code: &'static str,
    pub message: String,
}

impl Diagnosis {
    /// A diagnosis.
    pub fn new(code: &'static str, message: impl Into<String>) -> Self {
        Diagnosis {
            code,
            message: message.into(),
        }
    }
}

/// Every diagnosis code, most specific first (the order diagnoses are reported in).
pub const CODES: &[&str] = &[
    "unknown-symbol",
    "substituted-symbol",
    "syntax",
    "wrong-kind",
    "dimension",
    "undefined",
    "t-plus-v",
    "gave-lagrangian",
    "omega-squared",
    "omega-root",
    "small-angle",
    "swapped-symbols",
    "sign-error",
    "constant-factor",
    "velocity-term",
    "rounded-constant",
    "equation-count",
    "dependent-equations",
    "wrong-equation",
    "missing-item",
    "extra-item",
    "wrong-item",
    "up-to-constant",
    "equivalent-lagrangian",
    "not-equal",
];

/// The verdict on one answer.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Verdict {
    pub problem: String,
    pub part: String,
    pub status: Status,
    /// 0…1; partial credit for lists and systems.
    pub score: f64,
    pub reading: ReadAs,
    pub diagnoses: Vec<Diagnosis>,
    /// The sampling seed (from the problem and part ids).
    pub seed: u64,
    /// The reader's error, for rendering with a caret (not serialized).
    #[serde(skip)]
    pub parse_error: Option<crate::expr::ParseError>,
}

impl Verdict {
    /// Orders the diagnoses most specific first and removes repeats.
    pub fn sort(&mut self) {
        let rank = |c: &str| CODES.iter().position(|x| *x == c).unwrap_or(CODES.len());
        self.diagnoses.sort_by_key(|d| rank(d.code));
        self.diagnoses.dedup();
    }
}

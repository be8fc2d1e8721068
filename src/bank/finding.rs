//! A finding: something wrong with a problem file, located by file, part and line.

use std::fmt;

use super::FindingCode;
use crate::expr::error::{visible, visible_lines};

/// One problem found in a problem file.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct Finding {
    pub(crate) file: String,
    /// The problem id, when the file got far enough to have one.
    pub problem: Option<String>,
    /// The part id, when the finding is about a part.
    pub part: Option<String>,
    /// 1-based line in the file.
    pub line: usize,
    /// A stable code, e.g. `wrong-eom`.
    pub code: FindingCode,
    pub message: String,
}

/// File names, part ids and messages quote the file's own text, which may hold control or
/// invisible characters: they are shown escaped or named, never as themselves.
impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}: ", visible(&self.file), self.line)?;
        if let Some(p) = &self.part {
            write!(f, "part `{}`: ", visible(p))?;
        }
        write!(f, "{} [{}]", visible_lines(&self.message), self.code)
    }
}

/// The 1-based line of byte `offset` in `text`.
pub fn line_of(text: &str, offset: usize) -> usize {
    text.as_bytes()[..offset.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

impl From<&Finding> for crate::diagnostic::Diagnostic {
    /// The finding as a diagnostic: its location leads the message (a finding points at a
    /// line of a file, not at a span of an answer).
    fn from(f: &Finding) -> Self {
        let mut message = format!("{}:{}: ", visible(&f.file), f.line);
        if let Some(p) = &f.part {
            message.push_str(&format!("part `{}`: ", visible(p)));
        }
        message.push_str(&f.message);
        crate::diagnostic::Diagnostic::new(f.code.as_str(), message, "")
    }
}

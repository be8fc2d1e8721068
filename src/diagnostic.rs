//! One shape and one renderer for every message the library gives a person: parse errors,
//! mechanics errors, problem-file findings and verdict diagnoses all convert into a
//! [`Diagnostic`] (code, optional span, message, help). With a span, [`render`] shows the
//! source line with a caret under it; without one, a headline and the help. The CLI, the REPL
//! and the snapshot tests all go through [`render`].

use std::ops::Range;

use ariadne::{Config, IndexType, Label, Report, ReportKind, Source};

use crate::expr::ParseError;

/// A message, optionally about a span of some source text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// A stable code, e.g. `unknown-symbol`.
    pub code: String,
    /// What is wrong.
    pub message: String,
    /// Where, in bytes, when the message is about a piece of text.
    pub span: Option<Range<usize>>,
    /// A short label under the span (empty: none).
    pub label: String,
    /// How to fix it, in one line (empty: none).
    pub help: String,
}

impl Diagnostic {
    /// A diagnostic without a span.
    pub fn new(
        code: impl Into<String>,
        message: impl Into<String>,
        help: impl Into<String>,
    ) -> Self {
        Diagnostic {
            code: code.into(),
            message: message.into(),
            span: None,
            label: String::new(),
            help: help.into(),
        }
    }

    /// The same diagnostic with another help line (a face phrasing help for its own flags).
    pub fn with_help(mut self, help: impl Into<String>) -> Self {
        self.help = help.into();
        self
    }
}

impl From<&ParseError> for Diagnostic {
    fn from(e: &ParseError) -> Self {
        Diagnostic {
            code: e.kind.code().to_string(),
            message: e.kind.to_string(),
            span: Some(e.span.clone()),
            label: e.kind.label(),
            help: e.help(),
        }
    }
}

/// Renders `d` against `src`, which the header calls `name` (e.g. `input`, a file path).
/// A diagnostic without a span ignores `src` and prints `error[code]: message` and the help.
pub fn render(name: &str, src: &str, d: &Diagnostic, color: bool) -> String {
    let Some(span) = &d.span else {
        return render_plain(d);
    };
    // Clamp the span into the text so that no diagnostic can make the renderer panic.
    let mut start = span.start.min(src.len());
    while !src.is_char_boundary(start) {
        start -= 1;
    }
    let mut end = span.end.clamp(start, src.len());
    while !src.is_char_boundary(end) {
        end += 1;
    }
    let span = (name, start..end);
    let config = Config::default()
        .with_index_type(IndexType::Byte)
        .with_color(color);
    let mut report = Report::build(ReportKind::Error, span.clone())
        .with_config(config)
        .with_code(&d.code)
        .with_message(&d.message)
        .with_label(Label::new(span).with_message(&d.label));
    if !d.help.is_empty() {
        report = report.with_help(&d.help);
    }
    let mut out = Vec::new();
    // Writing into a Vec cannot fail; if it ever did, fall back to the plain form.
    if report
        .finish()
        .write((name, Source::from(src)), &mut out)
        .is_err()
    {
        return render_plain(d);
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// `error[code]: message` and, when there is one, an indented help line.
pub fn render_plain(d: &Diagnostic) -> String {
    let mut s = format!("error[{}]: {}\n", d.code, d.message);
    if !d.help.is_empty() {
        s.push_str(&format!("  help: {}\n", d.help));
    }
    s
}

/// Renders a parse error of `src`.
pub fn render_parse_error(name: &str, src: &str, e: &ParseError, color: bool) -> String {
    render(name, src, &Diagnostic::from(e), color)
}

//! One renderer for every diagnostic that points into a piece of text (an answer, a
//! Lagrangian, a TOML file): the source line, a caret under the span, the message and a
//! one-line help. The CLI, the REPL and the snapshot tests all go through [`render`].

use std::ops::Range;

use ariadne::{Config, IndexType, Label, Report, ReportKind, Source};

use crate::expr::ParseError;

/// A message about a span of some source text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// A stable code, e.g. `unknown-symbol`.
    pub code: String,
    /// What is wrong.
    pub message: String,
    /// Where, in bytes.
    pub span: Range<usize>,
    /// A short label under the span.
    pub label: String,
    /// How to fix it, in one line.
    pub help: String,
}

impl From<&ParseError> for Diagnostic {
    fn from(e: &ParseError) -> Self {
        Diagnostic {
            code: e.kind.code().to_string(),
            message: e.kind.to_string(),
            span: e.span.clone(),
            label: e.kind.label(),
            help: e.help(),
        }
    }
}

/// Renders `d` against `src`, which the header calls `name` (e.g. `input`, a file path).
pub fn render(name: &str, src: &str, d: &Diagnostic, color: bool) -> String {
    // Clamp the span into the text so that no diagnostic can make the renderer panic.
    let mut start = d.span.start.min(src.len());
    while !src.is_char_boundary(start) {
        start -= 1;
    }
    let mut end = d.span.end.clamp(start, src.len());
    while !src.is_char_boundary(end) {
        end += 1;
    }
    let span = (name, start..end);
    let config = Config::default()
        .with_index_type(IndexType::Byte)
        .with_color(color);
    let report = Report::build(ReportKind::Error, span.clone())
        .with_config(config)
        .with_code(&d.code)
        .with_message(&d.message)
        .with_label(Label::new(span).with_message(&d.label))
        .with_help(&d.help)
        .finish();
    let mut out = Vec::new();
    // Writing into a Vec cannot fail; if it ever did, fall back to one plain line.
    if report.write((name, Source::from(src)), &mut out).is_err() {
        return format!("error[{}]: {} ({})", d.code, d.message, d.help);
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// Renders a parse error of `src`.
pub fn render_parse_error(name: &str, src: &str, e: &ParseError, color: bool) -> String {
    render(name, src, &Diagnostic::from(e), color)
}

//! One shape and one renderer for every message the library gives a person: parse errors,
//! mechanics errors, problem-file findings and verdict diagnoses all convert into a
//! [`Diagnostic`] (code, optional span, message, help). With a span, [`render`] shows the
//! source line with a caret under it; without one, a headline and the help. The CLI, the REPL
//! and the snapshot tests all go through [`render`].

use std::ops::Range;

use ariadne::{Config, IndexType, Label, Report, ReportKind, Source};

use crate::expr::ParseError;
use crate::expr::error::{needs_showing, push_shown, visible_lines};

/// Longest source line shown whole under a diagnostic, in bytes; a longer one is cut to a
/// window around the span, so a 20,000-byte input does not fill the terminal.
const MAX_SHOWN_LINE: usize = 200;
/// How much of a long line is shown before the span, in bytes.
const SHOWN_BEFORE: usize = 60;
/// How much of a long line is shown from the span's start, in bytes.
const SHOWN_FROM: usize = 100;

/// A message, optionally about a span of some source text.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnostic {
    /// A stable code, e.g. `unknown-symbol`.
    pub(crate) code: String,
    /// What is wrong.
    pub(crate) message: String,
    /// Where, in bytes, when the message is about a piece of text.
    pub(crate) span: Option<Range<usize>>,
    /// A short label under the span (empty: none).
    pub(crate) label: String,
    /// How to fix it, in one line (empty: none).
    pub(crate) help: String,
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
    let (shown, range) = shown_source(src, start..end);
    let name = visible_lines(name);
    let name = name.as_str();
    let (message, label, help) = (
        visible_lines(&d.message),
        visible_lines(&d.label),
        visible_lines(&d.help),
    );
    let span = (name, range);
    let config = Config::default()
        .with_index_type(IndexType::Byte)
        .with_color(color);
    let mut report = Report::build(ReportKind::Error, span.clone())
        .with_config(config)
        .with_code(&d.code)
        .with_message(&message)
        .with_label(Label::new(span).with_message(&label));
    if !help.is_empty() {
        report = report.with_help(&help);
    }
    let mut out = Vec::new();
    // Writing into a Vec cannot fail; if it ever did, fall back to the plain form.
    if report
        .finish()
        .write((name, Source::from(shown)), &mut out)
        .is_err()
    {
        return render_plain(d);
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// `error[code]: message` and, when there is one, an indented help line.
/// Control and invisible characters in the message and help are made visible (user text is
/// echoed in messages, and must not drive the terminal).
pub fn render_plain(d: &Diagnostic) -> String {
    let mut s = format!("error[{}]: {}\n", d.code, visible_lines(&d.message));
    if !d.help.is_empty() {
        s.push_str(&format!("  help: {}\n", visible_lines(&d.help)));
    }
    s
}

/// The source text as shown under a diagnostic, and the span moved into it. Text whose
/// characters all show as themselves, on lines of reasonable length, is shown as it is.
/// Otherwise only the span's line is shown (preceded by empty lines, so its number stays),
/// cut to a window around the span when long (`…` marks the cuts), with control characters
/// escaped and invisible ones named; a span running past the window or the line is cut.
fn shown_source(src: &str, span: Range<usize>) -> (String, Range<usize>) {
    let line_start = src[..span.start].rfind('\n').map_or(0, |i| i + 1);
    let line_end = src[span.start..]
        .find('\n')
        .map_or(src.len(), |i| span.start + i);
    let longest = src.split('\n').map(str::len).max().unwrap_or(0);
    if longest <= MAX_SHOWN_LINE && !src.chars().any(|c| c != '\n' && needs_showing(c)) {
        return (src.to_string(), span);
    }
    let (mut lo, mut hi) = (line_start, line_end);
    if line_end - line_start > MAX_SHOWN_LINE {
        lo = span.start.saturating_sub(SHOWN_BEFORE).max(line_start);
        hi = (span.start + SHOWN_FROM).min(line_end);
        while !src.is_char_boundary(lo) {
            lo -= 1;
        }
        while !src.is_char_boundary(hi) {
            hi += 1;
        }
    }
    let end = span.end.clamp(span.start, hi);
    let mut out = "\n".repeat(src[..line_start].matches('\n').count());
    if lo > line_start {
        out.push('…');
    }
    let (mut new_start, mut new_end) = (None, None);
    for (i, c) in src[lo..hi].char_indices() {
        if lo + i == span.start {
            new_start = Some(out.len());
        }
        if lo + i == end {
            new_end = Some(out.len());
        }
        push_shown(&mut out, c, false);
    }
    let at_hi = out.len();
    if hi < line_end {
        out.push('…');
    }
    let new_start = new_start.unwrap_or(at_hi);
    (out, new_start..new_end.unwrap_or(at_hi).max(new_start))
}

/// Renders a parse error of `src`.
pub fn render_parse_error(name: &str, src: &str, e: &ParseError, color: bool) -> String {
    render(name, src, &Diagnostic::from(e), color)
}

/// The candidate closest to `name`: one it starts or ends, else one within a small edit
/// distance (with transpositions; more allowed for longer names); ties go to the first.
pub fn did_you_mean<'a>(name: &str, candidates: impl Iterator<Item = &'a str>) -> Option<String> {
    let name = name.trim();
    if name.is_empty() {
        return None;
    }
    let n = name.chars().count();
    let limit = if n <= 3 { 1 } else { 2 + n / 8 };
    let mut best: Option<(usize, &str)> = None;
    for c in candidates {
        if c.eq_ignore_ascii_case(name) {
            return Some(c.to_string());
        }
        let d = if n >= 3 && (c.starts_with(name) || c.ends_with(name)) {
            1
        } else {
            strsim::damerau_levenshtein(name, c)
        };
        if d <= limit && best.is_none_or(|(bd, _)| d < bd) {
            best = Some((d, c));
        }
    }
    best.map(|(_, c)| c.to_string())
}

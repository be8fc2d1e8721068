//! A class file's cells and the spreadsheet: a text cell a spreadsheet would run as a formula
//! is neutralised when written and read back as typed. A leaf: the reader ([`super::input`])
//! and the writers ([`super::output`]) both use it.

/// What a spreadsheet would run as a formula at the start of a cell.
const FORMULA_START: [char; 6] = ['=', '+', '-', '@', '\t', '\r'];

/// Whether a cell must be neutralised: it starts like a formula, or it is a neutralised cell
/// already (a `'` before such a start), so that reading back strips exactly one `'`.
pub(super) fn needs_quote(s: &str) -> bool {
    s.starts_with(FORMULA_START) || s.strip_prefix('\'').is_some_and(needs_quote)
}

/// A text cell a spreadsheet will show rather than run: a leading `'` before `=`, `+`, `-`,
/// `@`, a tab or a carriage return (`=HYPERLINK(…)` → `'=HYPERLINK(…)`). [`unquote_cell`]
/// gives the text back. The writers append it directly (`output::push_cell`); this is
/// the reference their tests compare with.
#[cfg(test)]
pub(super) fn quote_cell(s: &str) -> std::borrow::Cow<'_, str> {
    if needs_quote(s) {
        std::borrow::Cow::Owned(format!("'{s}"))
    } else {
        std::borrow::Cow::Borrowed(s)
    }
}

/// The text of a cell [`quote_cell`] wrote (the class file's own cells are read through it
/// too, so a results.csv graded again reads `-m g l cos θ` as typed).
pub fn unquote_cell(s: &str) -> &str {
    match s.strip_prefix('\'') {
        Some(rest) if needs_quote(rest) => rest,
        _ => s,
    }
}

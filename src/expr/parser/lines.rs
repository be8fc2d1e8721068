//! Equations on separate lines (a CSV cell holding one equation a line): a line break between
//! two equations separates them as `;` does. Only where nothing else can be meant: the text
//! before the break (since the last `;`, `,` or separating break) has a `=` at the top level,
//! the text after it (to the next one) has its own, and the line does not end in an operator
//! that carries on to the next. Without the separator such an input could only be refused
//! (two `=` in one equation), so no input that read before reads differently now; a line
//! break inside one equation (`m l² θ̈ +` ⏎ `m g l sin θ = 0`) is still whitespace.
//!
//! The break becomes `;` in place (one byte for one byte), so every span still points into
//! the input as typed.

use std::borrow::Cow;

/// `src` with each line break that separates two equations replaced by `;`.
pub(super) fn separate_lines(src: &str) -> Cow<'_, str> {
    if !src.contains('\n') {
        return Cow::Borrowed(src);
    }
    // Top-level separators (`;`, `,`, line breaks) and whether each segment between them has
    // a top-level `=`.
    let mut depth = 0usize;
    let mut breaks: Vec<(usize, char)> = Vec::new();
    let mut has_eq = vec![false];
    for (i, c) in src.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth = depth.saturating_sub(1),
            ';' | ',' | '\n' if depth == 0 => {
                breaks.push((i, c));
                has_eq.push(false);
            }
            '=' if depth == 0 => {
                if let Some(last) = has_eq.last_mut() {
                    *last = true;
                }
            }
            _ => {}
        }
    }
    let mut out = src.as_bytes().to_vec();
    let mut changed = false;
    // Whether the statement running up to the current break has a `=`.
    let mut statement_eq = false;
    let mut start = 0;
    for (k, &(i, c)) in breaks.iter().enumerate() {
        statement_eq |= has_eq[k];
        let carries_on = src[start..i]
            .trim_end()
            .ends_with(['+', '-', '*', '/', '^', '=', '−', '·', '×']);
        if c == '\n' && statement_eq && has_eq[k + 1] && !carries_on {
            out[i] = b';';
            changed = true;
        }
        if c != '\n' || out[i] == b';' {
            statement_eq = false;
        }
        start = i + 1;
    }
    if !changed {
        return Cow::Borrowed(src);
    }
    // Only an ASCII byte was replaced by another at a char boundary: still UTF-8.
    Cow::Owned(String::from_utf8(out).unwrap_or_else(|_| src.to_string()))
}

#[cfg(test)]
mod tests {
    use super::separate_lines;

    #[test]
    fn a_break_between_two_equations_separates_them() {
        assert_eq!(separate_lines("a = b\nc = d"), "a = b;c = d");
        assert_eq!(separate_lines("a = b\r\nc = d"), "a = b\r;c = d");
        assert_eq!(
            separate_lines("x = 1, y = 0\nx = 2, y = 3"),
            "x = 1, y = 0;x = 2, y = 3"
        );
        // A statement continued over a line, then the next equation.
        assert_eq!(separate_lines("a = b\n+ c\nd = e"), "a = b\n+ c;d = e");
    }

    #[test]
    fn a_break_inside_one_equation_is_whitespace() {
        for s in [
            "m*l^2*theta'' +\nm*g*l*sin(theta) = 0",
            "m*l^2*theta''\n+ m*g*l*sin(theta) = 0",
            "a = b +\nc = d",
            "f(a\n= b)",
            "a\nb",
            "a = b; c = d\n",
        ] {
            assert_eq!(separate_lines(s), s, "{s:?}");
        }
    }
}

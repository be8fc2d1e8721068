//! Wrapping the REPL's text at the terminal's width, by words: a line longer than the width
//! breaks at spaces (never inside a word), continued at the margin (prose) or under its own
//! indentation plus two columns (an indented line). Colour codes and combining accents (θ̇) take no column.

/// `text` wrapped at `width` columns (lines already short enough are kept as they are).
pub fn wrap(text: &str, width: usize) -> String {
    let width = width.max(20);
    let mut out = String::with_capacity(text.len() + 16);
    for (i, line) in text.split('\n').enumerate() {
        if i > 0 {
            out.push('\n');
        }
        wrap_line(line, width, &mut out);
    }
    out
}

/// `text` with the line breaks inside each paragraph made spaces (paragraphs are separated
/// by blank lines), ready to be wrapped at another width.
pub fn reflow(text: &str) -> String {
    text.split("\n\n")
        .map(|p| p.split('\n').map(str::trim).collect::<Vec<_>>().join(" "))
        .collect::<Vec<_>>()
        .join("\n\n")
}

/// One line wrapped into `out`.
fn wrap_line(line: &str, width: usize, out: &mut String) {
    if columns(line) <= width {
        out.push_str(line);
        return;
    }
    let indent = line.len() - line.trim_start().len();
    let lead = &line[..indent];
    // Prose (no indentation) goes on at the margin; an indented line under itself + 2.
    let more = if indent == 0 {
        String::new()
    } else {
        format!("{lead}  ")
    };
    let mut used = 0;
    let mut first = true;
    for word in line.trim_start().split(' ').filter(|w| !w.is_empty()) {
        let w = columns(word);
        if first {
            out.push_str(lead);
            out.push_str(word);
            used = indent + w;
            first = false;
        } else if used + 1 + w > width {
            out.push('\n');
            out.push_str(&more);
            out.push_str(word);
            used = more.len() + w;
        } else {
            out.push(' ');
            out.push_str(word);
            used += 1 + w;
        }
    }
}

/// The columns `s` takes on a terminal: escape sequences and combining marks take none.
pub fn columns(s: &str) -> usize {
    let mut n = 0;
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        if c == '\x1b' {
            // CSI … final byte (a letter).
            for d in chars.by_ref() {
                if d.is_ascii_alphabetic() {
                    break;
                }
            }
        } else if !('\u{300}'..='\u{36f}').contains(&c) {
            n += 1;
        }
    }
    n
}

/// `s` without its escape sequences (colour codes).
#[cfg(test)]
pub fn strip(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    let mut chars = s.chars();
    while let Some(c) = chars.next() {
        if c == '\x1b' {
            for d in chars.by_ref() {
                if d.is_ascii_alphabetic() {
                    break;
                }
            }
        } else {
            out.push(c);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wraps_by_words_under_the_indent() {
        let t = "  the frequencies of the small oscillations about the stable equilibrium";
        let w = wrap(t, 30);
        assert!(w.lines().all(|l| columns(l) <= 30), "{w}");
        assert!(w.contains("frequencies"), "{w}");
        assert!(w.lines().skip(1).all(|l| l.starts_with("    ")), "{w}");
        assert_eq!(wrap("short", 80), "short");
    }

    #[test]
    fn paragraphs_are_reflowed() {
        assert_eq!(reflow("a b\nc\n\nd\n e"), "a b c\n\nd e");
    }

    #[test]
    fn colour_and_accents_take_no_column() {
        assert_eq!(columns("\x1b[1mθ̇\x1b[0m"), 1);
    }
}

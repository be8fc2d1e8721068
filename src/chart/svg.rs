//! A figure as one self-contained SVG document: presentation attributes only (no `style`
//! attribute or element, so a strict Content-Security-Policy shows it), no script, no external
//! reference, every text XML-escaped, one element per line, coordinates to a tenth of a pixel
//! written from integers (the same bytes on every machine).

use std::borrow::Cow;

use super::Figure;
use super::layout::{Anchor, LABEL_SIZE, Mark, Rgb, TICK_SIZE};

impl Figure {
    /// The figure as an SVG document (`<svg class="chart" …>…</svg>`, ending in a newline):
    /// its title, then its [`marks`](Figure::marks); curves are `<path class="curve">`, axis
    /// labels `<text class="label">`.
    pub fn to_svg(&self) -> String {
        let (w, h) = self.size();
        let (w, h) = (w.to_string(), h.to_string());
        let mut out = String::new();
        for part in [
            "<svg xmlns=\"http://www.w3.org/2000/svg\" class=\"chart\" role=\"img\" width=\"",
            &w,
            "\" height=\"",
            &h,
            "\" viewBox=\"0 0 ",
            &w,
            " ",
            &h,
            "\" font-family=\"sans-serif\" font-size=\"",
            &px(TICK_SIZE),
            "\" fill=\"#333333\">\n<title>",
            &escape(&self.title),
            "</title>\n<rect width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n",
        ] {
            out.push_str(part);
        }
        for mark in self.marks() {
            element(&mark, &mut out);
            out.push('\n');
        }
        out.push_str("</svg>\n");
        out
    }
}

/// One mark as one SVG element.
fn element(mark: &Mark, out: &mut String) {
    match mark {
        Mark::Rect {
            x,
            y,
            width,
            height,
            stroke,
            fill,
        } => {
            let fill = fill.map_or_else(|| "none".to_string(), hex);
            let attrs = [
                ("x", px(*x)),
                ("y", px(*y)),
                ("width", px(*width)),
                ("height", px(*height)),
                ("fill", fill),
                ("stroke", hex(*stroke)),
            ];
            tag("rect", &attrs, out);
        }
        Mark::Line {
            from,
            to,
            stroke,
            width,
        } => {
            let attrs = [
                ("x1", px(from.0)),
                ("y1", px(from.1)),
                ("x2", px(to.0)),
                ("y2", px(to.1)),
                ("stroke", hex(*stroke)),
                ("stroke-width", px(*width)),
            ];
            tag("line", &attrs, out);
        }
        Mark::Curve {
            pieces,
            stroke,
            width,
        } => {
            let mut d = String::new();
            for piece in pieces {
                for (i, p) in piece.iter().enumerate() {
                    d.push(if i == 0 { 'M' } else { 'L' });
                    d.push_str(&px(p.0));
                    d.push(',');
                    d.push_str(&px(p.1));
                }
            }
            let attrs = [
                ("class", "curve".to_string()),
                ("d", d),
                ("fill", "none".to_string()),
                ("stroke", hex(*stroke)),
                ("stroke-width", px(*width)),
                ("stroke-linejoin", "round".to_string()),
            ];
            tag("path", &attrs, out);
        }
        Mark::Text {
            at,
            text,
            anchor,
            vertical,
            label,
        } => {
            let (x, y) = (px(at.0), px(at.1));
            let anchor = match anchor {
                Anchor::Start => "start",
                Anchor::Middle => "middle",
                Anchor::End => "end",
            };
            let mut attrs = vec![
                ("x", x.clone()),
                ("y", y.clone()),
                ("text-anchor", anchor.to_string()),
            ];
            if *label {
                attrs.push(("class", "label".to_string()));
                attrs.push(("font-size", px(LABEL_SIZE)));
                attrs.push(("fill", "#111111".to_string()));
            }
            if *vertical {
                attrs.push(("transform", ["rotate(-90 ", &x, " ", &y, ")"].concat()));
            }
            out.push_str("<text");
            attributes(&attrs, out);
            out.push('>');
            out.push_str(&escape(text));
            out.push_str("</text>");
        }
    }
}

/// An empty element with its attributes.
fn tag(name: &str, attrs: &[(&str, String)], out: &mut String) {
    out.push('<');
    out.push_str(name);
    attributes(attrs, out);
    out.push_str("/>");
}

/// ` name="value"` for each attribute, the value escaped.
fn attributes(attrs: &[(&str, String)], out: &mut String) {
    for (name, value) in attrs {
        out.push(' ');
        out.push_str(name);
        out.push_str("=\"");
        out.push_str(&escape(value));
        out.push('"');
    }
}

/// `#rrggbb`.
fn hex(c: Rgb) -> String {
    const DIGITS: &[u8; 16] = b"0123456789abcdef";
    let mut s = String::from("#");
    for b in [c.0, c.1, c.2] {
        s.push(char::from(DIGITS[usize::from(b >> 4)]));
        s.push(char::from(DIGITS[usize::from(b & 15)]));
    }
    s
}

/// A pixel coordinate to a tenth (`12.3`, `-0.5`, `7`), written from the rounded integer
/// number of tenths, so −0 never appears and no float formatting is involved.
fn px(v: f64) -> String {
    let tenths = (v * 10.0).round() as i64;
    let (whole, frac) = (tenths / 10, (tenths % 10).unsigned_abs());
    let sign = if tenths < 0 && whole == 0 { "-" } else { "" };
    if frac == 0 {
        [sign, &whole.to_string()].concat()
    } else {
        [sign, &whole.to_string(), ".", &frac.to_string()].concat()
    }
}

/// `text` safe inside an XML element or a double-quoted attribute: `&`, `<`, `>`, `"` and `'`
/// become entities, and characters XML 1.0 does not allow (control characters but tab and
/// newline, U+FFFE, U+FFFF, a lone surrogate cannot occur in a `str`) become U+FFFD.
pub fn escape(text: &str) -> Cow<'_, str> {
    let plain = |c: char| !matches!(c, '&' | '<' | '>' | '"' | '\'') && allowed(c);
    if text.chars().all(plain) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            c if allowed(c) => out.push(c),
            _ => out.push('\u{FFFD}'),
        }
    }
    Cow::Owned(out)
}

/// Whether XML 1.0 allows the character in a document.
fn allowed(c: char) -> bool {
    matches!(c, '\t' | '\n' | '\r' | ' '..='\u{D7FF}' | '\u{E000}'..='\u{FFFD}' | '\u{10000}'..)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markup_and_forbidden_characters_are_escaped() {
        let table: &[(&str, &str)] = &[
            ("θ₁ / rad", "θ₁ / rad"),
            ("a<b", "a&lt;b"),
            ("x & y", "x &amp; y"),
            ("</text><script>", "&lt;/text&gt;&lt;script&gt;"),
            ("\"q\"", "&quot;q&quot;"),
            ("it's", "it&apos;s"),
            ("bell\u{7}", "bell\u{FFFD}"),
            ("nul\0", "nul\u{FFFD}"),
            ("\u{FFFF}", "\u{FFFD}"),
            ("tab\tok", "tab\tok"),
            ("", ""),
        ];
        for &(raw, want) in table {
            assert_eq!(escape(raw), want, "{raw:?}");
        }
        assert!(matches!(escape("θ̇₁"), Cow::Borrowed(_)));
    }

    #[test]
    fn pixels_are_written_to_a_tenth_without_negative_zero() {
        let table: &[(f64, &str)] = &[
            (12.34, "12.3"),
            (12.36, "12.4"),
            (7.0, "7"),
            (-0.04, "0"),
            (-0.5, "-0.5"),
            (-12.25, "-12.3"),
            (0.0, "0"),
        ];
        for &(v, want) in table {
            assert_eq!(px(v), want, "{v}");
        }
        assert_eq!(hex(Rgb(0x1f, 0x5f, 0xa8)), "#1f5fa8");
    }
}

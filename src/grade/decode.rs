//! A class file's bytes as spreadsheets export them, made ready for the CSV reader: the
//! encoding (UTF-8 with or without a byte-order mark, UTF-16 with one; anything else refused
//! at its first bad line), the delimiter (`,`, or `;` as much of Europe writes it, chosen from
//! the header), the real line of every byte (LF, CRLF and CR-only endings), and quoted fields
//! that never close or run on too long (refused with the line they start on).

use std::borrow::Cow;

/// The most line breaks one quoted field may hold: more is an unbalanced quote swallowing
/// the rest of the file, not an answer.
pub const MAX_FIELD_LINES: usize = 100;
/// The most bytes one quoted field may hold.
pub const MAX_FIELD_BYTES: usize = 1024 * 1024;

/// A class file ready for the CSV reader.
pub struct Decoded<'a> {
    /// UTF-8 text, without a byte-order mark.
    pub text: Cow<'a, [u8]>,
    /// The field delimiter.
    pub delimiter: u8,
    /// The byte offset where each line starts (line 1 at offset 0).
    line_starts: Vec<usize>,
    /// Offsets where a record starts (a line begins outside any quoted field), about
    /// [`CUT_BYTES`] apart: the file can be read in pieces from there, in parallel.
    pub cuts: Vec<usize>,
}

/// The size of the pieces a class file is read in.
pub const CUT_BYTES: usize = 1 << 20;

impl Decoded<'_> {
    /// The 1-based line of a byte offset.
    pub fn line(&self, offset: usize) -> u64 {
        self.line_starts.partition_point(|&s| s <= offset) as u64
    }

    /// The line a record starting at `offset` is on: the CSV reader may place a record's start
    /// on the line break before it (the `\n` of a CRLF), so line breaks are skipped first.
    pub fn record_line(&self, offset: usize) -> u64 {
        let skip = self.text[offset.min(self.text.len())..]
            .iter()
            .take_while(|&&b| b == b'\r' || b == b'\n')
            .count();
        self.line(offset + skip)
    }
}

/// Decodes a class file, or says in one line why it cannot be read.
pub fn decode(bytes: &[u8]) -> Result<Decoded<'_>, String> {
    let text: Cow<[u8]> = if let Some(rest) = bytes.strip_prefix(b"\xef\xbb\xbf") {
        Cow::Borrowed(rest)
    } else if let Some(rest) = bytes.strip_prefix(b"\xff\xfe") {
        Cow::Owned(utf16(rest, u16::from_le_bytes)?.into_bytes())
    } else if let Some(rest) = bytes.strip_prefix(b"\xfe\xff") {
        Cow::Owned(utf16(rest, u16::from_be_bytes)?.into_bytes())
    } else {
        Cow::Borrowed(bytes)
    };
    let line_starts = line_starts(&text);
    if let Err(e) = std::str::from_utf8(&text) {
        let at = e.valid_up_to();
        let line = line_starts.partition_point(|&s| s <= at);
        return Err(format!(
            "line {line} is not UTF-8 (byte 0x{:02X}): the file is in a legacy 8-bit encoding; \
             save it as \"CSV UTF-8\" (Excel: File → Save As → CSV UTF-8) and grade it again",
            text[at]
        ));
    }
    let delimiter = delimiter(&text);
    let mut decoded = Decoded {
        text,
        delimiter,
        line_starts,
        cuts: Vec::new(),
    };
    decoded.cuts = check_quotes(&decoded)?;
    Ok(decoded)
}

/// UTF-16 code units (after the byte-order mark) as a string.
fn utf16(bytes: &[u8], unit: fn([u8; 2]) -> u16) -> Result<String, String> {
    if !bytes.len().is_multiple_of(2) {
        return Err("the file is UTF-16 with an odd number of bytes; save it as CSV UTF-8".into());
    }
    let units = bytes.chunks_exact(2).map(|c| unit([c[0], c[1]]));
    char::decode_utf16(units)
        .collect::<Result<String, _>>()
        .map_err(|_| "the file is not valid UTF-16; save it as CSV UTF-8".to_string())
}

/// Where each line starts: after every LF, every CRLF and every lone CR.
fn line_starts(text: &[u8]) -> Vec<usize> {
    let mut starts = vec![0];
    let mut i = 0;
    while i < text.len() {
        match text[i] {
            b'\n' => starts.push(i + 1),
            b'\r' if text.get(i + 1) == Some(&b'\n') => {
                starts.push(i + 2);
                i += 1;
            }
            b'\r' => starts.push(i + 1),
            _ => {}
        }
        i += 1;
    }
    starts
}

/// `;` when the header (outside quotes) has more semicolons than commas, else `,`.
fn delimiter(text: &[u8]) -> u8 {
    let (mut commas, mut semicolons, mut quoted) = (0, 0, false);
    for &b in text {
        match b {
            b'"' => quoted = !quoted,
            b'\n' | b'\r' if !quoted => break,
            b',' if !quoted => commas += 1,
            b';' if !quoted => semicolons += 1,
            _ => {}
        }
    }
    if semicolons > commas { b';' } else { b',' }
}

/// Refuses a quoted field that never closes or holds more than [`MAX_FIELD_LINES`] line
/// breaks or [`MAX_FIELD_BYTES`] bytes, naming the line it starts on. A quote opens a field
/// only at its start (elsewhere it is an ordinary character, as the CSV reader takes it).
/// Returns the record starts found on the way, about [`CUT_BYTES`] apart.
fn check_quotes(d: &Decoded) -> Result<Vec<usize>, String> {
    let text = &d.text;
    let mut at_start = true;
    let mut cuts = Vec::new();
    let mut next_cut = CUT_BYTES;
    let mut i = 0;
    while i < text.len() {
        let b = text[i];
        if b == b'"' && at_start {
            let open = i;
            let mut breaks = 0;
            i += 1;
            loop {
                match text.get(i) {
                    None => {
                        return Err(format!(
                            "line {}: a quoted field opened here is never closed (an unbalanced \
                             `\"`); nothing was graded",
                            d.line(open)
                        ));
                    }
                    Some(b'"') if text.get(i + 1) == Some(&b'"') => i += 2,
                    Some(b'"') => break,
                    Some(&c) => {
                        if c == b'\n' || (c == b'\r' && text.get(i + 1) != Some(&b'\n')) {
                            breaks += 1;
                        }
                        i += 1;
                    }
                }
                if breaks > MAX_FIELD_LINES || i - open > MAX_FIELD_BYTES {
                    return Err(format!(
                        "line {}: a quoted field opened here runs over {} lines or {} bytes \
                         (an unbalanced `\"`?); nothing was graded",
                        d.line(open),
                        MAX_FIELD_LINES,
                        MAX_FIELD_BYTES
                    ));
                }
            }
            at_start = false;
        } else {
            at_start = b == d.delimiter || b == b'\n' || b == b'\r';
            // A line break outside quotes (the `\n` of a CRLF) ends a record.
            let ends_line = b == b'\n' || (b == b'\r' && text.get(i + 1) != Some(&b'\n'));
            if ends_line && i + 1 >= next_cut {
                cuts.push(i + 1);
                next_cut = i + 1 + CUT_BYTES;
            }
        }
        i += 1;
    }
    Ok(cuts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_count_lf_crlf_and_lone_cr() {
        let d = decode(b"a\r\nb\rc\nd").unwrap_or_else(|e| panic!("{e}"));
        assert_eq!([0, 3, 5, 7].map(|o| d.line(o)), [1, 2, 3, 4]);
    }

    #[test]
    fn utf16_with_a_byte_order_mark_is_decoded() {
        let mut bytes = vec![0xff, 0xfe];
        for u in "student;é".encode_utf16() {
            bytes.extend(u.to_le_bytes());
        }
        let d = decode(&bytes).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(&*d.text, "student;é".as_bytes());
        assert_eq!(d.delimiter, b';');
    }

    #[test]
    fn an_unclosed_quote_names_its_line() {
        let e = decode(b"a,b\r\nx,\"y\r\nz,w\r\n").err().unwrap_or_default();
        assert!(e.starts_with("line 2:"), "{e}");
    }
}

//! A class file's bytes as spreadsheets export them, made ready for the CSV reader: the
//! encoding (UTF-8 with or without a byte-order mark, UTF-16 with one; anything else refused
//! at its first bad line), the delimiter (`,`, or `;` as much of Europe writes it, chosen from
//! the header), the real line of every byte (LF, CRLF and CR-only endings), and quoted fields
//! that never close or run on too long (refused with the line they start on).

use std::borrow::Cow;

use rayon::prelude::*;

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
    /// Offsets where a record starts (a line begins outside any quoted field), about
    /// [`CUT_BYTES`] apart, each with its line: the file can be read in pieces from there, in
    /// parallel.
    pub cuts: Vec<(usize, u64)>,
}

/// The size of the pieces a class file is read in.
pub const CUT_BYTES: usize = 1 << 20;

impl Decoded<'_> {
    /// The 1-based line of a byte offset (counted from the start: for messages).
    pub fn line(&self, offset: usize) -> u64 {
        1 + breaks(&self.text, 0, offset.min(self.text.len()))
    }
}

/// The line breaks in `text[a..b]`: each LF, and each CR not followed by an LF (a CRLF
/// counts once, at its LF): the lines start after them.
pub fn breaks(text: &[u8], a: usize, b: usize) -> u64 {
    let s = &text[a..b];
    // One branch-free pass (vectorised) for the LFs, and whether there is any CR at all.
    let (lf, any_cr) = s.iter().fold((0usize, false), |(n, cr), &c| {
        (n + usize::from(c == b'\n'), cr | (c == b'\r'))
    });
    let cr = if any_cr {
        (a..b)
            .filter(|&j| text[j] == b'\r' && text.get(j + 1) != Some(&b'\n'))
            .count()
    } else {
        0
    };
    (lf + cr) as u64
}

/// The lines of records read in order through one piece of a file: each record's line from
/// the previous one's, counting only the bytes between them.
pub struct Lines<'t> {
    text: &'t [u8],
    start: (usize, u64),
    at: (usize, u64),
}

impl<'t> Lines<'t> {
    /// Lines from offset `start`, which is on line `line`.
    pub fn new(text: &'t [u8], (start, line): (usize, u64)) -> Self {
        Lines {
            text,
            start: (start, line),
            at: (start, line),
        }
    }

    /// The line a record starting at `offset` is on: the CSV reader may place a record's
    /// start on the line break before it (the `\n` of a CRLF), so line breaks are skipped
    /// first.
    pub fn record(&mut self, offset: usize) -> u64 {
        let offset = offset.min(self.text.len());
        let skip = self.text[offset..]
            .iter()
            .take_while(|&&b| b == b'\r' || b == b'\n')
            .count();
        let to = offset + skip;
        if to < self.at.0 {
            // Records come in order; should one not, count again from the piece's start.
            self.at = self.start;
        }
        let (from, line) = self.at;
        let line = line + breaks(self.text, from, to);
        self.at = (to, line);
        line
    }
}

/// Decodes a class file, or says in one line why it cannot be read; the quote check cuts it
/// in pieces of about `cut` bytes ([`CUT_BYTES`]; small in tests, to cut often).
pub fn decode_cut(bytes: &[u8], cut: usize) -> Result<Decoded<'_>, String> {
    let text: Cow<[u8]> = if let Some(rest) = bytes.strip_prefix(b"\xef\xbb\xbf") {
        Cow::Borrowed(rest)
    } else if let Some(rest) = bytes.strip_prefix(b"\xff\xfe") {
        Cow::Owned(utf16(rest, u16::from_le_bytes)?.into_bytes())
    } else if let Some(rest) = bytes.strip_prefix(b"\xfe\xff") {
        Cow::Owned(utf16(rest, u16::from_be_bytes)?.into_bytes())
    } else {
        Cow::Borrowed(bytes)
    };
    if let Err(e) = std::str::from_utf8(&text) {
        let at = e.valid_up_to();
        let line = 1 + breaks(&text, 0, at);
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
        cuts: Vec::new(),
    };
    decoded.cuts = check_quotes(&decoded, cut.max(1))?;
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

/// Where the quote check is at a byte: outside any quoted field (`at_start`: a field may open
/// here), or inside one opened at `open` that has held `breaks` line breaks so far.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Quote {
    Outside { at_start: bool },
    Inside { open: usize, breaks: usize },
}

/// Refuses a quoted field that never closes or holds more than [`MAX_FIELD_LINES`] line
/// breaks or [`MAX_FIELD_BYTES`] bytes, naming the line it starts on. A quote opens a field
/// only at its start (elsewhere it is an ordinary character, as the CSV reader takes it).
/// Returns the record starts found on the way, about `cut` bytes apart, with their lines.
///
/// The file is checked in pieces of about `cut` bytes that start after a line break, in
/// parallel, each as if it started a record; joined in order, a piece whose start is in fact
/// inside a quoted field (rare: a field over two lines across the cut) is checked again from
/// the state the piece before it ended in. So the result is one pass's, error included.
fn check_quotes(d: &Decoded, cut: usize) -> Result<Vec<(usize, u64)>, String> {
    let text = &d.text;
    let mut starts = vec![0];
    let mut at = cut;
    while at < text.len() {
        let Some(k) = text[at..].iter().position(|&c| c == b'\n' || c == b'\r') else {
            break;
        };
        let mut next = at + k + 1;
        if text[at + k] == b'\r' && text.get(next) == Some(&b'\n') {
            next += 1;
        }
        if next >= text.len() {
            break;
        }
        starts.push(next);
        at = next + cut;
    }
    starts.push(text.len());
    let fresh = Quote::Outside { at_start: true };
    let scans: Vec<(Scanned, u64)> = starts
        .par_windows(2)
        .map(|w| (scan(d, fresh, w[0], w[1]), breaks(text, w[0], w[1])))
        .collect();
    let mut cuts = Vec::with_capacity(scans.len());
    let (mut state, mut pos, mut line) = (fresh, 0, 1);
    for (w, (scanned, lines)) in starts.windows(2).zip(scans) {
        let (start, end) = (w[0], w[1]);
        let result = if state == fresh && pos == start {
            cuts.push((start, line));
            scanned
        } else {
            scan(d, state, pos.max(start), end)
        };
        (state, pos) = result?;
        line += lines;
    }
    if let Quote::Inside { open, .. } = state {
        return Err(unclosed(d, open));
    }
    Ok(cuts)
}

/// The message for a quoted field opened at `open` that never closes.
fn unclosed(d: &Decoded, open: usize) -> String {
    format!(
        "line {}: a quoted field opened here is never closed (an unbalanced `\"`); nothing was \
         graded",
        d.line(open)
    )
}

/// What [`scan`] gives.
type Scanned = Result<(Quote, usize), String>;

/// The quote check of `text[from..to]` from `state`: the state after it and the offset it
/// stopped at (past `to` when a doubled quote straddles it), or the error.
fn scan(d: &Decoded, mut state: Quote, from: usize, to: usize) -> Scanned {
    let text = &d.text;
    let mut i = from;
    while i < to {
        match state {
            Quote::Inside { open, mut breaks } => {
                match text.get(i) {
                    None => return Err(unclosed(d, open)),
                    Some(b'"') if text.get(i + 1) == Some(&b'"') => i += 2,
                    Some(b'"') => {
                        // The closing quote: a field may not open right after it.
                        state = Quote::Outside { at_start: false };
                        i += 1;
                        continue;
                    }
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
                state = Quote::Inside { open, breaks };
            }
            Quote::Outside { at_start } => {
                let b = text[i];
                state = if b == b'"' && at_start {
                    Quote::Inside { open: i, breaks: 0 }
                } else {
                    Quote::Outside {
                        at_start: b == d.delimiter || b == b'\n' || b == b'\r',
                    }
                };
                i += 1;
            }
        }
    }
    Ok((state, i))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_count_lf_crlf_and_lone_cr() {
        let d = decode_cut(b"a\r\nb\rc\nd", CUT_BYTES).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!([0, 3, 5, 7].map(|o| d.line(o)), [1, 2, 3, 4]);
    }

    #[test]
    fn utf16_with_a_byte_order_mark_is_decoded() {
        let mut bytes = vec![0xff, 0xfe];
        for u in "student;é".encode_utf16() {
            bytes.extend(u.to_le_bytes());
        }
        let d = decode_cut(&bytes, CUT_BYTES).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(&*d.text, "student;é".as_bytes());
        assert_eq!(d.delimiter, b';');
    }

    /// The quote check as one serial pass (what the pieces checked in parallel must give).
    fn one_pass(text: &[u8]) -> Result<(), String> {
        let d = Decoded {
            text: Cow::Borrowed(text),
            delimiter: delimiter(text),
            cuts: Vec::new(),
        };
        match scan(&d, Quote::Outside { at_start: true }, 0, text.len())? {
            (Quote::Inside { open, .. }, _) => Err(unclosed(&d, open)),
            _ => Ok(()),
        }
    }

    /// Files of quoted fields over several lines, doubled quotes, unclosed and overlong
    /// fields, cut every few bytes: the pieces checked apart give one pass's verdict and
    /// message, and every cut is a record start with its own line.
    #[test]
    fn quotes_checked_in_pieces_are_checked_as_in_one_pass() {
        let bits: [&[u8]; 12] = [
            b"a,b\n",
            b"\"x\ny\",z\r\n",
            b"\"\"\"q\"\"\",\"\"\n",
            b"p\"q,r\r",
            b"\"",
            b"\n",
            b"\r\n",
            b",\"",
            b"\"\"",
            b"s,\"t\r\nu\nv\rw\"\n",
            b"x",
            b";",
        ];
        let mut seed = 7u64;
        for _ in 0..3000 {
            let mut text = Vec::new();
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            let n = (seed >> 59) as usize + 1;
            for k in 0..n {
                let r = (seed >> (k * 4 % 56)) as usize;
                text.extend_from_slice(bits[r % bits.len()]);
            }
            let want = one_pass(&text);
            for cut in [1, 2, 3, 5, 8, 13] {
                let got = decode_cut(&text, cut);
                assert_eq!(
                    got.as_ref().err(),
                    want.as_ref().err(),
                    "{:?} cut {cut}",
                    String::from_utf8_lossy(&text)
                );
                if let Ok(d) = got {
                    for &(at, line) in &d.cuts {
                        assert_eq!(line, d.line(at));
                    }
                }
            }
        }
        // A field over more lines than allowed, found across many pieces.
        let long = format!("a,\"{}\"\n", "x\n".repeat(MAX_FIELD_LINES + 1));
        let e = decode_cut(format!("h,i\n{long}").as_bytes(), 3)
            .err()
            .unwrap_or_default();
        assert!(
            e.starts_with("line 2: a quoted field opened here runs over"),
            "{e}"
        );
    }

    #[test]
    fn an_unclosed_quote_names_its_line() {
        let e = decode_cut(b"a,b\r\nx,\"y\r\nz,w\r\n", CUT_BYTES)
            .err()
            .unwrap_or_default();
        assert!(e.starts_with("line 2:"), "{e}");
    }
}

//! Where the representatives' words live — each one's reading and first message — until the
//! outputs are written: in memory (messages interned), or, for a class of many different
//! answers, in a nameless temporary file, so that a class of a million all-different answers
//! does not hold a million readings and messages (about 130 bytes each) at once (issue 20
//! §5). Both give back the same words, so no output depends on where they were kept.
//!
//! The file is made with `O_TMPFILE` where the system has it (`tempfile::tempfile_in`): it has
//! no name, so it replaces nothing, nobody else can open it, and the system removes it when
//! the run ends, however it ends.

use std::borrow::Cow;
use std::fs::File;
use std::io::Write as _;
use std::path::Path;
use std::sync::Mutex;

use super::super::intern::Interner;
use super::Words;

/// How many bytes of words are gathered before they are written to the file.
const PENDING: usize = 1 << 20;

/// The bytes of a record before its words: the reading's length and the grouping key.
const HEAD: usize = 4 + 16;

/// The representatives' words.
pub(in crate::grade) enum Store {
    /// Kept in memory: the readings one after the other, and the messages interned.
    Memory {
        /// Every reading, one after the other.
        readings: String,
        /// Where each representative's reading is in `readings`: (start, end).
        spans: Vec<(u32, u32)>,
        /// The first messages, each kept once.
        messages: Interner,
        /// The grouping keys, halves apart (a `u128` would be aligned to 16 bytes).
        fingerprints: Vec<[u64; 2]>,
    },
    /// Written to a nameless temporary file.
    Disk(Disk),
}

/// Words in a temporary file: for each representative, its reading's length (4 bytes, little
/// endian), its grouping key (16 bytes, little endian), its reading and its message, one
/// record after the other (a record ends where the next starts); the last records still in
/// memory until a whole buffer is gathered.
pub(in crate::grade) struct Disk {
    file: File,
    /// Records not yet written (they start at `written` in the file).
    pending: Vec<u8>,
    /// How many bytes are in the file.
    written: u64,
    /// Where each record starts: 8 bytes a representative.
    records: Vec<u64>,
    /// Why the file could not be written or read back, once it could not (the run then
    /// fails: [`Store::lost`]); nothing read after that is trusted.
    failed: Mutex<Option<String>>,
}

impl Store {
    /// Words kept in memory, with room for `reps` representatives and `text` bytes of
    /// readings and as many of messages (reserved, not touched: only what is written takes
    /// memory).
    pub(in crate::grade) fn memory(reps: usize, text: usize) -> Store {
        Store::Memory {
            readings: String::with_capacity(text),
            spans: Vec::with_capacity(reps),
            messages: Interner::with_capacity(reps, text),
            fingerprints: Vec::with_capacity(reps),
        }
    }

    /// Words kept in a nameless temporary file in `dir` (else in the system's temporary
    /// folder), or in memory when no such file can be made.
    pub(in crate::grade) fn disk(dir: &Path, reps: usize) -> Store {
        let file = tempfile::tempfile_in(dir).or_else(|_| tempfile::tempfile());
        match file {
            Ok(file) => Store::Disk(Disk {
                file,
                pending: Vec::with_capacity(PENDING + 4096),
                written: 0,
                records: Vec::with_capacity(reps),
                failed: Mutex::new(None),
            }),
            Err(_) => Store::memory(reps, 0),
        }
    }

    /// Adds the next representative's words; the number its message goes by
    /// ([`Store::message`]).
    pub(in crate::grade) fn push(&mut self, words: &Words) -> u32 {
        let (reading, message) = (words.reading.as_str(), words.message.as_str());
        match self {
            Store::Memory {
                readings,
                spans,
                messages,
                fingerprints,
            } => {
                let start = readings.len();
                // Offsets are 32-bit: past 4 GB of readings (never, for a 512 MB file) none
                // is kept.
                let span = match u32::try_from(start + reading.len()) {
                    Ok(end) => {
                        readings.push_str(reading);
                        (start as u32, end)
                    }
                    Err(_) => (0, 0),
                };
                spans.push(span);
                let f = words.fingerprint;
                fingerprints.push([(f >> 64) as u64, f as u64]);
                messages.intern(message)
            }
            Store::Disk(d) => d.push(reading, message, words.fingerprint),
        }
    }

    /// Representative `rep`'s grouping key, if the checker gave one.
    pub(in crate::grade) fn fingerprint(&self, rep: usize) -> Option<u128> {
        let f = match self {
            Store::Memory { fingerprints, .. } => {
                let [a, b] = fingerprints.get(rep).copied().unwrap_or_default();
                (u128::from(a) << 64) | u128::from(b)
            }
            Store::Disk(d) => d.fingerprint(rep),
        };
        (f != 0).then_some(f)
    }

    /// How representative `rep`'s answer was read (empty when it could not be).
    pub(in crate::grade) fn reading(&self, rep: usize) -> Cow<'_, str> {
        match self {
            Store::Memory {
                readings, spans, ..
            } => Cow::Borrowed(
                spans
                    .get(rep)
                    .map_or("", |&(a, b)| &readings[a as usize..b as usize]),
            ),
            Store::Disk(d) => d.read(rep, true),
        }
    }

    /// Message number `m` (as [`Store::push`] gave it).
    pub(in crate::grade) fn message(&self, m: u32) -> Cow<'_, str> {
        match self {
            Store::Memory { messages, .. } => Cow::Borrowed(messages.get(m)),
            Store::Disk(d) => d.read(m as usize, false),
        }
    }

    /// Why words were lost (the temporary file could not be written or read back), if they
    /// were: outputs made since are not to be trusted.
    pub(in crate::grade) fn lost(&self) -> Option<String> {
        match self {
            Store::Memory { .. } => None,
            Store::Disk(d) => d.failed.lock().unwrap_or_else(|e| e.into_inner()).clone(),
        }
    }
}

impl Disk {
    /// Adds a record; its number (a representative's own).
    fn push(&mut self, reading: &str, message: &str, fingerprint: u128) -> u32 {
        let n = self.records.len() as u32;
        self.records.push(self.written + self.pending.len() as u64);
        let Ok(a) = u32::try_from(reading.len()) else {
            self.fail("a reading over 4 GB".to_string());
            self.pending.extend_from_slice(&[0; HEAD]);
            return n;
        };
        self.pending.extend_from_slice(&a.to_le_bytes());
        self.pending.extend_from_slice(&fingerprint.to_le_bytes());
        self.pending.extend_from_slice(reading.as_bytes());
        self.pending.extend_from_slice(message.as_bytes());
        if self.pending.len() >= PENDING {
            self.write_pending();
        }
        n
    }

    /// Writes the gathered records to the file (whole records: a record is either all in the
    /// file or all in `pending`).
    fn write_pending(&mut self) {
        match self.file.write_all(&self.pending) {
            Ok(()) => {
                self.written += self.pending.len() as u64;
                self.pending.clear();
            }
            Err(e) => {
                self.fail(format!("cannot write grading's temporary file: {e}"));
                // Kept in memory from here on rather than lost.
                let mut rest = std::mem::take(&mut self.pending);
                rest.reserve(PENDING);
                self.pending = rest;
            }
        }
    }

    /// Remembers the first reason words were lost.
    fn fail(&self, why: String) {
        let mut failed = self.failed.lock().unwrap_or_else(|e| e.into_inner());
        failed.get_or_insert(why);
    }

    /// `len` bytes of the records at `at`: borrowed while still waiting in memory, else read
    /// from the file; or why they could not be had.
    fn bytes(&self, at: u64, len: usize) -> Result<Cow<'_, [u8]>, String> {
        if let Some(i) = at.checked_sub(self.written) {
            let i = i as usize;
            return (self.pending.get(i..i + len).map(Cow::Borrowed))
                .ok_or_else(|| "a record past the end".to_string());
        }
        let mut bytes = vec![0; len];
        read_at(&self.file, &mut bytes, at).map_err(|e| e.to_string())?;
        Ok(Cow::Owned(bytes))
    }

    /// Record `r`'s reading (`reading`) or message.
    fn read(&self, r: usize, reading: bool) -> Cow<'_, str> {
        let Some(&start) = self.records.get(r) else {
            return Cow::Borrowed("");
        };
        let end =
            (self.records.get(r + 1).copied()).unwrap_or(self.written + self.pending.len() as u64);
        match self.bytes(start, (end - start) as usize) {
            Ok(Cow::Borrowed(record)) => match part(record, reading) {
                Some(s) => Cow::Borrowed(s),
                None => self.lost("a record not whole"),
            },
            Ok(Cow::Owned(record)) => match part(&record, reading) {
                Some(s) => Cow::Owned(s.to_string()),
                None => self.lost("a record not whole"),
            },
            Err(why) => self.lost(&why),
        }
    }

    /// Record `r`'s grouping key (0: none, or lost).
    fn fingerprint(&self, r: usize) -> u128 {
        let Some(&start) = self.records.get(r) else {
            return 0;
        };
        let head = match self.bytes(start, HEAD) {
            Ok(head) => head,
            Err(why) => {
                self.lost(&why);
                return 0;
            }
        };
        let mut key = [0; 16];
        key.copy_from_slice(&head[4..HEAD]);
        u128::from_le_bytes(key)
    }

    /// An empty text, the reason remembered.
    fn lost(&self, why: &str) -> Cow<'_, str> {
        self.fail(format!("cannot read back grading's temporary file: {why}"));
        Cow::Borrowed("")
    }
}

/// A record's reading (`reading`) or message, if the record is whole.
fn part(record: &[u8], reading: bool) -> Option<&str> {
    let (head, words) = record.split_first_chunk::<HEAD>()?;
    let (len, _) = head.split_first_chunk::<4>()?;
    let (a, b) = words.split_at_checked(u32::from_le_bytes(*len) as usize)?;
    std::str::from_utf8(if reading { a } else { b }).ok()
}

/// Reads exactly `buf.len()` bytes at `offset`, without moving a shared position (so that
/// every worker may read at once).
#[cfg(unix)]
fn read_at(file: &File, buf: &mut [u8], offset: u64) -> std::io::Result<()> {
    use std::os::unix::fs::FileExt as _;
    file.read_exact_at(buf, offset)
}

/// Reads exactly `buf.len()` bytes at `offset`.
#[cfg(windows)]
fn read_at(file: &File, mut buf: &mut [u8], mut offset: u64) -> std::io::Result<()> {
    use std::os::windows::fs::FileExt as _;
    while !buf.is_empty() {
        match file.seek_read(buf, offset)? {
            0 => return Err(std::io::ErrorKind::UnexpectedEof.into()),
            n => {
                buf = &mut buf[n..];
                offset += n as u64;
            }
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Both stores give back every reading and message as pushed, also across the buffer's
    /// boundary and for empty words.
    #[test]
    fn a_disk_store_gives_back_what_a_memory_store_does() {
        let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
        let mut memory = Store::memory(0, 0);
        let mut disk = Store::disk(dir.path(), 0);
        assert!(matches!(disk, Store::Disk(_)));
        let words: Vec<(String, String)> = (0..40_000)
            .map(|i| {
                let reading = if i % 7 == 0 {
                    String::new()
                } else {
                    format!("θ'' + {i}·sin θ = 0")
                };
                let message = if i % 5 == 0 {
                    String::new()
                } else {
                    format!("off by a factor of {i}")
                };
                (reading, message)
            })
            .collect();
        let key = |i: usize| (i as u128 % 3) * (u128::MAX / 7 + i as u128);
        let ids: Vec<(u32, u32)> = (words.iter().enumerate())
            .map(|(i, (r, m))| {
                let w = Words {
                    reading: r.clone(),
                    message: m.clone(),
                    fingerprint: key(i),
                };
                (memory.push(&w), disk.push(&w))
            })
            .collect();
        for (rep, ((r, m), (a, b))) in words.iter().zip(&ids).enumerate() {
            assert_eq!(memory.reading(rep), r.as_str());
            assert_eq!(disk.reading(rep), r.as_str());
            assert_eq!(memory.message(*a), m.as_str());
            assert_eq!(disk.message(*b), m.as_str());
            let want = (key(rep) != 0).then_some(key(rep));
            assert_eq!(
                (memory.fingerprint(rep), disk.fingerprint(rep)),
                (want, want)
            );
        }
        assert_eq!((memory.lost(), disk.lost()), (None, None));
        // The folder holds no file of the store's: it has no name.
        let names = std::fs::read_dir(dir.path())
            .map(|d| d.count())
            .unwrap_or(1);
        assert_eq!(names, 0);
    }

    /// A file that cannot be written is reported by `lost`, and what was pushed is still
    /// read back (kept in memory) rather than silently empty.
    #[test]
    fn a_file_that_cannot_be_written_is_reported() {
        let dir = tempfile::tempdir().unwrap_or_else(|e| panic!("{e}"));
        let path = dir.path().join("read-only");
        std::fs::write(&path, b"").unwrap_or_else(|e| panic!("{e}"));
        let file = File::open(&path).unwrap_or_else(|e| panic!("{e}"));
        let mut store = Store::Disk(Disk {
            file,
            pending: Vec::new(),
            written: 0,
            records: Vec::new(),
            failed: Mutex::new(None),
        });
        let big = "x".repeat(PENDING);
        let m = store.push(&Words {
            reading: big.clone(),
            message: "off by a factor of 2".to_string(),
            fingerprint: 7,
        });
        assert!(store.lost().is_some_and(|why| why.contains("cannot write")));
        assert_eq!(store.reading(0), big.as_str());
        assert_eq!(store.message(m), "off by a factor of 2");
        assert_eq!(store.fingerprint(0), Some(7));
    }
}

//! Loading problem files: from text, from a folder, or the embedded bank. A file that
//! cannot be read becomes a finding with its line; the other files load regardless.

use super::FindingCode;
use std::path::Path;

use super::build::build;
use super::finding::{Finding, line_of};
use super::schema::ProblemFile;
use crate::problem::Problem;

/// Largest problem file read, in bytes: 256 KiB, some fifty times the largest problem of the
/// bank. A larger file is refused by name and size before it is read (a 600 kB file once made
/// every command that loads the folder slow), and only commands that need it read it.
pub const MAX_FILE_BYTES: usize = 256 * 1024;
/// Deepest nesting of arrays and tables accepted.
pub const MAX_NESTING: usize = 32;

/// Loaded problems and the files that failed to load.
#[derive(Debug, Default)]
pub struct Bank {
    pub problems: Vec<Problem>,
    pub failures: Vec<Finding>,
}

impl Bank {
    /// The problem with this id.
    pub fn problem(&self, id: &str) -> Option<&Problem> {
        self.problems.iter().find(|p| p.id == id)
    }

    /// Adds a problem loaded from `file`. A problem whose id another file already defines
    /// is refused, and so is the one loaded before it: neither is in the bank (a command
    /// would otherwise reach one file and a grader the other), and the `duplicate-id`
    /// finding names both files.
    pub fn add(&mut self, p: Problem, file: String) {
        let earlier = self.problems.iter().position(|q| q.id == p.id);
        let refused = self
            .failures
            .iter()
            .find(|f| {
                f.code == FindingCode::DuplicateId && f.problem.as_deref() == Some(p.id.as_str())
            })
            .map(|f| f.file.clone());
        let first = match (earlier, refused) {
            (Some(k), _) => self.problems.remove(k).file,
            (None, Some(f)) => f,
            (None, None) => {
                self.problems.push(p);
                return;
            }
        };
        self.failures.push(Finding {
            file: file.clone(),
            problem: Some(p.id.clone()),
            part: None,
            line: 1,
            code: FindingCode::DuplicateId,
            message: duplicate_message(&p.id, &first, &file),
        });
    }
}

/// A built-in problem that a problem of an added folder replaced (same id).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Replaced {
    /// The problem id.
    pub id: String,
    /// The file of the problem that replaces the built-in one.
    pub file: String,
}

impl Replaced {
    /// The note a face shows (on standard error): which file replaces which problem.
    pub fn note(&self) -> String {
        format!(
            "note: {} replaces the built-in problem `{}`",
            self.file,
            crate::expr::error::visible(&self.id)
        )
    }
}

/// The built-in bank `base` with the problems of `added` (a folder the instructor adds,
/// `--add-problems`): a problem whose id is built in replaces the built-in one, listed in the
/// second value so that the face can say so. The folder's failures are kept, so that two of
/// its files sharing an id (`duplicate-id`, naming both) still refuse the bank; the built-in
/// problem of that id is then left out too, so that no command judges by either file.
pub fn merge(base: Bank, added: Bank) -> (Bank, Vec<Replaced>) {
    let mut replaced = Vec::new();
    let clashes = |id: &str| {
        added.problems.iter().any(|p| p.id == id)
            || added
                .failures
                .iter()
                .any(|f| f.code == FindingCode::DuplicateId && f.problem.as_deref() == Some(id))
    };
    let mut problems: Vec<Problem> = Vec::with_capacity(base.problems.len() + added.problems.len());
    for p in base.problems {
        if clashes(&p.id) {
            if let Some(q) = added.problems.iter().find(|q| q.id == p.id) {
                replaced.push(Replaced {
                    id: p.id.clone(),
                    file: q.file.clone(),
                });
            }
            continue;
        }
        problems.push(p);
    }
    problems.extend(added.problems);
    let mut failures = base.failures;
    failures.extend(added.failures);
    (Bank { problems, failures }, replaced)
}

/// Why a problem defined by two files is refused, naming both.
pub fn duplicate_message(id: &str, first: &str, second: &str) -> String {
    format!(
        "the problem `{}` is defined by two files, {first} and {second}: neither is loaded until one of them is renamed or removed (an id names one problem)",
        crate::expr::error::visible(id)
    )
}

/// Why a folder of problem files gives no bank, or no answer about one problem.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum BankError {
    /// The folder cannot be listed.
    UnreadableFolder {
        /// The folder.
        folder: std::path::PathBuf,
        /// The system's reason.
        reason: String,
    },
    /// Two files define the problem asked for.
    DuplicateId {
        /// The problem id.
        id: String,
        /// The file read first.
        first: String,
        /// The other file.
        second: String,
    },
    /// No file defines the problem, and one that might have could not be loaded.
    NotLoaded {
        /// The problem id.
        id: String,
        /// The folder.
        folder: std::path::PathBuf,
        /// Why the first file that might define it failed.
        finding: Box<Finding>,
        /// How many more files failed.
        more: usize,
    },
}

impl std::fmt::Display for BankError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            BankError::UnreadableFolder { folder, reason } => {
                write!(f, "cannot read {}: {reason}", folder.display())
            }
            BankError::DuplicateId { id, first, second } => {
                f.write_str(&duplicate_message(id, first, second))
            }
            BankError::NotLoaded {
                id,
                folder,
                finding,
                more,
            } => {
                write!(
                    f,
                    "no problem `{}` loaded from {}: {}:{}: [{}] {}",
                    crate::expr::error::visible(id),
                    folder.display(),
                    finding.file,
                    finding.line,
                    finding.code,
                    finding.message,
                )?;
                if *more > 0 {
                    write!(
                        f,
                        " (and {more} more files; `lagrange problems verify` lists them)"
                    )?;
                }
                Ok(())
            }
        }
    }
}

impl std::error::Error for BankError {}

/// Loads one problem from TOML text; `file` names it in findings.
pub fn load_str(file: &str, text: &str) -> Result<Problem, Finding> {
    let fail = |line: usize, code: FindingCode, message: String| Finding {
        file: file.to_string(),
        problem: None,
        part: None,
        line,
        code,
        message,
    };
    if text.len() > MAX_FILE_BYTES {
        return Err(fail(
            1,
            FindingCode::TooLarge,
            format!(
                "the file is {} bytes; at most {MAX_FILE_BYTES} are read",
                text.len()
            ),
        ));
    }
    if let Some(at) = too_deep(text) {
        return Err(fail(
            line_of(text, at),
            FindingCode::TooDeep,
            format!("arrays and tables are nested more than {MAX_NESTING} deep"),
        ));
    }
    let pf: ProblemFile = toml::from_str(text).map_err(|e| {
        let line = e.span().map_or(1, |s| line_of(text, s.start));
        let msg = e.message().trim().to_string();
        let code = if msg.contains("unknown field") {
            FindingCode::UnknownKey
        } else if msg.contains("missing field") {
            FindingCode::MissingKey
        } else if msg.contains("invalid type") {
            FindingCode::WrongType
        } else {
            FindingCode::TomlSyntax
        };
        fail(line, code, msg)
    })?;
    build(file, text, pf)
}

/// The byte offset where nesting first exceeds the limit (outside strings and comments).
fn too_deep(text: &str) -> Option<usize> {
    let mut depth = 0usize;
    let mut in_str: Option<u8> = None;
    let mut comment = false;
    let b = text.as_bytes();
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        if comment {
            if c == b'\n' {
                comment = false;
            }
        } else if let Some(q) = in_str {
            if c == b'\\' && q == b'"' {
                i += 1;
            } else if c == q {
                in_str = None;
            }
        } else {
            match c {
                b'"' | b'\'' => in_str = Some(c),
                b'#' => comment = true,
                b'[' | b'{' => {
                    depth += 1;
                    if depth > MAX_NESTING {
                        return Some(i);
                    }
                }
                b']' | b'}' => depth = depth.saturating_sub(1),
                _ => {}
            }
        }
        i += 1;
    }
    None
}

/// Reads one problem file, refusing before reading anything that could hang or exhaust
/// memory: only a regular file (after following symlinks: a FIFO would block forever, a
/// device such as `/dev/zero` never ends) of at most [`MAX_FILE_BYTES`], and even then at
/// most that many bytes are read (the file may grow between the check and the read).
pub fn read_file(path: &Path) -> Result<String, Finding> {
    use std::io::Read;
    let fail = |code: FindingCode, message: String| Finding {
        file: path.display().to_string(),
        problem: None,
        part: None,
        line: 1,
        code,
        message,
    };
    let unreadable = |e: std::io::Error| fail(FindingCode::UnreadableFile, e.to_string());
    let meta = std::fs::metadata(path).map_err(unreadable)?;
    if !meta.is_file() {
        return Err(fail(
            FindingCode::NotAFile,
            format!(
                "this is a {}, not a regular file: a problem file must be a plain TOML file",
                file_kind(&meta)
            ),
        ));
    }
    let too_large = |len: u64| {
        fail(
            FindingCode::TooLarge,
            format!(
                "the file is {len} bytes; at most {MAX_FILE_BYTES} are read: split it, one problem per file"
            ),
        )
    };
    if meta.len() > MAX_FILE_BYTES as u64 {
        return Err(too_large(meta.len()));
    }
    let file = std::fs::File::open(path).map_err(unreadable)?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // One byte past the limit tells a file that grew since `metadata` from one at the limit.
    file.take(MAX_FILE_BYTES as u64 + 1)
        .read_to_end(&mut bytes)
        .map_err(unreadable)?;
    if bytes.len() > MAX_FILE_BYTES {
        return Err(too_large(bytes.len() as u64));
    }
    String::from_utf8(bytes).map_err(|_| {
        fail(
            FindingCode::NotUtf8,
            "the file is not UTF-8 text: save it as UTF-8".into(),
        )
    })
}

/// What kind of file system entry `meta` describes, for a message.
fn file_kind(meta: &std::fs::Metadata) -> &'static str {
    let t = meta.file_type();
    if t.is_dir() {
        return "folder";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() {
            return "named pipe (FIFO)";
        }
        if t.is_char_device() || t.is_block_device() {
            return "device";
        }
        if t.is_socket() {
            return "socket";
        }
    }
    "special file"
}

/// The `*.toml` files in `dir`, sorted by name.
pub(crate) fn toml_files(dir: &Path) -> Result<Vec<std::path::PathBuf>, BankError> {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .map_err(|e| BankError::UnreadableFolder {
            folder: dir.to_path_buf(),
            reason: e.to_string(),
        })?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    entries.sort();
    Ok(entries)
}

/// Loads only the problem `id` from the folder `dir`, so that a command about one problem
/// does not build a whole bank: a file is built only when it mentions the id and its `id`
/// line does not name another problem. Files that fail to load are skipped, as
/// [`load_dir`] would list them as failures. Two files that define the id are an error
/// naming both (the id would mean whichever file a command happened to read). When no file
/// defines it but one that might have could not be read or loaded (too large, not UTF-8, a
/// TOML error in a file that mentions the id), the error names that file and why, rather than
/// "no problem".
pub fn load_one(dir: &Path, id: &str) -> Result<Option<Problem>, BankError> {
    let mut unloaded: Vec<Finding> = Vec::new();
    let mut load = |path: &Path| -> Option<Problem> {
        let text = match read_file(path) {
            Ok(t) => t,
            Err(f) => {
                unloaded.push(f);
                return None;
            }
        };
        // A file that does not mention the id cannot define it (a fast substring search);
        // one whose `id` line names another problem does not either.
        if !text.contains(id) || declared_id(&text).is_some_and(|d| d != id) {
            return None;
        }
        match load_str(&path.display().to_string(), &text) {
            Ok(p) => Some(p).filter(|p| p.id == id),
            Err(f) => {
                unloaded.push(f);
                None
            }
        }
    };
    let mut found: Option<Problem> = None;
    for path in toml_files(dir)? {
        if let Some(p) = load(&path) {
            if let Some(first) = &found {
                return Err(BankError::DuplicateId {
                    id: id.to_string(),
                    first: first.file.clone(),
                    second: p.file.clone(),
                });
            }
            found = Some(p);
        }
    }
    if found.is_none()
        && let Some(f) = unloaded.first()
    {
        return Err(BankError::NotLoaded {
            id: id.to_string(),
            folder: dir.to_path_buf(),
            finding: Box::new(f.clone()),
            more: unloaded.len() - 1,
        });
    }
    Ok(found)
}

/// The id a problem file declares, found without parsing the TOML: a top-level line
/// `id = "…"` (or `'…'`) before the first table, outside multi-line strings. `None` when
/// the file says it some other way (escapes, a quoted key): then it is parsed to find out.
pub(super) fn declared_id(text: &str) -> Option<&str> {
    let mut open: Option<&str> = None;
    for line in text.lines() {
        let t = line.trim();
        if open.is_none() {
            if t.starts_with('[') {
                return None;
            }
            if let Some(v) = t.strip_prefix("id").map(str::trim_start)
                && let Some(v) = v.strip_prefix('=').map(str::trim)
            {
                return quoted(v);
            }
        }
        for delim in ["\"\"\"", "'''"] {
            if open.is_none_or(|d| d == delim) && line.matches(delim).count() % 2 == 1 {
                open = if open.is_some() { None } else { Some(delim) };
            }
        }
    }
    None
}

/// The contents of a simple one-line TOML string (no escapes), allowing a trailing comment.
fn quoted(v: &str) -> Option<&str> {
    let q = v.chars().next().filter(|c| *c == '"' || *c == '\'')?;
    let rest = &v[1..];
    let end = rest.find(q)?;
    let (body, after) = (&rest[..end], rest[end + 1..].trim_start());
    let simple = !body.contains('\\') && (after.is_empty() || after.starts_with('#'));
    simple.then_some(body)
}

/// Loads every `*.toml` file in `dir` (sorted by name).
pub fn load_dir(dir: &Path) -> Result<Bank, BankError> {
    let mut bank = Bank::default();
    for path in toml_files(dir)? {
        let name = path.display().to_string();
        let loaded = read_file(&path).and_then(|text| load_str(&name, &text));
        match loaded {
            Ok(p) => bank.add(p, name),
            Err(f) => bank.failures.push(f),
        }
    }
    Ok(bank)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_declared_id_is_read_from_simple_lines_only() {
        assert_eq!(
            declared_id("id = \"atwood\"\ntitle = \"A\""),
            Some("atwood")
        );
        assert_eq!(declared_id("# c\n  id='a-b'  # note\n"), Some("a-b"));
        // Escapes and quoted keys are left to the TOML parser.
        assert_eq!(declared_id("id = \"a\\u0062\""), None);
        assert_eq!(declared_id("\"id\" = \"a\""), None);
        // Not inside a multi-line string, not after the first table, not `identity`.
        assert_eq!(
            declared_id("s = \"\"\"\nid = \"fake\"\n\"\"\"\nid = \"real\""),
            Some("real")
        );
        assert_eq!(declared_id("[parameters]\nid = \"x\""), None);
        assert_eq!(declared_id("identity = \"x\"\nid = \"y\""), Some("y"));
    }

    #[test]
    fn only_regular_files_are_read() {
        let dir = std::env::temp_dir();
        assert_eq!(read_file(&dir).unwrap_err().code, "not-a-file");
        let missing = dir.join(format!("no-such-{}.toml", std::process::id()));
        assert_eq!(read_file(&missing).unwrap_err().code, "unreadable-file");
    }

    #[test]
    fn one_problem_is_found_by_file_name_or_by_id() {
        let dir = std::env::temp_dir().join(format!("lagrange-load-one-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let atwood = super::super::embedded::FILES
            .iter()
            .find(|(n, _)| *n == "atwood.toml")
            .map(|(_, t)| *t)
            .unwrap();
        std::fs::write(dir.join("other-name.toml"), atwood).unwrap();
        // A file named after the id that defines another id does not hide the real one.
        std::fs::write(
            dir.join("pendulum.toml"),
            atwood.replacen("id = \"atwood\"", "id = \"x\"", 1),
        )
        .unwrap();
        let by_id = load_one(&dir, "atwood");
        let named = load_one(&dir, "x");
        let wrong_name = load_one(&dir, "pendulum");
        let escape = load_one(&dir, "../atwood");
        std::fs::remove_dir_all(&dir).ok();
        assert_eq!(by_id.unwrap().map(|p| p.id), Some("atwood".to_string()));
        assert_eq!(named.unwrap().map(|p| p.id), Some("x".to_string()));
        assert!(wrong_name.unwrap().is_none());
        assert!(escape.unwrap().is_none());
    }
}

//! Writing output files without harming what is already there (DESIGN principle 7), for every
//! face that writes one: `grade`'s results, `simulate`'s CSV grid and pictures, `chaos`'s
//! pictures, the REPL's progress file.
//!
//! - A file is written whole under a unique temporary name created exclusively beside it
//!   (`tempfile`: `O_EXCL`, never following a link), synced, then renamed over its name, so a
//!   reader — or a run killed half-way — never sees half a file.
//! - Only a regular file (or a free name) is ever replaced. A symbolic link at the name is
//!   refused (lagrange never writes through a link it did not make), and so is a folder, a
//!   socket or a block device. A terminal, `/dev/null` or a FIFO the user names is written
//!   by streaming into it, never replaced; `-` is standard output.
//! - While it writes into a folder, lagrange holds a lock on it, so two runs do not interleave
//!   and a temporary file of a run killed before its rename (named `.NAME.XXXXXX.lagrange-tmp`)
//!   is recognised as stale and removed by the next run that writes NAME there.

use std::fs::{File, OpenOptions};
use std::io::Write as _;
use std::path::{Path, PathBuf};

use tempfile::NamedTempFile;

/// The suffix of every temporary file lagrange makes.
const TMP_SUFFIX: &str = ".lagrange-tmp";

/// What is at an output path now.
#[derive(Debug, PartialEq, Eq)]
enum Existing {
    /// Nothing: the name is free.
    Absent,
    /// A regular file: replaced by a rename.
    Regular,
    /// A character device (a terminal, `/dev/null`) or a FIFO: written by streaming into it.
    Stream,
}

/// What is at `path`, without following a link there; an error names what cannot be written.
fn inspect(path: &Path) -> Result<Existing, String> {
    let meta = match std::fs::symlink_metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Existing::Absent),
        Err(e) => return Err(format!("{}: {e}", path.display())),
    };
    let kind = meta.file_type();
    if kind.is_symlink() {
        return Err(format!(
            "{} is a symbolic link; lagrange does not write through a link it did not make \
             (remove it, or name the file it points to)",
            path.display()
        ));
    }
    if kind.is_file() {
        return Ok(Existing::Regular);
    }
    if kind.is_dir() {
        return Err(format!("{} is a folder, not a file", path.display()));
    }
    if streamable(&kind) {
        return Ok(Existing::Stream);
    }
    Err(format!(
        "{} is not a regular file; lagrange only replaces regular files",
        path.display()
    ))
}

/// A character device or a FIFO (Unix); nothing elsewhere.
fn streamable(kind: &std::fs::FileType) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt as _;
        kind.is_char_device() || kind.is_fifo()
    }
    #[cfg(not(unix))]
    {
        let _ = kind;
        false
    }
}

/// Checks that `path` can be an output: a free name or a regular file (with `stream`, also a
/// device or FIFO). The error is one line naming the path.
pub fn check(path: &Path, stream: bool) -> Result<(), String> {
    match inspect(path)? {
        Existing::Absent | Existing::Regular => Ok(()),
        Existing::Stream if stream => Ok(()),
        Existing::Stream => Err(format!(
            "{} is a device or a FIFO, not a file lagrange can replace",
            path.display()
        )),
    }
}

/// Writes a file the user named: `-` is standard output, a device or FIFO is streamed into,
/// a free name or a regular file is written under a temporary name and renamed; a link, a
/// folder or any other kind of file is refused. The error is one line naming the path.
pub fn write_named(path: &Path, bytes: &[u8]) -> Result<(), String> {
    if path == Path::new("-") {
        let mut out = std::io::stdout().lock();
        return out
            .write_all(bytes)
            .and_then(|()| out.flush())
            .map_err(|e| format!("cannot write to standard output: {e}"));
    }
    match inspect(path)? {
        Existing::Stream => stream_into(path, bytes),
        Existing::Absent | Existing::Regular => {
            let (dir, name) = split(path)?;
            let folder = Folder::open(&dir, &[name.as_str()])?;
            let staged = folder.stage(&name, bytes)?;
            commit(vec![staged]).map(|_| ())
        }
    }
}

/// Streams `bytes` into a device or FIFO (opened without creating or truncating anything).
fn stream_into(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let fail = |e: std::io::Error| format!("cannot write {}: {e}", path.display());
    let mut f = OpenOptions::new().write(true).open(path).map_err(fail)?;
    // What was opened, not what the name held a moment ago: never a regular file here.
    let opened = f.metadata().map_err(fail)?;
    if !streamable(&opened.file_type()) {
        return Err(format!("{} changed while being opened", path.display()));
    }
    f.write_all(bytes).and_then(|()| f.flush()).map_err(fail)
}

/// A path's folder (`.` for a bare name) and file name.
fn split(path: &Path) -> Result<(PathBuf, String), String> {
    let name = path
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| format!("{} does not name a file", path.display()))?;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Ok((dir, name.to_string()))
}

/// A folder lagrange writes outputs into, locked while it is open (a link to a folder, named
/// by the user, is followed: only the outputs' own names are never links).
pub struct Folder {
    dir: PathBuf,
    /// The lock on the folder, released when this is dropped (`None` where folders cannot be
    /// opened as files).
    _lock: Option<File>,
}

impl Folder {
    /// Creates `dir` if needed, waits for its lock, and removes the stale temporary files of
    /// `names` (left by a run that was killed: with the lock held, no live run has one).
    pub fn open(dir: &Path, names: &[&str]) -> Result<Folder, String> {
        std::fs::create_dir_all(dir)
            .map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
        let lock = File::open(dir).ok().filter(|f| f.lock().is_ok());
        if lock.is_some() {
            remove_stale(dir, names);
        }
        Ok(Folder {
            dir: dir.to_path_buf(),
            _lock: lock,
        })
    }

    /// The path of output `name` in this folder.
    pub fn path(&self, name: &str) -> PathBuf {
        self.dir.join(name)
    }

    /// Writes `bytes` whole into a new temporary file beside `name`, after checking `name`
    /// holds no link, device or folder. Nothing is replaced until [`commit`].
    pub fn stage(&self, name: &str, bytes: &[u8]) -> Result<Staged, String> {
        self.stage_with(name, &mut |w| w.write_all(bytes))
    }

    /// As [`Folder::stage`], the contents streamed by `write` into the temporary file
    /// (buffered), so a large output is never held whole in memory.
    pub fn stage_with(
        &self,
        name: &str,
        write: &mut dyn FnMut(&mut (dyn std::io::Write + Send)) -> std::io::Result<()>,
    ) -> Result<Staged, String> {
        let path = self.path(name);
        check(&path, false)?;
        let fail = |e: std::io::Error| format!("cannot write {}: {e}", path.display());
        let prefix = format!(".{name}.");
        let mut builder = tempfile::Builder::new();
        builder.prefix(&prefix).suffix(TMP_SUFFIX);
        // The mode a new file gets (0666 less the umask, as `File::create` gives), or the
        // replaced file's own: not tempfile's private 0600.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt as _;
            let mode = std::fs::symlink_metadata(&path)
                .ok()
                .filter(|m| m.is_file())
                .map_or(0o666, |m| m.permissions().mode() & 0o7777);
            builder.permissions(std::fs::Permissions::from_mode(mode));
        }
        let mut tmp = builder.tempfile_in(&self.dir).map_err(fail)?;
        let file = Writeback {
            file: tmp.as_file_mut(),
            written: 0,
            handed: 0,
        };
        let mut out = std::io::BufWriter::with_capacity(1 << 16, file);
        write(&mut out).and_then(|()| out.flush()).map_err(fail)?;
        drop(out);
        tmp.as_file().sync_all().map_err(fail)?;
        Ok(Staged { tmp, path })
    }
}

/// A file being written whose pages are handed to the disk every [`Writeback::EVERY`] bytes
/// (on Linux, `sync_file_range` starts writing them back without waiting), so that the
/// `fsync` ending a large output waits for little: writing to the disk overlaps making the
/// rest (results.csv of a 1M-row class spent about 60 ms in its `fsync`).
struct Writeback<'f> {
    file: &'f mut std::fs::File,
    /// Bytes written so far.
    written: u64,
    /// Bytes handed to the disk so far.
    handed: u64,
}

impl Writeback<'_> {
    const EVERY: u64 = 8 << 20;
}

impl std::io::Write for Writeback<'_> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        let n = self.file.write(buf)?;
        self.written += n as u64;
        if self.written - self.handed >= Self::EVERY {
            #[cfg(all(target_os = "linux", target_env = "gnu"))]
            {
                use std::os::fd::AsRawFd as _;
                let (from, len) = (self.handed as i64, (self.written - self.handed) as i64);
                // SAFETY: the descriptor is the open file's own for the call's duration; the
                // call only starts writeback of that range (a hint: its result is not needed).
                unsafe {
                    libc::sync_file_range(
                        self.file.as_raw_fd(),
                        from,
                        len,
                        libc::SYNC_FILE_RANGE_WRITE,
                    );
                }
            }
            self.handed = self.written;
        }
        Ok(n)
    }

    fn flush(&mut self) -> std::io::Result<()> {
        self.file.flush()
    }
}

/// Removes `dir/.NAME.*.lagrange-tmp` regular files of the given names.
fn remove_stale(dir: &Path, names: &[&str]) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let names: std::collections::HashSet<&str> = names.iter().copied().collect();
    for entry in entries.flatten() {
        let file = entry.file_name();
        let Some(file) = file.to_str() else { continue };
        // `.NAME.XXXXXX.lagrange-tmp`: NAME looked up, not compared with every name (the
        // feedback folder has two names per student).
        let ours = (file.strip_suffix(TMP_SUFFIX))
            .and_then(|f| f.strip_prefix('.'))
            .and_then(|f| f.rsplit_once('.'))
            .is_some_and(|(name, _)| names.contains(name));
        // A regular file only: a link or anything else with that name is left alone.
        if ours && entry.file_type().is_ok_and(|t| t.is_file()) {
            let _ = std::fs::remove_file(entry.path());
        }
    }
}

/// A whole output under its temporary name, waiting for [`commit`]; removed if dropped.
pub struct Staged {
    tmp: NamedTempFile,
    path: PathBuf,
}

/// Renames every staged file over its name, in order (so the last one, when present with the
/// same run id as the others, says the set is whole), re-checking each name just before;
/// the paths written.
pub fn commit(staged: Vec<Staged>) -> Result<Vec<PathBuf>, String> {
    let mut written = Vec::with_capacity(staged.len());
    for s in staged {
        check(&s.path, false)?;
        s.tmp
            .persist(&s.path)
            .map_err(|e| format!("cannot write {}: {}", s.path.display(), e.error))?;
        written.push(s.path);
    }
    Ok(written)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_regular_file_is_replaced_and_no_temporary_file_stays() {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("out.csv");
        std::fs::write(&path, "old").expect("write");
        write_named(&path, b"new").expect("written");
        assert_eq!(std::fs::read(&path).expect("read"), b"new");
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .expect("list")
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert_eq!(names.len(), 1, "{names:?}");
    }

    #[test]
    fn a_stale_temporary_file_of_an_output_is_removed_and_others_are_kept() {
        let dir = tempfile::tempdir().expect("temp dir");
        let stale = dir.path().join(".out.csv.abc123.lagrange-tmp");
        let other = dir.path().join(".notes.abc123.lagrange-tmp");
        std::fs::write(&stale, "half").expect("write");
        std::fs::write(&other, "mine").expect("write");
        write_named(&dir.path().join("out.csv"), b"x").expect("written");
        assert!(!stale.exists());
        assert!(other.exists());
    }

    #[cfg(unix)]
    #[test]
    fn a_link_at_the_name_is_refused_and_its_target_untouched() {
        let dir = tempfile::tempdir().expect("temp dir");
        let target = dir.path().join("precious.txt");
        std::fs::write(&target, "keep").expect("write");
        let link = dir.path().join("out.csv");
        std::os::unix::fs::symlink(&target, &link).expect("symlink");
        let e = write_named(&link, b"x").err().unwrap_or_default();
        assert!(e.contains("symbolic link"), "{e}");
        assert_eq!(std::fs::read(&target).expect("read"), b"keep");
        assert!(std::fs::symlink_metadata(&link).is_ok_and(|m| m.file_type().is_symlink()));
    }

    #[cfg(unix)]
    #[test]
    fn a_new_file_gets_the_usual_mode_and_a_replaced_one_keeps_its_own() {
        use std::os::unix::fs::PermissionsExt as _;
        let dir = tempfile::tempdir().expect("temp dir");
        let (new, old) = (dir.path().join("new.csv"), dir.path().join("old.csv"));
        std::fs::write(&old, "x").expect("write");
        let plain = std::fs::metadata(&old).expect("stat").permissions().mode() & 0o777;
        std::fs::set_permissions(&old, std::fs::Permissions::from_mode(0o640)).expect("chmod");
        write_named(&new, b"y").expect("written");
        write_named(&old, b"z").expect("written");
        let mode = |p: &Path| std::fs::metadata(p).expect("stat").permissions().mode() & 0o777;
        assert_eq!(mode(&new), plain, "as File::create makes it");
        assert_eq!(mode(&old), 0o640);
    }

    #[cfg(unix)]
    #[test]
    fn dev_null_is_streamed_into_not_replaced() {
        let null = Path::new("/dev/null");
        write_named(null, b"discarded").expect("streamed");
        let kind = std::fs::symlink_metadata(null).expect("stat").file_type();
        use std::os::unix::fs::FileTypeExt as _;
        assert!(kind.is_char_device(), "/dev/null is still a device");
        assert!(check(null, false).is_err());
    }
}

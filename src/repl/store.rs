//! Where the REPL keeps the student's progress and line history: `LAGRANGE_HOME` if set,
//! else the platform data directory (`directories::ProjectDirs`). Progress is read at start
//! and saved after every change through [`crate::face::outfile`] (a unique temporary name, then a
//! rename, the folder locked), merged into what is on disk so that two REPLs open at once both
//! keep their progress; a corrupt or unreadable file is moved aside as
//! `progress.json.corrupt-N`, never lost, never a crash; a FIFO, a folder or a link at the
//! name is an error said once, and the session goes on without saving.

use std::path::{Path, PathBuf};

use lagrange::tutor::Progress;

/// The data directory, or `None` when the platform has none.
pub fn data_dir() -> Option<PathBuf> {
    if let Some(home) = std::env::var_os("LAGRANGE_HOME") {
        return Some(PathBuf::from(home));
    }
    directories::ProjectDirs::from("", "", "lagrange").map(|d| d.data_dir().to_path_buf())
}

/// The progress file in `dir`, read or started afresh.
pub struct Store {
    dir: PathBuf,
    path: PathBuf,
    /// The progress as last read or written: what this session has added since is the
    /// difference between the session's progress and this.
    base: Progress,
    /// `false` when the path holds something that is not a file (nothing is ever saved).
    enabled: bool,
}

/// The progress file's name in the data directory.
const NAME: &str = "progress.json";

impl Store {
    /// Opens `dir/progress.json`: its progress (a fresh one if it is absent), and any warning
    /// to print (a corrupt file moved aside; a FIFO, a folder or a link at the name, which is
    /// never read — a FIFO would wait forever — nor written).
    pub fn open(dir: &Path) -> (Store, Progress, Option<String>) {
        let path = dir.join(NAME);
        let mut store = Store {
            dir: dir.to_path_buf(),
            path: path.clone(),
            base: Progress::new(),
            enabled: true,
        };
        if let Err(e) = crate::face::outfile::check(&path, false) {
            store.enabled = false;
            let warning = format!("error: {e}; progress will not be saved this session");
            return (store, Progress::new(), Some(warning));
        }
        let (mut progress, warning) = match read(&path) {
            Ok(p) => (p, None),
            Err(why) => (Progress::new(), Some(move_aside(&path, &why))),
        };
        // A file without a learner seed gets one now; it is written with the first change
        // (in the base too, so that drawing it alone does not count as a change to save).
        if progress.learner_seed.is_none() {
            progress.learner_seed = Some(draw_seed());
        }
        store.base = progress.clone();
        (store, progress, warning)
    }

    /// Saves `progress` if it changed since the last save: with the data directory locked,
    /// the file is read again and what this session added since is merged into it (another
    /// REPL's progress is kept), then written under a unique temporary name and renamed.
    pub fn save(&mut self, progress: &Progress) -> std::io::Result<()> {
        if !self.enabled || *progress == self.base {
            return Ok(());
        }
        let fail = |e: String| std::io::Error::other(e);
        let folder = crate::face::outfile::Folder::open(&self.dir, &[NAME]).map_err(fail)?;
        crate::face::outfile::check(&self.path, false).map_err(fail)?;
        // A file another session made unreadable meanwhile is not merged into (it is kept
        // by `open`'s move-aside on the next start): this session's progress is written.
        let disk = read(&self.path).unwrap_or_else(|_| self.base.clone());
        let merged = Progress::merged(&disk, &self.base, progress);
        let staged = folder
            .stage(NAME, merged.to_json().as_bytes())
            .map_err(fail)?;
        crate::face::outfile::commit(vec![staged]).map_err(fail)?;
        self.base = progress.clone();
        Ok(())
    }
}

/// A learner seed: unpredictable, different for two learners (and for two REPLs started at
/// once). `RandomState` keys its hasher from the operating system's randomness; the time and
/// the process id are mixed in as well.
fn draw_seed() -> u64 {
    use std::hash::{BuildHasher, Hasher};
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    let now = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos())
        .unwrap_or(0);
    h.write_u128(now);
    h.write_u32(std::process::id());
    h.finish()
}

/// The progress in `path` (absent: a fresh one), or why it cannot be read.
fn read(path: &Path) -> Result<Progress, String> {
    match std::fs::read(path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(Progress::new()),
        Err(e) => Err(e.to_string()),
        Ok(bytes) => match std::str::from_utf8(&bytes).map(Progress::from_json) {
            Ok(Ok(p)) => Ok(p),
            Ok(Err(e)) => Err(e.to_string()),
            Err(e) => Err(e.to_string()),
        },
    }
}

/// Moves a bad progress file to the first free `progress.json.corrupt-N`; the warning.
fn move_aside(path: &Path, why: &str) -> String {
    let name = path.display();
    for n in 1..1000 {
        let aside = PathBuf::from(format!("{}.corrupt-{n}", path.display()));
        if aside.exists() {
            continue;
        }
        return match std::fs::rename(path, &aside) {
            Ok(()) => format!(
                "warning: could not read {name} ({why}); moved it to {} and started afresh",
                aside.display()
            ),
            Err(e) => format!(
                "warning: could not read {name} ({why}) nor move it aside ({e}); starting afresh"
            ),
        };
    }
    format!("warning: could not read {name} ({why}); starting afresh")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_learner_seed_is_drawn_once_and_kept_with_the_progress() {
        let dir = tempfile::tempdir().expect("temp dir");
        let (mut a, mut pa, _) = Store::open(dir.path());
        let seed = pa.learner_seed.expect("drawn at open");
        // Drawing it is not a change: nothing is written until the learner does something.
        a.save(&pa).expect("nothing to save");
        assert!(!dir.path().join(NAME).exists());
        // Two learners (two fresh files) draw different seeds.
        let other = tempfile::tempdir().expect("temp dir");
        let (_, po, _) = Store::open(other.path());
        assert_ne!(po.learner_seed, Some(seed));
        pa.record_attempt("simple-pendulum", "kinetic", "x", true);
        a.save(&pa).expect("a saves");
        let (_, again, _) = Store::open(dir.path());
        assert_eq!(again.learner_seed, Some(seed), "kept in the file");
    }

    #[test]
    fn two_sessions_saving_in_turn_both_keep_their_progress() {
        let dir = tempfile::tempdir().expect("temp dir");
        let (mut a, mut pa, _) = Store::open(dir.path());
        let (mut b, mut pb, _) = Store::open(dir.path());
        pa.record_attempt("simple-pendulum", "kinetic", "x", true);
        a.save(&pa).expect("a saves");
        pb.record_attempt("simple-pendulum", "eom", "y", false);
        pb.record_attempt("simple-pendulum", "kinetic", "z", false);
        b.save(&pb).expect("b saves");
        let (_, p, warning) = Store::open(dir.path());
        assert!(warning.is_none());
        assert!(
            p.is_solved("simple-pendulum", "kinetic"),
            "a's progress kept"
        );
        let kinetic = p
            .part("simple-pendulum", "kinetic")
            .cloned()
            .unwrap_or_default();
        assert_eq!((kinetic.attempts, kinetic.answers.len()), (2, 2));
        assert_eq!(
            p.part("simple-pendulum", "eom").map(|x| x.attempts),
            Some(1)
        );
        let names: Vec<_> = std::fs::read_dir(dir.path())
            .expect("list")
            .flatten()
            .collect();
        assert_eq!(names.len(), 1, "no temporary file left: {names:?}");
    }

    #[test]
    fn a_folder_at_the_progress_path_is_an_error_and_never_saved_into() {
        let dir = tempfile::tempdir().expect("temp dir");
        std::fs::create_dir(dir.path().join("progress.json")).expect("mkdir");
        let (mut s, mut p, warning) = Store::open(dir.path());
        assert!(warning.is_some_and(|w| w.contains("is a folder")));
        p.record_attempt("simple-pendulum", "kinetic", "x", true);
        assert!(s.save(&p).is_ok());
        assert!(dir.path().join("progress.json").is_dir());
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_at_the_progress_path_is_an_error_not_a_hang() {
        let dir = tempfile::tempdir().expect("temp dir");
        let fifo = dir.path().join("progress.json");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if !made.is_ok_and(|s| s.success()) {
            return;
        }
        let (_, _, warning) = Store::open(dir.path());
        assert!(warning.is_some_and(|w| w.contains("FIFO") || w.contains("not a regular")));
    }

    #[test]
    fn corrupt_file_is_moved_aside() {
        let dir = tempfile::tempdir().unwrap();
        let dir = dir.path();
        std::fs::write(dir.join("progress.json"), "{not json").ok();
        let (_, p, warning) = Store::open(dir);
        assert!(warning.is_some_and(|w| w.contains("corrupt-1")));
        assert!(dir.join("progress.json.corrupt-1").exists());
        // Started afresh: no record, only the learner seed drawn for the new file.
        assert!(p.problems.is_empty() && p.learner_seed.is_some());
    }
}

//! Where the REPL keeps the student's progress and line history: `LAGRANGE_HOME` if set,
//! else the platform data directory (`directories::ProjectDirs`). Progress is read at start
//! and written after every change (to a temporary name, then renamed); a corrupt or
//! unreadable file is moved aside as `progress.json.corrupt-N`, never lost, never a crash.

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
    path: PathBuf,
    last: String,
}

impl Store {
    /// Opens `dir/progress.json`: its progress (a fresh one if it is absent), and any warning
    /// to print (a corrupt file moved aside).
    pub fn open(dir: &Path) -> (Store, Progress, Option<String>) {
        let path = dir.join("progress.json");
        let (progress, warning) = match std::fs::read(&path) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => (Progress::new(), None),
            Ok(bytes) => match std::str::from_utf8(&bytes).map(Progress::from_json) {
                Ok(Ok(p)) => (p, None),
                Ok(Err(e)) => (Progress::new(), Some(move_aside(&path, &e.to_string()))),
                Err(e) => (Progress::new(), Some(move_aside(&path, &e.to_string()))),
            },
            Err(e) => (Progress::new(), Some(move_aside(&path, &e.to_string()))),
        };
        let last = progress.to_json();
        (Store { path, last }, progress, warning)
    }

    /// Writes `progress` if it changed since the last write.
    pub fn save(&mut self, progress: &Progress) -> std::io::Result<()> {
        let json = progress.to_json();
        if json == self.last {
            return Ok(());
        }
        if let Some(dir) = self.path.parent() {
            std::fs::create_dir_all(dir)?;
        }
        let tmp = self.path.with_extension("json.tmp");
        std::fs::write(&tmp, &json)?;
        std::fs::rename(&tmp, &self.path)?;
        self.last = json;
        Ok(())
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
    fn corrupt_file_is_moved_aside() {
        let dir = std::env::temp_dir().join(format!("lagrange-store-{}", std::process::id()));
        std::fs::remove_dir_all(&dir).ok();
        std::fs::create_dir_all(&dir).ok();
        std::fs::write(dir.join("progress.json"), "{not json").ok();
        let (_, p, warning) = Store::open(&dir);
        assert!(warning.is_some_and(|w| w.contains("corrupt-1")));
        assert!(dir.join("progress.json.corrupt-1").exists());
        assert_eq!(p.to_json(), Progress::new().to_json());
        std::fs::remove_dir_all(&dir).ok();
    }
}

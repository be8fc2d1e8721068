//! What the faces of the binary share, and the only module they share: writing output files
//! ([`outfile`]), the progress bar ([`bar`]), pictures and terminal charts ([`plot`]), colour on
//! a terminal and printing a command's output ([`Terminal`], [`emit`]), and loading the bank
//! ([`load_bank`]). The faces (`cli`, `repl`, `grade`) use this module and the library, never
//! each other; this module uses the library only (the layering test in `src/layers.rs` checks
//! both).

pub mod bar;
pub mod outfile;
pub mod plot;
mod terminal;

pub use terminal::{Terminal, emit};

use std::path::{Path, PathBuf};

use lagrange::bank::load::{Replaced, load_one, merge};
use lagrange::bank::{Bank, FindingCode, Problem, embedded, load_dir};

/// The bank from `dir`, or the embedded one, refused whole when two files define one
/// problem id (a grade and a check would otherwise judge by different files).
pub fn load_bank(dir: Option<&Path>) -> Result<Bank, String> {
    let bank = load_bank_with_findings(dir)?;
    match bank
        .failures
        .iter()
        .find(|f| f.code == FindingCode::DuplicateId)
    {
        Some(f) => Err(f.message.clone()),
        None => Ok(bank),
    }
}

/// The bank from `dir`, or the embedded one, with every file that failed to load (a
/// duplicate id among them) as a finding: what `problems verify` reports.
pub fn load_bank_with_findings(dir: Option<&Path>) -> Result<Bank, String> {
    match (dir, ADDED.get()) {
        (Some(d), _) => load_dir(d).map_err(|e| e.to_string()),
        (None, Some(added)) => {
            let (bank, replaced) = merge(
                embedded::bank(),
                load_dir(added).map_err(|e| e.to_string())?,
            );
            for r in &replaced {
                eprintln!("{}", r.note());
            }
            Ok(bank)
        }
        (None, None) => Ok(embedded::bank()),
    }
}

/// The folder `--add-problems` adds to the built-in bank, set once from the command line.
/// Every face reaches the bank through [`load_bank`] and [`find_problem`] (the commands, the
/// grader, the REPL), so the folder is kept here rather than threaded through each command's
/// arguments beside `--problems`.
static ADDED: std::sync::OnceLock<PathBuf> = std::sync::OnceLock::new();

/// Records the `--add-problems` folder (the first call wins; `main` makes the only one).
pub fn set_added(dir: PathBuf) {
    let _ = ADDED.set(dir);
}

/// The one problem a command is about, from `dir` or the embedded bank (with the
/// `--add-problems` folder first), building only that problem (a folder of 30,000 files is
/// not loaded whole to check one answer).
pub fn find_problem(dir: Option<&Path>, id: &str) -> Result<Option<Problem>, String> {
    match (dir, ADDED.get()) {
        (Some(d), _) => load_one(d, id).map_err(|e| e.to_string()),
        (None, Some(added)) => match load_one(added, id).map_err(|e| e.to_string())? {
            Some(p) => {
                if embedded::is_built_in(id) {
                    let note = Replaced {
                        id: id.to_string(),
                        file: p.file.clone(),
                    };
                    eprintln!("{}", note.note());
                }
                Ok(Some(p))
            }
            None => Ok(embedded::problem(id)),
        },
        (None, None) => Ok(embedded::problem(id)),
    }
}

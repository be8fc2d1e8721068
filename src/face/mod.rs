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

use std::path::Path;

use lagrange::bank::{Bank, FindingCode, embedded, load_dir};

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
    match dir {
        Some(d) => load_dir(d).map_err(|e| e.to_string()),
        None => Ok(embedded::bank()),
    }
}

//! The built-in problems as files an instructor starts from (`lagrange problems export DIR`):
//! each file as the bank has it, under a first line that says where it came from and carries a
//! fingerprint of the rest, so that a later export can tell a file it wrote and nobody edited
//! (safe to replace) from the instructor's own work (kept unless `--force`). No I/O here: the
//! face reads what is at each name and writes the files.

use super::embedded::FILES;

/// The start of the first line of every exported file.
pub const HEADER_START: &str = "# Exported from lagrange's built-in bank";

/// One file to export: its name (`atwood.toml`) and its whole text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Exported {
    pub name: &'static str,
    pub text: String,
}

/// Every built-in problem as an exported file, in the bank's order.
pub fn exported() -> Vec<Exported> {
    FILES
        .iter()
        .map(|(name, body)| Exported {
            name,
            text: with_header(body),
        })
        .collect()
}

/// `body` under the header line naming its fingerprint.
fn with_header(body: &str) -> String {
    format!(
        "{HEADER_START} (lagrange {}, fingerprint {:016x}): edit freely; an edited file is never replaced without --force.\n{body}",
        env!("CARGO_PKG_VERSION"),
        fingerprint(body)
    )
}

/// What an existing file at an exported name is, for the decision to replace it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Existing {
    /// Exactly what would be written: nothing to do.
    Same,
    /// A file lagrange exported (any version) and nobody edited since: safe to replace.
    Unedited,
    /// Anything else — the instructor's work, or an export edited since: kept unless forced.
    Other,
}

/// Classifies the text already at an exported file's name against what would be written.
pub fn classify(existing: &str, new: &Exported) -> Existing {
    if existing == new.text {
        return Existing::Same;
    }
    let Some((first, body)) = existing.split_once('\n') else {
        return Existing::Other;
    };
    let stated = first
        .strip_prefix(HEADER_START)
        .and_then(|rest| rest.split_once("fingerprint "))
        .and_then(|(_, f)| f.get(..16))
        .and_then(|hex| u64::from_str_radix(hex, 16).ok());
    match stated {
        Some(f) if f == fingerprint(body) => Existing::Unedited,
        _ => Existing::Other,
    }
}

/// FNV-1a, 64 bits: stable across platforms and versions (unlike std's hasher), and enough to
/// notice an edit (this guards against accidents, not against an adversary).
fn fingerprint(text: &str) -> u64 {
    text.bytes().fold(0xcbf2_9ce4_8422_2325, |h, b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_export_is_told_from_an_edited_one_and_from_the_instructors_own() {
        let files = exported();
        assert_eq!(files.len(), FILES.len());
        let atwood = files.iter().find(|f| f.name == "atwood.toml").unwrap();
        assert_eq!(classify(&atwood.text, atwood), Existing::Same);
        // An export of another version of the file, unedited since.
        let older = with_header("id = \"atwood\"\ntitle = \"Atwood, as it once was\"\n");
        assert_eq!(classify(&older, atwood), Existing::Unedited);
        let edited = older.replace("once was", "I wrote it");
        assert_eq!(classify(&edited, atwood), Existing::Other);
        assert_eq!(classify("id = \"mine\"\n", atwood), Existing::Other);
        assert_eq!(classify("", atwood), Existing::Other);
    }

    #[test]
    fn every_exported_file_loads_as_the_built_in_problem() {
        for f in exported() {
            let p = super::super::load::load_str(f.name, &f.text).expect("loads");
            assert_eq!(Some(p.id.as_str()), f.name.strip_suffix(".toml"));
        }
    }
}

//! Target `toml`: problem files mutated from `problems/*.toml` and `tests/broken/*.toml`
//! (byte flips, line deletions and duplications, values swapped for huge numbers, NaN, deep
//! nesting, odd ids) into `load_str`, then verification as `problems verify` shows it.
//!
//! Some mutations are constructed to be refused (section 4 of issue 9: an absurd tolerance, a
//! reference multiplied by a vanishing factor, a parameter named `pi`, …). Such a file
//! starts with the comment line `# fuzz-expect: refused (why)`, and the oracle is that it
//! does not load or its verification has a finding.

use lagrange::bank::{Bank, load_str};
use lagrange::report::{Plain, verification};

use super::inputs::{self, Rng, below, chance, pick};

/// The first line of a file that must be refused.
const REFUSED: &str = "# fuzz-expect: refused";

thread_local! {
    /// The seed files: the bank and the broken examples, read once per thread.
    static SEEDS: &'static [String] = Box::leak(read_seeds().into_boxed_slice());
}

/// Every seed file's text.
fn read_seeds() -> Vec<String> {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut out = Vec::new();
    for dir in ["problems", "tests/broken"] {
        let Ok(entries) = std::fs::read_dir(root.join(dir)) else {
            continue;
        };
        let mut paths: Vec<_> = entries.filter_map(|e| Some(e.ok()?.path())).collect();
        // Sorted, so that a seed means the same file on every machine.
        paths.sort();
        for p in paths {
            if let Ok(text) = std::fs::read_to_string(&p) {
                out.push(text);
            }
        }
    }
    out
}

/// Values that replace a `key = value` line's value.
const VALUES: &[&str] = &[
    "1e300",
    "-1e308",
    "nan",
    "inf",
    "-inf",
    "-1",
    "0",
    "1.0",
    "\"\"",
    "\"\u{202e}x\"",
    "\"a\\nb\"",
    "[1.0, 2.0, 3.0]",
    "[-1e308, 1e308]",
    "[]",
    "[\"theta = 0\"]",
    "{}",
    "\"x''''\"",
    "\"1/0\"",
    "\"0*log(-1)\"",
    "true",
    "18446744073709551616",
    "\"pi\"",
];

/// One input: a mutated seed (85%) or a constructed file to refuse (15%).
pub fn generate(r: &mut Rng) -> Vec<u8> {
    let seeds = SEEDS.with(|s| *s);
    let base = pick(r, seeds).clone();
    if chance(r, 0.15)
        && let Some((text, why)) = refused(r, &base)
    {
        return format!("{REFUSED} ({why})\n{text}").into_bytes();
    }
    let mut lines: Vec<String> = base.lines().map(String::from).collect();
    for _ in 0..1 + below(r, 3) {
        mutate_lines(r, &mut lines);
    }
    let text = lines.join("\n");
    if chance(r, 0.3) {
        inputs::mutate(r, text.as_bytes())
    } else {
        text.into_bytes()
    }
}

/// One line-level mutation.
fn mutate_lines(r: &mut Rng, lines: &mut Vec<String>) {
    if lines.is_empty() {
        return;
    }
    let i = below(r, lines.len());
    match below(r, 6) {
        0 => {
            lines.remove(i);
        }
        1 => {
            let l = lines[i].clone();
            lines.insert(i, l);
        }
        2 => {
            let j = below(r, lines.len());
            lines.swap(i, j);
        }
        3 | 4 => {
            if let Some((key, _)) = lines[i].split_once(" = ") {
                lines[i] = format!("{key} = {}", pick(r, VALUES));
            }
        }
        _ => {
            let depth = 20 + below(r, 30);
            let nested = format!("{}1{}", "[".repeat(depth), "]".repeat(depth));
            if let Some((key, _)) = lines[i].split_once(" = ") {
                lines[i] = format!("{key} = {nested}");
            }
        }
    }
}

/// A file constructed to be refused, with why, if the seed allows the construction.
fn refused(r: &mut Rng, base: &str) -> Option<(String, String)> {
    if !base.contains("[[parts]]") || !base.contains("[parameters]") {
        return None;
    }
    // Into the first part's table.
    let after_kind =
        |text: &str, extra: &str| text.replacen("[[parts]]\n", &format!("[[parts]]\n{extra}\n"), 1);
    Some(match below(r, 8) {
        0 => {
            let t = pick(r, &["1e300", "1.0", "nan", "-1e-9"]);
            (
                after_kind(base, &format!("tolerance = {t}")),
                format!("tolerance: {t}"),
            )
        }
        1 => {
            let t = pick(r, &["nan", "-1"]);
            (
                after_kind(base, &format!("points = {t}")),
                format!("points: {t}"),
            )
        }
        2 => {
            let name = pick(r, &["pi", "t", "sin"]);
            let line = format!("{name} = {{ dimension = \"1\", range = [1.0, 2.0] }}");
            (
                base.replacen("[parameters]", &format!("[parameters]\n{line}"), 1),
                format!("reserved-name: a parameter named {name}"),
            )
        }
        3 => {
            let id = pick(r, &["\"\"", "\"a\\u202eb\"", "\"a\\nb\""]);
            let at = base.find("\nid = ")?;
            let end = at + 1 + base[at + 1..].find('\n')?;
            (
                format!("{}\nid = {id}{}", &base[..at], &base[end..]),
                format!("id: part id {id}"),
            )
        }
        4 => vanishing_reference(r, base)?,
        5 if !base.contains("answer = [\"theta = 0\", \"theta = pi\"]\nstability") => return None,
        5 => (
            base.replace(
                "answer = [\"theta = 0\", \"theta = pi\"]\nstability = [\"stable\", \"unstable\"]",
                "answer = [\"theta = 0\", \"theta = pi\", \"theta = -pi\"]\n\
                 stability = [\"stable\", \"unstable\", \"unstable\"]",
            ),
            "same-point: θ = π and θ = −π listed apart".into(),
        ),
        6 => {
            let at = base.find("range = [")?;
            let end = at + base[at..].find(']')?;
            (
                format!("{}range = [0.5, 1.0, 2.0{}", &base[..at], &base[end..]),
                "range: three numbers".into(),
            )
        }
        _ if base.contains("constraints") => return None,
        _ => (
            after_kind(base, "multiplier = 1"),
            "multiplier: no constraint".into(),
        ),
    })
}

/// The first equation of motion's reference multiplied by a velocity (the energy law) or by
/// the coordinate — not by a coordinate the equation divides by (`k/r^2`): where it vanishes
/// the equation is not finite, so the product still determines the accelerations wherever
/// the physics does (principle 6), and verification rightly accepts it.
fn vanishing_reference(r: &mut Rng, base: &str) -> Option<(String, String)> {
    let part = base.find("kind = \"equation\"")?;
    let at = part + base[part..].find("\nanswer = \"")? + "\nanswer = \"".len();
    let end = at + base[at..].find('"')?;
    let (lhs, rhs) = super::text::split_eq(&base[at..end]);
    if !lhs.contains("''") && !rhs.contains("''") {
        return None;
    }
    let coord = base.split("name = \"").nth(1)?.split('"').next()?;
    let singular = lhs.contains(&format!("/{coord}")) || rhs.contains(&format!("/{coord}"));
    let f = if singular {
        format!("{coord}'")
    } else {
        pick(r, &[format!("{coord}'"), coord.to_string()]).clone()
    };
    let eq = format!("({lhs})*{f} = ({rhs})*{f}");
    Some((
        format!("{}{eq}{}", &base[..at], &base[end..]),
        format!("vanishing-reference: times {f}"),
    ))
}

/// Loads and verifies one file; a file marked refused must not load cleanly and pass.
pub fn execute(input: &[u8]) -> Result<(), String> {
    let text = String::from_utf8_lossy(input);
    let mut bank = Bank::default();
    match load_str("fuzz.toml", &text) {
        Ok(p) => bank.problems.push(p),
        Err(f) => bank.failures.push(f),
    }
    let v = verification(&bank);
    let shown = v.render(&Plain);
    super::no_raw_controls(&shown, "verification")?;
    if text.starts_with(REFUSED) && v.failing() == 0 {
        let why = text.lines().next().unwrap_or_default();
        let family = why.split('(').nth(1).and_then(|w| w.split(':').next());
        return Err(format!(
            "false-accept[{}]: a file to refuse verifies: {why}",
            family.unwrap_or_default()
        ));
    }
    Ok(())
}

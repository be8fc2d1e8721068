//! Stability stated in an equilibrium answer — `r = 0 (unstable)`, `θ = 0 stable, θ = π
//! unstable`, `0 (stable), π (unstable)` — read off the text, and judged where the part has
//! stability data: a wrong one makes the answer incorrect (`wrong-stability`, naming the
//! point). A word that looks like a misspelt stability is a syntax error with a suggestion.
//!
//! Where the part gives no stability, the engine decides (the linearised equations at the
//! point, at a few sample parameter values); when it cannot, or its answers differ between
//! the samples, nothing is said.
//!
//! The words are blanked out (replaced by spaces, so byte offsets stay valid for error
//! carets) and remembered with their position, for the item reader to attach to its items.

use super::prepare::Prepared;
use super::verdict::{Code, Diagnosis};
use crate::expr::{ParseError, ParseErrorKind};

/// A stability a student can state.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Stated {
    Stable,
    Unstable,
    Marginal,
}

impl Stated {
    /// The word, as the bank's `stability` field spells it.
    pub(crate) fn word(self) -> &'static str {
        match self {
            Stated::Stable => "stable",
            Stated::Unstable => "unstable",
            Stated::Marginal => "marginal",
        }
    }

    fn from_word(w: &str) -> Option<Stated> {
        Some(match w {
            "stable" => Stated::Stable,
            "unstable" => Stated::Unstable,
            "marginal" | "neutral" => Stated::Marginal,
            _ => return None,
        })
    }
}

/// An input with its stability words blanked out, and what they said where.
pub(crate) struct Marked {
    /// The input, the same length, words (and the brackets around them) turned to spaces.
    pub(crate) text: String,
    /// Each statement and its byte offset.
    pub(crate) stated: Vec<(usize, Stated)>,
}

/// Finds the stability words of `input` (not declared symbols of the problem); a word close to
/// one of them is refused with a suggestion.
pub(crate) fn mark(p: &Prepared, input: &str) -> Result<Marked, ParseError> {
    let mut text = input.to_string();
    let mut stated = Vec::new();
    let words = words(input);
    let mut k = 0;
    while let Some(&(start, end)) = words.get(k) {
        k += 1;
        let w = input[start..end].to_ascii_lowercase();
        if p.context.is_declared(&input[start..end]) {
            continue;
        }
        // "marginally stable", "neutrally stable": one statement.
        let (w, end) = match (w.as_str(), words.get(k)) {
            ("marginally" | "neutrally", Some(&(s2, e2)))
                if input[s2..e2].eq_ignore_ascii_case("stable") =>
            {
                k += 1;
                ("marginal".to_string(), e2)
            }
            _ => (w, end),
        };
        if let Some(s) = Stated::from_word(&w) {
            stated.push((start, s));
            blank(&mut text, start, end);
            continue;
        }
        if let Some(suggestion) = looks_like_stability(&w) {
            return Err(ParseError::new(
                ParseErrorKind::UnknownName {
                    name: input[start..end].to_string(),
                    suggestion: Some(suggestion.into()),
                    split: None,
                },
                start..end,
            ));
        }
    }
    if !stated.is_empty() {
        blank_empty_brackets(&mut text);
    }
    Ok(Marked { text, stated })
}

/// Byte ranges of the runs of ASCII letters that start a word (not inside a name like `x2a`).
fn words(input: &str) -> Vec<(usize, usize)> {
    let b = input.as_bytes();
    let mut out = Vec::new();
    let mut i = 0;
    while i < b.len() {
        let starts = b[i].is_ascii_alphabetic()
            && (i == 0 || !(b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_'));
        if !starts {
            i += 1;
            continue;
        }
        let s = i;
        while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
            i += 1;
        }
        out.push((s, i));
    }
    out
}

fn blank(text: &mut String, start: usize, end: usize) {
    text.replace_range(start..end, &" ".repeat(end - start));
}

/// `( )` left where `(stable)` was: blanked too.
fn blank_empty_brackets(text: &mut String) {
    let b = text.as_bytes().to_vec();
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'(' || b[i] == b'[' {
            let mut j = i + 1;
            while j < b.len() && b[j] == b' ' {
                j += 1;
            }
            if j < b.len() && j > i + 1 && (b[j] == b')' || b[j] == b']') {
                blank(text, i, j + 1);
                i = j;
            }
        }
        i += 1;
    }
}

/// The stability word `w` is probably a misspelling of.
fn looks_like_stability(w: &str) -> Option<&'static str> {
    if w.len() < 4 {
        return None;
    }
    ["stable", "unstable", "marginal"]
        .into_iter()
        .find(|s| strsim::damerau_levenshtein(w, s) <= 2)
}

/// The stability of reference item `j`, if the part states it.
fn reference_stability(part: &crate::problem::Part, j: usize) -> Option<Stated> {
    part.stability.get(j).and_then(|s| Stated::from_word(s))
}

/// Most sample points the engine is asked at (each compiles the linearised equations).
const ENGINE_SAMPLES: usize = 3;

/// The engine's stability of a point given by its values at each sample point: the one
/// answer of every sample where it is defined, or `None`.
pub(crate) fn engine_stability(p: &mut Prepared, point: &[Option<Vec<f64>>]) -> Option<Stated> {
    use crate::mechanics::equilibria::Stability;
    let mut found: Option<Stated> = None;
    let defined = point
        .iter()
        .enumerate()
        .filter_map(|(k, q)| Some((k, q.as_ref()?)));
    for (k, q) in defined.take(ENGINE_SAMPLES) {
        let params = p.points.params(&p.system, k).to_vec();
        // The full linearization (velocity terms included), as `modes` and verify judge it.
        let modes = p.system.modes_at(&p.derivation, &params, q).ok()?;
        let st = match modes.stability {
            Stability::Stable => Stated::Stable,
            Stability::Unstable => Stated::Unstable,
            Stability::Marginal => Stated::Marginal,
        };
        if found.is_some_and(|f| f != st) {
            return None;
        }
        found = Some(st);
    }
    found
}

/// A wrong statement about student item `label`, which matched reference item `j`; where
/// the part gives no stability, `engine` (computed on demand) decides. `said` carries
/// whether L has terms linear in the velocities: a maximum of the effective potential may
/// then be stable (the fast rotating trap), so the reason is the linearised equations, not
/// the potential's minimum.
pub(crate) fn judge(
    part: &crate::problem::Part,
    label: &str,
    (said, gyroscopic): (Stated, bool),
    j: usize,
    engine: impl FnOnce() -> Option<Stated>,
) -> Option<Diagnosis> {
    let is = match reference_stability(part, j) {
        Some(is) => is,
        None if part.stability.is_empty() => engine()?,
        None => return None,
    };
    (is != said).then(|| {
        let why = if gyroscopic {
            "the terms linear in the velocities (Coriolis, gyroscopic) act here, so the potential alone does not decide: linearise the equations of motion about the point, those terms included, and see whether the small motions stay bounded (every frequency real) or grow"
        } else {
            "an equilibrium is stable where the (effective) potential has a minimum, so look at the sign of its second derivative there"
        };
        Diagnosis::new(
            Code::WrongStability,
            format!("you said {label} is {}, but it is not: {why}", said.word()),
        )
    })
}

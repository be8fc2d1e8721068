//! Labels on frequency items, read as what they state: `ω = …` (or `ω₁`, `omega_2`) an
//! angular frequency, `ω² = …` its square, `f = …` (or `ν`) an ordinary frequency, `T = …`
//! (or `τ`) a period. A label always names the quantity the part asks about, even where ω is
//! also a parameter of the problem (the spin rate of a wire): `ω² = 2ga − ω²` states the
//! square of the frequency asked for.
//!
//! An item whose label states another quantity than the part asks for (ω² for ω, ω for ω²,
//! f or T for either) is not the answer, whether the statement is true (`ω² = g/l` where ω is
//! asked) or its value is the asked one under the wrong name (`ω² = √(g/l)`, `f = √(g/l)`):
//! it is named — `omega-squared`, `omega-root`, `ordinary-frequency`, `period` — and earns
//! nothing. Items without a label, or with one naming the quantity asked, are judged by value.

use std::f64::consts::TAU;

use super::items::{Lists, same_item};
use super::prepare::Prepared;
use super::verdict::{Code, Diagnosis};
use crate::problem::Part;

/// The quantity a label states.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Said {
    /// `ω = …`: an angular frequency.
    Omega,
    /// `ω² = …`: its square.
    OmegaSquared,
    /// `f = …`: an ordinary frequency, ω/2π.
    Ordinary,
    /// `T = …`: a period, 2π/ω.
    Period,
}

impl Said {
    /// The quantity's symbol, as a label (Unicode).
    pub(crate) fn symbol(self) -> &'static str {
        self.label(crate::expr::Style::Unicode)
    }

    /// The quantity's symbol in `style` (`omega^2` plain, `ω²` in Unicode).
    pub(crate) fn label(self, style: crate::expr::Style) -> &'static str {
        let plain = style == crate::expr::Style::Plain;
        match self {
            Said::Omega if plain => "omega",
            Said::Omega => "ω",
            Said::OmegaSquared if plain => "omega^2",
            Said::OmegaSquared => "ω²",
            Said::Ordinary => "f",
            Said::Period => "T",
        }
    }

    /// What the label states, in words with its symbol.
    fn noun(self) -> &'static str {
        match self {
            Said::Omega => "the angular frequency ω",
            Said::OmegaSquared => "ω², the square of the angular frequency",
            Said::Ordinary => "an ordinary frequency f = ω/2π",
            Said::Period => "a period T = 2π/ω",
        }
    }

    /// The value this quantity has where the angular frequency is `w`.
    fn of_omega(self, w: f64) -> f64 {
        match self {
            Said::Omega => w,
            Said::OmegaSquared => w * w,
            Said::Ordinary => w / TAU,
            Said::Period => TAU / w,
        }
    }
}

/// The quantity a label names (`omega1^2`, `ω₂²`, `f`, `T_1`), or `None` for a label that
/// is no frequency's name (kept as a plain label, read by value).
pub(crate) fn said(label: &str) -> Option<Said> {
    let t: String = label.chars().filter(|c| !c.is_whitespace()).collect();
    let (base, squared) = match t
        .strip_suffix('²')
        .or_else(|| t.strip_suffix("^2"))
        .or_else(|| t.strip_suffix("**2"))
    {
        Some(b) => (b, true),
        None => (t.as_str(), false),
    };
    // An index: digits, subscript digits, after an optional `_`.
    let base = base.trim_end_matches(|c: char| c.is_ascii_digit() || ('₀'..='₉').contains(&c));
    let base = base.strip_suffix('_').unwrap_or(base);
    let s = match (base, squared) {
        ("ω" | "omega" | "w", false) => Said::Omega,
        ("ω" | "omega" | "w", true) => Said::OmegaSquared,
        ("f" | "ν" | "nu", false) => Said::Ordinary,
        ("T" | "τ" | "tau" | "P", false) => Said::Period,
        _ => return None,
    };
    Some(s)
}

/// What a frequencies part asks for.
pub(crate) fn asked(part: &Part) -> Said {
    if part.squared {
        Said::OmegaSquared
    } else {
        Said::Omega
    }
}

/// Whether an item labelled `said` is read by value: no label, or one naming what is asked.
pub(crate) fn fits(part: &Part, said: Option<Said>) -> bool {
    said.is_none_or(|s| s == asked(part))
}

/// The diagnosis of student item `i`, labelled `said` (not what the part asks for), shown as
/// `shown`; takes the reference item it states (truly or by value) out of `free`.
pub(crate) fn mislabelled(
    part: &Part,
    p: &Prepared,
    lists: &Lists,
    (i, said, shown): (usize, Said, &str),
    free: &mut Vec<usize>,
) -> Diagnosis {
    let asked = asked(part);
    // Reference values as the labelled quantity, from the angular frequency.
    let as_said = |j: usize| -> Vec<Option<Vec<f64>>> {
        lists.reference[j]
            .iter()
            .map(|x| {
                x.as_ref().map(|v| {
                    v.iter()
                        .map(|&r| {
                            let w = if part.squared { r.sqrt() } else { r };
                            said.of_omega(w)
                        })
                        .collect()
                })
            })
            .collect()
    };
    let student = &lists.student[i];
    let tol = part.tolerance;
    let true_statement = free
        .iter()
        .position(|&j| same_item(part, p, student, &as_said(j), tol));
    let asked_value = || {
        free.iter()
            .position(|&j| same_item(part, p, student, &lists.reference[j], tol))
    };
    // ω² where ω is asked is `omega-squared`, ω where ω² is asked `omega-root`; a right
    // value under the other name is the same confusion seen from the value: ω's value
    // called ω² is ω given for ω² (`omega-root`), and ω²'s value called ω `omega-squared`.
    let code = |value_named: bool| match (asked, said) {
        (_, Said::Ordinary) => Code::OrdinaryFrequency,
        (_, Said::Period) => Code::Period,
        (Said::OmegaSquared, _) if value_named => Code::OmegaSquared,
        (Said::OmegaSquared, _) => Code::OmegaRoot,
        _ if value_named => Code::OmegaRoot,
        _ => Code::OmegaSquared,
    };
    let want = asked.noun();
    if let Some(k) = true_statement {
        free.remove(k);
        let message = format!(
            "`{shown}` is true, but it states {}, and this part asks for {want}: {}",
            said.noun(),
            convert(asked, said)
        );
        return Diagnosis::new(code(false), message);
    }
    if let Some(k) = asked_value() {
        free.remove(k);
        let message = format!(
            "the value in `{shown}` is {want}, but your label says it is {}: the label is part of the answer, so name the value for what it is",
            said.noun()
        );
        return Diagnosis::new(code(true), message);
    }
    let message = format!(
        "`{shown}` states {}, but this part asks for {want} (and the value is not right for either)",
        said.noun()
    );
    Diagnosis::new(code(false), message)
}

/// How to get the asked quantity from the stated one.
fn convert(asked: Said, said: Said) -> &'static str {
    match (asked, said) {
        (Said::Omega, Said::OmegaSquared) => "give ω itself, the square root",
        (Said::Omega, Said::Ordinary) => "ω = 2π f",
        (Said::Omega, Said::Period) => "ω = 2π/T",
        (Said::OmegaSquared, Said::Omega) => "give ω², the square",
        (Said::OmegaSquared, Said::Ordinary) => "ω² = (2π f)²",
        (Said::OmegaSquared, Said::Period) => "ω² = (2π/T)²",
        _ => "give the quantity asked for",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_name_what_they_state() {
        for (label, s) in [
            ("ω", Some(Said::Omega)),
            ("omega", Some(Said::Omega)),
            ("ω₁", Some(Said::Omega)),
            ("omega_2", Some(Said::Omega)),
            ("ω²", Some(Said::OmegaSquared)),
            ("omega^2", Some(Said::OmegaSquared)),
            ("omega1^2", Some(Said::OmegaSquared)),
            ("ω₂²", Some(Said::OmegaSquared)),
            ("f", Some(Said::Ordinary)),
            ("nu", Some(Said::Ordinary)),
            ("T", Some(Said::Period)),
            ("T1", Some(Said::Period)),
            ("lambda", None),
            ("x", None),
            ("f^2", None),
        ] {
            assert_eq!(said(label), s, "{label}");
        }
    }
}

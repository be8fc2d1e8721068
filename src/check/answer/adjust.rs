//! What is settled after an answer is judged: defined quantities shown by their names, numbers
//! typed for a part in symbols, diagnoses a later one supersedes, and unlike dimensions that
//! make an answer wrong whatever its numbers.

use super::*;

/// A defined quantity the answer names (`ω sin θ₀`) is shown by its name, not its value,
/// in the reading and the diagnoses: the student reads back what they wrote.
pub(super) fn fold_definitions(p: &Prepared, input: &str, v: &mut Verdict) {
    if p.system.definitions.is_empty() {
        return;
    }
    // `±` does not lex on its own (it is read by the list reader): blanked for this.
    let input = input.replace(['±', '∓'], " ");
    let named: Vec<String> = crate::expr::lexer::lex(&input)
        .map(|toks| {
            toks.into_iter()
                .filter_map(|t| match t.tok {
                    crate::expr::lexer::Tok::Name { text, .. } => {
                        Some(crate::expr::names::normalize(&text))
                    }
                    _ => None,
                })
                .collect()
        })
        .unwrap_or_default();
    let pool = &p.system.pool;
    for (name, value) in &p.system.definitions {
        if !named.contains(name) {
            continue;
        }
        let (plain, unicode) = (pool.plain(*value), pool.unicode(*value));
        let greek = crate::expr::names::unicode_name(name);
        let r = &mut v.reading;
        r.plain = r.plain.replace(&plain, name);
        r.unicode = r.unicode.replace(&unicode, &greek);
        if let Some(n) = &mut r.note {
            *n = n.replace(&unicode, &greek);
        }
        for d in &mut v.diagnoses {
            d.message = d.message.replace(&unicode, &greek);
        }
    }
}

/// A part judged in symbols (it does not accept numbers) answered with numbers in place of
/// every parameter (`0.5*r'' + 60*(r - 0.8) = 0`): what that answer "gets wrong" — unlike
/// dimensions, a factor among the parameters — is no diagnosis. It is not an answer of the
/// kind asked for (`Invalid`, as a wrong kind is): the student is told to write the symbols.
/// Only an answer with a decimal and no parameter or defined name, to a part whose reference
/// names a parameter.
pub(super) fn numbers_for_symbols(part: &Part, p: &Prepared, input: &str, v: &mut Verdict) {
    use crate::expr::lexer::{Tok, lex};
    if part.numbers || v.status != Status::Incorrect {
        return;
    }
    let symbols: Vec<&str> = (p.system.parameters.iter().map(|q| q.name.as_str()))
        .chain(p.system.definitions.iter().map(|(n, _)| n.as_str()))
        .collect();
    // (names a symbol, has a decimal) of a text; `None` when it does not lex.
    let scan = |text: &str| -> Option<(bool, bool)> {
        let text = text.replace(['±', '∓'], " ");
        let toks = lex(&text).ok()?;
        let mut named = false;
        let mut decimal = false;
        for t in toks {
            match t.tok {
                Tok::Name { text, .. } => {
                    named |= symbols.contains(&crate::expr::names::normalize(&text).as_str())
                }
                // A decimal as typed (`0.5`, `9.81`, `1e-3`), not an integer or `1/2`.
                Tok::Num(_) => {
                    decimal |= text
                        .get(t.span.clone())
                        .is_some_and(|n| n.contains(['.', 'e', 'E']))
                }
                _ => {}
            }
        }
        Some((named, decimal))
    };
    // The answer first: it rarely is bare decimals, and then the references need no reading.
    if scan(input) != Some((false, true)) {
        return;
    }
    let reference_named = part
        .answers
        .iter()
        .any(|a| scan(a).is_some_and(|(named, _)| named));
    if !reference_named {
        return;
    }
    let mut names: Vec<String> = (p.system.parameters.iter())
        .map(|q| crate::expr::names::unicode_name(&q.name))
        .collect();
    crate::sort::sort(&mut names);
    v.status = Status::Invalid;
    v.score = 0.0;
    v.diagnoses = vec![Diagnosis::new(
        Code::NumbersForSymbols,
        format!(
            "this part asks for an expression in the problem's symbols ({}), not numbers: write each parameter by its name",
            names.join(", ")
        ),
    )];
}

/// Diagnoses a more principled one makes redundant or misleading: `h-vs-e` says all that
/// `t-plus-v` says for an energy function; a divided-out factor (`lost-root`) can also look
/// like two symbols swapped (`m (2ga − ω²)` for `r (2ga − ω²)`), which is not the mistake.
pub(super) fn drop_superseded(v: &mut Verdict) {
    const SUPERSEDES: &[(Code, Code)] = &[
        (Code::HVsE, Code::TPlusV),
        // T + V names the sign of V's terms: a term-level sign or factor finding on V says it
        // again, worse (the factor cos θ − 1 called wrong).
        (Code::TPlusV, Code::SignError),
        (Code::TPlusV, Code::WrongFactor),
        (Code::LostRoot, Code::SwappedSymbols),
    ];
    for &(by, gone) in SUPERSEDES {
        if v.diagnoses.iter().any(|d| d.code == by) {
            v.diagnoses.retain(|d| d.code != gone);
        }
    }
}

/// An answer whose terms have unlike dimensions is never correct, even where its numbers
/// agree with the reference (`(m + 1)·(θ'' + g/l·sin θ) = 0`).
pub(super) fn never_correct_with_unlike_dimensions(v: &mut Verdict) {
    if v.status == Status::Correct && v.diagnoses.iter().any(|d| d.code == Code::Dimension) {
        v.status = Status::Incorrect;
        v.score = 0.0;
        v.diagnoses.retain(|d| d.code == Code::Dimension);
    }
}

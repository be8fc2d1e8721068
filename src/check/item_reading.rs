//! Reading the items of a list answer: split at top-level `,` and `;`, labels (`ω₁ = …`)
//! dropped, `±` giving two items, points of several coordinates written as tuples
//! (`(0, 0), (π, π)`, in the coordinates' order), and stated stability (`0 (stable)`) set
//! aside for the stability check.
//!
//! Inputs with none of the newer notations take the original path, so their readings (and
//! error messages) are unchanged.

use super::freq_label::{self, Said};
use super::prepare::Prepared;
use super::stability::{self, Stated};
use crate::expr::{Id, Node, ParseError, ParseErrorKind, Reading, read, read_expr};
use crate::problem::{Part, PartKind};

/// Splits at top-level `,` and `;` (outside parentheses): (text, byte offset) per item.
fn split_items(input: &str) -> Vec<(&str, usize)> {
    split_at(input, &[',', ';'])
}

/// Splits at top-level `seps` (outside parentheses): (text, byte offset) per piece.
fn split_at<'a>(input: &'a str, seps: &[char]) -> Vec<(&'a str, usize)> {
    let mut out = Vec::new();
    let (mut depth, mut start) = (0i32, 0usize);
    for (i, c) in input.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            c if depth <= 0 && seps.contains(&c) => {
                out.push((&input[start..i], start));
                start = i + c.len_utf8();
            }
            _ => {}
        }
    }
    out.push((&input[start..], start));
    out
}

/// `omega1 = …` → (`…`, offset of it, the label); a bare item is returned as is.
fn strip_label(item: &str) -> (&str, usize, Option<&str>) {
    if let Some(k) = item.find('=') {
        let label = item[..k].trim();
        if !label.is_empty()
            && label.chars().all(|c| {
                c.is_alphanumeric() || c == '_' || c == ' ' || "₀₁₂₃₄₅₆₇₈₉²'^*".contains(c)
            })
        {
            return (&item[k + 1..], k + 1, Some(label));
        }
    }
    (item, 0, None)
}

/// Whether an item of the frequencies answer `input` is labelled as another quantity than
/// `part` asks for (`ω² = …` where ω is asked): such an answer states something else, and is
/// not followed through as a list of the asked frequencies.
pub fn states_another_frequency(part: &Part, input: &str) -> bool {
    part.kind == PartKind::Frequencies
        && split_items(input).iter().any(|(text, _)| {
            let said = strip_label(text).2.and_then(freq_label::said);
            !freq_label::fits(part, said)
        })
}

fn shifted(e: ParseError, by: usize) -> ParseError {
    ParseError::new(e.kind, e.span.start + by..e.span.end + by)
}

/// A frequency item's label that names a quantity (`ω² = …`, `omega1 = …`, `f = …`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ItemLabel {
    pub(crate) said: Said,
}

/// A list answer as read: the items (one value per coordinate each), the stability stated
/// for each (equilibria), and each item's label (frequencies).
pub(crate) struct StatedItems {
    pub(crate) items: Vec<Vec<Id>>,
    pub(crate) stated: Vec<Option<Stated>>,
    pub(crate) labels: Vec<Option<ItemLabel>>,
}

impl StatedItems {
    fn unlabelled(items: Vec<Vec<Id>>, stated: Vec<Option<Stated>>) -> StatedItems {
        let n = items.len();
        StatedItems {
            items,
            stated,
            labels: vec![None; n],
        }
    }
}

/// The student's items, the stability stated for each (equilibria only) and the label of
/// each (frequencies only).
pub(crate) fn read_stated_items(
    part: &Part,
    p: &mut Prepared,
    input: &str,
) -> Result<StatedItems, ParseError> {
    // `none`: the empty list, stated.
    if crate::problem::is_none_answer(input) {
        return Ok(StatedItems::unlabelled(Vec::new(), Vec::new()));
    }
    if part.kind != PartKind::Equilibria {
        let (items, labels) = read_values(part, p, input)?;
        let n = items.len();
        return Ok(StatedItems {
            items,
            stated: vec![None; n],
            labels,
        });
    }
    let input = &super::prepare::any_as_marker(p, input);
    let marked = stability::mark(p, input)?;
    let n = p.system.n();
    let tuples = n > 1 && has_tuple(&marked.text);
    if marked.stated.is_empty() && !input.contains(['±', '∓']) && !tuples {
        let items = read_points(p, input)?;
        let n = items.len();
        return Ok(StatedItems::unlabelled(items, vec![None; n]));
    }
    let pieces = if n == 1 || tuples {
        split_items(&marked.text)
    } else {
        split_at(&marked.text, &[';'])
    };
    let mut items = Vec::new();
    let mut stated = Vec::new();
    for (text, off) in pieces {
        let said = marked
            .stated
            .iter()
            .find(|(at, _)| (off..=off + text.len()).contains(at))
            .map(|(_, s)| *s);
        // `r = 0, unstable`: a statement standing alone belongs to the item before it.
        if text.trim().is_empty()
            && said.is_some()
            && let Some(last) = stated.last_mut()
        {
            *last = said;
            continue;
        }
        for variant in plus_minus(text, off)? {
            let point = if tuples {
                read_tuple(p, &variant, off)?
            } else {
                read_point_text(p, &variant, off)?
            };
            items.push(point);
            stated.push(said);
        }
    }
    Ok(StatedItems::unlabelled(items, stated))
}

/// Items of one value each, with the label of each.
type LabelledValues = (Vec<Vec<Id>>, Vec<Option<ItemLabel>>);

/// Values, frequencies: one expression per item (`±` giving two), and the label of each
/// that names a frequency's quantity (frequencies only; other labels are dropped).
fn read_values(part: &Part, p: &mut Prepared, input: &str) -> Result<LabelledValues, ParseError> {
    let mut items = Vec::new();
    let mut labels = Vec::new();
    for (text, off) in split_items(input) {
        let (body, k, label) = if matches!(part.kind, PartKind::Frequencies | PartKind::Values) {
            strip_label(text)
        } else {
            (text, 0, None)
        };
        let said = label
            .filter(|_| part.kind == PartKind::Frequencies)
            .and_then(freq_label::said);
        for variant in plus_minus(body, off + k)? {
            let id = read_expr(&variant, &p.context, &mut p.system.pool)
                .map_err(|e| shifted(e, off + k))?;
            items.push(vec![id]);
            labels.push(said.map(|said| ItemLabel { said }));
        }
    }
    Ok((items, labels))
}

/// Most `±` signs expanded in one item (2³ = 8 values).
const MAX_SIGN_CHOICES: usize = 3;

/// `±a` as `+ a` and `- a` (each `±` two bytes wide, like its replacements, so offsets
/// hold); `∓` takes the other sign of the one `±`. Several `±` are independent choices, each
/// combination an item (`±√((2 ± √2) g/l)` is four values), never paired silently; a `∓`
/// beside several `±`, or more than [`MAX_SIGN_CHOICES`] of them, is refused (`off` places
/// the error). Text without either is itself.
fn plus_minus(text: &str, off: usize) -> Result<Vec<String>, ParseError> {
    let pm = text.matches('±').count();
    let mp = text.matches('∓').count();
    if pm + mp == 0 {
        return Ok(vec![text.to_string()]);
    }
    let refuse = |reason: String| {
        let at = text.find(['±', '∓']).unwrap_or(0);
        Err(ParseError::new(
            ParseErrorKind::SignChoices { reason },
            off + at..off + text.len(),
        ))
    };
    if pm + mp > 1 && mp > 0 {
        return refuse("`∓` beside more than one `±`: which signs go together is not clear".into());
    }
    if pm > MAX_SIGN_CHOICES {
        return refuse(format!(
            "{pm} signs `±` in one item: at most {MAX_SIGN_CHOICES} are expanded"
        ));
    }
    if pm <= 1 {
        // `∓` is three bytes: padded to keep offsets.
        let with = |pm: &str, mp: &str| text.replace('±', pm).replace('∓', mp);
        return Ok(vec![with("+ ", "-  "), with("- ", "+  ")]);
    }
    // Each `±` chosen on its own: the combination's k-th bit is the k-th sign.
    Ok((0..1usize << pm)
        .map(|choice| {
            let mut k = 0;
            let mut out = String::with_capacity(text.len());
            for c in text.chars() {
                if c == '±' {
                    out.push_str(if choice >> k & 1 == 0 { "+ " } else { "- " });
                    k += 1;
                } else {
                    out.push(c);
                }
            }
            out
        })
        .collect())
}

/// Whether a point is written as a tuple `(a, b)`: a top-level bracket holding a `,`.
fn has_tuple(text: &str) -> bool {
    split_items(text).iter().any(|(t, _)| {
        let t = t.trim();
        let bracketed =
            (t.starts_with('(') && t.ends_with(')')) || (t.starts_with('[') && t.ends_with(']'));
        bracketed && split_items(&t[1..t.len() - 1]).len() > 1
    })
}

/// `(a, b)`: one value per coordinate, in the coordinates' order.
fn read_tuple(p: &mut Prepared, text: &str, off: usize) -> Result<Vec<Id>, ParseError> {
    let n = p.system.n();
    let lead = text.len() - text.trim_start().len();
    let t = text.trim();
    let span = off + lead..off + lead + t.len();
    let names = p
        .system
        .coordinates
        .iter()
        .map(|c| c.name.clone())
        .collect::<Vec<_>>()
        .join(", ");
    let wrong = || {
        ParseError::new(
            ParseErrorKind::PointSize {
                want: n,
                names: names.clone(),
            },
            span.clone(),
        )
    };
    let inner = t
        .strip_prefix(['(', '['])
        .and_then(|x| x.strip_suffix([')', ']']))
        .ok_or_else(wrong)?;
    let parts = split_items(inner);
    if parts.len() != n {
        return Err(wrong());
    }
    let at = off + lead + 1;
    parts
        .into_iter()
        .map(|(x, k)| read_expr(x, &p.context, &mut p.system.pool).map_err(|e| shifted(e, at + k)))
        .collect()
}

/// One point written as `θ = a` or `a` (one coordinate) or `θ₁ = a, θ₂ = b`.
fn read_point_text(p: &mut Prepared, text: &str, off: usize) -> Result<Vec<Id>, ParseError> {
    let r = read(text, &p.context, &mut p.system.pool).map_err(|e| shifted(e, off))?;
    point_of(p, &r).ok_or_else(|| {
        let s = r.span();
        ParseError::new(ParseErrorKind::EquationExpected, s.start + off..s.end + off)
    })
}

/// The point a reading gives: `θ = a` or `a` for one coordinate, a list of `qᵢ = aᵢ` for
/// several.
fn point_of(p: &mut Prepared, r: &Reading) -> Option<Vec<Id>> {
    let n = p.system.n();
    let coordinate_of = |p: &Prepared, lhs: Id| match p.system.pool.node(lhs) {
        Node::Var(s, 0) => p.system.coordinates.iter().position(|c| c.sym == *s),
        _ => None,
    };
    match r {
        Reading::Expr(e, _) if n == 1 => Some(vec![*e]),
        Reading::Equation { lhs, rhs, .. } if n == 1 && coordinate_of(p, *lhs) == Some(0) => {
            Some(vec![*rhs])
        }
        Reading::List(eqs, _) if n > 1 => {
            let mut pt = vec![None; n];
            for e in eqs {
                let Reading::Equation { lhs, rhs, .. } = e else {
                    return None;
                };
                pt[coordinate_of(p, *lhs)?] = Some(*rhs);
            }
            pt.into_iter().collect()
        }
        _ => None,
    }
}

/// Equilibria as originally read: the whole input parsed at once.
fn read_points(p: &mut Prepared, input: &str) -> Result<Vec<Vec<Id>>, ParseError> {
    let n = p.system.n();
    let reading = read(input, &p.context, &mut p.system.pool)?;
    let mut items = Vec::new();
    let bad = |r: &Reading| ParseError::new(ParseErrorKind::EquationExpected, r.span());
    let mut push = |p: &mut Prepared, r: &Reading| -> Result<(), ParseError> {
        items.push(point_of(p, r).ok_or_else(|| bad(r))?);
        Ok(())
    };
    match &reading {
        Reading::List(items_r, _) if n == 1 => {
            for r in items_r {
                push(p, r)?;
            }
        }
        Reading::System(items_r, _) => {
            for r in items_r {
                match r {
                    Reading::List(inner, _) if n == 1 => {
                        for x in inner {
                            push(p, x)?;
                        }
                    }
                    x => push(p, x)?,
                }
            }
        }
        r => push(p, r)?,
    }
    Ok(items)
}

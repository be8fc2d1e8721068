//! Unordered lists — equilibria, frequencies, values — matched item by item across every
//! sample point, with partial credit; why an unmatched item is wrong is `items.rs`'s business.

use super::common::{invalid_reading, verdict};
use super::compare::values;
use super::error::CheckError;
use super::items::{ItemFinding, Lists, classify_unmatched, same_item, what_of};
use super::prepare::{Prepared, read_frequency, read_one, read_point};
use super::verdict::{Code, Diagnosis, ReadAs, Status, Verdict};
use crate::expr::{Id, ParseError, Reading, Style, read, read_expr};
use crate::problem::{Part, PartKind, Problem};

/// Splits at top-level `,` and `;` (outside parentheses): (text, byte offset) per item.
fn split_items(input: &str) -> Vec<(&str, usize)> {
    let mut out = Vec::new();
    let (mut depth, mut start) = (0i32, 0usize);
    for (i, c) in input.char_indices() {
        match c {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            ',' | ';' if depth <= 0 => {
                out.push((&input[start..i], start));
                start = i + 1;
            }
            _ => {}
        }
    }
    out.push((&input[start..], start));
    out
}

/// `omega1 = …` → (`…`, offset of it); a bare item is returned as is.
fn strip_label(item: &str) -> (&str, usize) {
    if let Some(k) = item.find('=') {
        let label = item[..k].trim();
        if !label.is_empty()
            && label
                .chars()
                .all(|c| c.is_alphanumeric() || c == '_' || "₀₁₂₃₄₅₆₇₈₉²'".contains(c))
        {
            return (&item[k + 1..], k + 1);
        }
    }
    (item, 0)
}

fn shifted(e: ParseError, by: usize) -> ParseError {
    ParseError::new(e.kind, e.span.start + by..e.span.end + by)
}

/// The student's items, each one value per coordinate (equilibria) or one value.
pub(crate) fn read_items(
    part: &Part,
    p: &mut Prepared,
    input: &str,
) -> Result<Vec<Vec<Id>>, ParseError> {
    if part.kind == PartKind::Equilibria {
        let n = p.system.n();
        let reading = read(input, &p.context, &mut p.system.pool)?;
        let mut items = Vec::new();
        let point_of = |p: &mut Prepared, r: &Reading| -> Option<Vec<Id>> {
            match r {
                Reading::Expr(e, _) if n == 1 => Some(vec![*e]),
                Reading::Equation { lhs, rhs, .. }
                    if n == 1
                        && matches!(p.system.pool.node(*lhs), crate::expr::Node::Var(s, 0) if *s == p.system.coordinates[0].sym) =>
                {
                    Some(vec![*rhs])
                }
                Reading::List(eqs, _) if n > 1 => {
                    let mut pt = vec![None; n];
                    for e in eqs {
                        let Reading::Equation { lhs, rhs, .. } = e else {
                            return None;
                        };
                        let crate::expr::Node::Var(s, 0) = p.system.pool.node(*lhs) else {
                            return None;
                        };
                        let i = p.system.coordinates.iter().position(|c| c.sym == *s)?;
                        pt[i] = Some(*rhs);
                    }
                    pt.into_iter().collect()
                }
                _ => None,
            }
        };
        let bad =
            |r: &Reading| ParseError::new(crate::expr::ParseErrorKind::EquationExpected, r.span());
        match &reading {
            Reading::List(items_r, _) if n == 1 => {
                for r in items_r {
                    items.push(point_of(p, r).ok_or_else(|| bad(r))?);
                }
            }
            Reading::System(items_r, _) => {
                for r in items_r {
                    if n == 1 {
                        match r {
                            Reading::List(inner, _) => {
                                for x in inner {
                                    items.push(point_of(p, x).ok_or_else(|| bad(x))?);
                                }
                            }
                            x => items.push(point_of(p, x).ok_or_else(|| bad(x))?),
                        }
                    } else {
                        items.push(point_of(p, r).ok_or_else(|| bad(r))?);
                    }
                }
            }
            r => items.push(point_of(p, r).ok_or_else(|| bad(r))?),
        }
        return Ok(items);
    }
    let mut items = Vec::new();
    for (text, off) in split_items(input) {
        let (body, k) = if part.kind == PartKind::Frequencies {
            strip_label(text)
        } else {
            (text, 0)
        };
        let id =
            read_expr(body, &p.context, &mut p.system.pool).map_err(|e| shifted(e, off + k))?;
        items.push(vec![id]);
    }
    Ok(items)
}

fn reference_items(part: &Part, p: &mut Prepared) -> Result<Vec<Vec<Id>>, CheckError> {
    part.answers
        .iter()
        .map(|a| match part.kind {
            PartKind::Equilibria => read_point(p, a),
            PartKind::Frequencies => read_frequency(p, a).map(|x| vec![x]),
            _ => read_one(p, a).map(|x| vec![x]),
        })
        .collect()
}

/// Values of each item's components at every point (None where undefined).
fn item_values(p: &Prepared, items: &[Vec<Id>]) -> Vec<Vec<Option<Vec<f64>>>> {
    items
        .iter()
        .map(|it| {
            values(&p.system, it, &p.points).unwrap_or_else(|_| vec![None; p.points.points.len()])
        })
        .collect()
}

/// An item as text: `θ = π` for an equilibrium, the value otherwise.
fn show_item(part: &Part, p: &Prepared, coords: &[Id], it: &[Id], style: Style) -> String {
    if part.kind == PartKind::Equilibria {
        let pool = &p.system.pool;
        it.iter()
            .zip(coords)
            .map(|(x, c)| format!("{} = {}", pool.display(*c, style), pool.display(*x, style)))
            .collect::<Vec<_>>()
            .join(", ")
    } else {
        p.system.pool.display(it[0], style)
    }
}

/// Matches student items to reference items one to one: (matched reference, matched student).
fn match_items(part: &Part, p: &Prepared, lists: &Lists) -> (Vec<bool>, Vec<bool>) {
    let mut matched_ref = vec![false; lists.reference.len()];
    let mut matched_stu = vec![false; lists.student.len()];
    for (i, s) in lists.student.iter().enumerate() {
        if let Some(j) = (0..lists.reference.len()).find(|&j| {
            !matched_ref[j] && same_item(part, p, s, &lists.reference[j], part.tolerance)
        }) {
            matched_ref[j] = true;
            matched_stu[i] = true;
        }
    }
    (matched_ref, matched_stu)
}

/// How the items were read, joined as a student would type them.
fn list_reading(part: &Part, p: &Prepared, coords: &[Id], items: &[Vec<Id>]) -> ReadAs {
    let sep = if part.kind == PartKind::Equilibria && p.system.n() > 1 {
        "; "
    } else {
        ", "
    };
    let shown = |style: Style| -> String {
        items
            .iter()
            .map(|i| show_item(part, p, coords, i, style))
            .collect::<Vec<_>>()
            .join(sep)
    };
    ReadAs {
        plain: shown(Style::Plain),
        unicode: shown(Style::Unicode),
        note: None,
    }
}

/// The reference items, read once.
fn cached_reference(part: &Part, p: &mut Prepared) -> Result<Vec<Vec<Id>>, CheckError> {
    if let Some(r) = p.reference.get() {
        return Ok(r.clone());
    }
    let r = reference_items(part, p)?;
    Ok(p.reference.get_or_init(|| r).clone())
}

/// Checks a list answer.
pub fn check_list(problem: &Problem, part: &Part, p: &mut Prepared, input: &str) -> Verdict {
    let mut v = verdict(problem, part, Status::Incorrect);
    let items = match read_items(part, p, input) {
        Ok(i) => i,
        Err(e) => return invalid_reading(problem, part, e),
    };
    // The coordinates as expressions, interned once, to show equilibria as `θ = π`.
    let names: Vec<String> = p
        .system
        .coordinates
        .iter()
        .map(|c| c.name.clone())
        .collect();
    let coords: Vec<Id> = names.iter().map(|n| p.system.pool.sym(n)).collect();
    v.reading = list_reading(part, p, &coords, &items);
    let refs = match cached_reference(part, p) {
        Ok(r) => r,
        Err(m) => {
            v.status = Status::Invalid;
            v.diagnoses.push(Diagnosis::new(
                Code::Syntax,
                format!("the reference answer cannot be read: {m}"),
            ));
            return v;
        }
    };
    for &x in items.iter().flatten() {
        if let Err(e) = p.system.pool.dimension(x, &problem.dims) {
            v.diagnoses
                .push(Diagnosis::new(Code::Dimension, e.to_string()));
        }
    }
    let (sv, rv) = (item_values(p, &items), item_values(p, &refs));
    let lists = Lists {
        student: &sv,
        reference: &rv,
        reference_ids: &refs,
    };
    let (matched_ref, matched_stu) = match_items(part, p, &lists);
    let matched = matched_stu.iter().filter(|m| **m).count();
    let mut free: Vec<usize> = (0..refs.len()).filter(|&j| !matched_ref[j]).collect();
    for i in (0..items.len()).filter(|&i| !matched_stu[i]) {
        let label = format!(
            "item {} ({})",
            i + 1,
            show_item(part, p, &coords, &items[i], Style::Unicode)
        );
        let item = (i, items[i][0], label);
        let finding = classify_unmatched(problem, part, p, &lists, item, &mut free);
        v.diagnoses.push(finding.details());
    }
    if !free.is_empty() {
        let missing = ItemFinding::Missing {
            count: free.len(),
            what: what_of(part),
        };
        v.diagnoses.push(missing.details());
    }
    let total = refs.len().max(items.len()).max(1);
    v.score = matched as f64 / total as f64;
    if matched == refs.len()
        && items.len() == refs.len()
        && v.diagnoses.iter().all(|d| d.code != Code::Dimension)
    {
        v.status = Status::Correct;
        v.score = 1.0;
        v.diagnoses.clear();
    }
    super::misconception::list(problem, part, p, &items, &mut v);
    v
}

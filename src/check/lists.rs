//! Unordered lists — equilibria, frequencies, values — matched item by item across every
//! sample point, with partial credit and the items named: missing, extra, wrong, ω² for ω.

use super::common::{invalid_reading, verdict};
use super::compare::{close, values};
use super::error::CheckError;
use super::prepare::{Prepared, read_frequency, read_one, read_point, same_coordinate};
use super::tolerance;
use super::verdict::{Code, Diagnosis, ReadAs, Status, Verdict};
use crate::expr::{Id, ParseError, Reading, read, read_expr};
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
fn read_items(part: &Part, p: &mut Prepared, input: &str) -> Result<Vec<Vec<Id>>, ParseError> {
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

fn same_item(
    part: &Part,
    p: &Prepared,
    a: &[Option<Vec<f64>>],
    b: &[Option<Vec<f64>>],
    tol: f64,
) -> bool {
    let mut checked = 0;
    for (x, y) in a.iter().zip(b) {
        let Some(y) = y else { continue };
        let Some(x) = x else { return false };
        for (i, (u, w)) in x.iter().zip(y).enumerate() {
            let periodic = part.kind == PartKind::Equilibria && p.system.coordinates[i].periodic;
            let ok = if periodic && tol <= tolerance::STRICT {
                same_coordinate(true, *u, *w)
            } else {
                close(*u, *w, 0.0, tol)
            };
            if !ok {
                return false;
            }
        }
        checked += 1;
    }
    checked > 0
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
    let show = |p: &Prepared, it: &[Id], style: crate::expr::Style| -> String {
        if part.kind == PartKind::Equilibria {
            it.iter()
                .zip(&coords)
                .map(|(x, c)| {
                    let pool = &p.system.pool;
                    format!("{} = {}", pool.display(*c, style), pool.display(*x, style))
                })
                .collect::<Vec<_>>()
                .join(", ")
        } else {
            p.system.pool.display(it[0], style)
        }
    };
    let sep = if part.kind == PartKind::Equilibria && p.system.n() > 1 {
        "; "
    } else {
        ", "
    };
    v.reading = ReadAs {
        plain: items
            .iter()
            .map(|i| show(p, i, crate::expr::Style::Plain))
            .collect::<Vec<_>>()
            .join(sep),
        unicode: items
            .iter()
            .map(|i| show(p, i, crate::expr::Style::Unicode))
            .collect::<Vec<_>>()
            .join(sep),
        note: None,
    };
    let cached = p.reference.get().cloned();
    let refs = match cached.map_or_else(|| reference_items(part, p), Ok) {
        Ok(r) => p.reference.get_or_init(|| r).clone(),
        Err(m) => {
            v.status = Status::Invalid;
            v.diagnoses.push(Diagnosis::new(
                Code::Syntax,
                format!("the reference answer cannot be read: {m}"),
            ));
            return v;
        }
    };
    for it in &items {
        for &x in it {
            if let Err(e) = p.system.pool.dimension(x, &problem.dims) {
                v.diagnoses
                    .push(Diagnosis::new(Code::Dimension, e.to_string()));
            }
        }
    }
    let sv = item_values(p, &items);
    let rv = item_values(p, &refs);
    let tol = part.tolerance;
    let mut matched_ref = vec![false; refs.len()];
    let mut matched_stu = vec![false; items.len()];
    for (i, s) in sv.iter().enumerate() {
        if let Some(j) =
            (0..refs.len()).find(|&j| !matched_ref[j] && same_item(part, p, s, &rv[j], tol))
        {
            matched_ref[j] = true;
            matched_stu[i] = true;
        }
    }
    let matched = matched_stu.iter().filter(|m| **m).count();
    let missing: Vec<usize> = (0..refs.len()).filter(|&j| !matched_ref[j]).collect();
    let what = match part.kind {
        PartKind::Equilibria => "equilibrium",
        PartKind::Frequencies => "frequency",
        _ => "item",
    };
    let mut free_refs = missing.clone();
    for (i, s) in sv.iter().enumerate() {
        if matched_stu[i] {
            continue;
        }
        let label = format!(
            "item {} ({})",
            i + 1,
            show(p, &items[i], crate::expr::Style::Unicode)
        );
        // ω² for ω, or ω for ω².
        let squared_of = |a: &[Option<Vec<f64>>], b: &[Option<Vec<f64>>]| {
            let sq: Vec<Option<Vec<f64>>> = b
                .iter()
                .map(|x| x.as_ref().map(|v| v.iter().map(|y| y * y).collect()))
                .collect();
            same_item(part, p, a, &sq, tol)
        };
        if part.kind == PartKind::Frequencies {
            if let Some(k) = free_refs.iter().position(|&j| squared_of(s, &rv[j])) {
                free_refs.remove(k);
                let (code, msg) = if part.squared {
                    (
                        Code::OmegaSquared,
                        format!(
                            "{label} is the square of an ω²: this part asks for ω², square it back"
                        ),
                    )
                } else {
                    (
                        Code::OmegaSquared,
                        format!("{label} is ω², but this part asks for ω: take the square root"),
                    )
                };
                v.diagnoses.push(Diagnosis::new(code, msg));
                continue;
            }
            if let Some(k) = free_refs.iter().position(|&j| squared_of(&rv[j], s)) {
                free_refs.remove(k);
                let msg = if part.squared {
                    format!("{label} is ω, but this part asks for ω²: square it")
                } else {
                    format!("{label} is √ω: square it")
                };
                v.diagnoses.push(Diagnosis::new(Code::OmegaRoot, msg));
                continue;
            }
            // Agreement to a few digits only.
            if let Some(k) = free_refs
                .iter()
                .position(|&j| same_item(part, p, s, &rv[j], tolerance::ROUNDED))
            {
                free_refs.remove(k);
                v.diagnoses.push(Diagnosis::new(Code::RoundedConstant,
                    format!("{label} agrees only to a few significant digits: write exact constants such as sqrt(2), pi or 1/3"),
                ));
                continue;
            }
        }
        // An item of the wrong dimension says so.
        let want = match part.kind {
            PartKind::Frequencies if part.squared => Some(crate::expr::Dimension::new(0, 0, -2)),
            PartKind::Frequencies => Some(crate::expr::Dimension::new(0, 0, -1)),
            _ => None,
        };
        let have = p
            .system
            .pool
            .dimension(items[i][0], &problem.dims)
            .ok()
            .flatten();
        if let (Some(w), Some(h)) = (want, have)
            && w != h
        {
            if !free_refs.is_empty() {
                free_refs.remove(0);
            }
            v.diagnoses.push(Diagnosis::new(
                Code::Dimension,
                format!("{label} has dimension {h}, but a frequency is {w}"),
            ));
            continue;
        }
        if !free_refs.is_empty() {
            free_refs.remove(0);
            v.diagnoses
                .push(Diagnosis::new(Code::WrongItem, format!("{label} is wrong")));
        } else {
            let msg = if part.kind == PartKind::Equilibria {
                format!("one extra item: {label} is not an equilibrium")
            } else {
                format!("one extra item: {label} is not one of the {what} values asked for")
            };
            v.diagnoses.push(Diagnosis::new(Code::ExtraItem, msg));
        }
    }
    if !free_refs.is_empty() {
        let k = free_refs.len();
        v.diagnoses.push(Diagnosis::new(
            Code::MissingItem,
            if k == 1 {
                format!("one {what} is missing")
            } else {
                format!("{k} {what} values are missing")
            },
        ));
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
    v
}

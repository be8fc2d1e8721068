//! Searches for the mistake behind a wrong answer, each yielding a tutor's sentence: a sign
//! flipped in one term, one term off by a constant factor, two symbols swapped, constants
//! rounded. Each search takes a test `holds(candidate)`, so the same search serves
//! expressions (equal to the reference) and equations (satisfied by the true motion).
//!
//! Each candidate is a whole expression, built and evaluated at every sample point, so a
//! search over the terms is quadratic in their number: it runs only on answers of at most
//! [`MAX_SEARCH_TERMS`] terms (a 20 KB answer has over a thousand).

use super::prepare::Prepared;
use super::tolerance;
use super::verdict::{Code, Diagnosis};
use crate::expr::{Id, Node, Sym};
use rustc_hash::FxHashMap;

/// Most terms an answer may have for the one-term searches (a sign or a factor in one term)
/// to run. Tutors' answers have a handful; past this many, a slip in one term is not the
/// likely story, and the search would cost seconds.
pub const MAX_SEARCH_TERMS: usize = 64;

/// The terms of the expanded expression (so `½(m₁ − m₂)ẋ²` has two).
pub fn terms(p: &mut Prepared, e: Id) -> Vec<Id> {
    let x = p.system.pool.expand(e);
    match p.system.pool.node(x) {
        Node::Add(t) => t.to_vec(),
        _ => vec![x],
    }
}

/// `Some(text)` when `c` is a simple fraction (denominator ≤ 12), e.g. `2`, `½`, `−3/2`.
pub fn nice_fraction(c: f64) -> Option<String> {
    // Beyond this an integer is no "simple fraction" (and no longer fits the i64 it is
    // printed through): 1e300 is shown in scientific notation instead.
    if !c.is_finite() || c.abs() > 1e6 {
        return None;
    }
    for q in 1..=12i64 {
        let pn = (c * q as f64).round();
        if (pn / q as f64 - c).abs() <= tolerance::NUMBER * (1.0 + c.abs()) && pn != 0.0 {
            let p = pn as i64;
            return Some(
                match (p, q) {
                    (p, 1) => p.to_string(),
                    (1, 2) => "½".into(),
                    (-1, 2) => "−½".into(),
                    (p, q) => format!("{p}/{q}"),
                }
                .replace('-', "−"),
            );
        }
    }
    None
}

/// The terms of `e`, those without accelerations first: in an equation, flipping the inertia
/// term is equivalent to flipping all the others, and the force terms are where slips happen.
/// Empty unless there are 2 to [`MAX_SEARCH_TERMS`] terms (a one-term search is pointless
/// with one term, and too slow with very many).
fn terms_forces_first(p: &mut Prepared, e: Id) -> Vec<Id> {
    let mut ts = terms(p, e);
    if ts.len() < 2 || ts.len() > MAX_SEARCH_TERMS {
        return Vec::new();
    }
    crate::sort::sort_by_key(&mut ts, |&t| {
        p.system.pool.variables(t).iter().any(|v| v.1 == 2)
    });
    ts
}

/// A sign flipped in one term: `holds(e − 2t)` for a term t of `e`.
pub fn sign_in_term(
    p: &mut Prepared,
    e: Id,
    holds: &mut dyn FnMut(&mut Prepared, Id) -> bool,
) -> Option<Diagnosis> {
    for t in terms_forces_first(p, e) {
        let two = p.system.pool.int(2);
        let t2 = p.system.pool.mul(two, t);
        let cand = p.system.pool.sub(e, t2);
        if holds(p, cand) {
            return Some(Diagnosis::new(
                Code::SignError,
                format!(
                    "sign error: the term {} should have the opposite sign",
                    p.system.pool.unicode(t)
                ),
            ));
        }
    }
    None
}

/// One term off by a simple factor: `holds(e + (c − 1)·t)` for a term t and a nice c.
/// `factor_at` gives the c that would repair term t at the first sample point.
pub fn factor_in_term(
    p: &mut Prepared,
    e: Id,
    factor_at: &mut dyn FnMut(&mut Prepared, Id) -> Option<f64>,
    holds: &mut dyn FnMut(&mut Prepared, Id) -> bool,
) -> Option<Diagnosis> {
    // A term of bare numbers has a ratio to any value: no factor is read off it.
    let parameters = !p.system.parameter_syms().is_empty();
    for t in terms_forces_first(p, e) {
        if parameters && names_no_parameter(p, t) {
            continue;
        }
        let Some(c) = factor_at(p, t) else { continue };
        let Some(nice) = nice_fraction(c) else {
            continue;
        };
        if (c - 1.0).abs() < tolerance::NUMBER || (c + 1.0).abs() < tolerance::NUMBER {
            continue;
        }
        let cm1 = p.system.pool.num(rational(c - 1.0));
        let add = p.system.pool.mul(cm1, t);
        let cand = p.system.pool.add(e, add);
        if holds(p, cand) {
            return Some(Diagnosis::new(
                Code::ConstantFactor,
                format!(
                    "the term {} is off by a factor: it should be {nice} times what you wrote",
                    p.system.pool.unicode(t)
                ),
            ));
        }
    }
    None
}

/// The nearest simple fraction as an exact rational (for building candidates).
fn rational(x: f64) -> num_rational::BigRational {
    for q in 1..=12i64 {
        let pn = (x * q as f64).round();
        if (pn / q as f64 - x).abs() <= tolerance::NUMBER * (1.0 + x.abs()) {
            return num_rational::BigRational::new((pn as i64).into(), q.into());
        }
    }
    num_rational::BigRational::from_float(x).unwrap_or_default()
}

/// Two symbols exchanged: `holds(e with a ↔ b)`.
pub fn swapped(
    p: &mut Prepared,
    e: Id,
    holds: &mut dyn FnMut(&mut Prepared, Id) -> bool,
) -> Option<Diagnosis> {
    let mut syms: Vec<Sym> = p.system.parameter_syms();
    syms.extend(p.system.coordinate_syms());
    let present: Vec<Sym> = p
        .system
        .pool
        .variables(e)
        .into_iter()
        .map(|v| v.0)
        .collect();
    for (i, &a) in syms.iter().enumerate() {
        for &b in &syms[i + 1..] {
            if !present.contains(&a) && !present.contains(&b) {
                continue;
            }
            let mut map = FxHashMap::default();
            for o in 0..3u8 {
                let (va, vb) = (p.system.pool.var(a, o), p.system.pool.var(b, o));
                map.insert((a, o), vb);
                map.insert((b, o), va);
            }
            let cand = p.system.pool.substitute(e, &map);
            if cand != e && holds(p, cand) {
                let (na, nb) = (
                    p.system.pool.name(a).to_string(),
                    p.system.pool.name(b).to_string(),
                );
                let (va, vb) = (p.system.pool.sym(&na), p.system.pool.sym(&nb));
                return Some(Diagnosis::new(
                    Code::SwappedSymbols,
                    format!(
                        "{} and {} are swapped: exchanging them gives the right answer",
                        p.system.pool.unicode(va),
                        p.system.pool.unicode(vb)
                    ),
                ));
            }
        }
    }
    None
}

/// Whether `e` holds an approximate number the student typed: a decimal (a denominator that
/// is a multiple of 10: 0.333, 3.14, 1.01 are 333/1000, 157/50, 101/100) or a fraction past
/// the simple ones (355/113; ½, ⅕ and 2/3 are exact). Only such an answer can have "rounded"
/// constants: agreement to 1% without one is a different mistake (a velocity term small at
/// the sample points, not a rounding).
/// Walks the expression without recursion, each node once.
pub fn has_decimal(p: &Prepared, e: Id) -> bool {
    let ten = num_bigint::BigInt::from(10);
    let twelve = num_bigint::BigInt::from(12);
    p.system.pool.any_node(e, |n| {
        matches!(n, Node::Num(q) if (q.denom() % &ten) == num_bigint::BigInt::from(0) || *q.denom() > twelve)
    })
}

/// Agreement to only a few digits: `a` (which holds a decimal) is within
/// [`tolerance::ROUNDED`] of `b` everywhere but not within the tolerance.
pub fn rounded(p: &Prepared, a: Id, b: Id) -> Option<Diagnosis> {
    if !has_decimal(p, a) {
        return None;
    }
    // One evaluation gives the agreement; the digits follow from it (as many calls of
    // `relate` at tolerances 10⁻⁸ … 10⁻¹ would, at a ninth of the cost).
    let e = crate::check::compare::agreement(&p.system, a, b, &p.points).ok()??;
    if e.is_nan() || e > tolerance::ROUNDED {
        return None;
    }
    if student_numbers(p) {
        return Some(Diagnosis::new(
            Code::RoundedConstant,
            near_miss(
                "your value",
                relative_gap(p, a, b).unwrap_or(e),
                p.tolerance,
            ),
        ));
    }
    let digits = (1..=8).rev().find(|&k| e <= 10f64.powi(-k)).unwrap_or(1);
    Some(Diagnosis::new(
        Code::RoundedConstant,
        format!(
            "your answer agrees only to about {digits} significant digits: write exact constants such as sqrt(2), pi or 1/3 instead of decimals"
        ),
    ))
}

/// Whether `e` names none of the problem's parameters: only numbers, coordinates, velocities,
/// time (`−8.829·cos θ`, `2.335`).
pub fn names_no_parameter(p: &Prepared, e: Id) -> bool {
    let params = p.system.parameter_syms();
    !p.system
        .pool
        .variables(e)
        .iter()
        .any(|(s, _)| params.contains(s))
}

/// Whether the ratio of `s` to the reference `r` says nothing about a factor: `s` is bare
/// numbers (no parameter) where `r` has parameters. Any two numbers have a constant ratio —
/// another student's numbers are "12/5 times" this one's — so a factor read off it is no
/// diagnosis (and must earn no factor credit); a symbolic answer's factor (√(g/l) for
/// √(3g/2l), a missing ½ in m g l) still is one.
pub fn bare_numbers_for(p: &Prepared, s: Id, r: Id) -> bool {
    names_no_parameter(p, s) && !names_no_parameter(p, r)
}

/// Whether the parameters are pinned to a student's numbers (a part that accepts numbers,
/// judged for one student): a decimal is then the expected way to answer, and a near miss is
/// a matter of significant figures, not of an exact constant written as a decimal.
pub fn student_numbers(p: &Prepared) -> bool {
    p.system.parameters.iter().any(|q| q.range.0 == q.range.1)
}

/// A wrong value said by how far off it is, `f` being the student's value over the right one:
/// "about 73% too small", "about 140% too large", "of the wrong sign".
pub fn how_far_off(f: f64) -> String {
    if !f.is_finite() {
        return "far off".into();
    }
    if f < 0.0 {
        return format!(
            "of the wrong sign and {} times the right size",
            super::compare::fmt_value(-f)
        );
    }
    // Past ten times, a percentage is a long number nobody reads (1e300 → 10²⁹⁹ %).
    if f >= 10.0 {
        return format!(
            "about {} times the right value",
            super::compare::fmt_value(f)
        );
    }
    let pct = (f - 1.0).abs() * 100.0;
    let shown = if pct >= 10.0 {
        format!("{pct:.0}")
    } else {
        format!("{pct:.2}")
    };
    let way = if f > 1.0 { "large" } else { "small" };
    format!("about {shown}% too {way}")
}

/// The sentence for a near miss on a part judged with a student's numbers: off by `gap`
/// (relative), more than the part's `tolerance`.
pub fn near_miss(what: &str, gap: f64, tolerance: f64) -> String {
    format!(
        "{what} is off by {} (relative), more than this part's tolerance of {}: give more significant figures",
        percent(gap),
        tolerance_text(tolerance)
    )
}

/// A relative amount as a percentage to three significant digits: `0.104%`, `12.3%`.
pub fn percent(x: f64) -> String {
    let pct = x * 100.0;
    if !pct.is_finite() || pct <= 0.0 {
        return format!("{pct}%");
    }
    let decimals = (2 - pct.log10().floor() as i32).clamp(0, 12) as usize;
    format!("{pct:.decimals$}%")
}

/// A part's tolerance as the problem file writes it, with its percentage where that reads
/// (`1e-3 (0.1%)`; `1e-9` alone).
pub fn tolerance_text(tolerance: f64) -> String {
    if tolerance >= 1e-6 {
        format!(
            "{tolerance:e} ({}%)",
            super::compare::fmt_value(tolerance * 100.0)
        )
    } else {
        format!("{tolerance:e}")
    }
}

/// The largest relative difference of `a` from `b` (the reference) over the sample points
/// where both are defined: |a − b| / max(|a|, |b|).
pub fn relative_gap(p: &Prepared, a: Id, b: Id) -> Option<f64> {
    let vals = super::compare::values(&p.system, &[a, b], &p.points).ok()?;
    let mut worst: Option<f64> = None;
    for v in vals.iter().flatten() {
        let (x, y) = (v[0], v[1]);
        let scale = x.abs().max(y.abs());
        if !x.is_finite() || !y.is_finite() || scale <= tolerance::TINY {
            continue;
        }
        let e = (x - y).abs() / scale;
        worst = Some(worst.map_or(e, |w: f64| w.max(e)));
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::how_far_off;

    #[test]
    fn a_wrong_value_is_said_in_a_few_words_however_far_off() {
        for (f, said) in [
            (0.27, "about 73% too small"),
            (2.4, "about 140% too large"),
            (1.0005, "about 0.05% too large"),
        ] {
            assert_eq!(how_far_off(f), said, "{f}");
        }
        // A huge ratio (a student's 1e300) is a factor, not a 300-digit percentage.
        let huge = how_far_off(1e300);
        assert!(
            huge.starts_with("about ") && huge.ends_with(" times the right value"),
            "{huge}"
        );
        assert!(huge.len() < 60, "{huge}");
        assert_eq!(how_far_off(f64::INFINITY), "far off");
    }
}

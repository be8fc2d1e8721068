//! Why a list item is wrong: for an item that matched no reference item, the slip that
//! explains it — ω² for ω, f = ω/2π, a period, rounded constants, a factor (√2) or a sign under
//! the root, the same item listed twice — or that it is wrong, extra or missing.

use std::f64::consts::TAU;

use super::compare::{close, values};
use super::diagnose::{bare_numbers_for, has_decimal, near_miss, nice_fraction, student_numbers};
use super::prepare::Prepared;
use super::prepare::same_coordinate_within;
use super::terms::{Scaling, Terms, one_term};
use super::tolerance;
use super::verdict::{Code, Diagnosis};
use crate::expr::{Dimension, Id};
use crate::problem::{Part, PartKind, Problem};

mod point_sign;

/// Whether two items agree at every point where the reference one is defined (to `tol`;
/// equilibrium angles modulo 2π).
pub(super) fn same_item(
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
            // One relative tolerance for every kind: the part's (π + 1e-6 is not π).
            let ok = if periodic {
                same_coordinate_within(true, *u, *w, tol)
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

/// An item (or the lack of one) that matched no reference item, with its label
/// (`item 2 (…)`).
pub(super) enum ItemFinding {
    /// ω² for ω (`squared`: the square of an ω² for ω²).
    Squared { label: String, squared: bool },
    /// ω for ω² (`squared`), or √ω for ω.
    Root { label: String, squared: bool },
    /// Agreement to a few digits only; with the student's numbers, how far off (relative) and
    /// the part's tolerance.
    Rounded {
        label: String,
        off: Option<(f64, f64)>,
    },
    /// f = ω/2π for ω.
    Ordinary { label: String },
    /// A period 2π/ω for ω.
    Period { label: String },
    /// A finding inside the item (a sign under the root, a constant factor).
    Inside(Diagnosis),
    /// A frequency of the wrong dimension.
    Dimension {
        label: String,
        have: Dimension,
        want: Dimension,
    },
    /// Matches nothing while a reference item is unmatched.
    Wrong { label: String },
    /// The same item as one already matched (θ = −π after θ = π): listed twice.
    Twice { label: String, periodic: bool },
    /// One item too many (`equilibrium`: the part asks for equilibria).
    Extra {
        label: String,
        equilibrium: bool,
        what: &'static str,
    },
    /// `count` reference items were not given.
    Missing { count: usize, what: &'static str },
}

impl ItemFinding {
    /// The sentence for a finding.
    pub(super) fn details(self) -> Diagnosis {
        match self {
            ItemFinding::Squared { label, squared } => Diagnosis::new(
                Code::OmegaSquared,
                if squared {
                    format!("{label} is the square of an ω²: this part asks for ω², square it back")
                } else {
                    format!(
                        "{label} is the square of a frequency, but this part asks for the frequency itself: take the square root"
                    )
                },
            ),
            ItemFinding::Root { label, squared } => Diagnosis::new(
                Code::OmegaRoot,
                if squared {
                    format!("{label} is a frequency, but this part asks for its square: square it")
                } else {
                    format!("{label} is √ω: square it")
                },
            ),
            ItemFinding::Rounded {
                label,
                off: Some((gap, tolerance)),
            } => Diagnosis::new(Code::RoundedConstant, near_miss(&label, gap, tolerance)),
            ItemFinding::Rounded { label, off: None } => Diagnosis::new(
                Code::RoundedConstant,
                format!(
                    "{label} agrees only to a few significant digits: write exact constants such as sqrt(2), pi or 1/3"
                ),
            ),
            ItemFinding::Ordinary { label } => Diagnosis::new(
                Code::OrdinaryFrequency,
                format!(
                    "{label} is an ordinary frequency f = ω/2π (cycles per unit time), but the angular frequency ω is asked: multiply by 2π"
                ),
            ),
            ItemFinding::Period { label } => Diagnosis::new(
                Code::Period,
                format!(
                    "{label} is a period T = 2π/ω, but a frequency is asked: the angular frequency is 2π/T"
                ),
            ),
            ItemFinding::Inside(d) => d,
            ItemFinding::Dimension { label, have, want } => Diagnosis::new(
                Code::Dimension,
                format!("{label} has dimension {have}, but a frequency is {want}"),
            ),
            ItemFinding::Wrong { label } => {
                Diagnosis::new(Code::WrongItem, format!("{label} is wrong"))
            }
            ItemFinding::Twice { label, periodic } => Diagnosis::new(
                Code::ExtraItem,
                format!(
                    "{label} is listed twice: it is the same as another item you gave{}",
                    if periodic {
                        " (angles that differ by 2π are one position)"
                    } else {
                        ""
                    }
                ),
            ),
            ItemFinding::Extra {
                label,
                equilibrium: true,
                ..
            } => Diagnosis::new(
                Code::ExtraItem,
                format!("one extra item: {label} is not an equilibrium"),
            ),
            ItemFinding::Extra { label, what, .. } => Diagnosis::new(
                Code::ExtraItem,
                format!("one extra item: {label} is not one of the {what} values asked for"),
            ),
            ItemFinding::Missing { count: 1, what } => {
                Diagnosis::new(Code::MissingItem, format!("one {what} is missing"))
            }
            ItemFinding::Missing { count, what } => Diagnosis::new(
                Code::MissingItem,
                format!("{count} {what} values are missing"),
            ),
        }
    }
}

/// The values of a list: the student's and the reference's items at every point.
pub(super) struct Lists<'v> {
    pub(super) student: &'v [Vec<Option<Vec<f64>>>],
    pub(super) reference: &'v [Vec<Option<Vec<f64>>>],
    /// The reference items themselves (for the term-level search inside an item).
    pub(super) reference_ids: &'v [Vec<Id>],
    /// The student's items themselves (one id per coordinate of an equilibrium).
    pub(super) student_ids: &'v [Vec<Id>],
}

/// For a frequency that matches nothing: ω² for ω, ω for ω², rounded constants (only for an
/// item with a decimal), f = ω/2π, a period. Takes the
/// reference item it explains out of `free`.
fn frequency_slip(
    part: &Part,
    p: &Prepared,
    (s, decimal): (&[Option<Vec<f64>>], bool),
    rv: &[Vec<Option<Vec<f64>>>],
    free: &mut Vec<usize>,
    label: &str,
) -> Option<ItemFinding> {
    let tol = part.tolerance;
    // ω² for ω, or ω for ω².
    let squared_of = |a: &[Option<Vec<f64>>], b: &[Option<Vec<f64>>]| {
        let sq: Vec<Option<Vec<f64>>> = b
            .iter()
            .map(|x| x.as_ref().map(|v| v.iter().map(|y| y * y).collect()))
            .collect();
        same_item(part, p, a, &sq, tol)
    };
    // The item against a function of a reference item (ω/2π, 2π/ω).
    let mapped = |a: &[Option<Vec<f64>>], b: &[Option<Vec<f64>>], f: &dyn Fn(f64) -> f64| {
        let fb: Vec<Option<Vec<f64>>> = b
            .iter()
            .map(|x| x.as_ref().map(|v| v.iter().map(|y| f(*y)).collect()))
            .collect();
        same_item(part, p, a, &fb, tol)
    };
    let label = label.to_string();
    let squared = part.squared;
    let (k, finding) = if let Some(k) = free.iter().position(|&j| squared_of(s, &rv[j])) {
        (k, ItemFinding::Squared { label, squared })
    } else if let Some(k) = free.iter().position(|&j| squared_of(&rv[j], s)) {
        (k, ItemFinding::Root { label, squared })
    } else if let Some(k) = free
        .iter()
        .position(|&j| decimal && same_item(part, p, s, &rv[j], tolerance::ROUNDED))
    {
        let off = near_miss_of(part, p, s, &rv[free[k]]);
        (k, ItemFinding::Rounded { label, off })
    } else if let Some(k) = (!squared)
        .then(|| free.iter().position(|&j| mapped(s, &rv[j], &|w| w / TAU)))
        .flatten()
    {
        (k, ItemFinding::Ordinary { label })
    } else if let Some(k) = (!squared)
        .then(|| free.iter().position(|&j| mapped(s, &rv[j], &|w| TAU / w)))
        .flatten()
    {
        (k, ItemFinding::Period { label })
    } else {
        return None;
    };
    free.remove(k);
    Some(finding)
}

/// Whether an item is the same as a reference item already matched (not in `free`).
fn listed_twice(
    part: &Part,
    p: &Prepared,
    s: &[Option<Vec<f64>>],
    reference: &[Vec<Option<Vec<f64>>>],
    free: &[usize],
) -> bool {
    (0..reference.len())
        .any(|j| !free.contains(&j) && same_item(part, p, s, &reference[j], part.tolerance))
}

/// Classifies student item `i`, which matched no reference item; `free` holds the reference
/// items not yet matched or explained.
pub(super) fn classify_unmatched(
    problem: &Problem,
    part: &Part,
    p: &mut Prepared,
    lists: &Lists,
    item: (usize, Id, String),
    free: &mut Vec<usize>,
) -> ItemFinding {
    let (i, first, label) = item;
    let decimal = has_decimal(p, first);
    if part.kind == PartKind::Frequencies
        && let Some(f) = frequency_slip(
            part,
            p,
            (&lists.student[i], decimal),
            lists.reference,
            free,
            &label,
        )
    {
        return f;
    }
    if let Some(k) = free.iter().position(|&j| {
        decimal
            && same_item(
                part,
                p,
                &lists.student[i],
                &lists.reference[j],
                tolerance::ROUNDED,
            )
    }) {
        let off = near_miss_of(part, p, &lists.student[i], &lists.reference[free[k]]);
        free.remove(k);
        return ItemFinding::Rounded { label, off };
    }
    // The same as an item already matched: not wrong, only listed twice.
    if listed_twice(part, p, &lists.student[i], lists.reference, free) {
        let periodic =
            part.kind == PartKind::Equilibria && p.system.coordinates.iter().any(|c| c.periodic);
        return ItemFinding::Twice { label, periodic };
    }
    // A point with a coordinate of the wrong sign (x = −m g sin α/k), or a sign slip in one
    // term of a coordinate (r = l₀ − m g/k), as a frequency's sign is told.
    if part.kind == PartKind::Equilibria
        && let Some((k, d)) = point_sign::sign_error(part, p, lists, i, free, &label)
    {
        free.remove(k);
        return ItemFinding::Inside(d);
    }
    if part.kind == PartKind::Frequencies
        && let Some((k, d)) = inside_item(p, (first, part.squared), lists, free, &label)
    {
        free.remove(k);
        return ItemFinding::Inside(d);
    }
    // An item of the wrong dimension says so.
    let want = match part.kind {
        // A numeric part's units were checked before its numbers were read.
        _ if part.units.is_some() => None,
        // A number carries no unit: an item judged with the student's numbers (the problem
        // pinned to them, without dimensions) has no dimension.
        _ if part.numbers && problem.dims.is_empty() => None,
        PartKind::Frequencies if part.squared => Some(Dimension::new(0, 0, -2)),
        PartKind::Frequencies => Some(Dimension::new(0, 0, -1)),
        _ => None,
    };
    let have = p.system.pool.dimension(first, &problem.dims).ok().flatten();
    // 0 has every dimension (a free motion's ω = 0).
    if let (Some(want), Some(have)) = (want, have)
        && want != have
        && !p.system.pool.is_zero(first)
    {
        if !free.is_empty() {
            free.remove(0);
        }
        return ItemFinding::Dimension { label, have, want };
    }
    if !free.is_empty() {
        free.remove(0);
        return ItemFinding::Wrong { label };
    }
    ItemFinding::Extra {
        label,
        equilibrium: part.kind == PartKind::Equilibria,
        what: what_of(part),
    }
}

/// Why a frequency is wrong, found inside it against one free reference item: it is off by
/// a constant factor (√2), or one of its terms differs — under the root for a root (a sign
/// under the root), or itself for ω² and for an item without a root. The index in `free` of
/// the item it explains, and the diagnosis.
fn inside_item(
    p: &mut Prepared,
    (item, squared): (Id, bool),
    lists: &Lists,
    free: &[usize],
    label: &str,
) -> Option<(usize, Diagnosis)> {
    let root = !squared && is_root(p, item);
    let mine = if root {
        p.system.pool.powi(item, 2)
    } else {
        item
    };
    let mine = p.system.pool.expand(mine);
    // The whole item (or all under its root) negated explains more than one term's sign.
    for (k, &j) in free.iter().enumerate() {
        let r = *lists.reference_ids.get(j)?.first()?;
        let theirs = if root { p.system.pool.powi(r, 2) } else { r };
        if negated(p, mine, theirs) {
            let place = if root {
                "everything under the square root"
            } else {
                "the whole value"
            };
            let message = format!("{label}: sign error: {place} has the wrong sign");
            return Some((k, Diagnosis::new(Code::SignError, message)));
        }
    }
    let st = Terms::of_expression(p, mine);
    for (k, &j) in free.iter().enumerate() {
        let r = *lists.reference_ids.get(j)?.first()?;
        if let Some(d) = factor_of_item(p, item, r, label) {
            return Some((k, d));
        }
        let theirs = if root { p.system.pool.powi(r, 2) } else { r };
        let theirs = p.system.pool.expand(theirs);
        let rt = Terms::of_expression(p, theirs);
        let which = if root { "the square" } else { "it" };
        // Only what a term says plainly: a sign, a term too many. A factor between two whole
        // items would relate any two numbers, and a missing term of constants cannot be
        // described without giving it away.
        if let Some(d) = one_term(p, &st, &rt, Scaling::None, which)
            .filter(|d| d.code == Code::SignError || (d.code == Code::ExtraTerm && rt.len() > 1))
        {
            let place = if root { ", under the square root" } else { "" };
            let message = format!("{label}{place}: {}", d.message);
            return Some((k, Diagnosis::new(d.code, message)));
        }
    }
    None
}

/// Whether `a = −b` at every sample point where both are defined (and at some point).
fn negated(p: &Prepared, a: Id, b: Id) -> bool {
    let Ok(vals) = values(&p.system, &[a, b], &p.points) else {
        return false;
    };
    let mut seen = 0;
    for v in vals.iter().flatten() {
        let (x, y) = (v[0], v[1]);
        if !x.is_finite() || !y.is_finite() {
            continue;
        }
        if y.abs() <= tolerance::TINY || !close(x, -y, 0.0, tolerance::SAME) {
            return false;
        }
        seen += 1;
    }
    seen > 0
}

/// Whether `e` is a square root.
fn is_root(p: &Prepared, e: Id) -> bool {
    let half = |x: Id| matches!(p.system.pool.node(x), crate::expr::Node::Num(q) if *q == num_rational::BigRational::new(1.into(), 2.into()));
    match p.system.pool.node(e) {
        crate::expr::Node::Pow(_, x) => half(*x),
        _ => false,
    }
}

/// An item that is a simple constant times the reference item, or the root of one (√2).
fn factor_of_item(p: &Prepared, item: Id, r: Id, label: &str) -> Option<Diagnosis> {
    // Bare numbers have a ratio to any value: 2.335 is no "√(2/3) times" the right one.
    if bare_numbers_for(p, item, r) {
        return None;
    }
    let vals = values(&p.system, &[item, r], &p.points).ok()?;
    let ratios: Vec<f64> = vals
        .into_iter()
        .flatten()
        .filter(|v| v[1].abs() > tolerance::ZERO)
        .map(|v| v[0] / v[1])
        .collect();
    let c = *ratios.first()?;
    if ratios.len() < 2
        || !ratios.iter().all(|x| close(*x, c, 0.0, tolerance::NUMBER))
        || (c.abs() - 1.0).abs() < tolerance::ROUNDED
    {
        return None;
    }
    let text = match (nice_fraction(c), nice_fraction(c * c)) {
        (Some(n), _) => n,
        (None, Some(q)) if c > 0.0 && q.chars().all(|x| x.is_ascii_digit()) => format!("√{q}"),
        (None, Some(q)) if c > 0.0 => format!("√({q})"),
        _ => return None,
    };
    Some(Diagnosis::new(
        Code::ConstantFactor,
        format!("{label} is {text} times a right value: check the numerical factors"),
    ))
}

/// What the items of a part are called.
pub(super) fn what_of(part: &Part) -> &'static str {
    match part.kind {
        PartKind::Equilibria => "equilibrium",
        PartKind::Frequencies => "frequency",
        _ => "item",
    }
}

/// How far off (relative, the worst coordinate at the worst point) an item is from the
/// reference item it nearly matches, with the part's tolerance: said only where the part is
/// judged with the student's numbers (a decimal is then the answer, not the mistake).
fn near_miss_of(
    part: &Part,
    p: &Prepared,
    s: &[Option<Vec<f64>>],
    r: &[Option<Vec<f64>>],
) -> Option<(f64, f64)> {
    if !part.numbers || !student_numbers(p) {
        return None;
    }
    let mut worst: f64 = 0.0;
    for (x, y) in s.iter().zip(r) {
        let (Some(x), Some(y)) = (x, y) else { continue };
        for (u, w) in x.iter().zip(y) {
            let scale = u.abs().max(w.abs());
            if scale > tolerance::TINY {
                worst = worst.max((u - w).abs() / scale);
            }
        }
    }
    Some((worst, part.tolerance))
}

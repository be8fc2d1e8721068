//! Why a wrong expression (T, V, L, a momentum, h…) is wrong: the search for the mistake
//! after the comparison with the reference found nothing simple — the wrong quantity given
//! (T + V for L, L for h), a term-level difference in the student's own terms, a small-angle
//! form, a limit in which it is right — falling back to where it differs.

use super::common::state_text;
use super::compare::{Relation, fmt_value, relate, values};
use super::diagnose::{factor_in_term, rounded, sign_in_term, swapped};
use super::limits;
use super::prepare::Prepared;
use super::terms::{Scaling, Terms, one_term};
use super::tolerance;
use super::verdict::{Code, Diagnosis, Verdict};
use crate::expr::Id;
use crate::problem::{Part, PartKind, Quantity};

/// A mistake the search behind a wrong expression found.
enum Mistake {
    /// T + V where the Lagrangian T − V is asked.
    PlusForLagrangian,
    /// T + V where the energy function h (not T + V here) is asked; `moving` when T is not a
    /// quadratic form in the velocities (terms linear in them, or none: the frame moves).
    PlusForEnergy { moving: bool },
    /// The Lagrangian where `what` is asked.
    GaveLagrangian { what: &'static str },
    /// Found by one of the shared searches (rounding, swapped symbols, a term).
    Found(Diagnosis),
    /// Off by the constant `c`.
    Constant(f64),
    /// Yours is `yours` at sample `point` where it should be `want`; `vars` are the variables
    /// the two expressions use (the only ones worth showing).
    DiffersAt {
        point: usize,
        yours: f64,
        want: f64,
        vars: Vec<(crate::expr::Sym, u8)>,
    },
    /// No more to say.
    NotEqual,
}

impl Mistake {
    /// The sentence for a mistake.
    fn details(self, p: &Prepared) -> Diagnosis {
        match self {
            Mistake::PlusForLagrangian => {
                Diagnosis::new(Code::TPlusV, "you wrote T + V; the Lagrangian is L = T − V")
            }
            Mistake::PlusForEnergy { moving: true } => Diagnosis::new(
                Code::TPlusV,
                "you wrote T + V, but here h = Σ q̇ ∂L/∂q̇ − L is not T + V: T is not a quadratic form in the velocities (the frame moves), so compute h from its definition",
            ),
            Mistake::PlusForEnergy { moving: false } => Diagnosis::new(
                Code::TPlusV,
                "you wrote T + V, but here h = Σ q̇ ∂L/∂q̇ − L is not T + V, so compute h from its definition",
            ),
            Mistake::GaveLagrangian { what } => Diagnosis::new(
                Code::GaveLagrangian,
                format!("that is the Lagrangian L; this part asks for {what}"),
            ),
            Mistake::Found(d) => d,
            Mistake::Constant(c) => Diagnosis::new(
                Code::NotEqual,
                format!(
                    "your answer differs from the right one by the constant {}",
                    fmt_value(c)
                ),
            ),
            Mistake::DiffersAt {
                point,
                yours,
                want,
                vars,
            } => Diagnosis::new(
                Code::NotEqual,
                format!(
                    "not equal to the expected answer: at {}, yours is {} but it should be {}",
                    state_text(p, &p.points.points[point], Some(&vars)),
                    fmt_value(yours),
                    fmt_value(want)
                ),
            ),
            Mistake::NotEqual => Diagnosis::new(Code::NotEqual, "not equal to the expected answer"),
        }
    }
}

/// T + V, or the Lagrangian, given for another quantity.
fn wrong_quantity(part: &Part, p: &mut Prepared, s: Id) -> Vec<Mistake> {
    let eq_const = |p: &mut Prepared, cand: Id| {
        matches!(
            relate(&p.system, s, cand, &p.points, tolerance::SAME),
            Ok(Relation::Equal | Relation::UpToConstant(_))
        )
    };
    let mut out = Vec::new();
    if let (Some(t), Some(v)) = (p.system.kinetic, p.system.potential) {
        let tv = p.system.pool.add(t, v);
        if part.kind == PartKind::Lagrangian && eq_const(p, tv) {
            out.push(Mistake::PlusForLagrangian);
        }
        if part.quantity == Quantity::EnergyFunction && eq_const(p, tv) {
            let moving = not_quadratic(p, t);
            out.push(Mistake::PlusForEnergy { moving });
        }
    }
    let what = match part.quantity {
        Quantity::Kinetic => "the kinetic energy T",
        Quantity::Potential => "the potential energy V",
        Quantity::EnergyFunction => "the energy function h",
        Quantity::Momentum(_) => "the momentum",
        _ => return out,
    };
    if eq_const(p, p.system.lagrangian) {
        out.push(Mistake::GaveLagrangian { what });
    }
    out
}

/// Whether the kinetic energy `t` is not a quadratic form in the velocities: at rest (every
/// velocity 0) it, or its slope in some velocity, does not vanish at some sample point. A
/// frame that moves (a spinning wire, a rotating frame) gives such terms; a fixed one never.
fn not_quadratic(p: &mut Prepared, t: Id) -> bool {
    let coords = p.system.coordinate_syms();
    let zero = p.system.pool.zero();
    let rest: rustc_hash::FxHashMap<_, Id> = coords.iter().map(|&c| ((c, 1), zero)).collect();
    let mut at_rest = vec![t, p.system.pool.substitute(t, &rest)];
    for &c in &coords {
        let slope = p.system.pool.diff(t, c, 1);
        at_rest.push(p.system.pool.substitute(slope, &rest));
    }
    let Ok(vals) = values(&p.system, &at_rest, &p.points) else {
        return true;
    };
    // Relative to T itself at the same point, so that the scale of the masses does not
    // decide.
    vals.iter().flatten().any(|x| {
        x[1..]
            .iter()
            .any(|y| y.abs() > tolerance::SAME * (x[0].abs() + tolerance::TINY))
    })
}

/// Rounded constants, one term that differs (a sign, a factor, a wrong factor inside, a term
/// missing or extra), swapped symbols. A sign error in one term is said before a swap that
/// happens to repair it; the older whole-expression searches run only when the term matching
/// found nothing.
fn term_mistakes(p: &mut Prepared, s: Id, reference: Id) -> Vec<Mistake> {
    let eq = |p: &mut Prepared, cand: Id| {
        super::compare::equal(&p.system, cand, reference, &p.points, tolerance::SAME)
    };
    if let Some(d) = rounded(p, s, reference) {
        return vec![Mistake::Found(d)];
    }
    let (st, rt) = (
        Terms::of_expression(p, s),
        Terms::of_expression(p, reference),
    );
    let term = one_term(p, &st, &rt, Scaling::None, "your answer");
    if let Some(d) = term.as_ref().filter(|d| d.code == Code::SignError) {
        return vec![Mistake::Found(d.clone())];
    }
    let mut found = Vec::new();
    found.extend(swapped(p, s, &mut |p, c| eq(p, c)));
    if let Some(d) = term {
        found.push(d);
        return found.into_iter().map(Mistake::Found).collect();
    }
    found.extend(sign_in_term(p, s, &mut |p, c| eq(p, c)));
    let mut factor_at = |p: &mut Prepared, t: Id| -> Option<f64> {
        let vals = values(&p.system, &[s, reference, t], &p.points).ok()?;
        let x = vals
            .into_iter()
            .flatten()
            .find(|x| x[2].abs() > tolerance::ZERO)?;
        Some(1.0 + (x[1] - x[0]) / x[2])
    };
    found.extend(factor_in_term(p, s, &mut factor_at, &mut |p, c| eq(p, c)));
    found.into_iter().map(Mistake::Found).collect()
}

/// What is left to say when no mistake was found.
fn unexplained(p: &Prepared, s: Id, reference: Id, rel: Relation) -> Mistake {
    match rel {
        Relation::UpToConstant(c) => Mistake::Constant(c),
        Relation::Different { point } => {
            let vals = values(&p.system, &[s, reference], &p.points).ok();
            match vals.and_then(|x| x.get(point).cloned().flatten()) {
                Some(x) => {
                    let mut vars = p.system.pool.variables(s);
                    vars.extend(p.system.pool.variables(reference));
                    Mistake::DiffersAt {
                        point,
                        yours: x[0],
                        want: x[1],
                        vars,
                    }
                }
                None => Mistake::NotEqual,
            }
        }
        _ => Mistake::NotEqual,
    }
}

/// Searches for the mistake behind a wrong expression and adds its sentences to `v`.
pub(super) fn diagnose_expression(
    part: &Part,
    p: &mut Prepared,
    s: Id,
    reference: Id,
    rel: Relation,
    v: &mut Verdict,
) {
    let mut mistakes = wrong_quantity(part, p, s);
    match limits::small_angle(part, p, s, reference) {
        Some(d) => mistakes.push(Mistake::Found(d)),
        None => mistakes.extend(term_mistakes(p, s, reference)),
    }
    // A limit is the last resort; the literature's detectors (`super::misconception`) run
    // once this whole diagnosis is done, and name the principle when one applies.
    if mistakes.is_empty()
        && let Some(d) = limits::right_in_limit(p, s, reference)
    {
        mistakes.push(Mistake::Found(d));
    }
    if mistakes.is_empty() {
        mistakes.push(unexplained(p, s, reference, rel));
    }
    v.diagnoses
        .extend(mistakes.into_iter().map(|m| m.details(p)));
    super::misconception::expression(part, p, s, reference, v);
}

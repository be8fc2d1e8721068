//! `check(problem, part, input)`: read the answer, compare it with the reference by the
//! part's kind, and diagnose a wrong one. Expressions and equations live here; unordered lists
//! in `lists.rs`.

use rustc_hash::FxHashMap;

use super::common::{at_rest, invalid_reading, point_text, verdict};
use super::compare::{Relation, fmt_value, relate, values};
use super::diagnose::{factor_in_term, nice_fraction, rounded, sign_in_term, swapped};
use super::error::CheckError;
use super::prepare::{Prepared, prepare};
use super::tolerance;
use super::verdict::{Code, Diagnosis, ReadAs, Status, Verdict};
use super::{equations, lists};
use crate::expr::{Id, Reading, read, read_expr};
use crate::problem::{Part, PartKind, Problem, Quantity};

/// Checks answers to one problem, preparing each part once.
pub struct Checker<'a> {
    problem: &'a Problem,
    prepared: FxHashMap<String, Prepared>,
}

impl<'a> Checker<'a> {
    /// A checker for `problem`.
    pub fn new(problem: &'a Problem) -> Self {
        Checker {
            problem,
            prepared: FxHashMap::default(),
        }
    }

    /// Checks `input` against part `part_id`. Errors are usage errors (no such part, a part
    /// that cannot be prepared), never a judgement of the input.
    pub fn check(&mut self, part_id: &str, input: &str) -> Result<Verdict, CheckError> {
        let part = self
            .problem
            .part(part_id)
            .ok_or_else(|| CheckError::UnknownPart {
                problem: self.problem.id.clone(),
                part: part_id.to_string(),
            })?;
        let p = match self.prepared.entry(part_id.to_string()) {
            std::collections::hash_map::Entry::Occupied(o) => o.into_mut(),
            std::collections::hash_map::Entry::Vacant(v) => v.insert(prepare(self.problem, part)?),
        };
        Ok(check_prepared(self.problem, part, p, input))
    }
}

/// Checks one answer (preparing the part afresh; use [`Checker`] for many answers).
pub fn check(problem: &Problem, part: &Part, input: &str) -> Result<Verdict, CheckError> {
    let mut p = prepare(problem, part)?;
    Ok(check_prepared(problem, part, &mut p, input))
}

/// Checks against a prepared part.
pub fn check_prepared(problem: &Problem, part: &Part, p: &mut Prepared, input: &str) -> Verdict {
    let mut v = match part.kind {
        PartKind::Equilibria | PartKind::Frequencies | PartKind::Values => {
            lists::check_list(problem, part, p, input)
        }
        _ => match read(input, &p.context, &mut p.system.pool) {
            Err(e) => invalid_reading(problem, part, e),
            Ok(r) => match part.kind {
                PartKind::Equation | PartKind::Equations => {
                    equations::check_equations(problem, part, p, r)
                }
                _ => check_expression(problem, part, p, r),
            },
        },
    };
    v.sort();
    v
}

fn check_expression(problem: &Problem, part: &Part, p: &mut Prepared, r: Reading) -> Verdict {
    let s = match r {
        Reading::Expr(e, _) => e,
        Reading::Equation { .. } => {
            let mut v = verdict(problem, part, Status::Invalid);
            v.diagnoses.push(Diagnosis::new(
                Code::WrongKind,
                "this part asks for an expression, not an equation",
            ));
            return v;
        }
        Reading::List(..) | Reading::System(..) => {
            let mut v = verdict(problem, part, Status::Invalid);
            v.diagnoses.push(Diagnosis::new(
                Code::WrongKind,
                "this part asks for one expression, not a list",
            ));
            return v;
        }
    };
    let mut v = verdict(problem, part, Status::Incorrect);
    v.reading = ReadAs {
        plain: p.system.pool.plain(s),
        unicode: p.system.pool.unicode(s),
        note: None,
    };
    let reference = match p.reference.get() {
        Some(r) => r.first().and_then(|x| x.first()).copied().ok_or(()),
        None => {
            let r = read_expr(&part.answers[0], &p.context, &mut p.system.pool).map_err(|_| ());
            r.inspect(|&id| {
                p.reference.get_or_init(|| vec![vec![id]]);
            })
        }
    };
    let Ok(reference) = reference else {
        v.status = Status::Invalid;
        v.diagnoses.push(Diagnosis::new(
            Code::Syntax,
            "the reference answer of this part cannot be read",
        ));
        return v;
    };
    // Dimensions: a sum of unlike terms, or a different dimension from the reference.
    match p.system.pool.dimension(s, &problem.dims) {
        Err(e) => v
            .diagnoses
            .push(Diagnosis::new(Code::Dimension, e.to_string())),
        Ok(Some(ds)) => {
            if let Ok(Some(dr)) = p.system.pool.dimension(reference, &problem.dims)
                && ds != dr
                && !p.system.pool.is_zero(s)
            {
                v.diagnoses.push(Diagnosis::new(
                    Code::Dimension,
                    format!("your answer has dimension {ds}, but the answer must be {dr}"),
                ));
            }
        }
        Ok(None) => {}
    }
    let rel = match relate(&p.system, s, reference, &p.points, part.tolerance) {
        Ok(r) => r,
        Err(e) => {
            v.diagnoses
                .push(Diagnosis::new(Code::NotEqual, e.to_string()));
            return v;
        }
    };
    let lagrangian = part.kind == PartKind::Lagrangian;
    match rel {
        Relation::Equal => v.status = Status::Correct,
        Relation::UpToConstant(_) if part.up_to_constant || lagrangian => {
            v.status = Status::Correct;
            v.diagnoses.push(Diagnosis::new(Code::UpToConstant,
                "your answer differs from the reference by a constant; that is allowed here (the zero of potential energy is a free choice)",
            ));
        }
        Relation::Factor(f) if lagrangian => {
            v.status = Status::Correct;
            v.diagnoses.push(Diagnosis::new(Code::EquivalentLagrangian,
                format!("your L is {} times the reference; a constant factor gives the same equations of motion", nice_fraction(f).unwrap_or_else(|| fmt_value(f))),
            ));
        }
        Relation::Factor(f)
            if (f - 1.0).abs() < tolerance::ROUNDED && rounded(p, s, reference).is_some() =>
        {
            if let Some(d) = rounded(p, s, reference) {
                v.diagnoses.push(d);
            }
        }
        Relation::Factor(f) if (f + 1.0).abs() < tolerance::NUMBER => {
            v.diagnoses.push(Diagnosis::new(
                Code::SignError,
                "sign error: your answer is the negative of the right one",
            ));
        }
        Relation::Factor(f) => v.diagnoses.push(Diagnosis::new(
            Code::ConstantFactor,
            match nice_fraction(f) {
                Some(n) => format!(
                    "your answer is {n} times the right one: check the numerical factors (a ½, a 2)"
                ),
                None => format!(
                    "your answer is off by a constant factor of about {}",
                    fmt_value(f)
                ),
            },
        )),
        Relation::Undefined { point } => v.diagnoses.push(Diagnosis::new(
            Code::Undefined,
            format!(
                "your answer is undefined at {}, where the correct one is defined",
                point_text(p, point)
            ),
        )),
        Relation::UpToConstant(_) | Relation::Different { .. } => {
            if lagrangian && equivalent_lagrangian(p, s, reference) {
                v.status = Status::Correct;
                v.diagnoses.push(Diagnosis::new(Code::EquivalentLagrangian,
                    "your L differs from the reference by a total time derivative (or a constant); it gives the same equations of motion",
                ));
            } else {
                diagnose_expression(part, p, s, reference, rel, &mut v);
            }
        }
    }
    if v.status == Status::Correct {
        v.score = 1.0;
        v.diagnoses
            .retain(|d| matches!(d.code, Code::UpToConstant | Code::EquivalentLagrangian));
    }
    v
}

/// Same Euler–Lagrange equations (up to a nonzero factor) for two Lagrangians.
fn equivalent_lagrangian(p: &mut Prepared, a: Id, b: Id) -> bool {
    let coords = p.system.coordinate_syms();
    let mut ea = Vec::new();
    let mut eb = Vec::new();
    for &c in &coords {
        for (l, out) in [(a, &mut ea), (b, &mut eb)] {
            let pm = p.system.pool.diff(l, c, 1);
            let dp = p.system.pool.dt(pm, &coords);
            let dl = p.system.pool.diff(l, c, 0);
            out.push(p.system.pool.sub(dp, dl));
        }
    }
    let mut factor: Option<f64> = None;
    for (x, y) in ea.into_iter().zip(eb) {
        match relate(&p.system, x, y, &p.points, tolerance::SAME) {
            Ok(Relation::Equal) => factor = factor.or(Some(1.0)),
            Ok(Relation::Factor(f)) => {
                if factor.is_some_and(|g| (g - f).abs() > tolerance::NUMBER * f.abs()) {
                    return false;
                }
                factor = Some(f);
            }
            _ => return false,
        }
    }
    true
}

fn diagnose_expression(
    part: &Part,
    p: &mut Prepared,
    s: Id,
    reference: Id,
    rel: Relation,
    v: &mut Verdict,
) {
    let eq = |p: &mut Prepared, cand: Id| {
        relate(&p.system, cand, reference, &p.points, tolerance::SAME).ok() == Some(Relation::Equal)
    };
    let eq_const = |p: &mut Prepared, cand: Id, r: Id| {
        matches!(
            relate(&p.system, cand, r, &p.points, tolerance::SAME),
            Ok(Relation::Equal | Relation::UpToConstant(_))
        )
    };
    let before = v.diagnoses.len();
    let sys = &p.system;
    let (t, vv) = (sys.kinetic, sys.potential);
    if part.kind == PartKind::Lagrangian
        && let (Some(t), Some(vv)) = (t, vv)
    {
        let tv = p.system.pool.add(t, vv);
        if eq_const(p, s, tv) {
            v.diagnoses.push(Diagnosis::new(
                Code::TPlusV,
                "you wrote T + V; the Lagrangian is L = T − V",
            ));
        }
    }
    if part.quantity == Quantity::EnergyFunction
        && let (Some(t), Some(vv)) = (t, vv)
    {
        let tv = p.system.pool.add(t, vv);
        if eq_const(p, s, tv) {
            v.diagnoses.push(Diagnosis::new(Code::TPlusV,
                "you wrote T + V, but here h = Σ q̇ ∂L/∂q̇ − L is not T + V: T is not a quadratic form in the velocities (the frame moves), so compute h from its definition",
            ));
        }
    }
    if matches!(
        part.quantity,
        Quantity::Kinetic | Quantity::Potential | Quantity::EnergyFunction | Quantity::Momentum(_)
    ) {
        let l = p.system.lagrangian;
        if eq_const(p, s, l) {
            let what = match part.quantity {
                Quantity::Kinetic => "the kinetic energy T",
                Quantity::Potential => "the potential energy V",
                Quantity::EnergyFunction => "the energy function h",
                _ => "the momentum",
            };
            v.diagnoses.push(Diagnosis::new(
                Code::GaveLagrangian,
                format!("that is the Lagrangian L; this part asks for {what}"),
            ));
        }
    }
    if let Some(d) = rounded(p, s, reference) {
        v.diagnoses.push(d);
    }
    if let Some(d) = swapped(p, s, &mut |p, c| eq(p, c)) {
        v.diagnoses.push(d);
    }
    if let Some(d) = sign_in_term(p, s, &mut |p, c| eq(p, c)) {
        v.diagnoses.push(d);
    }
    let mut factor_at = |p: &mut Prepared, t: Id| -> Option<f64> {
        let vals = values(&p.system, &[s, reference, t], &p.points).ok()?;
        let x = vals
            .into_iter()
            .flatten()
            .find(|x| x[2].abs() > tolerance::ZERO)?;
        Some(1.0 + (x[1] - x[0]) / x[2])
    };
    if let Some(d) = factor_in_term(p, s, &mut factor_at, &mut |p, c| eq(p, c)) {
        v.diagnoses.push(d);
    }
    // Velocity-dependent terms: equal when every velocity is zero.
    if v.diagnoses.len() == before
        && let Some(still) = at_rest(p)
        && relate(&p.system, s, reference, &still, tolerance::SAME).ok() == Some(Relation::Equal)
        && !p.system.pool.variables(reference).iter().all(|x| x.1 == 0)
    {
        v.diagnoses.push(Diagnosis::new(Code::VelocityTerm,
            "your answer is right when nothing moves, so the mistake is in a velocity-dependent term (a missing or wrong q'² or q'₁q'₂ term)",
        ));
    }
    if v.diagnoses.len() == before {
        let msg = match rel {
            Relation::UpToConstant(c) => format!(
                "your answer differs from the right one by the constant {}",
                fmt_value(c)
            ),
            Relation::Different { point } => {
                let vals = values(&p.system, &[s, reference], &p.points).ok();
                let at = vals.and_then(|x| x.get(point).cloned().flatten());
                match at {
                    Some(x) => format!(
                        "not equal to the expected answer: at {}, yours is {} but it should be {}",
                        point_text(p, point),
                        fmt_value(x[0]),
                        fmt_value(x[1])
                    ),
                    None => "not equal to the expected answer".into(),
                }
            }
            _ => "not equal to the expected answer".into(),
        };
        v.diagnoses.push(Diagnosis::new(Code::NotEqual, msg));
    }
}

//! Verification of expression and equation parts: an expression against the truth the engine
//! derives (symbolic, or numbers per point for accelerations and multipliers), and equations
//! of motion or a condition at rest against the derivation.

use super::FindingCode;
use super::verify_failed::{Check, Failed, check_dimension, expected_dimension};
use crate::check::compare::{Relation, close, relate, values};
use crate::check::equations::equations_hold;
use crate::check::prepare::{Prepared, read_one, residuals};
use crate::check::tolerance;
use crate::expr::{Id, Style, read_expr};
use crate::mechanics::accel::Dynamics;
use crate::problem::{Part, PartKind, Problem, Quantity};

/// The truth of an expression part: a symbolic expression, or numbers per point.
enum Truth {
    Expr(Id),
    Numbers(Vec<Option<f64>>),
}

fn truth(part: &Part, p: &mut Prepared) -> Result<Option<Truth>, Failed> {
    let sys = &mut p.system;
    let d = &p.derivation;
    Ok(Some(match part.quantity {
        Quantity::Kinetic => Truth::Expr(sys.kinetic.ok_or(Failed::new(
            FindingCode::NoTruth,
            "a kinetic part needs bodies (or T and V) to check against".to_string(),
        ))?),
        Quantity::Potential => Truth::Expr(sys.potential.ok_or(Failed::new(
            FindingCode::NoTruth,
            "a potential part needs bodies (or T and V) to check against".to_string(),
        ))?),
        Quantity::Lagrangian => Truth::Expr(sys.lagrangian),
        Quantity::Momentum(i) => Truth::Expr(d.steps[i].momentum),
        Quantity::EnergyFunction => Truth::Expr(sys.energy(d).function),
        Quantity::Multiplier(j) | Quantity::Acceleration(j) => {
            let rows = sys.constraint_rows();
            let dynamics = Dynamics::new(sys, d)
                .map_err(|e| Failed::new(FindingCode::Unusable, e.to_string()))?;
            let mut scratch = dynamics.scratch();
            let nums = p
                .points
                .points
                .iter()
                .map(|x| {
                    if sys.constraints.is_empty() {
                        dynamics.accelerations(x, &mut scratch).ok().map(|a| a[j])
                    } else {
                        sys.multipliers_at(d, &rows, x).ok().map(|(a, l)| {
                            if matches!(part.quantity, Quantity::Multiplier(_)) {
                                l[j]
                            } else {
                                a[j]
                            }
                        })
                    }
                })
                .collect();
            Truth::Numbers(nums)
        }
        Quantity::Cyclic | Quantity::None => return Ok(None),
    }))
}

/// Whether `answer` matches the truth (exactly, or up to a constant where allowed).
fn matches_truth(part: &Part, p: &mut Prepared, answer: Id, truth: &Truth) -> Result<bool, Failed> {
    match truth {
        Truth::Expr(t) => {
            let r = relate(&p.system, answer, *t, &p.points, part.tolerance)
                .map_err(|e| Failed::new(FindingCode::Sampling, e.to_string()))?;
            Ok(match r {
                Relation::Equal => true,
                Relation::UpToConstant(_) => {
                    part.up_to_constant || part.kind == PartKind::Lagrangian
                }
                _ => false,
            })
        }
        Truth::Numbers(nums) => {
            let vals = values(&p.system, &[answer], &p.points)
                .map_err(|e| Failed::new(FindingCode::Sampling, e.to_string()))?;
            let scale = nums.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
            Ok(nums.iter().zip(&vals).all(|(t, v)| match (t, v) {
                (Some(t), Some(v)) => close(v[0], *t, scale, part.tolerance),
                (None, _) => true,
                (Some(_), None) => false,
            }))
        }
    }
}

fn show_truth(p: &mut Prepared, t: &Truth) -> String {
    match t {
        Truth::Expr(e) => {
            let s = p.system.simplify(*e);
            p.system.pool.unicode(s)
        }
        Truth::Numbers(n) => format!(
            "{:.6} at the first sample",
            n.iter().flatten().next().copied().unwrap_or(f64::NAN)
        ),
    }
}

pub(super) fn verify_expression(problem: &Problem, part: &Part, p: &mut Prepared) -> Check {
    let answer = read_one(p, &part.answers[0])?;
    if part.units.is_none() {
        check_dimension(problem, p, answer, expected_dimension(problem, part))?;
    }
    let Some(t) = truth(part, p)? else {
        return Ok(());
    };
    if !matches_truth(part, p, answer, &t)? {
        return Err(Failed::new(
            FindingCode::WrongAnswer,
            format!(
                "the stated answer {} is not what the physics gives: {}",
                p.system.pool.unicode(answer),
                show_truth(p, &t)
            ),
        ));
    }
    for w in &part.wrong {
        let Ok(id) = read_expr(w, &p.context, &mut p.system.pool) else {
            continue;
        };
        if matches_truth(part, p, id, &t)? {
            return Err(Failed::new(
                FindingCode::WrongAccepted,
                format!("the `wrong` example `{w}` is in fact correct"),
            ));
        }
    }
    Ok(())
}

pub(super) fn verify_equations(part: &Part, p: &mut Prepared) -> Check {
    let res = residuals(p, &part.answers)?;
    // A condition without accelerations: proportional to a generalized force at rest.
    if part.kind == PartKind::Equation
        && res.len() == 1
        && !p.system.pool.variables(res[0]).iter().any(|v| v.1 == 2)
    {
        let coords = p.system.coordinate_syms();
        let zero = p.system.pool.zero();
        let rest: rustc_hash::FxHashMap<_, _> = coords
            .iter()
            .flat_map(|&c| [((c, 1), zero), ((c, 2), zero)])
            .collect();
        for &f in &p.derivation.forcing.clone() {
            let f0 = p.system.pool.substitute(f, &rest);
            if crate::check::compare::proportional(
                &p.system,
                res[0],
                f0,
                &p.points,
                tolerance::SAME,
            ) {
                return Ok(());
            }
        }
        return Err(Failed::new(
            FindingCode::WrongCondition,
            format!(
                "the stated condition {} = 0 is not a generalized force at rest set to zero",
                p.system.pool.unicode(res[0])
            ),
        ));
    }
    let system = part.kind == PartKind::Equations;
    if let Some(why) = equations_hold(p, &res, system)? {
        let shown: Vec<String> = res
            .iter()
            .map(|&r| format!("{} = 0", p.system.pool.unicode(r)))
            .collect();
        let derived: Vec<String> = p
            .derivation
            .steps
            .iter()
            .map(|s| {
                let f = p.system.pool.factored(s.equation);
                format!("{} = 0", p.system.pool.display_factored(&f, Style::Unicode))
            })
            .collect();
        return Err(Failed::new(
            FindingCode::WrongEom,
            format!(
                "the stated equations {} are not the equations of motion ({why}); the physics gives {}",
                shown.join("; "),
                derived.join("; ")
            ),
        ));
    }
    for w in &part.wrong {
        let Ok(r) = residuals(p, std::slice::from_ref(w)) else {
            continue;
        };
        if equations_hold(p, &r, system)?.is_none() {
            return Err(Failed::new(
                FindingCode::WrongAccepted,
                format!("the `wrong` example `{w}` is in fact correct"),
            ));
        }
    }
    Ok(())
}

/// A `values` part listing the cyclic coordinates (or `none`): exactly the coordinates the
/// engine finds cyclic (∂L/∂q ≡ 0, no generalized force, in no constraint).
pub(super) fn verify_values(part: &Part, p: &mut Prepared) -> Check {
    if part.quantity != Quantity::Cyclic {
        return Ok(());
    }
    let names: Vec<String> = p
        .system
        .coordinates
        .iter()
        .map(|c| c.name.clone())
        .collect();
    let mut stated = Vec::new();
    for a in &part.answers {
        let name = crate::expr::names::normalize(a.trim());
        match names.iter().position(|n| *n == name) {
            Some(i) => stated.push(i),
            None => {
                return Err(Failed::new(
                    FindingCode::Unreadable,
                    format!("`{a}` is not a coordinate: list the cyclic coordinates by name"),
                ));
            }
        }
    }
    let cyclic = p.system.energy(&p.derivation).cyclic;
    if let Some(&i) = stated.iter().find(|i| !cyclic.contains(i)) {
        return Err(Failed::new(
            FindingCode::NotCyclic,
            format!("`{}` is not cyclic: {}", names[i], why_not_cyclic(p, i)),
        ));
    }
    if let Some(&i) = cyclic.iter().find(|i| !stated.contains(i)) {
        return Err(Failed::new(
            FindingCode::MissingCyclic,
            format!(
                "`{}` is cyclic (L does not depend on it, no force acts on it, and it is in no constraint), but the answer does not list it",
                names[i]
            ),
        ));
    }
    Ok(())
}

/// Why coordinate `i` is not cyclic, for the finding.
fn why_not_cyclic(p: &Prepared, i: usize) -> String {
    let sys = &p.system;
    let sym = sys.coordinates[i].sym;
    if !sys.is_zero(p.derivation.steps[i].force) {
        "L depends on it (∂L/∂q ≠ 0)".into()
    } else if !sys.is_zero(sys.forces[i]) {
        "a generalized force acts on it".into()
    } else if sys
        .constraints
        .iter()
        .any(|c| sys.pool.variables(c.expr).iter().any(|&(s, _)| s == sym))
    {
        "it appears in a constraint, whose force acts on it".into()
    } else {
        "the engine does not find it cyclic".into()
    }
}

//! Why an equation of motion is wrong: linearized (small angle), rounded constants, one term
//! that differs from the reference after the best common scaling (a sign, a factor, a wrong
//! factor inside, a term missing or extra), swapped symbols, or right in a limit (at rest, a
//! parameter zero) — which says where the mistake must be.

use nalgebra::{DMatrix, DVector};
use rustc_hash::FxHashMap;
use std::sync::Arc;

use super::compare::values;
use super::diagnose::{has_decimal, percent, student_numbers, swapped, tolerance_text};
use super::limits;
use super::prepare::Prepared;
use super::residual::{holds, miss};
use super::terms::{Scaling, Terms, one_term};
use super::tolerance;
use super::verdict::{Code, Diagnosis, Verdict};
use crate::expr::Id;
use crate::mechanics::accel::Dynamics;
use crate::problem::Part;

/// Accelerations of the equations linearized about q = 0, q' = 0.
fn linearized_accelerations(p: &mut Prepared) -> Vec<Option<Vec<f64>>> {
    let n = p.system.n();
    let coords = p.system.coordinate_syms();
    let zero = p.system.pool.zero();
    let rest: FxHashMap<_, _> = coords
        .iter()
        .flat_map(|&c| [((c, 0), zero), ((c, 1), zero), ((c, 2), zero)])
        .collect();
    let mut roots = Vec::new();
    for i in 0..n {
        for j in 0..n {
            roots.push(p.system.pool.substitute(p.derivation.mass[i][j], &rest));
        }
    }
    for i in 0..n {
        let f = p.derivation.forcing[i];
        roots.push(p.system.pool.substitute(f, &rest));
        for &c in &coords {
            let dq = p.system.pool.diff(f, c, 0);
            roots.push(p.system.pool.substitute(dq, &rest));
            let dv = p.system.pool.diff(f, c, 1);
            roots.push(p.system.pool.substitute(dv, &rest));
        }
    }
    let Ok(vals) = values(&p.system, &roots, &p.points) else {
        return vec![None; p.points.points.len()];
    };
    let at = p.system.state_layout();
    vals.into_iter()
        .zip(&p.points.points)
        .map(|(v, x)| {
            let v = v?;
            let m = DMatrix::from_fn(n, n, |i, j| v[i * n + j]);
            let mut rhs = DVector::zeros(n);
            for i in 0..n {
                let base = n * n + i * (1 + 2 * n);
                let mut s = v[base];
                for (j, _) in coords.iter().enumerate() {
                    s += v[base + 1 + 2 * j] * x[at.q(j)] + v[base + 2 + 2 * j] * x[at.qdot(j)];
                }
                rhs[i] = s;
            }
            m.lu().solve(&rhs).map(|s| s.iter().copied().collect())
        })
        .collect()
}

/// The part's reference equations (lhs, rhs) (only wrong answers need them).
fn reference_equations(part: &Part, p: &mut Prepared) -> Vec<(Id, Id)> {
    part.answers
        .iter()
        .filter_map(|a| crate::expr::read_equation(a, &p.context, &mut p.system.pool).ok())
        .collect()
}

/// The one term in which the student's equation differs from a reference equation (after
/// the best common scaling), trying each reference equation of a system.
fn term_in_equation(
    p: &mut Prepared,
    refs: &[(Id, Id)],
    (lhs, rhs): (Id, Id),
    which: &str,
) -> Option<Diagnosis> {
    let st = Terms::of_equation(p, lhs, rhs);
    refs.iter().find_map(|&(rl, rr)| {
        let rt = Terms::of_equation(p, rl, rr);
        one_term(p, &st, &rt, Scaling::Common, which)
    })
}

/// The most telling limit (at rest, a parameter zero) in which the equation holds for the
/// true motion: the mistake is in a term the limit removes. The limit must remove some terms
/// of the reference (or, for a system, of the student's equation) and keep others.
fn limit_finding(p: &mut Prepared, refs: &[(Id, Id)], r: Id, which: &str) -> Option<Diagnosis> {
    let basis = match refs {
        [(l, rr)] => p.system.pool.sub(*l, *rr),
        _ => r,
    };
    let limits = limits::applicable(p, basis);
    if limits.is_empty() {
        return None;
    }
    // One compiled dynamics for every limit.
    let dynamics = Dynamics::new(&p.system, &p.derivation).ok()?;
    let mut scratch = dynamics.scratch();
    for limit in limits {
        let pts = limits::points_in(p, limit);
        let acc: Vec<Option<Vec<f64>>> = pts
            .points
            .iter()
            .map(|x| dynamics.accelerations(x, &mut scratch).ok())
            .collect();
        if acc.iter().filter(|a| a.is_some()).count() * 2 < pts.points.len() {
            continue;
        }
        if holds(p, r, &pts, &acc) {
            return Some(limits::right_in(p, limit, which));
        }
    }
    None
}

/// Whether the equation depends on a coordinate itself (not only its derivatives): a
/// linearized equation does (θ'' + g/l·θ), while `ψ'' = 0` holds in every approximation and
/// is no small-angle slip.
fn has_coordinate(p: &Prepared, r: Id) -> bool {
    let coords = p.system.coordinate_syms();
    p.system
        .pool
        .variables(r)
        .iter()
        .any(|(s, o)| *o == 0 && coords.contains(s))
}

pub(super) fn diagnose_equation(
    part: &Part,
    p: &mut Prepared,
    (eq, r): ((Id, Id), Id),
    which: &str,
    truth: &[Option<Vec<f64>>],
    v: &mut Verdict,
) {
    let pts = p.points.clone();
    let lin = match &p.linearized {
        Some(lin) => lin.clone(),
        None => {
            let lin: Arc<[_]> = linearized_accelerations(p).into();
            p.linearized = Some(lin.clone());
            lin
        }
    };
    if has_coordinate(p, r) && holds(p, r, &pts, &lin) {
        v.diagnoses.push(Diagnosis::new(Code::SmallAngle,
            format!("{which} is the small-angle (linearized) equation, but the full equation is asked: keep sin θ and cos θ, and the velocity terms"),
        ));
        return;
    }
    let truth = truth.to_vec();
    if has_decimal(p, r) && miss(p, r, &pts, &truth, tolerance::ROUNDED).is_none() {
        let message = if student_numbers(p) {
            // With the student's numbers a decimal is the answer: the digits are too few. How
            // few: the least of 10⁻⁸ … 10⁻² to which the equation holds.
            let within = (2..=8)
                .rev()
                .map(|k| 10f64.powi(-k))
                .find(|&tol| miss(p, r, &pts, &truth, tol).is_none())
                .unwrap_or(tolerance::ROUNDED);
            format!(
                "{which} holds only to within {} (relative), not to this part's tolerance of {}: give more significant figures",
                percent(within),
                tolerance_text(p.tolerance)
            )
        } else {
            format!(
                "{which} holds only to a few significant digits: write exact constants such as sqrt(2), pi or 1/3 instead of decimals"
            )
        };
        v.diagnoses
            .push(Diagnosis::new(Code::RoundedConstant, message));
        return;
    }
    let refs = match &p.reference_equations {
        Some(refs) => refs.clone(),
        None => {
            let refs: Arc<[_]> = reference_equations(part, p).into();
            p.reference_equations = Some(refs.clone());
            refs
        }
    };
    let term = term_in_equation(p, &refs, eq, which);
    if let Some(d) = term.as_ref().filter(|d| d.code == Code::SignError) {
        v.diagnoses.push(d.clone());
        return;
    }
    let mut holds_true = |p: &mut Prepared, c: Id| holds(p, c, &pts, &truth);
    if let Some(d) = swapped(p, r, &mut holds_true) {
        v.diagnoses.push(d);
        return;
    }
    // A limit is the last resort; the literature's detectors (`super::misconception`) run
    // once this whole diagnosis is done, and name the principle when one applies.
    if let Some(d) = term {
        v.diagnoses.push(d);
        return;
    }
    if let Some(d) = limit_finding(p, &refs, r, which) {
        v.diagnoses.push(d);
    }
}

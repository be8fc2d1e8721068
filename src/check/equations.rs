//! Equations compared through the accelerations they imply: an answer's equations must hold
//! at the true accelerations (one equation), or determine exactly them (a system). Also the
//! diagnosis of a wrong equation: linearized, a sign or factor in one term, swapped symbols, a
//! velocity term; and conditions without accelerations, compared up to a factor.

use nalgebra::{DMatrix, DVector};
use rustc_hash::FxHashMap;

use super::common::{at_rest, point_text, undefined_everywhere, verdict};
use super::compare::{Relation, relate, values};
use super::degenerate::degeneracy;
use super::diagnose::{factor_in_term, sign_in_term, swapped};
use super::error::CheckError;
use super::points::PointSet;
use super::prepare::Prepared;
use super::tolerance;
use super::verdict::{Code, Diagnosis, ReadAs, Status, Verdict};
use crate::expr::{Id, Reading};
use crate::mechanics::accel::Dynamics;
use crate::problem::{Part, PartKind, Problem};

/// True accelerations at every point.
pub(crate) fn true_accelerations(p: &Prepared) -> Result<Vec<Option<Vec<f64>>>, CheckError> {
    if let Some(a) = p.accelerations.get() {
        return Ok(a.clone());
    }
    let a = compute_accelerations(p)?;
    Ok(p.accelerations.get_or_init(|| a).clone())
}

fn compute_accelerations(p: &Prepared) -> Result<Vec<Option<Vec<f64>>>, CheckError> {
    let sys = &p.system;
    if !sys.constraints.is_empty() {
        let mut s = sys.clone();
        let rows = s.constraint_rows();
        return Ok(p
            .points
            .points
            .iter()
            .map(|x| {
                s.multipliers_at(&p.derivation, &rows, x)
                    .ok()
                    .map(|(a, _)| a)
            })
            .collect());
    }
    let dynamics =
        Dynamics::new(sys, &p.derivation).map_err(|error| CheckError::Dynamics { error })?;
    let mut scratch = dynamics.scratch();
    Ok(p.points
        .points
        .iter()
        .map(|x| dynamics.accelerations(x, &mut scratch).ok())
        .collect())
}

/// Whether the equations `res` determine the true accelerations (`equations`), or hold at
/// them (`equation`). Returns a description of the failure. The same tests as the checker's:
/// each equation holds at the true accelerations, and together they have full rank.
pub(crate) fn equations_hold(
    p: &mut Prepared,
    res: &[Id],
    system: bool,
) -> Result<Option<String>, CheckError> {
    let n = p.system.n();
    if system && res.len() != n {
        return Ok(Some(format!("{} equations for {n} coordinates", res.len())));
    }
    let truth = true_accelerations(p)?;
    let pts = p.points.clone();
    for &r in res {
        let tol = p.tolerance;
        match miss(p, r, &pts, &truth, tol) {
            None => {}
            Some(Miss::Residual(x)) if !system => {
                return Ok(Some(format!(
                    "it does not hold for the true accelerations (residual {x:.3e})"
                )));
            }
            Some(Miss::NoAcceleration) if !system => {
                return Ok(Some("it contains no acceleration".into()));
            }
            Some(_) => {
                return Ok(Some(
                    "they do not give the accelerations the physics gives".into(),
                ));
            }
        }
    }
    if system && rank_of(p, res) < n {
        return Ok(Some(
            "the equations do not determine the accelerations".into(),
        ));
    }
    Ok(degeneracy(p, res, None).map(|d| d.details().message))
}

/// An equation's affine form at one point: the coefficients of q'' and the rest.
type AffineRow = (Vec<f64>, f64);

/// One equation's affine form at each point: the row A (coefficients of q'') and b (the rest).
fn affine(p: &mut Prepared, r: Id, pts: &PointSet) -> Result<Vec<Option<AffineRow>>, CheckError> {
    let coords = p.system.coordinate_syms();
    let mut roots: Vec<Id> = coords
        .iter()
        .map(|&c| p.system.pool.diff(r, c, 2))
        .collect();
    roots.push(r);
    let vals = values(&p.system, &roots, pts)?;
    let n = coords.len();
    let at = p.system.state_layout();
    Ok(vals
        .into_iter()
        .zip(&pts.points)
        .map(|(v, x)| {
            let v = v?;
            let a: Vec<f64> = v[..n].to_vec();
            let b = v[n] - (0..n).map(|j| a[j] * x[at.qddot(j)]).sum::<f64>();
            Some((a, b))
        })
        .collect())
}

/// Why an equation fails at given accelerations.
enum Miss {
    /// The residual at the first point where it does not vanish.
    Residual(f64),
    /// It contains no acceleration.
    NoAcceleration,
    /// It could not be evaluated anywhere.
    Unevaluable,
}

/// `None` when equation `r` holds at accelerations `acc` (per point), to the relative
/// tolerance `tol`, and involves them.
fn miss(
    p: &mut Prepared,
    r: Id,
    pts: &PointSet,
    acc: &[Option<Vec<f64>>],
    tol: f64,
) -> Option<Miss> {
    let Ok(rows) = affine(p, r, pts) else {
        return Some(Miss::Unevaluable);
    };
    let mut any_acc = false;
    let mut checked = 0;
    for (row, a) in rows.iter().zip(acc) {
        let (Some((coef, b)), Some(a)) = (row, a) else {
            continue;
        };
        let lhs: f64 = coef.iter().zip(a).map(|(c, x)| c * x).sum();
        let scale = coef.iter().zip(a).map(|(c, x)| (c * x).abs()).sum::<f64>() + b.abs();
        if coef.iter().any(|c| *c != 0.0) {
            any_acc = true;
        }
        if (lhs + b).abs() > tol * (scale + tolerance::TINY) {
            return Some(Miss::Residual(lhs + b));
        }
        checked += 1;
    }
    match (any_acc, checked) {
        (_, 0) => Some(Miss::Unevaluable),
        (false, _) => Some(Miss::NoAcceleration),
        _ => None,
    }
}

/// Whether equation `r` holds at accelerations `acc` (per point), to the part's tolerance,
/// and involves them.
fn holds(p: &mut Prepared, r: Id, pts: &PointSet, acc: &[Option<Vec<f64>>]) -> bool {
    let tol = p.tolerance;
    miss(p, r, pts, acc, tol).is_none()
}

/// True accelerations at arbitrary points.
fn accelerations_at(p: &Prepared, pts: &PointSet) -> Vec<Option<Vec<f64>>> {
    let Ok(d) = Dynamics::new(&p.system, &p.derivation) else {
        return vec![None; pts.points.len()];
    };
    let mut scratch = d.scratch();
    pts.points
        .iter()
        .map(|x| d.accelerations(x, &mut scratch).ok())
        .collect()
}

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

/// The equations of a reading (a bare expression e read as e = 0, which sets `bare`), or
/// `None` when an item is not an equation.
fn equations_of(p: &mut Prepared, r: Reading) -> Option<(Vec<(Id, Id)>, bool)> {
    let mut eqs: Vec<(Id, Id)> = Vec::new();
    let mut bare = false;
    let mut flat = Vec::new();
    match r {
        Reading::System(items, _) | Reading::List(items, _) => flat.extend(items),
        other => flat.push(other),
    }
    for it in flat {
        match it {
            Reading::Expr(e, _) => {
                bare = true;
                eqs.push((e, p.system.pool.zero()));
            }
            Reading::Equation { lhs, rhs, .. } => eqs.push((lhs, rhs)),
            _ => return None,
        }
    }
    Some((eqs, bare))
}

/// How the equations were read: plain and unicode, joined by `; `.
fn reading_of(p: &Prepared, eqs: &[(Id, Id)], bare: bool) -> ReadAs {
    let shown = |style: crate::expr::Style| -> Vec<String> {
        eqs.iter()
            .map(|&(l, r)| p.system.pool.display_equation(l, r, style))
            .collect()
    };
    ReadAs {
        plain: shown(crate::expr::Style::Plain).join("; "),
        unicode: shown(crate::expr::Style::Unicode).join("; "),
        note: bare.then(|| "an expression without `=` was read as expression = 0".to_string()),
    }
}

/// For an `equation` part whose reference has no accelerations: its residual (decided once).
fn condition_of(part: &Part, p: &mut Prepared) -> Option<Id> {
    if let Some(c) = p.condition.get() {
        return *c;
    }
    let c = (part.kind == PartKind::Equation)
        .then(|| crate::expr::read_equation(&part.answers[0], &p.context, &mut p.system.pool).ok())
        .flatten()
        .map(|(rl, rr)| p.system.pool.sub(rl, rr))
        .filter(|&r| !p.system.pool.variables(r).iter().any(|v| v.1 == 2));
    *p.condition.get_or_init(|| c)
}

/// What comparing a condition (no accelerations) with the reference found.
enum ConditionFinding {
    /// Not one equation.
    Count(usize),
    /// The reference up to a nonzero factor.
    Equivalent,
    /// Undefined at sample `point`, where the reference is defined.
    Undefined { point: usize },
    /// A sign in one term, or swapped symbols (the search's diagnosis).
    Found(Diagnosis),
    /// Nothing more to say.
    NotEquivalent,
}

impl ConditionFinding {
    /// The sentence for a finding (none when the condition is right).
    fn details(self, p: &Prepared) -> Option<Diagnosis> {
        Some(match self {
            ConditionFinding::Equivalent => return None,
            ConditionFinding::Count(k) => Diagnosis::new(
                Code::EquationCount,
                format!("one equation is asked for, but you gave {k}"),
            ),
            ConditionFinding::Undefined { point } => Diagnosis::new(
                Code::Undefined,
                format!(
                    "your equation is undefined at {}, where the correct one is defined",
                    point_text(p, point)
                ),
            ),
            ConditionFinding::Found(d) => d,
            ConditionFinding::NotEquivalent => Diagnosis::new(
                Code::NotEqual,
                "this condition is not equivalent to the right one",
            ),
        })
    }
}

/// Compares a condition with the reference up to a nonzero factor.
fn judge_condition(part: &Part, p: &mut Prepared, res: &[Id], reference: Id) -> ConditionFinding {
    let [r0] = res else {
        return ConditionFinding::Count(res.len());
    };
    let r0 = *r0;
    let eq = |p: &mut Prepared, c: Id| {
        super::compare::proportional(&p.system, c, reference, &p.points, tolerance::SAME)
    };
    match relate(&p.system, r0, reference, &p.points, part.tolerance) {
        Ok(Relation::Equal | Relation::Factor(_)) => ConditionFinding::Equivalent,
        _ if eq(p, r0) => ConditionFinding::Equivalent,
        Ok(Relation::Undefined { point }) => ConditionFinding::Undefined { point },
        _ => sign_in_term(p, r0, &mut |p, c| eq(p, c))
            .or_else(|| swapped(p, r0, &mut |p, c| eq(p, c)))
            .map_or(ConditionFinding::NotEquivalent, ConditionFinding::Found),
    }
}

/// Checks an answer to an `equation` or `equations` part.
pub fn check_equations(problem: &Problem, part: &Part, p: &mut Prepared, r: Reading) -> Verdict {
    let mut v = verdict(problem, part, Status::Incorrect);
    let Some((eqs, bare)) = equations_of(p, r) else {
        let mut w = verdict(problem, part, Status::Invalid);
        w.diagnoses.push(Diagnosis::new(
            Code::WrongKind,
            "write equations separated by `;`",
        ));
        return w;
    };
    v.reading = reading_of(p, &eqs, bare);
    if eqs
        .iter()
        .any(|&(l, r)| p.system.pool.is_undefined(l) || p.system.pool.is_undefined(r))
    {
        v.diagnoses.push(undefined_everywhere());
        return v;
    }
    for &(l, r) in &eqs {
        if let Err(e) = p.system.pool.check_equation_dimension(l, r, &problem.dims) {
            v.diagnoses
                .push(Diagnosis::new(Code::Dimension, e.to_string()));
        }
    }
    let res: Vec<Id> = eqs.iter().map(|&(l, r)| p.system.pool.sub(l, r)).collect();
    // A condition (a reference equation without accelerations, such as an equilibrium
    // condition) is compared with the reference up to a nonzero factor.
    if let Some(reference) = condition_of(part, p) {
        let finding = judge_condition(part, p, &res, reference);
        if matches!(finding, ConditionFinding::Equivalent) {
            v.status = Status::Correct;
            v.score = 1.0;
        }
        v.diagnoses.extend(finding.details(p));
        return v;
    }
    let shown: Vec<String> = eqs
        .iter()
        .map(|&(l, r)| {
            p.system
                .pool
                .display_equation(l, r, crate::expr::Style::Unicode)
        })
        .collect();
    check_motion(part, p, &res, &shown, &mut v);
    v
}

/// Equations of motion: each must hold at the true accelerations and together (for a
/// system) determine them. Adds the diagnoses and score to `v`.
fn check_motion(part: &Part, p: &mut Prepared, res: &[Id], shown: &[String], v: &mut Verdict) {
    let truth = match true_accelerations(p) {
        Ok(t) => t,
        Err(e) => {
            v.diagnoses
                .push(Diagnosis::new(Code::NotEqual, e.to_string()));
            return;
        }
    };
    let pts = p.points.clone();
    let ok: Vec<bool> = res.iter().map(|&r| holds(p, r, &pts, &truth)).collect();
    let want = if part.kind == PartKind::Equations {
        p.system.n()
    } else {
        1
    };
    // Independent equations that hold: rank of their acceleration rows at a sample point.
    let holding: Vec<Id> = res
        .iter()
        .zip(&ok)
        .filter(|(_, o)| **o)
        .map(|(r, _)| *r)
        .collect();
    let rank = rank_of(p, &holding);
    let mut degenerate = false;
    if res.len() != want {
        v.diagnoses.push(Diagnosis::new(
            Code::EquationCount,
            format!(
                "{want} equation{} {} asked for, but you gave {}",
                if want == 1 { "" } else { "s" },
                if want == 1 { "is" } else { "are" },
                res.len()
            ),
        ));
    } else if ok.iter().all(|o| *o) {
        if rank == want {
            // Holding at the true accelerations is not enough: the equations must determine
            // them everywhere, not only away from where a factor vanishes.
            let reference = single_reference(part, p);
            match degeneracy(p, res, reference) {
                None => v.status = Status::Correct,
                Some(d) => {
                    v.diagnoses.push(d.details());
                    degenerate = true;
                }
            }
        } else {
            v.diagnoses.push(Diagnosis::new(Code::DependentEquations,
                "each of your equations holds, but together they do not determine the accelerations: one is a multiple or combination of the others",
            ));
        }
    }
    for (i, &r) in res.iter().enumerate().filter(|(i, _)| !ok[*i]) {
        let which = if res.len() > 1 {
            format!("equation {}", i + 1)
        } else {
            "your equation".to_string()
        };
        if res.len() > 1 || part.kind == PartKind::Equations {
            v.diagnoses.push(Diagnosis::new(
                Code::WrongEquation,
                format!("{which} ({}) does not hold for the true motion", shown[i]),
            ));
        }
        diagnose_equation(p, r, &which, &truth, v);
    }
    super::misconception::equations(part, p, res, v);
    if v.status != Status::Correct && v.diagnoses.is_empty() {
        v.diagnoses.push(Diagnosis::new(
            Code::NotEqual,
            "your equation does not hold for the true motion",
        ));
    }
    v.score = score(v.status, degenerate, rank, want, res.len());
}

/// Partial credit for equations: the share of the asked equations that hold independently,
/// less for extra ones; none for equations that stop determining the motion somewhere.
fn score(status: Status, degenerate: bool, rank: usize, want: usize, given: usize) -> f64 {
    if status == Status::Correct {
        return 1.0;
    }
    if degenerate {
        return 0.0;
    }
    let extra = if given > want {
        want as f64 / given as f64
    } else {
        1.0
    };
    rank.min(want) as f64 / want as f64 * extra
}

/// For an `equation` part of a system with several coordinates: the residual of its reference
/// equation, against which one answer equation is judged for vanishing factors.
fn single_reference(part: &Part, p: &mut Prepared) -> Option<Id> {
    if part.kind != PartKind::Equation || p.system.n() < 2 {
        return None;
    }
    let (l, r) =
        crate::expr::read_equation(&part.answers[0], &p.context, &mut p.system.pool).ok()?;
    Some(p.system.pool.sub(l, r))
}

fn rank_of(p: &mut Prepared, rows: &[Id]) -> usize {
    if rows.is_empty() {
        return 0;
    }
    let pts = PointSet {
        points: vec![p.points.points[0].clone()],
    };
    let mut m = Vec::new();
    for &r in rows {
        match affine(p, r, &pts)
            .ok()
            .and_then(|v| v.into_iter().next().flatten())
        {
            Some((a, _)) => m.push(a),
            None => return 0,
        }
    }
    let n = p.system.n();
    // Each row is scaled to unit length first: an equation multiplied by 1e-9 or 1e9 is the
    // same equation, and must not look dependent next to an unscaled one.
    for row in &mut m {
        let norm = row.iter().map(|x| x * x).sum::<f64>().sqrt();
        if norm > 0.0 {
            row.iter_mut().for_each(|x| *x /= norm);
        }
    }
    let a = DMatrix::from_fn(m.len(), n, |i, j| m[i][j]);
    let scale = a.amax().max(tolerance::TINY);
    a.svd(false, false)
        .singular_values
        .iter()
        .filter(|s| **s > tolerance::RANK * scale)
        .count()
}

fn diagnose_equation(
    p: &mut Prepared,
    r: Id,
    which: &str,
    truth: &[Option<Vec<f64>>],
    v: &mut Verdict,
) {
    let pts = p.points.clone();
    let lin = linearized_accelerations(p);
    if holds(p, r, &pts, &lin) {
        v.diagnoses.push(Diagnosis::new(Code::SmallAngle,
            format!("{which} is the small-angle (linearized) equation, but the full equation is asked: keep sin θ and cos θ, and the velocity terms"),
        ));
        return;
    }
    let truth = truth.to_vec();
    if miss(p, r, &pts, &truth, tolerance::ROUNDED).is_none() {
        v.diagnoses.push(Diagnosis::new(
            Code::RoundedConstant,
            format!("{which} holds only to a few significant digits: write exact constants such as sqrt(2), pi or 1/3 instead of decimals"),
        ));
        return;
    }
    let mut holds_true = |p: &mut Prepared, c: Id| holds(p, c, &pts, &truth);
    if let Some(d) = swapped(p, r, &mut holds_true) {
        v.diagnoses.push(d);
        return;
    }
    if let Some(d) = sign_in_term(p, r, &mut holds_true) {
        v.diagnoses.push(d);
        return;
    }
    let mut factor_at = |p: &mut Prepared, t: Id| -> Option<f64> {
        // c with R + (c − 1)·T = 0 at the first defined point.
        let ar = affine(p, r, &pts).ok()?;
        let at = affine(p, t, &pts).ok()?;
        for ((rr, tt), acc) in ar.iter().zip(&at).zip(&truth) {
            let (Some((ca, cb)), Some((ta, tb)), Some(acc)) = (rr, tt, acc) else {
                continue;
            };
            let rv: f64 = ca.iter().zip(acc).map(|(c, x)| c * x).sum::<f64>() + cb;
            let tv: f64 = ta.iter().zip(acc).map(|(c, x)| c * x).sum::<f64>() + tb;
            if tv.abs() > tolerance::ZERO {
                return Some(1.0 - rv / tv);
            }
        }
        None
    };
    if let Some(d) = factor_in_term(p, r, &mut factor_at, &mut holds_true) {
        v.diagnoses.push(d);
        return;
    }
    if let Some(still) = at_rest(p) {
        let acc = accelerations_at(p, &still);
        if holds(p, r, &still, &acc) {
            v.diagnoses.push(Diagnosis::new(Code::VelocityTerm,
                format!("{which} is right when nothing moves, so a velocity term is missing or wrong (a q'² or q'₁q'₂ term)"),
            ));
        }
    }
}

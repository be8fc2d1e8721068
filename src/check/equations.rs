//! Equations compared through the accelerations they imply: an answer's equations must hold
//! at the true accelerations (one equation), or determine exactly them (a system); conditions
//! without accelerations are compared up to a factor. Why a wrong equation is wrong is
//! `equation_diagnosis.rs`'s business.

use nalgebra::DMatrix;

use super::common::{point_text, undefined_everywhere, verdict};
use super::compare::{Relation, relate};
use super::degenerate::degeneracy;
use super::diagnose::{sign_in_term, swapped};
use super::equation_diagnosis::diagnose_equation;
use super::error::CheckError;
use super::points::PointSet;
use super::prepare::{Prepared, true_accelerations};
use super::residual::{Miss, affine, holds, miss};
use super::terms::{Scaling, Terms, one_term};
use super::tolerance;
use super::verdict::{Code, Diagnosis, ReadAs, Status, Verdict};
use crate::expr::{Id, Node, Reading, Style};
use crate::problem::{Part, PartKind, Problem};

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
fn judge_condition(
    part: &Part,
    p: &mut Prepared,
    (eqs, res): (&[(Id, Id)], &[Id]),
    reference: Id,
) -> ConditionFinding {
    let ([r0], [(lhs, rhs)]) = (res, eqs) else {
        return ConditionFinding::Count(res.len());
    };
    let r0 = *r0;
    let eq = |p: &mut Prepared, c: Id| {
        super::compare::proportional(&p.system, c, reference, &p.points, tolerance::SAME)
    };
    match relate(&p.system, r0, reference, &p.points, part.tolerance) {
        Ok(Relation::Equal | Relation::Factor(_)) => ConditionFinding::Equivalent,
        _ if eq(p, r0) => ConditionFinding::Equivalent,
        _ if equivalent_under_assumptions(p, r0, reference) => ConditionFinding::Equivalent,
        Ok(Relation::Undefined { point }) => ConditionFinding::Undefined { point },
        // One term as the student wrote it first; the whole-residual searches after.
        _ => {
            let st = Terms::of_equation(p, *lhs, *rhs);
            let rt = Terms::of_expression(p, reference);
            one_term(p, &st, &rt, Scaling::Common, "your equation")
                .or_else(|| sign_in_term(p, r0, &mut |p, c| eq(p, c)))
                .or_else(|| swapped(p, r0, &mut |p, c| eq(p, c)))
                .map_or(ConditionFinding::NotEquivalent, ConditionFinding::Found)
        }
    }
}

/// Whether `r0` is the reference without some of its factors, each a function of the
/// parameters alone that the problem's assumptions keep away from zero (`r = 0` for
/// `r (2ga − ω²) = 0` where 2ga > ω²): the two conditions then hold at the same states. A
/// factor the reference does not have (`r (2ga + ω²) = 0`) is not this, even where it cannot
/// vanish either: it is the sign slip the part is about.
fn equivalent_under_assumptions(p: &mut Prepared, r0: Id, reference: Id) -> bool {
    let factors: Vec<Id> = match p.system.pool.node(reference) {
        Node::Mul(f) => f.to_vec(),
        _ => return false,
    };
    let time = p.system.pool.time();
    let coords = p.system.coordinate_syms();
    let constant = |p: &Prepared, f: Id| {
        !p.system
            .pool
            .variables(f)
            .iter()
            .any(|(s, _)| *s == time || coords.contains(s))
    };
    let (dropped, kept): (Vec<Id>, Vec<Id>) = factors
        .into_iter()
        .partition(|&f| constant(p, f) && p.system.pool.as_num(f).is_none());
    if dropped.is_empty() || kept.is_empty() {
        return false;
    }
    let rest = p.system.pool.product(kept);
    let proportional = matches!(
        relate(&p.system, r0, rest, &p.points, p.tolerance),
        Ok(Relation::Equal | Relation::Factor(_))
    );
    // Nonzero and finite at every sample, whose parameters satisfy the assumptions.
    proportional
        && dropped.iter().all(|&f| {
            super::compare::values(&p.system, &[f], &p.points).is_ok_and(|vals| {
                vals.iter()
                    .all(|v| v.as_ref().is_some_and(|v| v[0].is_finite() && v[0] != 0.0))
            })
        })
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
        let finding = judge_condition(part, p, (&eqs, &res), reference);
        if matches!(finding, ConditionFinding::Equivalent) {
            v.status = Status::Correct;
            v.score = 1.0;
        }
        v.diagnoses.extend(finding.details(p));
        super::misconception::condition(p, &res, &mut v);
        return v;
    }
    check_motion(part, p, (&eqs, &res), &mut v);
    v
}

/// Equations of motion: each must hold at the true accelerations and together (for a
/// system) determine them. Adds the diagnoses and score to `v`.
fn check_motion(part: &Part, p: &mut Prepared, (eqs, res): (&[(Id, Id)], &[Id]), v: &mut Verdict) {
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
    let degenerate = judge_together(part, p, res, (&ok, rank, want), v);
    for (i, &r) in res.iter().enumerate().filter(|(i, _)| !ok[*i]) {
        let which = if res.len() > 1 {
            format!("equation {}", i + 1)
        } else {
            "your equation".to_string()
        };
        if res.len() > 1 || part.kind == PartKind::Equations {
            v.diagnoses.push(Diagnosis::new(
                Code::WrongEquation,
                format!(
                    "{which} ({}) does not hold for the true motion",
                    p.system
                        .pool
                        .display_equation(eqs[i].0, eqs[i].1, Style::Unicode)
                ),
            ));
        }
        diagnose_equation(part, p, (eqs[i], r), &which, &truth, v);
    }
    // Equations that all hold for the true motion have no documented mistake in them (what is
    // wrong is their number, rank or a vanishing factor): the literature's detectors, which
    // rebuild the system, are for equations that fail.
    if !ok.iter().all(|o| *o) {
        super::misconception::equations(part, p, res, v);
    }
    if v.status != Status::Correct && v.diagnoses.is_empty() {
        v.diagnoses.push(Diagnosis::new(
            Code::NotEqual,
            "your equation does not hold for the true motion",
        ));
    }
    v.score = score(v.status, degenerate, rank, want, res.len());
}

/// The equations as a whole: their number, whether those that hold determine the
/// accelerations, and (all holding) whether a factor makes them vanish somewhere. Sets the
/// status when they are right; returns whether they degenerate (a vanishing factor).
fn judge_together(
    part: &Part,
    p: &mut Prepared,
    res: &[Id],
    (ok, rank, want): (&[bool], usize, usize),
    v: &mut Verdict,
) -> bool {
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
    degenerate
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

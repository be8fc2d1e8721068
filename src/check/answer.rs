//! `check(problem, part, input)`: read the answer, compare it with the reference by the
//! part's kind, and diagnose a wrong one. Expressions and equations live here; unordered lists
//! in `lists.rs`.

use nalgebra::{DMatrix, DVector};
use rustc_hash::FxHashMap;

use super::compare::{Relation, close, fmt_value, relate, values};
use super::diagnose::{factor_in_term, nice_fraction, rounded, sign_in_term, swapped};
use super::equations::true_accelerations;
use super::points::PointSet;
use super::prepare::{Prepared, prepare};
use super::verdict::{Diagnosis, ReadAs, Status, Verdict};
use crate::expr::{Id, ParseErrorKind, Reading, read, read_expr};
use crate::mechanics::accel::Dynamics;
use crate::mechanics::sample::seed_from;
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
    pub fn check(&mut self, part_id: &str, input: &str) -> Result<Verdict, String> {
        let part = self
            .problem
            .part(part_id)
            .ok_or_else(|| format!("problem `{}` has no part `{part_id}`", self.problem.id))?;
        if !self.prepared.contains_key(part_id) {
            let p = prepare(self.problem, part)?;
            self.prepared.insert(part_id.to_string(), p);
        }
        let p = self
            .prepared
            .get_mut(part_id)
            .ok_or_else(|| "internal: preparation vanished".to_string())?;
        Ok(check_prepared(self.problem, part, p, input))
    }
}

/// Checks one answer (preparing the part afresh; use [`Checker`] for many answers).
pub fn check(problem: &Problem, part: &Part, input: &str) -> Result<Verdict, String> {
    let mut p = prepare(problem, part)?;
    Ok(check_prepared(problem, part, &mut p, input))
}

/// A verdict skeleton.
fn verdict(problem: &Problem, part: &Part, status: Status) -> Verdict {
    Verdict {
        problem: problem.id.clone(),
        part: part.id.clone(),
        status,
        score: if status == Status::Correct { 1.0 } else { 0.0 },
        reading: ReadAs::default(),
        diagnoses: Vec::new(),
        seed: seed_from(&[&problem.id, &part.id]),
        parse_error: None,
    }
}

/// Checks against a prepared part.
pub fn check_prepared(problem: &Problem, part: &Part, p: &mut Prepared, input: &str) -> Verdict {
    let mut v = match part.kind {
        PartKind::Equilibria | PartKind::Frequencies | PartKind::Values => {
            super::lists::check_list(problem, part, p, input)
        }
        _ => match read(input, &p.context, &mut p.system.pool) {
            Err(e) => invalid_reading(problem, part, e),
            Ok(r) => match part.kind {
                PartKind::Equation | PartKind::Equations => check_equations(problem, part, p, r),
                _ => check_expression(problem, part, p, r),
            },
        },
    };
    v.sort();
    v
}

/// The verdict on an input that could not be read.
pub fn invalid_reading(problem: &Problem, part: &Part, e: crate::expr::ParseError) -> Verdict {
    let mut v = verdict(problem, part, Status::Invalid);
    let d = match &e.kind {
        ParseErrorKind::UnknownName { name, .. } => {
            match part
                .substitute
                .iter()
                .find(|(k, _)| crate::expr::names::normalize(k) == *name)
            {
                Some((k, val)) => Diagnosis::new(
                    "substituted-symbol",
                    format!("this part sets {k} = {val}: write your answer with {val}, not {k}"),
                ),
                None => Diagnosis::new("unknown-symbol", format!("{}; {}", e.kind, e.help())),
            }
        }
        _ => Diagnosis::new("syntax", format!("{}; {}", e.kind, e.help())),
    };
    v.diagnoses.push(d);
    v.parse_error = Some(e);
    v
}

fn point_text(p: &Prepared, k: usize) -> String {
    let x = &p.points.points[k];
    let mut parts = Vec::new();
    for (i, c) in p.system.coordinates.iter().enumerate() {
        parts.push(format!("{} = {}", c.name, fmt_value(x[1 + 3 * i])));
    }
    let off = 1 + 3 * p.system.n();
    for (j, q) in p.system.parameters.iter().enumerate() {
        parts.push(format!("{} = {}", q.name, fmt_value(x[off + j])));
    }
    parts.join(", ")
}

fn check_expression(problem: &Problem, part: &Part, p: &mut Prepared, r: Reading) -> Verdict {
    let s = match r {
        Reading::Expr(e, _) => e,
        Reading::Equation { .. } => {
            let mut v = verdict(problem, part, Status::Invalid);
            v.diagnoses.push(Diagnosis::new(
                "wrong-kind",
                "this part asks for an expression, not an equation",
            ));
            return v;
        }
        Reading::List(..) | Reading::System(..) => {
            let mut v = verdict(problem, part, Status::Invalid);
            v.diagnoses.push(Diagnosis::new(
                "wrong-kind",
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
    let Ok(reference) = read_expr(&part.answers[0], &p.context, &mut p.system.pool) else {
        v.status = Status::Invalid;
        v.diagnoses.push(Diagnosis::new(
            "syntax",
            "the reference answer of this part cannot be read",
        ));
        return v;
    };
    // Dimensions: a sum of unlike terms, or a different dimension from the reference.
    match p.system.pool.dimension(s, &problem.dims) {
        Err(e) => v.diagnoses.push(Diagnosis::new("dimension", e.to_string())),
        Ok(Some(ds)) => {
            if let Ok(Some(dr)) = p.system.pool.dimension(reference, &problem.dims)
                && ds != dr
                && !p.system.pool.is_zero(s)
            {
                v.diagnoses.push(Diagnosis::new(
                    "dimension",
                    format!("your answer has dimension {ds}, but the answer must be {dr}"),
                ));
            }
        }
        Ok(None) => {}
    }
    let rel = match relate(&p.system, s, reference, &p.points, part.tolerance) {
        Ok(r) => r,
        Err(e) => {
            v.diagnoses.push(Diagnosis::new("not-equal", e));
            return v;
        }
    };
    let lagrangian = part.kind == PartKind::Lagrangian;
    match rel {
        Relation::Equal => v.status = Status::Correct,
        Relation::UpToConstant(_) if part.up_to_constant || lagrangian => {
            v.status = Status::Correct;
            v.diagnoses.push(Diagnosis::new(
                "up-to-constant",
                "your answer differs from the reference by a constant; that is allowed here (the zero of potential energy is a free choice)",
            ));
        }
        Relation::Factor(f) if lagrangian => {
            v.status = Status::Correct;
            v.diagnoses.push(Diagnosis::new(
                "equivalent-lagrangian",
                format!("your L is {} times the reference; a constant factor gives the same equations of motion", nice_fraction(f).unwrap_or_else(|| fmt_value(f))),
            ));
        }
        Relation::Factor(f) if (f - 1.0).abs() < 1e-2 && rounded(p, s, reference).is_some() => {
            if let Some(d) = rounded(p, s, reference) {
                v.diagnoses.push(d);
            }
        }
        Relation::Factor(f) if (f + 1.0).abs() < 1e-9 => {
            v.diagnoses.push(Diagnosis::new(
                "sign-error",
                "sign error: your answer is the negative of the right one",
            ));
        }
        Relation::Factor(f) => v.diagnoses.push(Diagnosis::new(
            "constant-factor",
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
            "undefined",
            format!(
                "your answer is undefined at {}, where the correct one is defined",
                point_text(p, point)
            ),
        )),
        Relation::UpToConstant(_) | Relation::Different { .. } => {
            if lagrangian && equivalent_lagrangian(p, s, reference) {
                v.status = Status::Correct;
                v.diagnoses.push(Diagnosis::new(
                    "equivalent-lagrangian",
                    "your L differs from the reference by a total time derivative (or a constant); it gives the same equations of motion",
                ));
            } else {
                diagnose_expression(problem, part, p, s, reference, rel, &mut v);
            }
        }
    }
    if v.status == Status::Correct {
        v.score = 1.0;
        v.diagnoses
            .retain(|d| matches!(d.code, "up-to-constant" | "equivalent-lagrangian"));
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
        match relate(&p.system, x, y, &p.points, 1e-9) {
            Ok(Relation::Equal) => factor = factor.or(Some(1.0)),
            Ok(Relation::Factor(f)) => {
                if factor.is_some_and(|g| (g - f).abs() > 1e-9 * f.abs()) {
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
    problem: &Problem,
    part: &Part,
    p: &mut Prepared,
    s: Id,
    reference: Id,
    rel: Relation,
    v: &mut Verdict,
) {
    let eq = |p: &mut Prepared, cand: Id| {
        relate(&p.system, cand, reference, &p.points, 1e-9).ok() == Some(Relation::Equal)
    };
    let eq_const = |p: &mut Prepared, cand: Id, r: Id| {
        matches!(
            relate(&p.system, cand, r, &p.points, 1e-9),
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
                "t-plus-v",
                "you wrote T + V; the Lagrangian is L = T − V",
            ));
        }
    }
    if part.quantity == Quantity::EnergyFunction
        && let (Some(t), Some(vv)) = (t, vv)
    {
        let tv = p.system.pool.add(t, vv);
        if eq_const(p, s, tv) {
            v.diagnoses.push(Diagnosis::new(
                "t-plus-v",
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
                "gave-lagrangian",
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
        let x = vals.into_iter().flatten().find(|x| x[2].abs() > 1e-9)?;
        Some(1.0 + (x[1] - x[0]) / x[2])
    };
    if let Some(d) = factor_in_term(p, s, &mut factor_at, &mut |p, c| eq(p, c)) {
        v.diagnoses.push(d);
    }
    // Velocity-dependent terms: equal when every velocity is zero.
    if v.diagnoses.len() == before
        && let Some(still) = at_rest(p)
        && relate(&p.system, s, reference, &still, 1e-9).ok() == Some(Relation::Equal)
        && !p.system.pool.variables(reference).iter().all(|x| x.1 == 0)
    {
        v.diagnoses.push(Diagnosis::new(
            "velocity-term",
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
        v.diagnoses.push(Diagnosis::new("not-equal", msg));
    }
    let _ = problem;
}

/// The sample points with every velocity (and acceleration) set to zero.
fn at_rest(p: &Prepared) -> Option<PointSet> {
    let n = p.system.n();
    let points = p
        .points
        .points
        .iter()
        .map(|x| {
            let mut y = x.clone();
            for i in 0..n {
                y[1 + 3 * i + 1] = 0.0;
                y[1 + 3 * i + 2] = 0.0;
            }
            y
        })
        .collect();
    Some(PointSet { points })
}

/// An equation's affine form at one point: the coefficients of q'' and the rest.
type AffineRow = (Vec<f64>, f64);

/// One equation's affine form at each point: the row A (coefficients of q'') and b (the rest).
fn affine(p: &mut Prepared, r: Id, pts: &PointSet) -> Result<Vec<Option<AffineRow>>, String> {
    let coords = p.system.coordinate_syms();
    let mut roots: Vec<Id> = coords
        .iter()
        .map(|&c| p.system.pool.diff(r, c, 2))
        .collect();
    roots.push(r);
    let vals = values(&p.system, &roots, pts)?;
    let n = coords.len();
    Ok(vals
        .into_iter()
        .zip(&pts.points)
        .map(|(v, x)| {
            let v = v?;
            let a: Vec<f64> = v[..n].to_vec();
            let b = v[n] - (0..n).map(|j| a[j] * x[1 + 3 * j + 2]).sum::<f64>();
            Some((a, b))
        })
        .collect())
}

/// Whether equation `r` holds at accelerations `acc` (per point), and involves them.
fn holds(p: &mut Prepared, r: Id, pts: &PointSet, acc: &[Option<Vec<f64>>]) -> bool {
    let Ok(rows) = affine(p, r, pts) else {
        return false;
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
        if (lhs + b).abs() > 1e-7 * (scale + 1e-300) {
            return false;
        }
        checked += 1;
    }
    any_acc && checked > 0
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
                    s +=
                        v[base + 1 + 2 * j] * x[1 + 3 * j] + v[base + 2 + 2 * j] * x[1 + 3 * j + 1];
                }
                rhs[i] = s;
            }
            m.lu().solve(&rhs).map(|s| s.iter().copied().collect())
        })
        .collect()
}

fn check_equations(problem: &Problem, part: &Part, p: &mut Prepared, r: Reading) -> Verdict {
    let mut v = verdict(problem, part, Status::Incorrect);
    // Collect the equations; a bare expression e is read as e = 0.
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
            _ => {
                let mut w = verdict(problem, part, Status::Invalid);
                w.diagnoses.push(Diagnosis::new(
                    "wrong-kind",
                    "write equations separated by `;`",
                ));
                return w;
            }
        }
    }
    let shown: Vec<String> = eqs
        .iter()
        .map(|&(l, r)| {
            p.system
                .pool
                .display_equation(l, r, crate::expr::Style::Plain)
        })
        .collect();
    let shown_u: Vec<String> = eqs
        .iter()
        .map(|&(l, r)| {
            p.system
                .pool
                .display_equation(l, r, crate::expr::Style::Unicode)
        })
        .collect();
    v.reading = ReadAs {
        plain: shown.join("; "),
        unicode: shown_u.join("; "),
        note: bare.then(|| "an expression without `=` was read as expression = 0".to_string()),
    };
    for &(l, r) in &eqs {
        if let Err(e) = p.system.pool.check_equation_dimension(l, r, &problem.dims) {
            v.diagnoses.push(Diagnosis::new("dimension", e.to_string()));
        }
    }
    let res: Vec<Id> = eqs.iter().map(|&(l, r)| p.system.pool.sub(l, r)).collect();
    // A condition (a reference equation without accelerations, such as an equilibrium
    // condition) is compared with the reference up to a nonzero factor.
    if part.kind == PartKind::Equation
        && let Ok((rl, rr)) =
            crate::expr::read_equation(&part.answers[0], &p.context, &mut p.system.pool)
    {
        let reference = p.system.pool.sub(rl, rr);
        if !p.system.pool.variables(reference).iter().any(|v| v.1 == 2) {
            if res.len() != 1 {
                v.diagnoses.push(Diagnosis::new(
                    "equation-count",
                    format!("one equation is asked for, but you gave {}", res.len()),
                ));
                return v;
            }
            match relate(&p.system, res[0], reference, &p.points, part.tolerance) {
                Ok(Relation::Equal | Relation::Factor(_)) => {
                    v.status = Status::Correct;
                    v.score = 1.0;
                }
                _ if super::compare::proportional(
                    &p.system, res[0], reference, &p.points, 1e-9,
                ) =>
                {
                    v.status = Status::Correct;
                    v.score = 1.0;
                }
                Ok(Relation::Undefined { point }) => v.diagnoses.push(Diagnosis::new(
                    "undefined",
                    format!(
                        "your equation is undefined at {}, where the correct one is defined",
                        point_text(p, point)
                    ),
                )),
                _ => {
                    let r0 = res[0];
                    let eq = |p: &mut Prepared, c: Id| {
                        super::compare::proportional(&p.system, c, reference, &p.points, 1e-9)
                    };
                    let d = sign_in_term(p, r0, &mut |p, c| eq(p, c))
                        .or_else(|| swapped(p, r0, &mut |p, c| eq(p, c)));
                    v.diagnoses.push(d.unwrap_or_else(|| {
                        Diagnosis::new(
                            "not-equal",
                            "this condition is not equivalent to the right one",
                        )
                    }));
                }
            }
            return v;
        }
    }
    let n = p.system.n();
    let truth = match true_accelerations(p) {
        Ok(t) => t,
        Err((_, m)) => {
            v.diagnoses.push(Diagnosis::new("not-equal", m));
            return v;
        }
    };
    let pts = p.points.clone();
    let ok: Vec<bool> = res.iter().map(|&r| holds(p, r, &pts, &truth)).collect();
    let want = if part.kind == PartKind::Equations {
        n
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
    if res.len() != want {
        v.diagnoses.push(Diagnosis::new(
            "equation-count",
            format!(
                "{want} equation{} {} asked for, but you gave {}",
                if want == 1 { "" } else { "s" },
                if want == 1 { "is" } else { "are" },
                res.len()
            ),
        ));
    } else if ok.iter().all(|o| *o) {
        if rank == want {
            v.status = Status::Correct;
        } else {
            v.diagnoses.push(Diagnosis::new(
                "dependent-equations",
                "each of your equations holds, but together they do not determine the accelerations: one is a multiple or combination of the others",
            ));
        }
    }
    for (i, &r) in res.iter().enumerate() {
        if ok[i] {
            continue;
        }
        let which = if res.len() > 1 {
            format!("equation {}", i + 1)
        } else {
            "your equation".to_string()
        };
        if res.len() > 1 || part.kind == PartKind::Equations {
            v.diagnoses.push(Diagnosis::new(
                "wrong-equation",
                format!("{which} ({}) does not hold for the true motion", shown_u[i]),
            ));
        }
        diagnose_equation(p, r, &which, &truth, &mut v);
    }
    if v.status != Status::Correct && v.diagnoses.is_empty() {
        v.diagnoses.push(Diagnosis::new(
            "not-equal",
            "your equation does not hold for the true motion",
        ));
    }
    v.score = if v.status == Status::Correct {
        1.0
    } else {
        rank.min(want) as f64 / want as f64
            * if res.len() > want {
                want as f64 / res.len() as f64
            } else {
                1.0
            }
    };
    v
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
    let a = DMatrix::from_fn(m.len(), n, |i, j| m[i][j]);
    let scale = a.amax().max(1e-300);
    a.svd(false, false)
        .singular_values
        .iter()
        .filter(|s| **s > 1e-9 * scale)
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
        v.diagnoses.push(Diagnosis::new(
            "small-angle",
            format!("{which} is the small-angle (linearized) equation, but the full equation is asked: keep sin θ and cos θ, and the velocity terms"),
        ));
        return;
    }
    let truth = truth.to_vec();
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
            if tv.abs() > 1e-9 {
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
            v.diagnoses.push(Diagnosis::new(
                "velocity-term",
                format!("{which} is right when nothing moves, so a velocity term is missing or wrong (a q'² or q'₁q'₂ term)"),
            ));
            return;
        }
    }
    let _ = close;
}

//! Localising a mistake by limiting cases, as a tutor does: when a wrong answer agrees with
//! the reference at rest, or with one parameter set to zero (ω = 0, m₂ = 0, k = 0, a = 0),
//! the mistake must be in a term that the limit removes. The limits are tried most telling
//! first (the one that removes the fewest terms), and a limit is used only where it applies:
//! it must remove some of the reference's terms and keep others (a momentum at rest is zero
//! whatever its mistake, so "right at rest" says nothing about it). Also the small-angle
//! approximation of an expression (its quadratic part about q = 0).

use super::compare::{Relation, relate};
use super::points::PointSet;
use super::prepare::Prepared;
use super::tolerance;
use super::verdict::{Code, Diagnosis};
use crate::expr::{Id, Node, Program, Style};
use crate::problem::{Part, PartKind, Quantity};

/// A limiting case: at rest, or one parameter (by index) set to zero.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Limit {
    /// Every velocity and acceleration zero.
    Rest,
    /// Every coordinate zero (the point a small-angle approximation is made about).
    Origin,
    /// Parameter `j` zero.
    Zero(usize),
}

/// The sample points in the limit.
pub(super) fn points_in(p: &Prepared, limit: Limit) -> PointSet {
    let at = p.system.state_layout();
    let points = p
        .points
        .points
        .iter()
        .map(|x| {
            let mut y = x.clone();
            match limit {
                Limit::Rest => {
                    for i in 0..at.coordinates() {
                        y[at.qdot(i)] = 0.0;
                        y[at.qddot(i)] = 0.0;
                    }
                }
                Limit::Origin => {
                    for i in 0..at.coordinates() {
                        y[at.q(i)] = 0.0;
                    }
                }
                Limit::Zero(j) => y[at.param(j)] = 0.0,
            }
            y
        })
        .collect();
    PointSet { points }
}

/// How many of the terms (the outputs of `prog`) vanish at every point of the limit, or
/// `None` when some cannot be evaluated there.
fn vanishing(prog: &Program, n: usize, pts: &PointSet) -> Option<usize> {
    let mut scratch = prog.scratch();
    let mut rows = Vec::with_capacity(pts.points.len());
    for x in &pts.points {
        prog.run(x, &mut scratch).ok()?;
        rows.push(
            (0..n)
                .map(|k| prog.output(k, &scratch))
                .collect::<Vec<f64>>(),
        );
    }
    Some(
        (0..n)
            .filter(|&i| {
                rows.iter().all(|r| {
                    let size: f64 = r.iter().map(|x| x.abs()).sum();
                    r[i].abs() <= 1e-12 * size
                })
            })
            .count(),
    )
}

/// The limits that apply to `e` (an answer, or an equation's residual), most telling first:
/// each removes at least one of its terms (expanded) and keeps at least one.
pub(super) fn applicable(p: &mut Prepared, e: Id) -> Vec<Limit> {
    let x = p.system.pool.expand(e);
    // Terms with an acceleration are left out: in an equation the acceleration is the true
    // one, never zero, so "vanishing at rest" says nothing about them.
    let terms: Vec<Id> = match p.system.pool.node(x) {
        Node::Add(t) => t.to_vec(),
        _ => vec![x],
    }
    .into_iter()
    .filter(|&t| !p.system.pool.variables(t).iter().any(|v| v.1 == 2))
    .collect();
    if terms.len() > super::diagnose::MAX_SEARCH_TERMS {
        return Vec::new();
    }
    let Ok(prog) = Program::compile(&p.system.pool, &terms, &p.system.layout()) else {
        return Vec::new();
    };
    let mut found: Vec<(usize, usize, Limit)> = Vec::new();
    let candidates =
        std::iter::once(Limit::Rest).chain((0..p.system.parameters.len()).map(Limit::Zero));
    for (rank, limit) in candidates.enumerate() {
        let pts = points_in(p, limit);
        if let Some(k) = vanishing(&prog, terms.len(), &pts)
            && k > 0
            && k < terms.len()
        {
            found.push((k, rank, limit));
        }
    }
    crate::sort::sort_by_key(&mut found, |&(k, rank, _)| (k, rank));
    found.into_iter().map(|(_, _, l)| l).collect()
}

/// The sentence for an answer right in `limit`; `which` is "your answer" or "equation 2".
pub(super) fn right_in(p: &Prepared, limit: Limit, which: &str) -> Diagnosis {
    match limit {
        Limit::Rest | Limit::Origin => Diagnosis::new(
            Code::VelocityTerm,
            format!(
                "{which} is right when nothing moves, so the mistake is in a term with a velocity"
            ),
        ),
        Limit::Zero(j) => {
            let s = p.system.parameters[j].sym;
            let name = p.system.pool.var_name(s, 0, Style::Unicode);
            Diagnosis::new(
                Code::RightInLimit,
                format!(
                    "{which} is right when {name} = 0, so the mistake is in a term with {name}"
                ),
            )
        }
    }
}

/// The second-order Taylor polynomial of `e` about q = 0, q̇ = 0 (every coordinate and
/// velocity): what a small-angle approximation of a potential or a Lagrangian keeps.
pub(super) fn quadratic_about_zero(p: &mut Prepared, e: Id) -> Id {
    let coords = p.system.coordinate_syms();
    let zero = p.system.pool.zero();
    let rest: rustc_hash::FxHashMap<_, _> = coords
        .iter()
        .flat_map(|&c| [((c, 0), zero), ((c, 1), zero), ((c, 2), zero)])
        .collect();
    let vars: Vec<(crate::expr::Sym, u8)> =
        coords.iter().flat_map(|&c| [(c, 0u8), (c, 1u8)]).collect();
    let mut sum = p.system.pool.substitute(e, &rest);
    for (a, &(sa, oa)) in vars.iter().enumerate() {
        let da = p.system.pool.diff(e, sa, oa);
        let ga = p.system.pool.substitute(da, &rest);
        let xa = p.system.pool.var(sa, oa);
        let t = p.system.pool.mul(ga, xa);
        sum = p.system.pool.add(sum, t);
        for &(sb, ob) in &vars[a..] {
            let dab = p.system.pool.diff(da, sb, ob);
            let gab = p.system.pool.substitute(dab, &rest);
            let xb = p.system.pool.var(sb, ob);
            // ½ f_aa x_a² on the diagonal, f_ab x_a x_b (a < b) off it.
            let k = if (sa, oa) == (sb, ob) {
                p.system.pool.ratio(1, 2)
            } else {
                p.system.pool.one()
            };
            let xab = p.system.pool.mul(xa, xb);
            let c = p.system.pool.mul(k, gab);
            let t = p.system.pool.mul(c, xab);
            sum = p.system.pool.add(sum, t);
        }
    }
    sum
}

/// Whether `e` applies a function (sin, cos, exp, …) to something that depends on a
/// coordinate. Walks the expression without recursion, each node once.
pub(super) fn has_function_of_coordinate(p: &Prepared, e: Id) -> bool {
    let coords = p.system.coordinate_syms();
    let pool = &p.system.pool;
    pool.any_node(e, |n| {
        matches!(n, Node::Func(_, a) if pool.variables(*a).iter().any(|(s, _)| coords.contains(s)))
    })
}

/// The most telling limit (at rest, a parameter zero) in which the answer is right, said as
/// where the mistake must be. Only limits that remove some of the reference's terms and keep
/// others apply.
pub(super) fn right_in_limit(p: &mut Prepared, s: Id, reference: Id) -> Option<Diagnosis> {
    for limit in applicable(p, reference) {
        let pts = points_in(p, limit);
        if super::compare::equal(&p.system, s, reference, &pts, tolerance::SAME) {
            return Some(right_in(p, limit, "your answer"));
        }
    }
    None
}

/// A potential, a Lagrangian or an energy expanded to second order about q = 0 where the
/// full expression is asked (`½ m g l θ²` for V).
pub(super) fn small_angle(
    part: &Part,
    p: &mut Prepared,
    s: Id,
    reference: Id,
) -> Option<Diagnosis> {
    let energy = matches!(
        part.quantity,
        Quantity::Potential | Quantity::Lagrangian | Quantity::EnergyFunction | Quantity::Kinetic
    ) || part.kind == PartKind::Lagrangian;
    // Only a reference with a function of a coordinate (cos θ) has a small-angle form to
    // mistake for it: the quadratic truncation of a polynomial T (the bead on a parabola's
    // 4a²r²ṙ² dropped) is a missing term, not a small-angle approximation. A quadratic
    // approximation has no function of a coordinate left (cheap to rule out first).
    if !energy || !has_function_of_coordinate(p, reference) || has_function_of_coordinate(p, s) {
        return None;
    }
    // The approximation is the mistake to name even where the part fixes the constant (the
    // expansion of −m·g·l·cos θ is −m·g·l + ½·m·g·l·θ², and the constant is often dropped).
    let constant_ok = true;
    // At q = 0 the quadratic approximation of a T, V or L (at most quadratic in the
    // velocities) is the expression itself: a cheap numeric test before the Taylor expansion.
    let origin = points_in(p, Limit::Origin);
    match relate(&p.system, s, reference, &origin, tolerance::SAME).ok()? {
        Relation::Equal => {}
        Relation::UpToConstant(_) if constant_ok => {}
        _ => return None,
    }
    let quadratic = quadratic_about_zero(p, reference);
    match relate(&p.system, s, quadratic, &p.points, tolerance::SAME).ok()? {
        Relation::Equal => {}
        Relation::UpToConstant(_) if constant_ok => {}
        _ => return None,
    }
    Some(Diagnosis::new(
        Code::SmallAngle,
        "your answer is the small-angle (quadratic) approximation about 0, but the full expression is asked: keep cos θ and sin θ as they are",
    ))
}

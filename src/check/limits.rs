//! Localising a mistake by limiting cases, as a tutor does: when a wrong answer agrees with
//! the reference at rest, or with one parameter set to zero (ω = 0, m₂ = 0, k = 0, a = 0),
//! the mistake must be in a term that the limit removes. The limits are tried most telling
//! first (the one that removes the fewest terms), and a limit is used only where it applies:
//! it must remove some of the reference's terms and keep others (a momentum at rest is zero
//! whatever its mistake, so "right at rest" says nothing about it).

use super::compare::values;
use super::points::PointSet;
use super::prepare::Prepared;
use super::verdict::{Code, Diagnosis};
use crate::expr::{Id, Node, Style};

/// A limiting case: at rest, or one parameter (by index) set to zero.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Limit {
    /// Every velocity and acceleration zero.
    Rest,
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
                Limit::Zero(j) => y[at.param(j)] = 0.0,
            }
            y
        })
        .collect();
    PointSet { points }
}

/// How many of `terms` vanish at every point of the limit, or `None` when some cannot be
/// evaluated there.
fn vanishing(p: &Prepared, terms: &[Id], pts: &PointSet) -> Option<usize> {
    let vals = values(&p.system, terms, pts).ok()?;
    let rows: Vec<Vec<f64>> = vals.into_iter().collect::<Option<Vec<_>>>()?;
    Some(
        (0..terms.len())
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
    let mut found: Vec<(usize, usize, Limit)> = Vec::new();
    let candidates =
        std::iter::once(Limit::Rest).chain((0..p.system.parameters.len()).map(Limit::Zero));
    for (rank, limit) in candidates.enumerate() {
        let pts = points_in(p, limit);
        if let Some(k) = vanishing(p, &terms, &pts)
            && k > 0
            && k < terms.len()
        {
            found.push((k, rank, limit));
        }
    }
    found.sort_by_key(|&(k, rank, _)| (k, rank));
    found.into_iter().map(|(_, _, l)| l).collect()
}

/// The sentence for an answer right in `limit`; `which` is "your answer" or "equation 2".
pub(super) fn right_in(p: &Prepared, limit: Limit, which: &str) -> Diagnosis {
    match limit {
        Limit::Rest => Diagnosis::new(
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

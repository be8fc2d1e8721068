//! `lost-root`: equilibria missing exactly where a factor of the equilibrium condition
//! vanishes (sin θ divided out of sin θ·(g − R ω² cos θ) = 0), the student's other equilibria
//! all right.

use super::super::compare::values;
use super::super::points::PointSet;
use super::super::prepare::Prepared;
use super::super::verdict::{Code, Diagnosis};
use crate::expr::{Func, Id, Node, Pool, Sym};

/// Values of `e` at every sample point (`None` where undefined or on failure).
fn at_points(p: &Prepared, e: Id) -> Vec<Option<f64>> {
    values(&p.system, &[e], &p.points).map_or_else(
        |_| vec![None; p.points.points.len()],
        |v| v.into_iter().map(|x| x.map(|x| x[0])).collect(),
    )
}

/// Whether two angle values agree at every sample point (modulo 2π).
fn same_angle(a: &[Option<f64>], b: &[Option<f64>]) -> bool {
    let mut checked = 0;
    for (x, y) in a.iter().zip(b) {
        let (Some(x), Some(y)) = (x, y) else { continue };
        if (1.0 - (x - y).cos()).abs() > 1e-12 {
            return false;
        }
        checked += 1;
    }
    checked > 0
}

/// The factors a student may divide the condition by, for coordinate q: sin q and cos q, and
/// q itself only for a coordinate that never appears inside a trigonometric function in L (a
/// length such as r): nobody divides sin θ = 0 by θ.
pub fn factors(p: &mut Prepared, sym: Sym) -> Vec<Id> {
    let q = p.system.pool.var(sym, 0);
    let mut out = vec![
        p.system.pool.func(Func::Sin, q),
        p.system.pool.func(Func::Cos, q),
    ];
    if !in_trig(&p.system.pool, p.system.lagrangian, sym) {
        out.push(q);
    }
    out
}

/// Whether the coordinate `q` (order 0) occurs inside a sin, cos or tan anywhere in `root`
/// (iterative, each shared node visited once, so bounded by the pool's size).
pub fn in_trig(pool: &Pool, root: Id, q: Sym) -> bool {
    pool.any_node(root, |n| {
        matches!(n, Node::Func(Func::Sin | Func::Cos | Func::Tan, a) if pool.variables(*a).contains(&(q, 0)))
    })
}

/// `lost-root` for a one-coordinate equilibria answer whose items are all right.
pub fn lost_root(p: &mut Prepared, items: &[Vec<Id>], refs: &[Vec<Id>]) -> Option<Diagnosis> {
    if p.system.n() != 1 || !p.system.coordinates[0].periodic || items.is_empty() {
        return None;
    }
    let sv: Vec<Vec<Option<f64>>> = items.iter().map(|it| at_points(p, it[0])).collect();
    let rv: Vec<Vec<Option<f64>>> = refs.iter().map(|it| at_points(p, it[0])).collect();
    if !sv.iter().all(|s| rv.iter().any(|r| same_angle(s, r))) {
        return None;
    }
    let missing: Vec<&Vec<Option<f64>>> = rv
        .iter()
        .filter(|r| !sv.iter().any(|s| same_angle(s, r)))
        .collect();
    if missing.is_empty() {
        return None;
    }
    let sym = p.system.coordinates[0].sym;
    for f in factors(p, sym) {
        let zero_at = |p: &mut Prepared, vals: &[Option<f64>]| -> bool {
            value_at(p, f, vals).is_some_and(|v| v.iter().all(|x| x.abs() < 1e-9))
        };
        let lost = missing.iter().all(|m| zero_at(p, m));
        let kept = sv
            .iter()
            .all(|s| value_at(p, f, s).is_some_and(|v| v.iter().all(|x| x.abs() > 1e-6)));
        if lost && kept && divides(p, f, missing[0]) {
            let shown = p.system.pool.unicode(f);
            return Some(Diagnosis::new(
                Code::LostRoot,
                format!(
                    "lost roots: you divided the equilibrium condition by {shown}, but where {shown} = 0 the condition holds too, so those equilibria are missing (dividing an equation loses the zeros of the divisor)"
                ),
            ));
        }
    }
    None
}

/// The sample points with the coordinate set to `vals` (per point, where defined).
fn moved(p: &Prepared, vals: &[Option<f64>], eps: f64) -> PointSet {
    let at = p.system.state_layout();
    let points = p
        .points
        .points
        .iter()
        .zip(vals)
        .filter_map(|(x, v)| {
            let mut y = x.clone();
            y[at.q(0)] = (*v)? + eps;
            for o in 1..3 {
                y[at.var(0, o)] = 0.0;
            }
            Some(y)
        })
        .collect();
    PointSet { points }
}

/// `e` at the sample points moved to the coordinate values `vals`.
fn value_at(p: &mut Prepared, e: Id, vals: &[Option<f64>]) -> Option<Vec<f64>> {
    let pts = moved(p, vals, 0.0);
    if pts.points.is_empty() {
        return None;
    }
    let v = values(&p.system, &[e], &pts).ok()?;
    v.into_iter().map(|x| x.map(|x| x[0])).collect()
}

/// Whether `f` divides the equilibrium condition ∂L/∂q at rest near the root `root`: the
/// quotient stays finite and settles as the root is approached.
fn divides(p: &mut Prepared, f: Id, root: &[Option<f64>]) -> bool {
    let sym = p.system.coordinates[0].sym;
    let l = p.system.lagrangian;
    let force = p.system.pool.diff(l, sym, 0);
    let quotient = p.system.pool.div(force, f);
    let near = |p: &mut Prepared, eps: f64| -> Option<Vec<f64>> {
        let pts = moved(p, root, eps);
        let v = values(&p.system, &[quotient], &pts).ok()?;
        v.into_iter().map(|x| x.map(|x| x[0])).collect()
    };
    match (near(p, 1e-4), near(p, 1e-6)) {
        (Some(a), Some(b)) => {
            !a.is_empty()
                && a.iter().zip(&b).all(|(x, y)| {
                    x.is_finite()
                        && y.is_finite()
                        && (x - y).abs() <= 1e-2 * (x.abs() + y.abs() + 1e-9)
                })
        }
        _ => false,
    }
}

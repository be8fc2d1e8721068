//! Numeric relations between two expressions over a point set.

use super::error::CheckError;
use super::points::PointSet;
use super::tolerance;
use crate::expr::{Id, Program};
use crate::mechanics::System;

/// How two expressions relate on the sample points.
#[derive(Clone, Debug, PartialEq)]
pub enum Relation {
    /// Equal at every point.
    Equal,
    /// They differ by the same constant everywhere (`a = b + c`).
    UpToConstant(f64),
    /// One is a constant multiple of the other (`a = c·b`).
    Factor(f64),
    /// Not related that simply; `point` is a sample where they differ.
    Different { point: usize },
    /// `a` is undefined at a point where `b` is defined.
    Undefined { point: usize },
}

/// Whether `x` and `y` agree to `tol` relative to `scale`.
pub fn close(x: f64, y: f64, scale: f64, tol: f64) -> bool {
    (x - y).abs() <= tol * (scale + x.abs().max(y.abs()) + tolerance::TINY)
}

/// Evaluates `ids` at each point; `None` where undefined.
pub fn values(
    sys: &System,
    ids: &[Id],
    pts: &PointSet,
) -> Result<Vec<Option<Vec<f64>>>, CheckError> {
    let prog = Program::compile(&sys.pool, ids, &sys.layout())
        .map_err(|u| CheckError::UnknownSymbol { name: u.name })?;
    let mut scratch = prog.scratch();
    Ok(pts
        .points
        .iter()
        .map(|x| {
            prog.run(x, &mut scratch).ok()?;
            Some((0..ids.len()).map(|k| prog.output(k, &scratch)).collect())
        })
        .collect())
}

/// How `a` relates to `b` (the reference) over `pts`. Points where `b` is undefined are
/// skipped.
/// The least tolerance at which `a` and `b` are [`Relation::Equal`] by [`relate`]'s first test
/// (each point against the size of its own terms); `None` where `a` is undefined and `b` is
/// not. One evaluation, for a caller that would otherwise call [`relate`] at many tolerances.
pub fn agreement(sys: &System, a: Id, b: Id, pts: &PointSet) -> Result<Option<f64>, CheckError> {
    let vals = values(sys, &[b], pts)?;
    let avals = values(sys, &[a], pts)?;
    let sizes = term_sizes(sys, a, b, pts)?;
    let mut worst: Option<f64> = None;
    for (k, (va, vb)) in avals.iter().zip(&vals).enumerate() {
        let Some(vb) = vb else { continue };
        let Some(va) = va else { return Ok(None) };
        let (x, y, (sa, sb)) = (va[0], vb[0], sizes[k]);
        let e = (x - y).abs() / (sa + sb + x.abs().max(y.abs()) + tolerance::TINY);
        worst = Some(worst.map_or(e, |w: f64| w.max(e)));
    }
    Ok(worst)
}

pub fn relate(
    sys: &System,
    a: Id,
    b: Id,
    pts: &PointSet,
    tol: f64,
) -> Result<Relation, CheckError> {
    let pairs = match pairs(sys, a, b, pts)? {
        Ok(pairs) => pairs,
        Err(point) => return Ok(Relation::Undefined { point }),
    };
    if pairs.is_empty() {
        return Err(CheckError::ReferenceUndefined);
    }
    if all_close(&pairs, tol) {
        return Ok(Relation::Equal);
    }
    // Up to a constant: the difference does not change when the state (t, q, q', q'') changes
    // and the parameters stay — the constant may depend on parameters (a zero level m·g·l).
    let c = pairs[0].1 - pairs[0].2;
    if pairs
        .iter()
        .all(|&(_, x, y, (sa, sb))| close(x - y, c, sa + sb, tol))
    {
        return Ok(Relation::UpToConstant(c));
    }
    if same_difference_when_moved(sys, a, b, pts, &pairs, tol)? {
        return Ok(Relation::UpToConstant(c));
    }
    if let Some(&(_, x0, y0, _)) = pairs
        .iter()
        .find(|p| p.2.abs() > tolerance::FACTOR_FLOOR * (p.3.1 + tolerance::TINY))
    {
        let f = x0 / y0;
        if f.is_finite()
            && f != 0.0
            && pairs
                .iter()
                .all(|&(_, x, y, (sa, sb))| close(x, f * y, sa + f.abs() * sb, tol))
        {
            return Ok(Relation::Factor(f));
        }
    }
    let bad = pairs
        .iter()
        .find(|&&(_, x, y, (sa, sb))| !close(x, y, sa + sb, tol))
        .map_or(0, |p| p.0);
    Ok(Relation::Different { point: bad })
}

/// Whether [`relate`] finds `a` and `b` [`Relation::Equal`], without the tests for the other
/// relations (a constant, a factor: half of its work) that a caller asking only this needs
/// not run.
pub fn equal(sys: &System, a: Id, b: Id, pts: &PointSet, tol: f64) -> bool {
    matches!(pairs(sys, a, b, pts), Ok(Ok(pairs)) if !pairs.is_empty() && all_close(&pairs, tol))
}

/// An expression evaluated once at a point set, to be compared with many others
/// ([`equal_sampled`]): its values and those of its top-level terms, `None` where undefined.
pub(crate) struct Sampled {
    values: Vec<Option<Vec<f64>>>,
    terms: Vec<Option<Vec<f64>>>,
}

impl Sampled {
    /// `e` at `pts`; an error where it cannot be evaluated (a symbol without a value).
    pub(crate) fn of(sys: &System, e: Id, pts: &PointSet) -> Result<Sampled, CheckError> {
        Ok(Sampled {
            values: values(sys, &[e], pts)?,
            terms: values(sys, &top_terms(sys, e), pts)?,
        })
    }
}

/// [`equal`] of two sampled expressions (at the same points): the same comparisons, each
/// side evaluated once however many it is compared with. Each value and each term's value
/// is the same whichever program computes it, and the terms of both sides are defined at a
/// point exactly where each side's are, so the sizes are [`term_sizes`]' too.
pub(crate) fn equal_sampled(a: &Sampled, b: &Sampled, tol: f64) -> bool {
    let sum = |v: &[f64]| v.iter().map(|x| x.abs()).sum::<f64>();
    let mut pairs = Vec::with_capacity(b.values.len());
    for (k, (va, vb)) in a.values.iter().zip(&b.values).enumerate() {
        let Some(vb) = vb else { continue };
        let Some(va) = va else { return false };
        let sizes = match (&a.terms[k], &b.terms[k]) {
            (Some(ta), Some(tb)) => (sum(ta), sum(tb)),
            _ => (0.0, 0.0),
        };
        pairs.push((k, va[0], vb[0], sizes));
    }
    !pairs.is_empty() && all_close(&pairs, tol)
}

/// The top-level terms of `e` (itself when it is no sum).
fn top_terms(sys: &System, e: Id) -> Vec<Id> {
    match sys.pool.node(e) {
        crate::expr::Node::Add(t) => t.to_vec(),
        _ => vec![e],
    }
}

/// One point's comparison: (point, a, b, size of the terms of a and of b at that point).
type Pair = (usize, f64, f64, (f64, f64));

/// The comparisons at every point where `b` is defined; `Err(k)`: `a` is undefined at point
/// `k`, where `b` is defined.
fn pairs(
    sys: &System,
    a: Id,
    b: Id,
    pts: &PointSet,
) -> Result<Result<Vec<Pair>, usize>, CheckError> {
    let vals = values(sys, &[b], pts)?;
    let avals = values(sys, &[a], pts)?;
    let sizes = term_sizes(sys, a, b, pts)?;
    let mut pairs = Vec::new();
    for (k, (va, vb)) in avals.iter().zip(&vals).enumerate() {
        let Some(vb) = vb else { continue };
        let Some(va) = va else {
            return Ok(Err(k));
        };
        pairs.push((k, va[0], vb[0], sizes[k]));
    }
    Ok(Ok(pairs))
}

/// Whether `a` and `b` agree at every point. Every comparison is relative to the size of the
/// quantities at its own point (the sum of the magnitudes of the terms of both sides there),
/// never to other points: a point where everything is small must not be judged against one
/// where everything is large.
fn all_close(pairs: &[Pair], tol: f64) -> bool {
    pairs
        .iter()
        .all(|&(_, x, y, (sa, sb))| close(x, y, sa + sb, tol))
}

/// Whether `a = c·b` with c nonzero and independent of the state (it may depend on the
/// parameters, like the m in m·r·(ω² − 2ga) = 0).
pub(crate) fn proportional(sys: &System, a: Id, b: Id, pts: &PointSet, tol: f64) -> bool {
    let Some(moved) = moved_states(sys, pts) else {
        return false;
    };
    let (Ok(va), Ok(vb), Ok(ma), Ok(mb)) = (
        values(sys, &[a], pts),
        values(sys, &[b], pts),
        values(sys, &[a], &moved),
        values(sys, &[b], &moved),
    ) else {
        return false;
    };
    let mut checked = 0;
    for k in 0..pts.points.len() {
        let (Some(x), Some(y), Some(u), Some(w)) = (&va[k], &vb[k], &ma[k], &mb[k]) else {
            continue;
        };
        let (x, y, u, w) = (x[0], y[0], u[0], w[0]);
        // x/y = u/w, written without division; both sides must not vanish together.
        let scale = (x * w).abs() + (u * y).abs();
        if scale == 0.0 {
            continue;
        }
        if (x == 0.0) != (y == 0.0) || (x * w - u * y).abs() > tol * scale {
            return false;
        }
        checked += 1;
    }
    checked > 0 && monomial_ratio(sys, a, b, pts)
}

/// Whether a/b depends on the parameters only as a monomial (k·m·g/l, never 2ga + ω²):
/// doubling any one parameter scales the ratio by the same power of 2 at every point.
fn monomial_ratio(sys: &System, a: Id, b: Id, pts: &PointSet) -> bool {
    let ratio = |set: &PointSet| -> Option<Vec<Option<f64>>> {
        let va = values(sys, &[a], set).ok()?;
        let vb = values(sys, &[b], set).ok()?;
        Some(
            va.iter()
                .zip(&vb)
                .map(|(x, y)| match (x, y) {
                    (Some(x), Some(y)) if y[0] != 0.0 && x[0] != 0.0 => Some(x[0] / y[0]),
                    _ => None,
                })
                .collect(),
        )
    };
    let Some(base) = ratio(pts) else { return false };
    let start = sys.state_layout().params_start();
    for j in 0..sys.parameters.len() {
        let doubled = PointSet {
            points: pts
                .points
                .iter()
                .map(|x| {
                    let mut y = x.clone();
                    y[start + j] *= 2.0;
                    y
                })
                .collect(),
        };
        let Some(r2) = ratio(&doubled) else {
            return false;
        };
        let mut exponent: Option<f64> = None;
        for (u, w) in base.iter().zip(&r2) {
            let (Some(u), Some(w)) = (u, w) else { continue };
            let q = w / u;
            if q <= 0.0 {
                return false;
            }
            let e = q.log2();
            if (e * 2.0 - (e * 2.0).round()).abs() > tolerance::EXPONENT
                || exponent.is_some_and(|f| (f - e).abs() > tolerance::EXPONENT)
            {
                return false;
            }
            exponent = Some(e);
        }
    }
    true
}

/// The points with each one's state (t, q, q', q'') taken from the next point and its
/// parameters kept.
fn moved_states(sys: &System, pts: &PointSet) -> Option<PointSet> {
    let k = pts.points.len();
    if k < 2 {
        return None;
    }
    let state = sys.state_layout().params_start();
    let points = (0..k)
        .map(|i| {
            let mut x = pts.points[i].clone();
            x[..state].copy_from_slice(&pts.points[(i + 1) % k][..state]);
            x
        })
        .collect();
    Some(PointSet { points })
}

/// Parameter values for a message: `g = 9.8100, l = 1.2000`.
pub(crate) fn parameter_text(sys: &System, params: &[f64]) -> String {
    sys.parameters
        .iter()
        .zip(params)
        .map(|(q, x)| format!("{} = {x:.4}", q.name))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A number for people: multiples of π/2 by name, otherwise six significant decimals.
pub fn fmt_value(x: f64) -> String {
    let pi = std::f64::consts::PI;
    for (k, name) in [(1.0, "π"), (-1.0, "−π"), (0.5, "π/2"), (-0.5, "−π/2")] {
        if (x - k * pi).abs() < tolerance::ANGLE {
            return name.to_string();
        }
    }
    // Very small and very large values in scientific notation: 1e-12 is not "0", and 1e300
    // is not a 301-digit number.
    if x != 0.0 && x.is_finite() && !(1e-4..1e7).contains(&x.abs()) {
        let s = format!("{x:.5e}");
        let (mantissa, exponent) = s.split_once('e').unwrap_or((&s, "0"));
        let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
        return format!("{mantissa}e{exponent}");
    }
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.').to_string();
    if s == "-0" { "0".into() } else { s }
}

/// The size of the quantities in `a` and in `b` at each point: the sum of the magnitudes of
/// each one's top-level terms (0 where undefined). Rounding in a sum is relative to this, not
/// to the sum itself, which may cancel to (nearly) nothing.
fn term_sizes(sys: &System, a: Id, b: Id, pts: &PointSet) -> Result<Vec<(f64, f64)>, CheckError> {
    let (ta, tb) = (top_terms(sys, a), top_terms(sys, b));
    let ids: Vec<Id> = ta.iter().chain(&tb).copied().collect();
    let sum = |v: &[f64]| v.iter().map(|x| x.abs()).sum::<f64>();
    Ok(values(sys, &ids, pts)?
        .into_iter()
        .map(|v| v.map_or((0.0, 0.0), |v| (sum(&v[..ta.len()]), sum(&v[ta.len()..]))))
        .collect())
}

/// For a reference that depends on the state: whether a − b stays the same at every point
/// when only the state moves (the parameters stay), i.e. the difference is a constant that may
/// depend on the parameters.
fn same_difference_when_moved(
    sys: &System,
    a: Id,
    b: Id,
    pts: &PointSet,
    pairs: &[Pair],
    tol: f64,
) -> Result<bool, CheckError> {
    let time = sys.pool.time();
    let stateful = sys
        .pool
        .variables(b)
        .iter()
        .any(|(s, _)| *s == time || sys.coordinates.iter().any(|c| c.sym == *s));
    let Some(moved) = moved_states(sys, pts).filter(|_| stateful) else {
        return Ok(false);
    };
    let da = values(sys, &[a], &moved)?;
    let db = values(sys, &[b], &moved)?;
    let moved_sizes = term_sizes(sys, a, b, &moved)?;
    Ok(pairs
        .iter()
        .all(|&(k, x, y, (sa, sb))| match (&da[k], &db[k]) {
            (Some(u), Some(w)) => {
                let size = sa + sb + moved_sizes[k].0 + moved_sizes[k].1;
                close(x - y, u[0] - w[0], size, tol)
            }
            _ => true,
        }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sampled_comparisons_agree_with_equal() {
        let pr = crate::bank::embedded::problem("simple-pendulum").expect("problem in the bank");
        let part = pr.part("frequencies").expect("part");
        let mut p = crate::check::prepare::prepare(&pr, part).expect("prepared");
        let texts = [
            "sqrt(g/l)",
            "sqrt(1.000003*g/l)",
            "g/l",
            "sqrt(-g/l)",
            "sqrt(g/l) + 1e-12",
            "1/theta",
            "sqrt(g/l) + theta - theta",
            "sqrt(g/l) + sin(theta)^2 + cos(theta)^2 - 1",
            "0",
        ];
        let ids: Vec<Id> = (texts.iter())
            .map(|t| crate::expr::read_expr(t, &p.context, &mut p.system.pool).expect("reads"))
            .collect();
        let sampled: Vec<Sampled> = (ids.iter())
            .map(|&e| Sampled::of(&p.system, e, &p.points).expect("evaluates"))
            .collect();
        for (i, &a) in ids.iter().enumerate() {
            for (j, &b) in ids.iter().enumerate() {
                assert_eq!(
                    equal_sampled(&sampled[i], &sampled[j], p.tolerance),
                    equal(&p.system, a, b, &p.points, p.tolerance),
                    "{} vs {}",
                    texts[i],
                    texts[j]
                );
            }
        }
    }
}

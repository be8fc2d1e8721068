//! An equation's residual at given accelerations: its affine form in the accelerations at
//! each point, and whether it holds there — shared by the check of equations and the
//! diagnosis of wrong ones.

use super::compare::values;
use super::error::CheckError;
use super::points::PointSet;
use super::prepare::Prepared;
use super::tolerance;
use crate::expr::Id;
use std::sync::Arc;

/// An equation's affine form at one point: the coefficients of q'' and the rest.
pub(super) type AffineRow = (Vec<f64>, f64);

/// One equation's affine form at each point: the row A (coefficients of q'') and b (the rest).
pub(super) fn affine(
    p: &mut Prepared,
    r: Id,
    pts: &PointSet,
) -> Result<Vec<Option<AffineRow>>, CheckError> {
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

/// [`affine`], kept for the last equation read at the sample points: a wrong equation is
/// tried at the true accelerations, then at the linearized ones and to a looser tolerance,
/// and its affine form is the same each time (it does not depend on the accelerations).
fn affine_once(
    p: &mut Prepared,
    r: Id,
    pts: &PointSet,
) -> Result<Arc<[Option<AffineRow>]>, CheckError> {
    let samples = pts.points == p.points.points;
    if let Some((id, rows)) = &p.last_affine
        && samples
        && *id == r
    {
        return Ok(rows.clone());
    }
    let rows: Arc<[_]> = affine(p, r, pts)?.into();
    if samples {
        p.last_affine = Some((r, rows.clone()));
    }
    Ok(rows)
}

/// Why an equation fails at given accelerations.
pub(super) enum Miss {
    /// The residual at the first point where it does not vanish.
    Residual(f64),
    /// It contains no acceleration.
    NoAcceleration,
    /// It could not be evaluated anywhere.
    Unevaluable,
}

/// `None` when equation `r` holds at accelerations `acc` (per point), to the relative
/// tolerance `tol`, and involves them.
pub(super) fn miss(
    p: &mut Prepared,
    r: Id,
    pts: &PointSet,
    acc: &[Option<Vec<f64>>],
    tol: f64,
) -> Option<Miss> {
    let Ok(rows) = affine_once(p, r, pts) else {
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
pub(super) fn holds(p: &mut Prepared, r: Id, pts: &PointSet, acc: &[Option<Vec<f64>>]) -> bool {
    let tol = p.tolerance;
    miss(p, r, pts, acc, tol).is_none()
}

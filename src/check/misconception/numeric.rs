//! The numeric tests the detectors share: an answer equal to a generated one, the accelerations
//! a generated (wrong) set of equations implies, and whether an equation holds at them.

use super::super::compare::{Relation, relate, values};
use super::super::points::PointSet;
use super::super::prepare::Prepared;
use super::super::tolerance;
use crate::expr::{Id, Node};

/// Whether `s` equals `cand` at every sample point (up to a constant when `up_to_constant`).
pub fn equal(p: &Prepared, s: Id, cand: Id, up_to_constant: bool) -> bool {
    if !up_to_constant {
        return super::super::compare::equal(&p.system, s, cand, &p.points, p.tolerance);
    }
    match relate(&p.system, s, cand, &p.points, p.tolerance) {
        Ok(Relation::Equal) => true,
        Ok(Relation::UpToConstant(_)) => up_to_constant,
        _ => false,
    }
}

/// Whether a generated candidate is a mistake at all and not one the checker already names:
/// it must differ from the reference by more than a constant, and not be its negative or a
/// multiple (sign and factor errors are told as such).
pub fn distinct(p: &Prepared, cand: Id, reference: Id) -> bool {
    matches!(
        relate(&p.system, cand, reference, &p.points, p.tolerance),
        Ok(Relation::Different { .. })
    )
}

/// Most coordinates a generated system may have for its accelerations to be solved here.
const MAX_COORDINATES: usize = 6;

/// The accelerations the equations `res` (one per coordinate, affine in the accelerations)
/// imply at each sample point; `None` where they are undefined or singular.
pub fn accelerations(p: &mut Prepared, res: &[Id]) -> Vec<Option<Vec<f64>>> {
    let n = p.system.n();
    let none = vec![None; p.points.points.len()];
    if res.len() != n || n == 0 || n > MAX_COORDINATES {
        return none;
    }
    let coords = p.system.coordinate_syms();
    let mut roots = Vec::with_capacity(n * (n + 1));
    for &r in res {
        roots.push(r);
        for &c in &coords {
            roots.push(p.system.pool.diff(r, c, 2));
        }
    }
    let Ok(vals) = values(&p.system, &roots, &p.points) else {
        return none;
    };
    let at = p.system.state_layout();
    vals.into_iter()
        .zip(&p.points.points)
        .map(|(v, x)| {
            let v = v?;
            // Row i: A_i·q̈ + b_i = 0, with b_i = r_i − A_i·q̈(point).
            let mut a = vec![vec![0.0; n]; n];
            let mut b = vec![0.0; n];
            for i in 0..n {
                let row = &v[i * (n + 1)..(i + 1) * (n + 1)];
                a[i].copy_from_slice(&row[1..]);
                b[i] = -(row[0] - (0..n).map(|j| row[1 + j] * x[at.qddot(j)]).sum::<f64>());
            }
            solve(a, b)
        })
        .collect()
}

/// Solves A·x = b by Gaussian elimination with partial pivoting; `None` when singular.
fn solve(mut a: Vec<Vec<f64>>, mut b: Vec<f64>) -> Option<Vec<f64>> {
    let n = b.len();
    let scale = a
        .iter()
        .flatten()
        .fold(0.0f64, |m, x| m.max(x.abs()))
        .max(tolerance::TINY);
    for k in 0..n {
        let piv = (k..n).max_by(|&i, &j| a[i][k].abs().total_cmp(&a[j][k].abs()))?;
        if a[piv][k].abs() <= tolerance::RANK * scale {
            return None;
        }
        a.swap(k, piv);
        b.swap(k, piv);
        let (top, rest) = a.split_at_mut(k + 1);
        let pivot = &top[k];
        for (i, row) in rest.iter_mut().enumerate() {
            let f = row[k] / pivot[k];
            for (x, y) in row[k..].iter_mut().zip(&pivot[k..]) {
                *x -= f * y;
            }
            b[k + 1 + i] -= f * b[k];
        }
    }
    let mut x = vec![0.0; n];
    for k in (0..n).rev() {
        let s: f64 = (k + 1..n).map(|j| a[k][j] * x[j]).sum();
        x[k] = (b[k] - s) / a[k][k];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The sample points with their accelerations replaced by `acc` (points where `acc` is
/// undefined are dropped).
fn with_accelerations(p: &Prepared, acc: &[Option<Vec<f64>>]) -> PointSet {
    let at = p.system.state_layout();
    let points = p
        .points
        .points
        .iter()
        .zip(acc)
        .filter_map(|(x, a)| {
            let a = a.as_ref()?;
            let mut y = x.clone();
            for (j, v) in a.iter().enumerate() {
                y[at.qddot(j)] = *v;
            }
            Some(y)
        })
        .collect();
    PointSet { points }
}

/// Whether the equation `r = 0` involves the accelerations and holds at `acc` at every point
/// (relative to the size of its terms there), at no fewer than half the sample points.
pub fn holds_at(p: &mut Prepared, r: Id, acc: &[Option<Vec<f64>>]) -> bool {
    if !p.system.pool.variables(r).iter().any(|v| v.1 == 2) {
        return false;
    }
    let pts = with_accelerations(p, acc);
    if pts.points.len() * 2 < p.points.points.len() {
        return false;
    }
    // The top-level terms as written (not expanded: expanding a hostile answer could blow
    // up); a coarser split only makes the test stricter.
    let mut roots = vec![r];
    match p.system.pool.node(r) {
        Node::Add(t) => roots.extend(t.iter().copied()),
        _ => roots.push(r),
    }
    let Ok(vals) = values(&p.system, &roots, &pts) else {
        return false;
    };
    vals.iter().all(|v| {
        v.as_ref().is_some_and(|v| {
            let scale: f64 = v[1..].iter().map(|t| t.abs()).sum();
            v[0].abs() <= p.tolerance * (scale + tolerance::TINY)
        })
    })
}

/// Whether two sets of accelerations differ at some point where both are defined.
pub fn differ(a: &[Option<Vec<f64>>], b: &[Option<Vec<f64>>]) -> bool {
    a.iter().zip(b).any(|(x, y)| match (x, y) {
        (Some(x), Some(y)) => x
            .iter()
            .zip(y)
            .any(|(u, w)| (u - w).abs() > 1e-6 * (u.abs() + w.abs() + 1.0)),
        _ => false,
    })
}

/// Whether the student's equations determine the accelerations: their q̈-coefficient rows
/// have full rank at the first point where they can be evaluated.
pub fn full_rank(p: &mut Prepared, res: &[Id]) -> bool {
    let n = p.system.n();
    if res.len() != n {
        return false;
    }
    let coords = p.system.coordinate_syms();
    let mut roots = Vec::new();
    for &r in res {
        for &c in &coords {
            roots.push(p.system.pool.diff(r, c, 2));
        }
    }
    let Ok(vals) = values(&p.system, &roots, &p.points) else {
        return false;
    };
    vals.into_iter().flatten().next().is_some_and(|v| {
        let a: Vec<Vec<f64>> = v.chunks(n).map(<[f64]>::to_vec).collect();
        solve(a, vec![1.0; n]).is_some()
    })
}

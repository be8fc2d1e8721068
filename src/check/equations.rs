//! Equations compared through the accelerations they imply: an answer's equations must hold
//! at the true accelerations (one equation), or determine exactly them (a system).

use nalgebra::{DMatrix, DVector};

use super::compare::{close, values};
use super::prepare::{Failure, Prepared};
use crate::expr::Id;
use crate::mechanics::accel::Dynamics;

/// True accelerations at every point.
pub fn true_accelerations(p: &Prepared) -> Result<Vec<Option<Vec<f64>>>, Failure> {
    if let Some(a) = p.accelerations.get() {
        return Ok(a.clone());
    }
    let a = compute_accelerations(p)?;
    let _ = p.accelerations.set(a.clone());
    Ok(a)
}

fn compute_accelerations(p: &Prepared) -> Result<Vec<Option<Vec<f64>>>, Failure> {
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
    let dynamics = Dynamics::new(sys, &p.derivation).map_err(|e| ("unusable", e.to_string()))?;
    let mut scratch = dynamics.scratch();
    Ok(p.points
        .points
        .iter()
        .map(|x| dynamics.accelerations(x, &mut scratch).ok())
        .collect())
}

/// Whether the equations `res` determine the true accelerations (`equations`), or hold at
/// them (`equation`). Returns a description of the failure.
pub fn equations_hold(
    p: &mut Prepared,
    res: &[Id],
    system: bool,
) -> Result<Option<String>, Failure> {
    let n = p.system.n();
    let truth = true_accelerations(p)?;
    let coords = p.system.coordinate_syms();
    // A and b with R = A q'' + b.
    let mut roots = Vec::new();
    for &r in res {
        for &c in &coords {
            roots.push(p.system.pool.diff(r, c, 2));
        }
    }
    roots.extend(res.iter().copied());
    let vals = values(&p.system, &roots, &p.points).map_err(|e| ("sampling", e))?;
    let m = res.len();
    for (k, (t, v)) in truth.iter().zip(&vals).enumerate() {
        let (Some(t), Some(v)) = (t, v) else { continue };
        let a = DMatrix::from_fn(m, n, |i, j| v[i * n + j]);
        let acc_terms: Vec<f64> = (0..m)
            .map(|i| (0..n).map(|j| a[(i, j)] * t[j]).sum())
            .collect();
        if system {
            if m != n {
                return Ok(Some(format!("{m} equations for {n} coordinates")));
            }
            // b = R − A q'' at the sampled q''.
            let x = &p.points.points[k];
            let b = DVector::from_fn(n, |i, _| {
                v[m * n + i] - (0..n).map(|j| a[(i, j)] * x[1 + 3 * j + 2]).sum::<f64>()
            });
            let Some(sol) = a.clone().lu().solve(&(-b)) else {
                return Ok(Some(
                    "the equations do not determine the accelerations".into(),
                ));
            };
            let scale = t.iter().fold(0.0f64, |s, x| s.max(x.abs()));
            if !sol.iter().zip(t).all(|(x, y)| close(*x, *y, scale, 1e-7)) {
                return Ok(Some(format!(
                    "they give q'' = {:?} where the physics gives {:?}",
                    sol.as_slice(),
                    t
                )));
            }
        } else {
            let x = &p.points.points[k];
            for i in 0..m {
                let b = v[m * n + i] - (0..n).map(|j| a[(i, j)] * x[1 + 3 * j + 2]).sum::<f64>();
                let r = acc_terms[i] + b;
                let scale = acc_terms[i].abs() + b.abs();
                if r.abs() > 1e-7 * (scale + 1e-300) {
                    return Ok(Some(format!(
                        "it does not hold for the true accelerations (residual {r:.3e})"
                    )));
                }
            }
            if (0..m).any(|i| (0..n).all(|j| a[(i, j)] == 0.0)) {
                return Ok(Some("it contains no acceleration".into()));
            }
        }
    }
    Ok(None)
}

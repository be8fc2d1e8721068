//! Small linear algebra: symbolic determinants (Laplace expansion, for the few-coordinate
//! systems where closed forms are wanted) and the generalized symmetric eigenproblem
//! K v = λ M v by Cholesky reduction and nalgebra's `SymmetricEigen`.

use nalgebra::{DMatrix, DVector, SymmetricEigen};

use super::error::MechError;
use crate::expr::{Id, Pool};

/// det(m) by cofactor expansion along the first row (fine up to 4×4).
pub fn det(pool: &mut Pool, m: &[Vec<Id>]) -> Id {
    let n = m.len();
    match n {
        0 => pool.one(),
        1 => m[0][0],
        _ => {
            let mut terms = Vec::with_capacity(n);
            for j in 0..n {
                if pool.is_zero(m[0][j]) {
                    continue;
                }
                let minor: Vec<Vec<Id>> = m[1..]
                    .iter()
                    .map(|row| {
                        row.iter()
                            .enumerate()
                            .filter(|&(k, _)| k != j)
                            .map(|(_, &x)| x)
                            .collect()
                    })
                    .collect();
                let dm = det(pool, &minor);
                let t = pool.mul(m[0][j], dm);
                terms.push(if j % 2 == 1 { pool.neg(t) } else { t });
            }
            pool.sum(terms)
        }
    }
}

/// Solves `a x = b` symbolically by Cramer's rule; `None` when det(a) is identically 0.
pub(crate) fn cramer(pool: &mut Pool, a: &[Vec<Id>], b: &[Id]) -> Option<Vec<(Id, Id)>> {
    let d = det(pool, a);
    let d = pool.expand(d);
    if pool.is_zero(d) {
        return None;
    }
    let n = a.len();
    let mut out = Vec::with_capacity(n);
    for j in 0..n {
        let aj: Vec<Vec<Id>> = a
            .iter()
            .zip(b)
            .map(|(row, &bi)| {
                let mut r = row.clone();
                r[j] = bi;
                r
            })
            .collect();
        let num = det(pool, &aj);
        out.push((pool.expand(num), d));
    }
    Some(out)
}

/// Eigenvalues (ascending) and M-orthonormal eigenvectors (columns) of K v = λ M v, for
/// symmetric K and symmetric positive definite M.
pub(crate) fn generalized_eigen(
    k: &DMatrix<f64>,
    m: &DMatrix<f64>,
) -> Result<(DVector<f64>, DMatrix<f64>), MechError> {
    let n = k.nrows();
    let chol = m
        .clone()
        .cholesky()
        .ok_or(MechError::MassNotPositiveDefinite)?;
    let l = chol.l();
    let linv = l.clone().try_inverse().ok_or(MechError::SingularMassHere)?;
    let mut a = &linv * k * linv.transpose();
    // Symmetrize away rounding so SymmetricEigen sees an exactly symmetric matrix.
    a = (&a + a.transpose()) * 0.5;
    let eig = SymmetricEigen::new(a);
    let mut order: Vec<usize> = (0..n).collect();
    crate::sort::sort_by(&mut order, |&i, &j| {
        eig.eigenvalues[i].total_cmp(&eig.eigenvalues[j])
    });
    let values = DVector::from_fn(n, |i, _| eig.eigenvalues[order[i]]);
    let y = DMatrix::from_fn(n, n, |r, c| eig.eigenvectors[(r, order[c])]);
    let v = linv.transpose() * y;
    Ok((values, v))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn double_pendulum_eigenvalues() {
        // m = l = g = 1: K = [[2,0],[0,1]], M = [[2,1],[1,1]] → λ = 2 ∓ √2.
        let k = DMatrix::from_row_slice(2, 2, &[2.0, 0.0, 0.0, 1.0]);
        let m = DMatrix::from_row_slice(2, 2, &[2.0, 1.0, 1.0, 1.0]);
        let (vals, vecs) = generalized_eigen(&k, &m).unwrap();
        assert!((vals[0] - (2.0 - 2f64.sqrt())).abs() < 1e-12);
        assert!((vals[1] - (2.0 + 2f64.sqrt())).abs() < 1e-12);
        // mode ratios θ₂/θ₁ = ±√2
        let r0 = vecs[(1, 0)] / vecs[(0, 0)];
        let r1 = vecs[(1, 1)] / vecs[(0, 1)];
        assert!((r0 - 2f64.sqrt()).abs() < 1e-10, "{r0}");
        assert!((r1 + 2f64.sqrt()).abs() < 1e-10, "{r1}");
    }
}

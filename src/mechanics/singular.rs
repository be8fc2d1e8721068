//! The one rule for "this mass matrix is singular", shared by the checker, `derive` and the
//! simulator so that they never disagree about a state: M is singular when its smallest
//! singular value is at most [`SINGULAR`] times its largest (or M is zero or not finite).
//!
//! [`is_singular`] applies the rule with nalgebra's SVD. The simulator's hot path,
//! [`solve_in_place`], solves by Gaussian elimination without allocating and decides the same
//! rule from bounds that bracket the condition number: closed-form singular values for 2×2,
//! and κ₂ ≤ ‖M‖_F‖M⁻¹‖_F ≤ n·κ₂ for larger M, falling back to the SVD inside the bracket. The
//! equality of the two paths is a property test below.

use nalgebra::DMatrix;

/// M is singular when σ_min ≤ SINGULAR · σ_max: a condition number of 10¹² leaves about four
/// significant digits in the accelerations, the least a verdict or a motion can stand on.
pub const SINGULAR: f64 = 1e-12;

/// Whether `m` is singular by the rule (SVD; any size).
pub fn is_singular(m: &DMatrix<f64>) -> bool {
    if m.is_empty() {
        return false;
    }
    if !m.iter().all(|v| v.is_finite()) {
        return true;
    }
    let sv = m.singular_values();
    let (lo, hi) = sv
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
    !(hi > 0.0 && lo > SINGULAR * hi)
}

/// Whether the 2×2 matrix [[a, b], [c, d]] is singular by the rule, from its singular values
/// in closed form: σ_max² = (s + √(s² − 4 det²))/2 with s = ‖M‖_F², and σ_min σ_max = |det|.
pub fn is_singular_2x2(a: f64, b: f64, c: f64, d: f64) -> bool {
    let scale = a.abs().max(b.abs()).max(c.abs()).max(d.abs());
    // f64::max drops a NaN, so finiteness is checked entry by entry.
    if !(scale > 0.0 && [a, b, c, d].iter().all(|v| v.is_finite())) {
        return true;
    }
    // The ratio is scale-free; scaling first keeps s² from overflowing.
    let k = 1.0 / scale;
    let (a, b, c, d) = (a * k, b * k, c * k, d * k);
    let s = a * a + b * b + c * c + d * d;
    let det = a * d - b * c;
    // s/2 ≤ σ_max² ≤ s settles all but a thin band without the square root (the hot path of
    // the flip-time map's lanes).
    if det.abs() > SINGULAR * s {
        return false;
    }
    if det.abs() <= SINGULAR * 0.5 * s {
        return true;
    }
    let max2 = 0.5 * (s + (s * s - 4.0 * det * det).max(0.0).sqrt());
    // σ_min / σ_max = |det| / σ_max².
    det.abs() <= SINGULAR * max2
}

/// Solves M x = f for the row-major n × n `m` in place (x overwrites `f`; `m` is destroyed) by
/// Gaussian elimination with partial pivoting, without allocating for n ≤ 2. `None` when M is
/// singular by the rule.
pub fn solve_in_place(n: usize, m: &mut [f64], f: &mut [f64]) -> Option<()> {
    if n == 0 {
        return Some(());
    }
    if n == 1 {
        if !(m[0] != 0.0 && m[0].is_finite()) {
            return None;
        }
        f[0] /= m[0];
        return Some(());
    }
    if n == 2 {
        if is_singular_2x2(m[0], m[1], m[2], m[3]) {
            return None;
        }
        let det = m[0] * m[3] - m[1] * m[2];
        let (f0, f1) = (f[0], f[1]);
        f[0] = (f0 * m[3] - m[1] * f1) / det;
        f[1] = (m[0] * f1 - m[2] * f0) / det;
        return Some(());
    }
    match condition_bracket(n, m) {
        Bracket::Regular => {}
        Bracket::Singular => return None,
        Bracket::Unsure => {
            if is_singular(&DMatrix::from_row_slice(n, n, m)) {
                return None;
            }
        }
    }
    eliminate(n, m, f).then_some(())
}

/// Where ‖M‖_F‖M⁻¹‖_F places M against the rule.
enum Bracket {
    Regular,
    Singular,
    Unsure,
}

/// κ₂ ≤ ‖M‖_F‖M⁻¹‖_F ≤ n·κ₂: a product clearly below 1/SINGULAR is regular, clearly above
/// n/SINGULAR is singular, and anything else (or a failed inverse) is left to the SVD. M⁻¹
/// comes from an elimination of a copy; its relative error near the threshold is about
/// κ·ε ≈ 10⁻⁴, well inside the margin.
fn condition_bracket(n: usize, m: &[f64]) -> Bracket {
    const MARGIN: f64 = 0.5;
    if !m.iter().all(|v| v.is_finite()) {
        return Bracket::Singular;
    }
    let norm = m.iter().map(|v| v * v).sum::<f64>().sqrt();
    if norm == 0.0 {
        return Bracket::Singular;
    }
    let mut inv_norm2 = 0.0;
    // The simulator calls this at every step: no allocation up to 8 coordinates.
    let (mut lu_stack, mut col_stack) = ([0.0f64; 64], [0.0f64; 8]);
    let (mut lu_heap, mut col_heap) = (Vec::new(), Vec::new());
    let (lu, col): (&mut [f64], &mut [f64]) = if n <= 8 {
        (&mut lu_stack[..n * n], &mut col_stack[..n])
    } else {
        lu_heap.resize(n * n, 0.0);
        col_heap.resize(n, 0.0);
        (&mut lu_heap, &mut col_heap)
    };
    // One elimination per column of M⁻¹ keeps this simple; n ≥ 3 systems are rare and small.
    for j in 0..n {
        lu.copy_from_slice(m);
        col.fill(0.0);
        col[j] = 1.0;
        if !eliminate(n, lu, col) || !col.iter().all(|v| v.is_finite()) {
            return Bracket::Unsure;
        }
        inv_norm2 += col.iter().map(|v| v * v).sum::<f64>();
    }
    let kappa_f = norm * inv_norm2.sqrt();
    if kappa_f < MARGIN / SINGULAR {
        Bracket::Regular
    } else if kappa_f > n as f64 / (MARGIN * SINGULAR) {
        Bracket::Singular
    } else {
        Bracket::Unsure
    }
}

/// Gaussian elimination with partial pivoting; false on a zero pivot.
fn eliminate(n: usize, m: &mut [f64], f: &mut [f64]) -> bool {
    for k in 0..n {
        let Some(p) = (k..n).max_by(|&a, &b| m[a * n + k].abs().total_cmp(&m[b * n + k].abs()))
        else {
            return false;
        };
        if m[p * n + k] == 0.0 {
            return false;
        }
        if p != k {
            for c in 0..n {
                m.swap(k * n + c, p * n + c);
            }
            f.swap(k, p);
        }
        let pivot = m[k * n + k];
        for r in k + 1..n {
            let factor = m[r * n + k] / pivot;
            if factor != 0.0 {
                for c in k..n {
                    m[r * n + c] -= factor * m[k * n + c];
                }
                f[r] -= factor * f[k];
            }
        }
    }
    for k in (0..n).rev() {
        let mut s = f[k];
        for c in k + 1..n {
            s -= m[k * n + c] * f[c];
        }
        f[k] = s / m[k * n + k];
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{DMatrix, DVector};
    use proptest::prelude::*;

    /// U diag(σ) Vᵀ with orthogonal U, V from QR of the given entries.
    fn with_singular_values(n: usize, u: &[f64], v: &[f64], sigma: &[f64]) -> DMatrix<f64> {
        let q = |e: &[f64]| DMatrix::from_row_slice(n, n, e).qr().q();
        q(u) * DMatrix::from_diagonal(&DVector::from_row_slice(sigma)) * q(v).transpose()
    }

    #[test]
    fn hand_solutions_and_singular_matrices() {
        // [[0, 2], [3, 1]] x = [4, 5] → x = (1, 2).
        let mut m = [0.0, 2.0, 3.0, 1.0];
        let mut f = [4.0, 5.0];
        assert!(solve_in_place(2, &mut m, &mut f).is_some());
        assert!((f[0] - 1.0).abs() < 1e-15 && (f[1] - 2.0).abs() < 1e-15);
        assert!(solve_in_place(2, &mut [1.0, 2.0, 2.0, 4.0], &mut [1.0, 1.0]).is_none());
        let mut m = [2.0, 0.0, 0.0, 0.0, 3.0, 0.0, 0.0, 0.0, 4.0];
        let mut f = [2.0, 6.0, 12.0];
        assert!(solve_in_place(3, &mut m, &mut f).is_some());
        assert_eq!(f, [1.0, 2.0, 3.0]);
        let mut rank2 = [1.0, 2.0, 3.0, 2.0, 4.0, 6.0, 0.0, 1.0, 1.0];
        assert!(solve_in_place(3, &mut rank2, &mut [0.0; 3]).is_none());
        assert!(solve_in_place(1, &mut [0.0], &mut [1.0]).is_none());
        assert!(solve_in_place(2, &mut [f64::NAN, 0.0, 0.0, 1.0], &mut [1.0, 1.0]).is_none());
        // A huge and a tiny mass together are still regular (ratio 10⁻⁸).
        assert!(solve_in_place(2, &mut [1e4, 0.0, 0.0, 1e-4], &mut [1.0, 1.0]).is_some());
        assert!(!is_singular_2x2(1e150, 0.0, 0.0, 1e150));
    }

    proptest! {
        /// The fast path decides the rule exactly as the SVD does, away from a thin band
        /// around the threshold where rounding may tip either way.
        #[test]
        fn the_fast_solve_applies_the_svd_rule(
            n in 2usize..6,
            u in proptest::collection::vec(-1.0f64..1.0, 25),
            v in proptest::collection::vec(-1.0f64..1.0, 25),
            spread in proptest::collection::vec(0.0f64..1.0, 5),
            log_ratio in -16.0f64..-8.0,
            scale in -6.0f64..6.0,
        ) {
            let mut sigma: Vec<f64> = spread[..n].iter().map(|s| 10f64.powf(scale) * (1.0 + s)).collect();
            sigma[n - 1] = sigma[0] * 10f64.powf(log_ratio);
            let m = with_singular_values(n, &u[..n * n], &v[..n * n], &sigma);
            let (lo, hi) = sigma.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &x| (a.min(x), b.max(x)));
            let ratio = lo / hi;
            prop_assume!((ratio / SINGULAR).log10().abs() > 0.3);
            let want = ratio <= SINGULAR;
            prop_assert_eq!(is_singular(&m), want);
            let mut rows: Vec<f64> = m.transpose().iter().copied().collect();
            let mut f = vec![1.0; n];
            prop_assert_eq!(solve_in_place(n, &mut rows, &mut f).is_none(), want);
            if n == 2 {
                prop_assert_eq!(is_singular_2x2(m[(0, 0)], m[(0, 1)], m[(1, 0)], m[(1, 1)]), want);
            }
        }
    }
}

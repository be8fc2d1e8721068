//! The linearized problem M ẍ + C ẋ + K x = 0 with velocity terms (C = G + D: gyroscopic
//! and damping parts) or a non-symmetric K, through the quadratic eigenproblem
//! (λ² M + λ C + K) v = 0. nalgebra has no generalized non-symmetric solver, so M = L Lᵀ
//! (Cholesky) reduces it to ÿ + C̃ ẏ + K̃ y = 0 with C̃ = L⁻¹ C L⁻ᵀ, K̃ = L⁻¹ K L⁻ᵀ, whose
//! 2n×2n companion matrix [[0, I], [−K̃, −C̃]] has the eigenvalues λ (Schur form).
//!
//! Each λ is classified with tolerances relative to the problem's own rate scale, never
//! relative to 1: zero (a free direction), a growth (Re λ > 0), a decay (Re λ < 0, with its
//! damping ratio when it oscillates), or an undamped oscillation (λ = ±iω).

use nalgebra::DMatrix;

use super::equilibria::{EIGENVALUE_ZERO, Stability};
use super::error::MechError;

/// A real part within this fraction of the rate scale is rounding: a simple eigenvalue is
/// computed to ~1e-15 of it, a defective pair (two modes colliding) to ~1e-8.
const REAL_PART_ZERO: f64 = 1e-7;

/// QR sweeps allowed per row of the companion matrix.
const SCHUR_SWEEPS: usize = 200;

/// An oscillation that decays: λ = −γ ± i ω_d.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Damped {
    /// The damped angular frequency ω_d = Im λ.
    pub frequency: f64,
    /// The decay rate γ = −Re λ (amplitude ∝ e^(−γt)).
    pub decay_rate: f64,
    /// The damping ratio ζ = γ/|λ| (0 undamped, 1 critical).
    pub damping_ratio: f64,
}

/// The classified spectrum of M ẍ + C ẋ + K x = 0.
#[derive(Clone, Debug)]
pub struct Spectrum {
    /// Undamped angular frequencies, ascending, with one 0 for each mode of zero frequency.
    pub(crate) frequencies: Vec<f64>,
    /// Growth rates Re λ > 0, one per mode, ascending.
    pub(crate) growth_rates: Vec<f64>,
    /// Damped oscillations, by ascending frequency.
    pub(crate) damped: Vec<Damped>,
    /// Decay rates of the modes that decay without oscillating (overdamped), ascending.
    pub(crate) decay_rates: Vec<f64>,
    /// Directions along which a displacement is not restored (the null space of K), in the
    /// original coordinates, each normalized so its largest component is 1.
    pub(crate) free_directions: Vec<Vec<f64>>,
    /// Unstable if anything grows; marginal if some λ = 0; otherwise stable.
    pub(crate) stability: Stability,
}

impl Spectrum {
    fn empty() -> Spectrum {
        Spectrum {
            frequencies: Vec::new(),
            growth_rates: Vec::new(),
            damped: Vec::new(),
            decay_rates: Vec::new(),
            free_directions: Vec::new(),
            stability: Stability::Marginal,
        }
    }
}

/// Solves M ẍ + C ẋ + K x = 0. `rate_floor` is a rate below which nothing is resolved (from
/// the size of the terms of K and C, so that rounding left over from cancelling terms is
/// zero even when every eigenvalue is tiny).
pub(crate) fn solve(
    m: &DMatrix<f64>,
    c: &DMatrix<f64>,
    k: &DMatrix<f64>,
    rate_floor: f64,
) -> Result<Spectrum, MechError> {
    let l = m
        .clone()
        .cholesky()
        .ok_or(MechError::MassNotPositiveDefinite)?
        .l();
    let linv = l.try_inverse().ok_or(MechError::SingularMassHere)?;
    let kt = &linv * k * linv.transpose();
    let ct = &linv * c * linv.transpose();
    let eig = companion_eigenvalues(&kt, &ct)?;
    let scale = eig.iter().fold(rate_floor, |s, z| s.max(z.norm()));
    let zero = EIGENVALUE_ZERO.sqrt() * scale;
    let re_zero = REAL_PART_ZERO * scale;
    let mut out = Spectrum::empty();
    let mut zeros = 0usize;
    for z in eig.iter() {
        if z.norm() <= zero {
            zeros += 1;
        } else if z.im < -re_zero.max(zero) {
            // The conjugate of a pair is counted with its partner.
        } else if z.re > re_zero {
            out.growth_rates.push(z.re);
        } else if z.re < -re_zero {
            if z.im > zero {
                out.damped.push(Damped {
                    frequency: z.im,
                    decay_rate: -z.re,
                    damping_ratio: -z.re / z.norm(),
                });
            } else {
                out.decay_rates.push(-z.re);
            }
        } else {
            out.frequencies.push(z.im.abs());
        }
    }
    out.free_directions = null_space(&kt, zero * zero)
        .into_iter()
        .map(|y| normalize(&(linv.transpose() * y)))
        .collect();
    let growing = eig
        .iter()
        .filter(|z| z.norm() > zero && z.re > re_zero)
        .count();
    let undamped = (c + c.transpose()).iter().all(|x| *x == 0.0);
    let zero_modes = if undamped {
        // The spectrum pairs λ with −λ: of the n modes, each oscillation uses one pair, each
        // growing λ one pair with its decaying mirror, and what is left has ω = 0 (a free
        // motion, or a pair of conjugate neutral directions such as a guiding centre).
        (m.nrows()).saturating_sub(out.frequencies.len() + growing)
    } else {
        // With damping: λ = 0 beyond the static null directions are uniform motions x = v t.
        zeros.saturating_sub(out.free_directions.len())
    };
    out.frequencies.extend(std::iter::repeat_n(0.0, zero_modes));
    crate::sort::sort_by(&mut out.frequencies, f64::total_cmp);
    crate::sort::sort_by(&mut out.growth_rates, f64::total_cmp);
    crate::sort::sort_by(&mut out.decay_rates, f64::total_cmp);
    crate::sort::sort_by(&mut out.damped, |a, b| a.frequency.total_cmp(&b.frequency));
    out.stability = if !out.growth_rates.is_empty() {
        Stability::Unstable
    } else if zeros > 0 {
        Stability::Marginal
    } else {
        Stability::Stable
    };
    Ok(out)
}

/// The eigenvalues of the companion matrix [[0, I], [−K̃, −C̃]] of ÿ + C̃ ẏ + K̃ y = 0.
fn companion_eigenvalues(
    kt: &DMatrix<f64>,
    ct: &DMatrix<f64>,
) -> Result<Vec<nalgebra::Complex<f64>>, MechError> {
    let n = kt.nrows();
    let mut a = DMatrix::<f64>::zeros(2 * n, 2 * n);
    for i in 0..n {
        a[(i, n + i)] = 1.0;
        for j in 0..n {
            a[(n + i, j)] = -kt[(i, j)];
            a[(n + i, n + j)] = -ct[(i, j)];
        }
    }
    if !a.iter().all(|x| x.is_finite()) {
        return Err(MechError::Undefined {
            what: "the linearized equations".into(),
        });
    }
    // A bounded number of QR sweeps (convergence takes a few per eigenvalue).
    let eig = nalgebra::Schur::try_new(a, f64::EPSILON, SCHUR_SWEEPS * (2 * n).max(1))
        .ok_or(MechError::Undefined {
            what: "the eigenvalues of the linearized equations (no convergence)".into(),
        })?
        .complex_eigenvalues();
    Ok(eig.iter().copied().collect())
}

/// An orthonormal basis of the vectors v with |K v| ≤ tol |v| (right singular vectors).
pub(crate) fn null_space(k: &DMatrix<f64>, tol: f64) -> Vec<nalgebra::DVector<f64>> {
    let n = k.ncols();
    if n == 0 {
        return Vec::new();
    }
    // Padding to a square matrix keeps every right singular vector in the thin SVD.
    let rows = k.nrows().max(n);
    let padded = DMatrix::from_fn(rows, n, |r, c| if r < k.nrows() { k[(r, c)] } else { 0.0 });
    let svd = padded.svd(false, true);
    let Some(vt) = svd.v_t else {
        return Vec::new();
    };
    (0..n)
        .filter(|&i| svd.singular_values[i] <= tol)
        .map(|i| vt.row(i).transpose())
        .collect()
}

/// Largest component 1 (by size), first nonzero component positive, rounding set to 0.
pub(crate) fn normalize(v: &nalgebra::DVector<f64>) -> Vec<f64> {
    let big = v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    if big == 0.0 {
        return v.iter().copied().collect();
    }
    let mut s: Vec<f64> = v
        .iter()
        .map(|x| if x.abs() <= 1e-9 * big { 0.0 } else { x / big })
        .collect();
    if s.iter().find(|x| **x != 0.0).is_some_and(|x| *x < 0.0) {
        s.iter_mut().for_each(|x| *x = -*x);
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mat(n: usize, v: &[f64]) -> DMatrix<f64> {
        DMatrix::from_row_slice(n, n, v)
    }

    /// A particle in an isotropic trap of frequency 2 seen from a frame rotating at Ω:
    /// ẍ − 2Ωẏ + (4 − Ω²)x = 0, ÿ + 2Ωẋ + (4 − Ω²)y = 0 → ω = 2 ∓ Ω (textbook, in the
    /// rotating frame), stable for every Ω (the trap is isotropic).
    #[test]
    fn rotating_isotropic_trap() {
        for om in [0.5, 1.0, 3.0] {
            let m = mat(2, &[1.0, 0.0, 0.0, 1.0]);
            let c = mat(2, &[0.0, -2.0 * om, 2.0 * om, 0.0]);
            let k = mat(2, &[4.0 - om * om, 0.0, 0.0, 4.0 - om * om]);
            let s = solve(&m, &c, &k, 0.0).unwrap();
            assert_eq!(s.stability, Stability::Stable, "Ω = {om}");
            let mut want = [(2.0f64 - om).abs(), 2.0 + om];
            crate::sort::sort_by(&mut want, f64::total_cmp);
            assert_eq!(s.frequencies.len(), 2);
            for (a, b) in s.frequencies.iter().zip(want) {
                assert!((a - b).abs() < 1e-12, "{:?} vs {want:?}", s.frequencies);
            }
        }
    }

    /// A damped oscillator ẍ + 2ζω₀ẋ + ω₀²x = 0: decay rate ζω₀, ω_d = ω₀√(1 − ζ²).
    #[test]
    fn damped_oscillator() {
        let (w0, zeta) = (3.0, 0.1);
        let s = solve(
            &mat(1, &[1.0]),
            &mat(1, &[2.0 * zeta * w0]),
            &mat(1, &[w0 * w0]),
            0.0,
        )
        .unwrap();
        assert_eq!(s.stability, Stability::Stable);
        assert!(s.frequencies.is_empty() && s.growth_rates.is_empty());
        let d = s.damped[0];
        assert!((d.decay_rate - zeta * w0).abs() < 1e-12);
        assert!((d.damping_ratio - zeta).abs() < 1e-12);
        assert!((d.frequency - w0 * (1.0 - zeta * zeta).sqrt()).abs() < 1e-12);
    }

    /// A free particle with linear drag: one free direction, no frequency, a decay rate.
    #[test]
    fn free_particle_with_drag() {
        let s = solve(&mat(1, &[2.0]), &mat(1, &[1.0]), &mat(1, &[0.0]), 0.0).unwrap();
        assert_eq!(s.stability, Stability::Marginal);
        assert_eq!(s.free_directions, vec![vec![1.0]]);
        assert!(s.frequencies.is_empty());
        assert!((s.decay_rates[0] - 0.5).abs() < 1e-12);
    }
}

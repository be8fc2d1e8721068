//! The linearized equations about a point at rest: M δq̈ + C δq̇ + K δq = 0 with
//! M = M(q₀), K = −∂f/∂q and C = −∂f/∂q' at (q₀, q' = 0). Every entry is evaluated with its
//! rounding magnitude, so an entry that is rounding left over from cancelling terms is exactly
//! 0 (never decided relative to 1: a Coriolis term 2·m·Ω with m = 1e-15 is real).
//!
//! With holonomic constraints φ(q) = 0 the motion is linearized on the constraint manifold:
//! the multipliers at rest λ₀ solve Aᵀλ₀ = −f(q₀) (A = ∂φ/∂q), the constraint forces add
//! −Σ λ₀ⱼ ∂²φⱼ/∂q² to K, and every matrix is restricted to the tangent space T = null(A):
//! Tᵀ M T, Tᵀ K T, Tᵀ C T. (The Cartesian pendulum x² + y² = L² gets ω² = g/L this way.)

use nalgebra::{DMatrix, DVector};

use super::derive::Derivation;
use super::error::MechError;
use super::magnitude::Sized;
use super::quadratic::null_space;
use super::system::{ConstraintKind, System};
use crate::expr::Id;

/// A point is on a constraint, or an equilibrium on the manifold, when the residual is
/// within this fraction of the size of its terms.
const RESIDUAL_ZERO: f64 = 1e-8;

/// The linearized equations at one point.
#[derive(Clone, Debug)]
pub(crate) struct Linear {
    /// The mass matrix M(q₀).
    pub(crate) m: DMatrix<f64>,
    /// The stiffness K = −∂f/∂q (with the constraint forces' curvature on a manifold).
    pub(crate) k: DMatrix<f64>,
    /// The velocity matrix C = −∂f/∂q' = G + D (gyroscopic and damping parts).
    pub(crate) c: DMatrix<f64>,
    /// The size of K's terms per unit mass (the ω² scale that rounding is measured against).
    pub(crate) k_size: f64,
    /// The size of C's terms per unit mass (a rate scale).
    pub(crate) c_size: f64,
    /// Columns: the coordinates' displacement for each reduced coordinate (identity when
    /// there are no constraints).
    pub(crate) tangent: DMatrix<f64>,
}

impl Linear {
    /// Whether K is symmetric and C is zero, so the symmetric eigenproblem is exact.
    pub fn conservative(&self) -> bool {
        let tol = 1e-9 * self.k_size * self.m.diagonal().amax().max(f64::MIN_POSITIVE);
        let asym = (&self.k - self.k.transpose()).amax();
        self.c.iter().all(|x| *x == 0.0) && asym <= tol
    }
}

impl System {
    /// M, K and C at rest at `q0`, on the constraint manifold when there are constraints.
    pub(crate) fn linearize(
        &mut self,
        d: &Derivation,
        params: &[f64],
        q0: &[f64],
    ) -> Result<Linear, MechError> {
        let n = self.n();
        let coords = self.coordinate_syms();
        let mut roots: Vec<Id> = d.mass.iter().flatten().copied().collect();
        for order in [0u8, 1] {
            for &f in &d.forcing {
                for &q in &coords {
                    let df = self.pool.diff(f, q, order);
                    roots.push(self.pool.neg(df));
                }
            }
        }
        let v = self.sized(&roots, params, q0)?;
        let entry = |s: Sized| if s.negligible() { 0.0 } else { s.value };
        let block = |k: usize| DMatrix::from_fn(n, n, |r, c| entry(v[k * n * n + r * n + c]));
        let size = |k: usize| DMatrix::from_fn(n, n, |r, c| v[k * n * n + r * n + c].magnitude);
        let m = block(0);
        let lin = Linear {
            k_size: per_unit_mass(&size(1), &m),
            c_size: per_unit_mass(&size(2), &m),
            k: block(1),
            c: block(2),
            m,
            tangent: DMatrix::identity(n, n),
        };
        if self.constraints.is_empty() {
            return Ok(lin);
        }
        self.on_manifold(d, params, q0, lin)
    }

    /// The values of `roots` at rest at `q0`, with their magnitudes; every one finite.
    fn sized(&self, roots: &[Id], params: &[f64], q0: &[f64]) -> Result<Vec<Sized>, MechError> {
        self.magnitudes(roots)?
            .eval(&self.state_layout().at_rest(q0, params))
            .filter(|v| v.iter().all(|s| s.value.is_finite()))
            .ok_or_else(|| MechError::Undefined {
                what: "the linearized equations".into(),
            })
    }

    /// f, then each φⱼ, then for each j and i: ∂φⱼ/∂qᵢ followed by ∂²φⱼ/∂qᵢ∂qₖ for every k.
    fn constraint_roots(&mut self, d: &Derivation) -> Vec<Id> {
        let coords = self.coordinate_syms();
        let phis: Vec<Id> = self.constraints.iter().map(|c| c.expr).collect();
        let mut roots: Vec<Id> = d.forcing.clone();
        roots.extend(phis.iter().copied());
        for &phi in &phis {
            for &qi in &coords {
                let a = self.pool.diff(phi, qi, 0);
                roots.push(a);
                for &qk in &coords {
                    roots.push(self.pool.diff(a, qk, 0));
                }
            }
        }
        roots
    }

    /// Restricts `lin` to the holonomic constraints' tangent space at `q0`, with the
    /// constraint forces' stiffness.
    fn on_manifold(
        &mut self,
        d: &Derivation,
        params: &[f64],
        q0: &[f64],
        lin: Linear,
    ) -> Result<Linear, MechError> {
        let n = self.n();
        if self
            .constraints
            .iter()
            .any(|c| c.kind == ConstraintKind::Nonholonomic)
        {
            return Err(MechError::ModesRolling);
        }
        let mm = self.constraints.len();
        let roots = self.constraint_roots(d);
        let v = self.sized(&roots, params, q0)?;
        if let Some(j) = (0..mm).find(|&j| !near_zero(v[n + j])) {
            return Err(MechError::OffConstraint { index: j + 1 });
        }
        let at = |j: usize, i: usize| n + mm + j * n * (n + 1) + i * (n + 1);
        let a = DMatrix::from_fn(mm, n, |j, i| v[at(j, i)].value);
        let f0 = DVector::from_fn(n, |i, _| v[i].value);
        let f_size = (0..n).fold(0.0f64, |s, i| s.max(v[i].magnitude));
        // Aᵀλ = −f in least squares; a residual means the point is no equilibrium here.
        let at_t = a.transpose();
        let lambda = at_t
            .clone()
            .svd(true, true)
            .solve(&(-&f0), 1e-12 * a.amax())
            .map_err(|_| MechError::DependentConstraints)?;
        let residual = (&f0 + &at_t * &lambda).amax();
        if residual > RESIDUAL_ZERO * f_size {
            return Err(MechError::NotConstrainedEquilibrium { residual });
        }
        let mut k = lin.k.clone();
        for j in 0..mm {
            for i in 0..n {
                for kk in 0..n {
                    k[(i, kk)] -= lambda[j] * v[at(j, i) + 1 + kk].value;
                }
            }
        }
        let t = tangent_basis(&a)?;
        let tt = t.transpose();
        // The constraint forces' stiffness is measured against the size of the forces they
        // balance (f's terms over |A|), not against its own value: a multiplier that is
        // rounding (nothing to balance) gives a stiffness that is rounding too.
        let curvature = (0..mm)
            .flat_map(|j| (0..n * n).map(move |e| (j, e)))
            .fold(0.0f64, |s, (j, e)| {
                s.max(v[at(j, e / n) + 1 + e % n].magnitude)
            });
        let min_mass = lin
            .m
            .diagonal()
            .iter()
            .fold(f64::INFINITY, |s, x| s.min(x.abs()));
        let constraint_size = f_size / a.amax().max(f64::MIN_POSITIVE) * curvature / min_mass;
        let k_size = if constraint_size.is_finite() {
            lin.k_size.max(constraint_size)
        } else {
            lin.k_size
        };
        Ok(Linear {
            m: &tt * &lin.m * &t,
            k: &tt * k * &t,
            c: &tt * &lin.c * &t,
            tangent: t,
            k_size,
            ..lin
        })
    }
}

/// An orthonormal basis (columns) of null(A); dependent constraints are refused.
fn tangent_basis(a: &DMatrix<f64>) -> Result<DMatrix<f64>, MechError> {
    let n = a.ncols();
    let tol = 1e-10 * a.amax();
    let basis = null_space(a, tol);
    if basis.len() + a.nrows() != n {
        return Err(MechError::DependentConstraints);
    }
    if basis.is_empty() {
        return Err(MechError::ModesNoFreedom);
    }
    Ok(DMatrix::from_columns(&basis))
}

fn near_zero(s: Sized) -> bool {
    s.value.abs() <= RESIDUAL_ZERO * s.magnitude
}

/// maxᵢ Σⱼ |entry sizes|ᵢⱼ / Mᵢᵢ: the scale per unit mass that rounding is measured against.
fn per_unit_mass(sizes: &DMatrix<f64>, m: &DMatrix<f64>) -> f64 {
    (0..sizes.nrows())
        .map(|i| sizes.row(i).sum() / m[(i, i)].abs())
        .filter(|v| v.is_finite())
        .fold(0.0, f64::max)
}

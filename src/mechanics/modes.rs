//! Small oscillations about an equilibrium: M₀ = M(q₀) and K = −∂f/∂q at (q₀, q' = 0); the
//! generalized eigenproblem K v = ω² M₀ v gives frequencies, mode shapes and growth rates.
//! When velocity-linear terms survive at the equilibrium (rotating frames), the first-order
//! 2n×2n problem is solved instead. The symbolic analysis is in
//! [`symbolic_modes`](super::symbolic_modes).

use nalgebra::DMatrix;

use super::derive::Derivation;
use super::equilibria::{EIGENVALUE_ZERO, Stability, Statics};
use super::error::MechError;
use super::system::System;

pub use super::symbolic_modes::SymbolicModes;
use crate::expr::Id;

/// One normal mode.
#[derive(Clone, Debug)]
pub struct Mode {
    /// The eigenvalue ω² (negative for an unstable direction).
    pub omega_squared: f64,
    /// Shape, normalized so that the largest component is 1 (empty when not available).
    pub shape: Vec<f64>,
}

/// The small-oscillation analysis at one point.
#[derive(Clone, Debug)]
pub struct Modes {
    pub point: Vec<f64>,
    pub stability: Stability,
    /// Angular frequencies ω of the oscillating modes, ascending.
    pub frequencies: Vec<f64>,
    /// Growth rates of the unstable directions, ascending.
    pub growth_rates: Vec<f64>,
    pub modes: Vec<Mode>,
    /// Velocity-linear terms survive, so the first-order problem was solved.
    pub gyroscopic: bool,
}

impl Modes {
    /// For two coordinates: "in phase" / "antiphase" with the amplitude ratio q₂/q₁.
    pub fn describe(&self, names: &[String]) -> Vec<String> {
        self.modes
            .iter()
            .map(|m| {
                if m.shape.len() != 2 || m.shape[0].abs() < 1e-12 {
                    return String::new();
                }
                let r = m.shape[1] / m.shape[0];
                let kind = if r > 0.0 { "in phase" } else { "antiphase" };
                format!("{kind}, {}/{} = {:.6}", names[1], names[0], r)
            })
            .collect()
    }
}

impl System {
    /// Normal modes about `q0` with parameter values `params`.
    pub fn modes_at(
        &mut self,
        d: &Derivation,
        params: &[f64],
        q0: &[f64],
    ) -> Result<Modes, MechError> {
        let statics = Statics::new(self, d, params)?;
        let n = self.n();
        let (stability, vals, vecs) = statics.stability(q0)?;
        // Velocity-linear terms at the equilibrium: C = ∂f/∂q' at (q₀, 0).
        if let Some(c) = self.velocity_coupling(d, params, q0)? {
            return self.first_order_modes(d, params, q0, c);
        }
        let mut modes = Vec::with_capacity(n);
        let mut frequencies = Vec::new();
        let mut growth_rates = Vec::new();
        for (k, &w2) in vals.iter().enumerate() {
            let col: Vec<f64> = (0..n).map(|r| vecs[(r, k)]).collect();
            modes.push(Mode {
                omega_squared: w2,
                shape: normalize_shape(&col),
            });
            if w2 > 0.0 {
                frequencies.push(w2.sqrt());
            } else if w2 < 0.0 {
                growth_rates.push((-w2).sqrt());
            }
        }
        frequencies.sort_by(f64::total_cmp);
        growth_rates.sort_by(f64::total_cmp);
        Ok(Modes {
            point: q0.to_vec(),
            stability,
            frequencies,
            growth_rates,
            modes,
            gyroscopic: false,
        })
    }

    /// C = ∂f/∂q' at (q₀, 0), or `None` when every entry is zero up to rounding relative to
    /// its own terms (never relative to 1: a Coriolis term 2·m·Ω with m = 1e-15 is real).
    fn velocity_coupling(
        &mut self,
        d: &Derivation,
        params: &[f64],
        q0: &[f64],
    ) -> Result<Option<DMatrix<f64>>, MechError> {
        let n = self.n();
        let coords = self.coordinate_syms();
        let mut roots = Vec::with_capacity(n * n);
        for &f in &d.forcing {
            for &c in &coords {
                roots.push(self.pool.diff(f, c, 1));
            }
        }
        let v = self
            .magnitudes(&roots)?
            .eval(&self.state_layout().at_rest(q0, params))
            .ok_or_else(|| MechError::Undefined {
                what: "the linearized equations".into(),
            })?;
        if v.iter().all(|x| x.negligible()) {
            return Ok(None);
        }
        Ok(Some(DMatrix::from_fn(n, n, |r, c| v[r * n + c].value)))
    }

    /// The values of `roots` at rest at `q0` (for the linearized equations).
    fn values_at_rest(
        &self,
        roots: &[Id],
        params: &[f64],
        q0: &[f64],
    ) -> Result<Vec<f64>, MechError> {
        let prog = self.compile(roots)?;
        prog.eval(&self.state_layout().at_rest(q0, params))
            .map_err(|_| MechError::Undefined {
                what: "the linearized equations".into(),
            })
    }

    /// The first-order problem ẋ = A x, x = (δq, δq'), A = [[0, I], [M⁻¹(−K), M⁻¹C]].
    fn first_order_modes(
        &mut self,
        d: &Derivation,
        params: &[f64],
        q0: &[f64],
        c: DMatrix<f64>,
    ) -> Result<Modes, MechError> {
        let n = self.n();
        let coords = self.coordinate_syms();
        let mut roots: Vec<Id> = d.mass.iter().flatten().copied().collect();
        for &f in &d.forcing {
            for &q in &coords {
                roots.push(self.pool.diff(f, q, 0));
            }
        }
        let v = self.values_at_rest(&roots, params, q0)?;
        let m = DMatrix::from_fn(n, n, |r, cc| v[r * n + cc]);
        let fq = DMatrix::from_fn(n, n, |r, cc| v[n * n + r * n + cc]);
        let minv = m.try_inverse().ok_or(MechError::SingularMassHere)?;
        let mut a = DMatrix::<f64>::zeros(2 * n, 2 * n);
        for i in 0..n {
            a[(i, n + i)] = 1.0;
        }
        let lower_left = &minv * fq;
        let lower_right = &minv * c;
        for i in 0..n {
            for j in 0..n {
                a[(n + i, j)] = lower_left[(i, j)];
                a[(n + i, n + j)] = lower_right[(i, j)];
            }
        }
        let eig = a.complex_eigenvalues();
        let scale = eig.iter().fold(0.0f64, |s, z| s.max(z.norm())).max(1e-300);
        let mut frequencies = Vec::new();
        let mut growth_rates = Vec::new();
        for z in eig.iter() {
            if z.re > EIGENVALUE_ZERO * scale {
                growth_rates.push(z.re);
            } else if z.im > EIGENVALUE_ZERO * scale {
                frequencies.push(z.im);
            }
        }
        frequencies.sort_by(f64::total_cmp);
        growth_rates.sort_by(f64::total_cmp);
        let stability = if !growth_rates.is_empty() {
            Stability::Unstable
        } else if frequencies.len() == n {
            Stability::Stable
        } else {
            Stability::Marginal
        };
        Ok(Modes {
            point: q0.to_vec(),
            stability,
            frequencies,
            growth_rates,
            modes: Vec::new(),
            gyroscopic: true,
        })
    }
}

fn normalize_shape(v: &[f64]) -> Vec<f64> {
    let k = v
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
        .map_or(0, |(i, _)| i);
    let big = v.get(k).copied().unwrap_or(1.0);
    if big == 0.0 {
        return v.to_vec();
    }
    // Largest component 1; then make the first nonzero component positive.
    let mut s: Vec<f64> = v.iter().map(|x| x / big).collect();
    if let Some(first) = s.iter().find(|x| x.abs() > 1e-12)
        && *first < 0.0
    {
        s.iter_mut().for_each(|x| *x = -*x);
    }
    s
}

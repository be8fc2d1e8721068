//! Small oscillations about an equilibrium: the linearized equations M δq̈ + C δq̇ + K δq = 0
//! (see `linearize`, on the constraint manifold when there are
//! constraints). Without velocity terms and with a symmetric K, the generalized symmetric
//! eigenproblem K v = ω² M v gives frequencies, mode shapes and growth rates; otherwise the
//! quadratic eigenproblem (see `quadratic`) gives frequencies, damping and
//! growth. ω² = 0 (a free direction: a cart, a translating chain) is decided relative to the
//! matrices' scale, never by the sign of rounding. The symbolic analysis is in
//! `symbolic_modes`.

use nalgebra::DMatrix;

use super::derive::Derivation;
use super::equilibria::{EIGENVALUE_ZERO, Stability, Statics};
use super::error::MechError;
use super::linalg::generalized_eigen;
use super::linearize::Linear;
use super::quadratic::{self, Damped};
pub use super::symbolic_modes::SymbolicModes;
use super::system::System;

/// One normal mode.
#[derive(Clone, Debug)]
pub struct Mode {
    /// The eigenvalue ω² (negative for an unstable direction; exactly 0 for a free motion).
    pub omega_squared: f64,
    /// Shape, normalized so that the largest component is 1, rounding set to 0 (empty when
    /// not available).
    pub shape: Vec<f64>,
}

/// The small-oscillation analysis at one point.
#[derive(Clone, Debug)]
pub struct Modes {
    /// The point analysed, one value per coordinate.
    pub(crate) point: Vec<f64>,
    /// Unstable if anything grows, marginal with a zero mode, otherwise stable.
    pub stability: Stability,
    /// Angular frequencies ω of the undamped modes, ascending, with 0 for each free motion.
    pub frequencies: Vec<f64>,
    /// Growth rates of the unstable modes, ascending.
    pub growth_rates: Vec<f64>,
    /// The normal modes (only without velocity terms, where shapes are real).
    pub modes: Vec<Mode>,
    /// Antisymmetric velocity terms (rotating frames, magnetic fields) survive.
    pub gyroscopic: bool,
    /// Symmetric velocity terms (friction, drag) survive.
    pub damping: bool,
    /// Damped oscillations: frequency, decay rate, damping ratio.
    pub damped: Vec<Damped>,
    /// Decay rates of modes that decay without oscillating.
    pub decay_rates: Vec<f64>,
    /// Directions along which a displacement is not restored (ω = 0), largest component 1.
    pub free_directions: Vec<Vec<f64>>,
}

impl Modes {
    /// What each mode's shape means, where it means something: "only x moves" when one
    /// coordinate moves; in phase / antiphase with the ratio when exactly two move; a free
    /// motion for ω = 0; nothing otherwise.
    pub fn describe(&self, names: &[String]) -> Vec<String> {
        self.modes
            .iter()
            .map(|m| {
                let moving: Vec<usize> =
                    (0..m.shape.len()).filter(|&i| m.shape[i] != 0.0).collect();
                let name = |i: usize| names.get(i).map_or("?", String::as_str);
                let w2 = m.omega_squared;
                let degenerate = self
                    .modes
                    .iter()
                    .filter(|o| (o.omega_squared - w2).abs() <= 1e-9 * w2.abs())
                    .count()
                    > 1;
                match moving[..] {
                    _ if w2 == 0.0 => "free motion (ω = 0)".into(),
                    // Any combination of modes with one ω² is a mode: no shape is special.
                    _ if degenerate => {
                        "degenerate: any combination of the modes with this ω² is a mode".into()
                    }
                    // With one coordinate there is nothing to compare.
                    [_] if m.shape.len() == 1 => String::new(),
                    [i] => format!("only {} moves", name(i)),
                    [i, j] => {
                        let r = m.shape[j] / m.shape[i];
                        let kind = if r > 0.0 { "in phase" } else { "antiphase" };
                        format!("{kind}, {}/{} = {:.6}", name(j), name(i), r)
                    }
                    _ => String::new(),
                }
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
        // The static analysis refuses what it cannot analyse; its refusals hold here too.
        Statics::new(self, d, params)?;
        let lin = self.linearize(d, params, q0)?;
        if lin.conservative() {
            symmetric_modes(&lin, q0)
        } else {
            quadratic_modes(&lin, q0)
        }
    }
}

/// How many rounding units (ε) of the scale an eigenvalue of the symmetric problem may be off
/// by: generous for the reduction and the QR iterations of a small matrix.
const RESOLUTION: f64 = 1e3 * f64::EPSILON;

/// The condition number of the (symmetric positive definite) mass matrix: how much the
/// reduction by its Cholesky factor can magnify rounding.
fn condition(m: &DMatrix<f64>) -> f64 {
    let e = m.clone().symmetric_eigenvalues();
    let (lo, hi) = e.iter().fold((f64::INFINITY, 0.0_f64), |(lo, hi), &x| {
        (lo.min(x.abs()), hi.max(x.abs()))
    });
    if lo > 0.0 && hi.is_finite() {
        hi / lo
    } else {
        f64::INFINITY
    }
}

/// K v = ω² M v, with ω² = 0 decided relative to the scale of K's terms and eigenvalues.
fn symmetric_modes(lin: &Linear, q0: &[f64]) -> Result<Modes, MechError> {
    let k = (&lin.k + lin.k.transpose()) * 0.5;
    let (vals, vecs) = generalized_eigen(&k, &lin.m)?;
    let scale = vals.iter().fold(lin.k_size, |a, v| a.max(v.abs()));
    // Zero within what the arithmetic can resolve: K's entries carry their own rounding (terms
    // that cancel are already exactly 0), and the Cholesky-reduced eigen-solve adds about
    // ε·cond(M)·‖K‖. Beyond that an ω² is real, however small beside the others (a spring
    // 1e-12 as stiff as its neighbour is a restoring force, not a free motion).
    let tol = (RESOLUTION * condition(&lin.m) * scale).min(EIGENVALUE_ZERO * scale);
    let full = &lin.tangent * vecs;
    let mut out = empty(q0);
    for (col, &w2) in vals.iter().enumerate() {
        let w2 = if w2.abs() <= tol { 0.0 } else { w2 };
        let shape = shape_of(&full.column(col).iter().copied().collect::<Vec<_>>());
        if w2 > 0.0 {
            out.frequencies.push(w2.sqrt());
        } else if w2 < 0.0 {
            out.growth_rates.push((-w2).sqrt());
        } else {
            out.frequencies.push(0.0);
            out.free_directions.push(shape.clone());
        }
        out.modes.push(Mode {
            omega_squared: w2,
            shape,
        });
    }
    crate::sort::sort_by(&mut out.frequencies, f64::total_cmp);
    crate::sort::sort_by(&mut out.growth_rates, f64::total_cmp);
    out.stability = if !out.growth_rates.is_empty() {
        Stability::Unstable
    } else if out.free_directions.is_empty() {
        Stability::Stable
    } else {
        Stability::Marginal
    };
    Ok(out)
}

/// λ² M + λ C + K = 0 through the companion form.
fn quadratic_modes(lin: &Linear, q0: &[f64]) -> Result<Modes, MechError> {
    let floor = lin.k_size.sqrt().max(lin.c_size);
    let s = quadratic::solve(&lin.m, &lin.c, &lin.k, floor)?;
    let gyro = &lin.c - lin.c.transpose();
    let damp = &lin.c + lin.c.transpose();
    let mut out = empty(q0);
    out.stability = s.stability;
    out.frequencies = s.frequencies;
    out.growth_rates = s.growth_rates;
    out.gyroscopic = gyro.iter().any(|x| *x != 0.0);
    out.damping = damp.iter().any(|x| *x != 0.0);
    if out.damping {
        out.damped = s.damped;
        out.decay_rates = s.decay_rates;
    }
    // Without damping the spectrum is symmetric under λ → −λ: a decaying λ is only the
    // time-reversed partner of a growing one, not a mode of its own.
    out.free_directions = s
        .free_directions
        .iter()
        .map(|v| {
            let full = &lin.tangent * DMatrix::from_column_slice(v.len(), 1, v);
            shape_of(full.as_slice())
        })
        .collect();
    Ok(out)
}

/// No modes yet at `q0`, stability undecided (marginal): what an analysis fills in, and what
/// is reported where there is nothing to analyse (a singular chart).
pub fn empty(q0: &[f64]) -> Modes {
    Modes {
        point: q0.to_vec(),
        stability: Stability::Marginal,
        frequencies: Vec::new(),
        growth_rates: Vec::new(),
        modes: Vec::new(),
        gyroscopic: false,
        damping: false,
        damped: Vec::new(),
        decay_rates: Vec::new(),
        free_directions: Vec::new(),
    }
}

/// Largest component 1, first nonzero positive, and components that are rounding relative
/// to the largest set to exactly 0 (so that "θ/x = 0.000000" is never shown as a ratio).
fn shape_of(v: &[f64]) -> Vec<f64> {
    quadratic::normalize(&nalgebra::DVector::from_column_slice(v))
}

//! The result of an integration: counts, the final state, and the continuous solution as one
//! interpolant per step (DOP853's 7th-degree dense output, or a cubic Hermite interpolant from
//! the step's end values and slopes for the fixed-step methods).

use serde::Serialize;

use super::SimError;

/// The integration method.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Method {
    /// Adaptive Dormand–Prince 8(5,3).
    Dop853,
    /// Classical fixed-step Runge–Kutta, order 4.
    Rk4,
    /// 2-stage Gauss–Legendre, order 4, implicit and symplectic.
    Gauss,
}

/// Work counts of an integration.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Stats {
    /// Steps accepted.
    pub accepted: usize,
    /// Steps rejected by the error control (always 0 for fixed steps).
    pub rejected: usize,
    /// Evaluations of the right-hand side.
    pub rhs_evals: usize,
}

impl std::ops::AddAssign for Stats {
    /// The work of two runs together.
    fn add_assign(&mut self, other: Stats) {
        self.accepted += other.accepted;
        self.rejected += other.rejected;
        self.rhs_evals += other.rhs_evals;
    }
}

/// How each step's interpolant is stored.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Dense {
    /// DOP853: 8 coefficient vectors per step, evaluated in Hairer's nested form.
    Dop853,
    /// y₀, y₁, h·f₀, h·f₁ per step.
    Hermite,
}

impl Dense {
    fn width(self) -> usize {
        match self {
            Dense::Dop853 => 8,
            Dense::Hermite => 4,
        }
    }
}

/// An integrated motion on [t0, t_end].
#[derive(Clone, Debug)]
pub struct Trajectory {
    /// The method used.
    pub(crate) method: Method,
    /// Work counts.
    pub stats: Stats,
    /// Start time.
    pub t0: f64,
    /// End time (reached exactly).
    pub(crate) t_end: f64,
    /// The initial state y(t0).
    pub y0: Vec<f64>,
    /// The final state y(t_end).
    pub y_final: Vec<f64>,
    dense: Dense,
    /// Start time of each step.
    starts: Vec<f64>,
    /// Length of each step.
    lengths: Vec<f64>,
    /// Interpolation coefficients, `dense.width() · dim` per step.
    coef: Vec<f64>,
}

/// The most numbers a trajectory stores (240 MB): a run that would need more steps is
/// refused, whatever its step limit, rather than exhausting memory.
pub const MAX_STORED: usize = 30_000_000;

impl Trajectory {
    /// The most steps this trajectory can store within [`MAX_STORED`].
    pub(super) fn step_limit(&self) -> usize {
        MAX_STORED / (self.dense.width() * self.dim() + 2)
    }

    pub(super) fn new(method: Method, dense: Dense, t0: f64, y0: &[f64]) -> Self {
        Trajectory {
            method,
            stats: Stats::default(),
            t0,
            t_end: t0,
            y0: y0.to_vec(),
            y_final: y0.to_vec(),
            dense,
            starts: Vec::new(),
            lengths: Vec::new(),
            coef: Vec::new(),
        }
    }

    /// Records an accepted step from `t` of length `h`, with its interpolation data.
    pub(super) fn push_step<'a>(
        &mut self,
        t: f64,
        h: f64,
        coef: impl IntoIterator<Item = &'a [f64]>,
        y_end: &[f64],
    ) {
        self.starts.push(t);
        self.lengths.push(h);
        for c in coef {
            self.coef.extend_from_slice(c);
        }
        self.t_end = t + h;
        self.y_final.copy_from_slice(y_end);
    }

    /// The dimension of the state.
    pub fn dim(&self) -> usize {
        self.y0.len()
    }

    /// The times at which steps ended (the integrator's own grid, t0 first).
    pub fn step_times(&self) -> Vec<f64> {
        let mut v = vec![self.t0];
        v.extend(self.starts.iter().zip(&self.lengths).map(|(t, h)| t + h));
        v
    }

    /// y(t) written into `out`, for t in [t0, t_end]; `false` outside.
    pub fn at_into(&self, t: f64, out: &mut [f64]) -> bool {
        let n = self.dim();
        if !(t >= self.t0 && t <= self.t_end) || out.len() != n {
            return false;
        }
        if self.starts.is_empty() {
            out.copy_from_slice(&self.y0);
            return true;
        }
        // The last step starting at or before t.
        let k = self.starts.partition_point(|&s| s <= t).saturating_sub(1);
        let s = (t - self.starts[k]) / self.lengths[k];
        let w = self.dense.width();
        let c = &self.coef[k * w * n..(k + 1) * w * n];
        let r = |j: usize, i: usize| c[j * n + i];
        for (i, o) in out.iter_mut().enumerate() {
            *o = match self.dense {
                Dense::Dop853 => {
                    let s1 = 1.0 - s;
                    let inner = r(5, i) + s1 * (r(6, i) + s * r(7, i));
                    let mid = r(3, i) + s1 * (r(4, i) + s * inner);
                    r(0, i) + s * (r(1, i) + s1 * (r(2, i) + s * mid))
                }
                Dense::Hermite => {
                    let (y0, y1, d0, d1) = (r(0, i), r(1, i), r(2, i), r(3, i));
                    let s2 = s * s;
                    let s3 = s2 * s;
                    (2.0 * s3 - 3.0 * s2 + 1.0) * y0
                        + (s3 - 2.0 * s2 + s) * d0
                        + (-2.0 * s3 + 3.0 * s2) * y1
                        + (s3 - s2) * d1
                }
            };
        }
        true
    }

    /// y(t) for t in [t0, t_end].
    pub fn at(&self, t: f64) -> Result<Vec<f64>, SimError> {
        let mut out = vec![0.0; self.dim()];
        if self.at_into(t, &mut out) {
            Ok(out)
        } else {
            Err(SimError::Invalid(format!(
                "t = {t} is outside the integrated interval [{}, {}]",
                self.t0, self.t_end
            )))
        }
    }

    /// The solution at each of `times` (each in [t0, t_end]).
    pub fn sample_at(&self, times: &[f64]) -> Result<Vec<Vec<f64>>, SimError> {
        times.iter().map(|&t| self.at(t)).collect()
    }

    /// `samples` evenly spaced points (t, y(t)) from t0 to t_end inclusive (`samples` ≥ 2).
    pub fn sample_even(&self, samples: usize) -> Vec<(f64, Vec<f64>)> {
        let samples = samples.max(2);
        let span = self.t_end - self.t0;
        (0..samples)
            .map(|k| {
                let t = if k + 1 == samples {
                    self.t_end
                } else {
                    self.t0 + span * k as f64 / (samples - 1) as f64
                };
                let mut y = vec![0.0; self.dim()];
                self.at_into(t, &mut y);
                (t, y)
            })
            .collect()
    }
}

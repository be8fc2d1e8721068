//! Fixed-step methods: classical RK4 and the 2-stage Gauss–Legendre collocation method
//! (order 4, A-stable, symplectic: the energy of a conservative system oscillates without
//! secular drift), its stage equations solved by fixed-point iteration to 1e-14. The step is
//! `dt` shrunk so that a whole number of steps ends exactly at t_end; each step stores a cubic
//! Hermite interpolant for output between steps.

use super::trajectory::{Dense, Method, Trajectory};
use super::{Ode, SimError, check_start};
use crate::progress::{Progress, Silent, tick};

/// Steps between two progress reports of a fixed-step run.
const REPORT_EVERY: usize = 256;

/// Stage equations of the Gauss method are solved when the stage increments change by less
/// than this, relative to the size of the state.
const GAUSS_TOL: f64 = 1e-14;
/// Fixed-point iterations allowed per Gauss step.
const GAUSS_ITERATIONS: usize = 60;

/// Buffers of a fixed-step method.
struct Work {
    k: [Vec<f64>; 4],
    tmp: Vec<f64>,
    f0: Vec<f64>,
    f1: Vec<f64>,
    ynew: Vec<f64>,
    /// h·F at the end of the step (interpolation data).
    d1: Vec<f64>,
    /// Whether k[0], k[1] hold the previous Gauss step's stage slopes.
    have_stages: bool,
    evals: usize,
}

impl Work {
    fn new(n: usize) -> Self {
        let z = || vec![0.0; n];
        Work {
            k: [z(), z(), z(), z()],
            tmp: z(),
            f0: z(),
            f1: z(),
            ynew: z(),
            d1: z(),
            have_stages: false,
            evals: 0,
        }
    }

    /// k[target] = F(t, y + h Σ a_j k[j]).
    fn stage(
        &mut self,
        ode: &mut dyn Ode,
        (t, y, h): (f64, &[f64], f64),
        terms: &[(usize, f64)],
        target: usize,
    ) -> Result<(), SimError> {
        for (i, v) in self.tmp.iter_mut().enumerate() {
            *v = y[i] + h * terms.iter().map(|&(j, a)| a * self.k[j][i]).sum::<f64>();
        }
        self.evals += 1;
        ode.eval(t, &self.tmp, &mut self.k[target])
    }

    /// One classical RK4 step from (t, y) with F(t, y) in `f0`; result in `ynew`.
    fn rk4(&mut self, ode: &mut dyn Ode, t: f64, y: &[f64], h: f64) -> Result<(), SimError> {
        self.k[0].copy_from_slice(&self.f0);
        self.stage(ode, (t + 0.5 * h, y, h), &[(0, 0.5)], 1)?;
        self.stage(ode, (t + 0.5 * h, y, h), &[(1, 0.5)], 2)?;
        self.stage(ode, (t + h, y, h), &[(2, 1.0)], 3)?;
        for (i, v) in self.ynew.iter_mut().enumerate() {
            let k = |j: usize| self.k[j][i];
            *v = y[i] + h / 6.0 * (k(0) + 2.0 * k(1) + 2.0 * k(2) + k(3));
        }
        Ok(())
    }

    /// One 2-stage Gauss–Legendre step: stage slopes K₁, K₂ (in k[0], k[1]) by fixed-point
    /// iteration, then y + h (K₁ + K₂)/2. The first guess extrapolates the previous step's
    /// collocation polynomial (its derivative is the line through (c₁, K₁), (c₂, K₂)), or is
    /// F(t, y) on the first step.
    fn gauss(&mut self, ode: &mut dyn Ode, t: f64, y: &[f64], h: f64) -> Result<(), SimError> {
        let r = 3f64.sqrt() / 6.0;
        let (c1, c2) = (0.5 - r, 0.5 + r);
        let (a11, a12, a21, a22) = (0.25, 0.25 - r, 0.25 + r, 0.25);
        if self.have_stages {
            let [k0, k1, ..] = &mut self.k;
            let (w1, w2) = (1.0 / (c2 - c1), (1.0 + c2 - c1) / (c2 - c1));
            for (a, b) in k0.iter_mut().zip(k1.iter_mut()) {
                let (p, q) = (*a, *b);
                *a = p + w1 * (q - p);
                *b = p + w2 * (q - p);
            }
        } else {
            self.k[0].copy_from_slice(&self.f0);
            self.k[1].copy_from_slice(&self.f0);
        }
        self.have_stages = true;
        let scale = y.iter().fold(1.0f64, |m, v| m.max(v.abs()));
        for _ in 0..GAUSS_ITERATIONS {
            let [k0, k1, k2, k3] = &mut self.k;
            k2.copy_from_slice(k0);
            k3.copy_from_slice(k1);
            self.stage(ode, (t + c1 * h, y, h), &[(2, a11), (3, a12)], 0)?;
            self.stage(ode, (t + c2 * h, y, h), &[(2, a21), (3, a22)], 1)?;
            let change = (0..y.len()).fold(0.0f64, |m, i| {
                let d0 = (self.k[0][i] - self.k[2][i]).abs();
                let d1 = (self.k[1][i] - self.k[3][i]).abs();
                m.max(d0).max(d1)
            });
            if !change.is_finite() {
                return Err(SimError::Diverges { t });
            }
            if h.abs() * change <= GAUSS_TOL * scale {
                for (i, v) in self.ynew.iter_mut().enumerate() {
                    *v = y[i] + h * 0.5 * (self.k[0][i] + self.k[1][i]);
                }
                return Ok(());
            }
        }
        Err(SimError::NoConvergence { t })
    }
}

/// Integrates with `method`'s fixed step no longer than `dt`.
fn integrate(
    ode: &mut dyn Ode,
    (t0, y0, t_end): (f64, &[f64], f64),
    dt: f64,
    (method, progress): (Method, &mut dyn Progress),
) -> Result<Trajectory, SimError> {
    check_start(ode, t0, y0, t_end)?;
    let span = t_end - t0;
    if !(dt > 0.0 && dt.is_finite()) || span / dt > 1e9 {
        return Err(SimError::Invalid(format!(
            "the step {dt} must be positive and give at most 1e9 steps"
        )));
    }
    let steps = ((span / dt) - 1e-9).ceil().max(1.0) as usize;
    let h = span / steps as f64;
    let mut w = Work::new(y0.len());
    let mut traj = Trajectory::new(method, Dense::Hermite, t0, y0);
    if steps > traj.step_limit() {
        return Err(SimError::Invalid(format!(
            "the step {dt} needs {steps} steps, more than the {} a run may store; take a longer step or a shorter interval",
            traj.step_limit()
        )));
    }
    let mut y = y0.to_vec();
    w.evals += 1;
    ode.eval(t0, &y, &mut w.f0)?;
    for s in 0..steps {
        let t = t0 + h * s as f64;
        let t_next = if s + 1 == steps {
            t_end
        } else {
            t0 + h * (s + 1) as f64
        };
        match method {
            Method::Gauss => w.gauss(ode, t, &y, h)?,
            _ => w.rk4(ode, t, &y, h)?,
        }
        w.evals += 1;
        ode.eval(t_next, &w.ynew, &mut w.f1)?;
        for i in 0..y.len() {
            w.tmp[i] = h * w.f0[i];
            w.d1[i] = h * w.f1[i];
        }
        let coef = [y.as_slice(), &w.ynew, &w.tmp, &w.d1];
        traj.push_step(t, t_next - t, coef, &w.ynew);
        y.copy_from_slice(&w.ynew);
        std::mem::swap(&mut w.f0, &mut w.f1);
        if (s + 1) % REPORT_EVERY == 0 || s + 1 == steps {
            tick(progress, (s + 1) as u64, steps as u64)?;
        }
    }
    traj.stats.accepted = steps;
    traj.stats.rhs_evals = w.evals;
    traj.t_end = t_end;
    Ok(traj)
}

/// Integrates y' = F(t, y) from (t0, y0) to t_end with classical RK4 (4 evaluations a step),
/// at the step `dt` shrunk to divide the interval.
pub fn rk4(
    ode: &mut dyn Ode,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    dt: f64,
) -> Result<Trajectory, SimError> {
    integrate(ode, (t0, y0, t_end), dt, (Method::Rk4, &mut Silent))
}

/// [`rk4`] that reports the steps done out of all; a `Break` ends it with
/// [`SimError::Interrupted`].
pub fn rk4_with(
    ode: &mut dyn Ode,
    (t0, y0, t_end): (f64, &[f64], f64),
    dt: f64,
    progress: &mut dyn Progress,
) -> Result<Trajectory, SimError> {
    integrate(ode, (t0, y0, t_end), dt, (Method::Rk4, progress))
}

/// Integrates y' = F(t, y) from (t0, y0) to t_end with the 2-stage Gauss–Legendre method,
/// at the step `dt` shrunk to divide the interval.
pub fn gauss(
    ode: &mut dyn Ode,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    dt: f64,
) -> Result<Trajectory, SimError> {
    integrate(ode, (t0, y0, t_end), dt, (Method::Gauss, &mut Silent))
}

/// [`gauss`] that reports the steps done out of all; a `Break` ends it with
/// [`SimError::Interrupted`].
pub fn gauss_with(
    ode: &mut dyn Ode,
    (t0, y0, t_end): (f64, &[f64], f64),
    dt: f64,
    progress: &mut dyn Progress,
) -> Result<Trajectory, SimError> {
    integrate(ode, (t0, y0, t_end), dt, (Method::Gauss, progress))
}

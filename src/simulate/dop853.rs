//! DOP853: the explicit Runge–Kutta method of Dormand and Prince of order 8 with the error
//! estimate of orders 5 and 3 and step control as in Hairer's `dop853` (safety 0.9, step
//! ratio in [1/3, 6], no PI stabilisation), its initial-step heuristic, and the 7th-degree
//! dense output from three extra stages per accepted step.

// Stage arithmetic reads component i of several vectors at once; an index reads best.
#![allow(clippy::needless_range_loop)]

use super::dop853_tableau::*;
use super::trajectory::{Dense, Method, Trajectory};
use super::{Ode, SimError, Tolerances, check_start};
use crate::progress::{PARTS, Progress, Silent, fraction, tick};

/// Safety factor, bounds of the step ratio (hnew/h ∈ [FAC1, FAC2]) and error exponent.
const SAFE: f64 = 0.9;
const FAC1: f64 = 0.333;
const FAC2: f64 = 6.0;
const EXPO: f64 = 1.0 / 8.0;

/// Stage vectors k[1..=16] (k[0] unused), a stage input, the new state, the 8th-order slope
/// and the dense-output coefficients.
struct Work {
    n: usize,
    k: Vec<Vec<f64>>,
    tmp: Vec<f64>,
    ynew: Vec<f64>,
    bsum: Vec<f64>,
    rcont: Vec<Vec<f64>>,
    evals: usize,
}

impl Work {
    fn new(n: usize) -> Self {
        Work {
            n,
            k: vec![vec![0.0; n]; 17],
            tmp: vec![0.0; n],
            ynew: vec![0.0; n],
            bsum: vec![0.0; n],
            rcont: vec![vec![0.0; n]; 8],
            evals: 0,
        }
    }

    /// k[target] = F(t + c h, y + h Σ a_j k[j]).
    fn stage(
        &mut self,
        ode: &mut dyn Ode,
        (t, y, h): (f64, &[f64], f64),
        c: f64,
        terms: &[(usize, f64)],
        target: usize,
    ) -> Result<(), SimError> {
        for i in 0..self.n {
            let s: f64 = terms.iter().map(|&(j, a)| a * self.k[j][i]).sum();
            self.tmp[i] = y[i] + h * s;
        }
        self.evals += 1;
        ode.eval(t + c * h, &self.tmp, &mut self.k[target])
    }

    /// Stages 2–12, the 8th-order solution `ynew` and its slope `bsum`.
    fn step(&mut self, ode: &mut dyn Ode, at: (f64, &[f64], f64)) -> Result<(), SimError> {
        self.stage(ode, at, C2, &[(1, A21)], 2)?;
        self.stage(ode, at, C3, &[(1, A31), (2, A32)], 3)?;
        self.stage(ode, at, C4, &[(1, A41), (3, A43)], 4)?;
        self.stage(ode, at, C5, &[(1, A51), (3, A53), (4, A54)], 5)?;
        self.stage(ode, at, C6, &[(1, A61), (4, A64), (5, A65)], 6)?;
        self.stage(ode, at, C7, &[(1, A71), (4, A74), (5, A75), (6, A76)], 7)?;
        let a8 = [(1, A81), (4, A84), (5, A85), (6, A86), (7, A87)];
        self.stage(ode, at, C8, &a8, 8)?;
        let a9 = [(1, A91), (4, A94), (5, A95), (6, A96), (7, A97), (8, A98)];
        self.stage(ode, at, C9, &a9, 9)?;
        let a10 = [
            (1, A101),
            (4, A104),
            (5, A105),
            (6, A106),
            (7, A107),
            (8, A108),
            (9, A109),
        ];
        self.stage(ode, at, C10, &a10, 10)?;
        let a11 = [
            (1, A111),
            (4, A114),
            (5, A115),
            (6, A116),
            (7, A117),
            (8, A118),
            (9, A119),
            (10, A1110),
        ];
        self.stage(ode, at, C11, &a11, 11)?;
        let a12 = [
            (1, A121),
            (4, A124),
            (5, A125),
            (6, A126),
            (7, A127),
            (8, A128),
            (9, A129),
            (10, A1210),
            (11, A1211),
        ];
        self.stage(ode, at, 1.0, &a12, 12)?;
        let b = [
            (1, B1),
            (6, B6),
            (7, B7),
            (8, B8),
            (9, B9),
            (10, B10),
            (11, B11),
            (12, B12),
        ];
        let (_, y, h) = at;
        for i in 0..self.n {
            self.bsum[i] = b.iter().map(|&(j, w)| w * self.k[j][i]).sum();
            self.ynew[i] = y[i] + h * self.bsum[i];
        }
        Ok(())
    }

    /// The scaled error of the step (≤ 1 to accept), Hairer's blend of the 5th- and
    /// 3rd-order estimates.
    fn error(&self, y: &[f64], h: f64, tol: &Tolerances) -> f64 {
        let e5 = [
            (1, ER1),
            (6, ER6),
            (7, ER7),
            (8, ER8),
            (9, ER9),
            (10, ER10),
            (11, ER11),
            (12, ER12),
        ];
        let (mut err, mut err2) = (0.0, 0.0);
        for i in 0..self.n {
            let sk = tol.atol + tol.rtol * y[i].abs().max(self.ynew[i].abs());
            let k = |j: usize| self.k[j][i];
            let e3 = self.bsum[i] - BHH1 * k(1) - BHH2 * k(9) - BHH3 * k(12);
            let e5: f64 = e5.iter().map(|&(j, w)| w * k(j)).sum();
            err2 += (e3 / sk).powi(2);
            err += (e5 / sk).powi(2);
        }
        let mut deno = err + 0.01 * err2;
        if deno <= 0.0 {
            deno = 1.0;
        }
        h.abs() * err * (1.0 / (deno * self.n as f64)).sqrt()
    }

    /// The dense-output coefficients of an accepted step (k[13] = F at its end is known):
    /// three more stages, then the eight coefficient vectors.
    fn dense(&mut self, ode: &mut dyn Ode, at: (f64, &[f64], f64)) -> Result<(), SimError> {
        let d = [
            [D41, D46, D47, D48, D49, D410, D411, D412],
            [D51, D56, D57, D58, D59, D510, D511, D512],
            [D61, D66, D67, D68, D69, D610, D611, D612],
            [D71, D76, D77, D78, D79, D710, D711, D712],
        ];
        let d_late = [
            [D413, D414, D415, D416],
            [D513, D514, D515, D516],
            [D613, D614, D615, D616],
            [D713, D714, D715, D716],
        ];
        let early = [1, 6, 7, 8, 9, 10, 11, 12];
        let a14 = [
            (1, A141),
            (7, A147),
            (8, A148),
            (9, A149),
            (10, A1410),
            (11, A1411),
            (12, A1412),
            (13, A1413),
        ];
        self.stage(ode, at, C14, &a14, 14)?;
        let a15 = [
            (1, A151),
            (6, A156),
            (7, A157),
            (8, A158),
            (11, A1511),
            (12, A1512),
            (13, A1513),
            (14, A1514),
        ];
        self.stage(ode, at, C15, &a15, 15)?;
        let a16 = [
            (1, A161),
            (6, A166),
            (7, A167),
            (8, A168),
            (9, A169),
            (13, A1613),
            (14, A1614),
            (15, A1615),
        ];
        self.stage(ode, at, C16, &a16, 16)?;
        let (_, y, h) = at;
        for i in 0..self.n {
            let k = |j: usize| self.k[j][i];
            let diff = self.ynew[i] - y[i];
            let bspl = h * k(1) - diff;
            self.rcont[0][i] = y[i];
            self.rcont[1][i] = diff;
            self.rcont[2][i] = bspl;
            self.rcont[3][i] = diff - h * k(13) - bspl;
            for (r, (row, late)) in d.iter().zip(&d_late).enumerate() {
                let s: f64 = early.iter().zip(row).map(|(&j, &w)| w * k(j)).sum();
                let l: f64 = [13, 14, 15, 16]
                    .iter()
                    .zip(late)
                    .map(|(&j, &w)| w * k(j))
                    .sum();
                self.rcont[4 + r][i] = h * (s + l);
            }
        }
        Ok(())
    }
}

impl Work {
    /// The cubic Hermite data of an accepted step (no extra evaluations): y, ynew, h·k₁, h·k₁₃.
    fn hermite(&mut self, y: &[f64], h: f64) {
        for i in 0..self.n {
            self.rcont[0][i] = y[i];
            self.rcont[1][i] = self.ynew[i];
            self.rcont[2][i] = h * self.k[1][i];
            self.rcont[3][i] = h * self.k[13][i];
        }
    }
}

/// Hairer's initial step: an explicit Euler step sized from |y|/|f|, then the second
/// derivative estimated from it, so that h⁸ · max(|f|, |y''|) ≈ 0.01.
fn initial_step(
    ode: &mut dyn Ode,
    (t, y): (f64, &[f64]),
    w: &mut Work,
    tol: &Tolerances,
) -> Result<f64, SimError> {
    let sk = |i: usize| tol.atol + tol.rtol * y[i].abs();
    let (mut dnf, mut dny) = (0.0, 0.0);
    for i in 0..w.n {
        dnf += (w.k[1][i] / sk(i)).powi(2);
        dny += (y[i] / sk(i)).powi(2);
    }
    let mut h = if dnf <= 1e-10 || dny <= 1e-10 {
        1e-6
    } else {
        (dny / dnf).sqrt() * 0.01
    };
    h = h.min(tol.max_step);
    for i in 0..w.n {
        w.tmp[i] = y[i] + h * w.k[1][i];
    }
    w.evals += 1;
    ode.eval(t + h, &w.tmp, &mut w.k[2])?;
    let der2 = (0..w.n)
        .map(|i| ((w.k[2][i] - w.k[1][i]) / sk(i)).powi(2))
        .sum::<f64>()
        .sqrt()
        / h;
    let der12 = der2.abs().max(dnf.sqrt());
    let h1 = if der12 <= 1e-15 {
        (h * 1e-3).max(1e-6)
    } else {
        (0.01 / der12).powf(1.0 / 8.0)
    };
    Ok((100.0 * h).min(h1).min(tol.max_step))
}

/// The interpolant `tol` asks for, once its settings are checked.
fn dense_kind(tol: &Tolerances) -> Result<Dense, SimError> {
    if !(tol.rtol > 0.0 && tol.atol >= 0.0 && tol.max_step > 0.0) {
        return Err(SimError::Invalid(
            "rtol must be positive, atol non-negative and the largest step positive".into(),
        ));
    }
    Ok(if tol.dense {
        Dense::Dop853
    } else {
        Dense::Hermite
    })
}

/// Integrates y' = F(t, y) from (t0, y0) to t_end with DOP853 under `tol`.
pub fn dop853(
    ode: &mut dyn Ode,
    t0: f64,
    y0: &[f64],
    t_end: f64,
    tol: &Tolerances,
) -> Result<Trajectory, SimError> {
    dop853_with(ode, (t0, y0, t_end), tol, &mut Silent)
}

/// [`dop853`] that reports after every accepted step how far t is through the interval (in
/// [`PARTS`](crate::progress::PARTS)); a `Break` ends it with [`SimError::Interrupted`].
pub fn dop853_with(
    ode: &mut dyn Ode,
    (t0, y0, t_end): (f64, &[f64], f64),
    tol: &Tolerances,
    progress: &mut dyn Progress,
) -> Result<Trajectory, SimError> {
    check_start(ode, t0, y0, t_end)?;
    let mut traj = Trajectory::new(Method::Dop853, dense_kind(tol)?, t0, y0);
    let mut w = Work::new(y0.len());
    let mut y = y0.to_vec();
    let mut t = t0;
    w.evals += 1;
    ode.eval(t, &y, &mut w.k[1])?;
    let mut h = initial_step(ode, (t, &y), &mut w, tol)?;
    let mut last_rejected = false;
    let max = tol.max_steps.min(traj.step_limit());
    loop {
        if traj.stats.accepted + traj.stats.rejected >= max {
            return Err(SimError::TooManySteps { max, t });
        }
        if 0.1 * h.abs() <= t.abs() * f64::EPSILON {
            return Err(SimError::StepUnderflow { t });
        }
        let last = t + 1.01 * h >= t_end;
        if last {
            h = t_end - t;
        }
        w.step(ode, (t, &y, h))?;
        let err = w.error(&y, h, tol);
        if !err.is_finite() {
            return Err(SimError::Diverges { t });
        }
        let fac11 = err.powf(EXPO);
        if err > 1.0 {
            h /= (1.0 / FAC1).min(fac11 / SAFE);
            traj.stats.rejected += 1;
            last_rejected = true;
            continue;
        }
        let t_new = if last { t_end } else { t + h };
        w.evals += 1;
        let (k13, ynew) = (&mut w.k[13], &w.ynew);
        ode.eval(t_new, ynew, k13)?;
        if tol.dense {
            w.dense(ode, (t, &y, h))?;
        } else {
            w.hermite(&y, h);
        }
        let width = if tol.dense { 8 } else { 4 };
        let coef = w.rcont.iter().take(width).map(|v| v.as_slice());
        traj.push_step(t, h, coef, &w.ynew);
        traj.stats.accepted += 1;
        y.copy_from_slice(&w.ynew);
        w.k.swap(1, 13);
        t = t_new;
        tick(progress, fraction(t, t0, t_end), PARTS)?;
        if last {
            break;
        }
        let fac = (1.0 / FAC2).max((1.0 / FAC1).min(fac11 / SAFE));
        let mut h_new = (h / fac).min(tol.max_step);
        if last_rejected {
            h_new = h_new.min(h);
        }
        last_rejected = false;
        h = h_new;
    }
    traj.t_end = t_end;
    traj.stats.rhs_evals = w.evals;
    Ok(traj)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::FnOde;

    /// One step of y' = (y₁, −sin y₀)-like nonlinear test problem, error against a
    /// 64-substep reference: the local error of an order-8 method shrinks by 2⁹ when h halves.
    #[test]
    fn one_step_has_local_order_nine() {
        let f = |_t: f64, y: &[f64], dy: &mut [f64]| {
            dy[0] = y[1];
            dy[1] = -y[0].sin() * (1.0 + 0.3 * y[1] * y[1]);
        };
        let y0 = [1.3, 0.4];
        let step = |h: f64| {
            let mut ode = FnOde::new(2, f);
            let mut w = Work::new(2);
            ode.eval(0.0, &y0, &mut w.k[1]).unwrap();
            w.step(&mut ode, (0.0, &y0, h)).unwrap();
            let mut e = w.ynew.clone();
            // reference: 64 substeps
            let mut y = y0.to_vec();
            for s in 0..64 {
                let hs = h / 64.0;
                ode.eval(s as f64 * hs, &y, &mut w.k[1]).unwrap();
                w.step(&mut ode, (s as f64 * hs, &y.clone(), hs)).unwrap();
                y.copy_from_slice(&w.ynew);
            }
            e[0] -= y[0];
            e[1] -= y[1];
            e[0].abs().max(e[1].abs())
        };
        let (e1, e2) = (step(0.4), step(0.2));
        let order = (e1 / e2).log2();
        eprintln!("local errors {e1:.2e} {e2:.2e} order {order}");
        assert!(order > 8.5, "{order}");
    }
}

//! The potential V(q) = h(q, 0) of a one-coordinate system as the portrait family needs it:
//! its lowest point on the coordinate's range (one period for an angle) and its highest
//! barrier, found on a grid and refined by golden-section search.

use super::{Coordinate1, GRID, PortraitError};
use crate::simulate::{Rhs, SimError};

/// What the family needs of V: its minimum, highest barrier and the values at the range's ends.
pub(super) struct Shape {
    pub(super) q_min: f64,
    pub(super) v_min: f64,
    pub(super) barrier: Option<f64>,
    /// The lower of V at the two ends (non-periodic ranges).
    pub(super) v_ends: f64,
}

impl Shape {
    pub(super) fn of(rhs: &mut Rhs, c: &Coordinate1) -> Result<Shape, PortraitError> {
        let (lo, hi) = if c.periodic {
            (c.range.0, c.range.0 + std::f64::consts::TAU)
        } else {
            c.range
        };
        let step = (hi - lo) / GRID as f64;
        let xs: Vec<f64> = (0..=GRID).map(|k| lo + step * k as f64).collect();
        let vs = xs
            .iter()
            .map(|&q| potential(rhs, q))
            .collect::<Result<Vec<_>, _>>()?;
        let (v_lo, v_hi) = vs
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        let spread = v_hi - v_lo;
        if spread.is_nan() || spread <= 1e-12 * v_lo.abs().max(v_hi.abs()).max(1e-300) {
            return Err(PortraitError::Flat {
                name: c.name.clone(),
                lo: c.range.0,
                hi: c.range.1,
            });
        }
        let k_min = (0..=GRID)
            .min_by(|&a, &b| vs[a].total_cmp(&vs[b]))
            .unwrap_or(0);
        if !c.periodic && (k_min == 0 || k_min == GRID) {
            return Err(PortraitError::NoMinimum {
                name: c.name.clone(),
                lo,
                hi,
            });
        }
        let (q_min, v_min) = refine(rhs, &xs, k_min, c.periodic, -1.0)?;
        let mut barrier: Option<f64> = None;
        for k in local_maxima(&vs, c.periodic) {
            let (_, v) = refine(rhs, &xs, k, c.periodic, 1.0)?;
            barrier = Some(barrier.map_or(v, |b| b.max(v)));
        }
        Ok(Shape {
            q_min,
            v_min,
            barrier,
            v_ends: vs[0].min(vs[GRID]),
        })
    }
}

/// V(q) = h(q, 0).
fn potential(rhs: &mut Rhs, q: f64) -> Result<f64, SimError> {
    rhs.energy(0.0, &[q, 0.0])
}

/// Grid indices of strict interior local maxima of V (cyclic for an angle; the last grid
/// point of a period is the first again).
fn local_maxima(vs: &[f64], periodic: bool) -> Vec<usize> {
    let m = vs.len() - 1;
    let at = |k: isize| -> f64 {
        if periodic {
            vs[k.rem_euclid(m as isize) as usize]
        } else {
            vs[k as usize]
        }
    };
    let (first, last) = if periodic { (0, m) } else { (1, m - 1) };
    (first..last)
        .filter(|&k| {
            let k = k as isize;
            let v = at(k);
            v > at(k - 1) && v >= at(k + 1)
        })
        .collect()
}

/// Golden-section refinement of the extremum of V near grid point `k` (`sign` −1 for a
/// minimum, +1 for a maximum): (q, V(q)).
fn refine(
    rhs: &mut Rhs,
    xs: &[f64],
    k: usize,
    periodic: bool,
    sign: f64,
) -> Result<(f64, f64), SimError> {
    let step = xs[1] - xs[0];
    let (mut a, mut b) = (xs[k] - step, xs[k] + step);
    if !periodic {
        a = a.max(xs[0]);
        b = b.min(xs[xs.len() - 1]);
    }
    let g = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..80 {
        let (c, d) = (b - g * (b - a), a + g * (b - a));
        if sign * potential(rhs, c)? > sign * potential(rhs, d)? {
            b = d;
        } else {
            a = c;
        }
    }
    let q = 0.5 * (a + b);
    Ok((q, potential(rhs, q)?))
}

impl Shape {
    /// The period 2π √(a / V″) of small oscillations about q*, a = ∂²h/∂q̇² there; `None`
    /// when V″ or a is not positive (a flat bottom).
    pub(super) fn small_period(&self, rhs: &mut Rhs) -> Result<Option<f64>, SimError> {
        let q = self.q_min;
        let d = 1e-4 * q.abs().max(1.0);
        let v2 =
            (potential(rhs, q + d)? - 2.0 * potential(rhs, q)? + potential(rhs, q - d)?) / (d * d);
        let h0 = rhs.energy(0.0, &[q, 0.0])?;
        let a = rhs.energy(0.0, &[q, 1.0])? + rhs.energy(0.0, &[q, -1.0])? - 2.0 * h0;
        let period = std::f64::consts::TAU * (a / v2).sqrt();
        Ok((v2 > 0.0 && a > 0.0 && period.is_finite()).then_some(period))
    }
}

//! Where det C vanishes: at the sample points, at special points (velocities and coordinates
//! 0, ±π/2, π, equal parameters of one dimension) and along lines through a sample point, where
//! a sign change or a minimum reaching zero is looked for.

use std::f64::consts::PI;

use super::det::{Det, DetC};
use crate::check::points::Filter;
use crate::check::prepare::Prepared;
use crate::check::tolerance;

/// Grid points on each line scanned through a sample point.
const GRID: usize = 24;
/// Golden-section steps refining a local minimum of |det C| found on a line.
pub(super) const REFINE: usize = 48;
/// A value of det C above this fraction of its typical size is not a candidate zero.
const SCREEN: f64 = 1e-3;
/// How many sample points serve as bases for special points and line scans.
const BASES: usize = 2;

/// The size det C has at `x`'s parameter values: the largest |det C| over the states of the
/// first few sample points with those parameters. Parameters may span many decades (wide
/// points), so a value is small or not only next to others at the same parameters.
fn local_scale(p: &Prepared, det: &DetC, x: &[f64]) -> f64 {
    let start = p.system.state_layout().params_start();
    p.points
        .points
        .iter()
        .take(4)
        .filter_map(|y| {
            let mut y = y.clone();
            y[start..].copy_from_slice(&x[start..]);
            match det.at(&y) {
                Det::Value(d) => Some(d.abs()),
                _ => None,
            }
        })
        .fold(0.0, f64::max)
}

/// Where det C was found to vanish.
pub(super) enum Found {
    /// At this point (zero, or undefined when `undefined`).
    At { x: Vec<f64>, undefined: bool },
    /// Opposite signs at these points.
    Between(Vec<f64>, Vec<f64>),
}

/// Looks for a point where det C vanishes, is undefined, or changes sign.
pub(super) fn probe(p: &Prepared, det: &DetC) -> Option<Found> {
    let filter = Filter::new(&p.system, &p.assumptions, &[]).ok()?;
    let mut candidates: Vec<Vec<f64>> = p.points.points.clone();
    for base in p.points.points.iter().take(BASES) {
        candidates.extend(
            special_points(p, base)
                .into_iter()
                .filter(|x| filter.accepts(x)),
        );
    }
    // Only a value far below the typical one is worth the comparison at its own parameters.
    let typical = median(
        p.points
            .points
            .iter()
            .filter_map(|x| match det.at(x) {
                Det::Value(d) => Some(d.abs()),
                _ => None,
            })
            .collect(),
    )
    .unwrap_or(0.0);
    let vanishes = |x: &[f64], d: f64| {
        d == 0.0
            || (d.abs() <= SCREEN * typical
                && d.abs() <= tolerance::SAME * local_scale(p, det, x).max(d.abs()))
    };
    let mut signed: Option<(f64, Vec<f64>)> = None;
    for x in candidates {
        match det.at(&x) {
            Det::Skip => {}
            Det::Undefined => return Some(Found::At { x, undefined: true }),
            Det::Value(d) if vanishes(&x, d) => {
                return Some(Found::At {
                    x,
                    undefined: false,
                });
            }
            Det::Value(d) => match &signed {
                Some((s, y)) if s.signum() != d.signum() => {
                    return Some(Found::Between(y.clone(), x));
                }
                Some(_) => {}
                None => signed = Some((d, x)),
            },
        }
    }
    p.points
        .points
        .iter()
        .take(BASES)
        .find_map(|base| scan_lines(p, det, &filter, base))
}

/// Points derived from `base`: each velocity 0, all velocities 0, each coordinate at 0 (and
/// ±π/2, π for an angle), parameters of one dimension made equal, t = 0.
fn special_points(p: &Prepared, base: &[f64]) -> Vec<Vec<f64>> {
    let at = p.system.state_layout();
    let mut out = Vec::new();
    let with = |k: usize, v: f64| {
        let mut x = base.to_vec();
        x[k] = v;
        x
    };
    let mut still = base.to_vec();
    for (i, c) in p.system.coordinates.iter().enumerate() {
        out.push(with(at.qdot(i), 0.0));
        still[at.qdot(i)] = 0.0;
        out.push(with(at.q(i), 0.0));
        if c.periodic {
            for v in [PI / 2.0, -PI / 2.0, PI] {
                out.push(with(at.q(i), v));
            }
        }
    }
    out.push(still);
    out.push(with(at.time(), 0.0));
    let params = &p.system.parameters;
    for j in 0..params.len() {
        for k in j + 1..params.len() {
            if params[j].dimension.is_some() && params[j].dimension == params[k].dimension {
                out.push(with(at.param(k), base[at.param(j)]));
            }
        }
    }
    out
}

/// Scans lines through `base` in each coordinate, velocity and parameter for a sign change of
/// det C or a minimum of |det C| that reaches zero.
fn scan_lines(p: &Prepared, det: &DetC, filter: &Filter, base: &[f64]) -> Option<Found> {
    let at = p.system.state_layout();
    let mut lines: Vec<(usize, f64, f64)> = Vec::new();
    for (i, c) in p.system.coordinates.iter().enumerate() {
        let (lo, hi) = if c.periodic {
            (-2.0 * PI, 2.0 * PI)
        } else {
            let (mid, half) = (0.5 * (c.range.0 + c.range.1), 0.5 * (c.range.1 - c.range.0));
            (mid - 4.0 * half, mid + 4.0 * half)
        };
        lines.push((at.q(i), lo, hi));
        lines.push((at.qdot(i), -4.0, 4.0));
    }
    for (j, q) in p.system.parameters.iter().enumerate() {
        lines.push((at.param(j), q.range.0 / 4.0, q.range.1 * 4.0));
    }
    lines
        .into_iter()
        .find_map(|(k, lo, hi)| scan_line(det, filter, base, k, lo, hi))
}

/// One line: `base` with entry `k` running over [lo, hi].
fn scan_line(
    det: &DetC,
    filter: &Filter,
    base: &[f64],
    k: usize,
    lo: f64,
    hi: f64,
) -> Option<Found> {
    let point = |t: f64| {
        let mut x = base.to_vec();
        x[k] = t;
        x
    };
    let value = |t: f64| -> Option<f64> {
        let x = point(t);
        if !filter.accepts(&x) {
            return None;
        }
        match det.at(&x) {
            Det::Value(d) => Some(d),
            _ => None,
        }
    };
    let ts: Vec<f64> = (0..GRID)
        .map(|g| lo + (hi - lo) * g as f64 / (GRID - 1) as f64)
        .collect();
    let vs: Vec<Option<f64>> = ts.iter().map(|&t| value(t)).collect();
    // Zero relative to the largest value on this line.
    let line_max = vs.iter().flatten().fold(0.0, |m: f64, v| m.max(v.abs()));
    let zero = tolerance::SAME * line_max;
    for g in 1..GRID {
        let (Some(a), Some(b)) = (vs[g - 1], vs[g]) else {
            continue;
        };
        if a.signum() != b.signum() && a.abs() > zero && b.abs() > zero {
            return Some(Found::Between(point(ts[g - 1]), point(ts[g])));
        }
    }
    for g in 1..GRID - 1 {
        let (Some(a), Some(b), Some(c)) = (vs[g - 1], vs[g], vs[g + 1]) else {
            continue;
        };
        // A strict local minimum well below the line's largest value (a plateau is not one).
        if b.abs() < a.abs() && b.abs() <= c.abs() && b.abs() < 0.5 * line_max {
            let t = golden_min(
                &|t| value(t).map_or(f64::INFINITY, f64::abs),
                ts[g - 1],
                ts[g + 1],
            );
            if value(t).is_some_and(|d| d.abs() <= zero) {
                return Some(Found::At {
                    x: point(t),
                    undefined: false,
                });
            }
        }
    }
    None
}

/// The argument of the least value of `f` on [a, b] (golden-section search).
fn golden_min(f: &dyn Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let r = 0.5 * (5f64.sqrt() - 1.0);
    let (mut c, mut d) = (b - r * (b - a), a + r * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..REFINE {
        if fc < fd {
            b = d;
            (d, fd) = (c, fc);
            c = b - r * (b - a);
            fc = f(c);
        } else {
            a = c;
            (c, fc) = (d, fd);
            d = a + r * (b - a);
            fd = f(d);
        }
    }
    if fc < fd { c } else { d }
}

pub(super) fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let m = v[v.len() / 2];
    (m > 0.0).then_some(m)
}

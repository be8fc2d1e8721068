//! Where det C vanishes inside the problem's domain: at the sample points, at special points
//! (velocities and coordinates 0, ±π/2, π, equal parameters of one dimension), between two
//! points of opposite sign, and along lines through a sample point, where a sign change or a
//! minimum reaching zero is looked for.
//!
//! A sign change is a zero only if the bisection that follows it ends on small values: one
//! through a pole (1/sin θ, whose zero the physics shares) ends on huge ones, and one through
//! a place where the physics is singular or that leaves the domain is not judged.

use std::f64::consts::PI;

use super::det::{Det, DetC, median};
use crate::check::points::Filter;
use crate::check::prepare::Prepared;

/// Grid points on each line scanned through a sample point.
const GRID: usize = 24;
/// Golden-section steps refining a local minimum of |det C| found on a line.
const REFINE: usize = 48;
/// Bisection steps that follow a sign change to its zero (or pole).
const BISECT: usize = 60;
/// A value of det C above this fraction of its typical size (over all samples) is not a
/// candidate zero, so the careful test is not needed.
const SCREEN: f64 = 1e-3;
/// At the end of a bisection, values below this fraction of det C's typical size mean a
/// zero was bracketed; a pole leaves values far above it.
const CROSSING: f64 = 1e-6;
/// How many sample points serve as bases for special points and line scans.
const BASES: usize = 2;
/// How many sign changes between sample points are followed.
const PAIRS: usize = 4;

/// Where det C was found to vanish.
pub(super) enum Found {
    /// At this point (zero, or undefined when `undefined`).
    At { x: Vec<f64>, undefined: bool },
}

/// Looks for a point of the domain where the answer stops determining the accelerations the
/// physics determines.
pub(super) fn probe(p: &Prepared, det: &DetC<'_>) -> Option<Found> {
    let filter = Filter::new(&p.system, &p.assumptions, &[]).ok()?;
    // Each candidate with the point its zero test is scaled by: itself, or the sample
    // point a special point was derived from.
    let mut candidates: Vec<(Vec<f64>, &[f64])> = p
        .points
        .points
        .iter()
        .map(|x| (x.clone(), x.as_slice()))
        .collect();
    for base in p.points.points.iter().take(BASES) {
        candidates.extend(
            special_points(p, base)
                .into_iter()
                .map(|x| (x, base.as_slice())),
        );
    }
    candidates.retain(|(x, _)| filter.accepts(x));
    // Only a value far below the typical one is worth the careful test at its own parameters.
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
    let mut signed: Vec<(f64, &[f64])> = Vec::new();
    for (x, reference) in &candidates {
        match judge(det, x, det.at(x), typical, reference) {
            Judged::Fault(found) => return Some(found),
            Judged::Sign(d) => signed.push((d, x)),
            Judged::Nothing => {}
        }
    }
    if let Some(&(first, x)) = signed.first() {
        let opposite = signed.iter().filter(|(d, _)| d.signum() != first.signum());
        for &(_, y) in opposite.take(PAIRS) {
            if let Some(found) = crossing(det, &filter, x, y, typical) {
                return Some(found);
            }
        }
    }
    p.points
        .points
        .iter()
        .take(BASES)
        .find_map(|base| scan_lines(p, det, &filter, base, typical))
}

/// What one evaluation says.
enum Judged {
    /// The answer stops determining an acceleration here.
    Fault(Found),
    /// A regular value, with its sign.
    Sign(f64),
    /// Nothing to judge here.
    Nothing,
}

/// Judges `value`, det C at `x`; a zero is judged against the typical size at the
/// parameters of `reference`.
fn judge(det: &DetC<'_>, x: &[f64], value: Det, typical: f64, reference: &[f64]) -> Judged {
    let careful = match value {
        // Far from zero against the typical size over all samples, or against the one at
        // the reference's parameters: a regular value, without the careful test.
        Det::Value(d) if d.abs() > SCREEN * typical || !det.is_zero(reference, d) => {
            return Judged::Sign(d);
        }
        Det::Value(_) => det.careful(x),
        other => other,
    };
    match careful {
        Det::Skip | Det::Singular { deficient: false } => Judged::Nothing,
        Det::Undefined => Judged::Fault(Found::At {
            x: x.to_vec(),
            undefined: true,
        }),
        Det::Singular { deficient: true } => Judged::Fault(Found::At {
            x: x.to_vec(),
            undefined: false,
        }),
        Det::Value(d) if det.is_zero(reference, d) => Judged::Fault(Found::At {
            x: x.to_vec(),
            undefined: false,
        }),
        Det::Value(d) => Judged::Sign(d),
    }
}

/// Follows a sign change of det C from `x` to `y` along the segment between them: a zero
/// where the physics is regular is a fault; a pole, a singularity of the physics or a step
/// out of the domain is not.
fn crossing(det: &DetC<'_>, filter: &Filter, x: &[f64], y: &[f64], typical: f64) -> Option<Found> {
    let along = |s: f64| -> Vec<f64> { x.iter().zip(y).map(|(a, b)| a + s * (b - a)).collect() };
    let sign = match det.at(x) {
        Det::Value(d) => d.signum(),
        _ => return None,
    };
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..BISECT {
        let mid = 0.5 * (lo + hi);
        let z = along(mid);
        if !filter.accepts(&z) {
            return None;
        }
        // Values are followed to the end, so the zero is found to rounding; only a fault
        // that is not a value (undefined, a lost rank) ends the search early.
        match det.at(&z) {
            Det::Value(d) if d.signum() == sign => lo = mid,
            Det::Value(_) => hi = mid,
            other => {
                return match judge(det, &z, other, typical, x) {
                    Judged::Fault(found) => Some(found),
                    _ => None,
                };
            }
        }
    }
    // Bracketed to rounding: a zero leaves small values, a pole huge ones.
    let (a, b) = (along(lo), along(hi));
    let scale = det.typical_det(x);
    let small = |z: &[f64]| match det.at(z) {
        Det::Value(d) => d.abs() <= CROSSING * scale,
        _ => false,
    };
    if !(small(&a) || small(&b)) {
        return None;
    }
    let z = along(0.5 * (lo + hi));
    match det.careful(&z) {
        Det::Skip | Det::Singular { deficient: false } => None,
        _ => Some(Found::At {
            x: z,
            undefined: false,
        }),
    }
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
fn scan_lines(
    p: &Prepared,
    det: &DetC<'_>,
    filter: &Filter,
    base: &[f64],
    typical: f64,
) -> Option<Found> {
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
    lines.into_iter().find_map(|(k, lo, hi)| {
        let line = Line {
            det,
            filter,
            base,
            k,
        };
        line.scan(lo, hi, typical)
    })
}

/// One line: `base` with entry `k` running over an interval.
struct Line<'a> {
    det: &'a DetC<'a>,
    filter: &'a Filter,
    base: &'a [f64],
    k: usize,
}

impl Line<'_> {
    fn point(&self, t: f64) -> Vec<f64> {
        let mut x = self.base.to_vec();
        x[self.k] = t;
        x
    }

    /// det C at `t`, if the point is in the domain and regular there.
    fn value(&self, t: f64) -> Option<f64> {
        let x = self.point(t);
        if !self.filter.accepts(&x) {
            return None;
        }
        match self.det.at(&x) {
            Det::Value(d) => Some(d),
            _ => None,
        }
    }

    fn scan(&self, lo: f64, hi: f64, typical: f64) -> Option<Found> {
        let ts: Vec<f64> = (0..GRID)
            .map(|g| lo + (hi - lo) * g as f64 / (GRID - 1) as f64)
            .collect();
        let vs: Vec<Option<f64>> = ts.iter().map(|&t| self.value(t)).collect();
        for g in 1..GRID {
            let (Some(a), Some(b)) = (vs[g - 1], vs[g]) else {
                continue;
            };
            if a.signum() != b.signum()
                && let Some(found) = crossing(
                    self.det,
                    self.filter,
                    &self.point(ts[g - 1]),
                    &self.point(ts[g]),
                    typical,
                )
            {
                return Some(found);
            }
        }
        let line_max = vs.iter().flatten().fold(0.0, |m: f64, v| m.max(v.abs()));
        for g in 1..GRID - 1 {
            let (Some(a), Some(b), Some(c)) = (vs[g - 1], vs[g], vs[g + 1]) else {
                continue;
            };
            // A strict local minimum of |det C| well below the line's largest value (a
            // plateau, or rounding noise on a constant det C, is not one).
            if b.abs() < a.abs() && b.abs() <= c.abs() && b.abs() < 0.5 * line_max {
                let t = golden_min(
                    &|t| self.value(t).map_or(f64::INFINITY, f64::abs),
                    ts[g - 1],
                    ts[g + 1],
                );
                let x = self.point(t);
                let value = self.det.at(&x);
                if let Judged::Fault(found) = judge(self.det, &x, value, typical, self.base) {
                    return Some(found);
                }
            }
        }
        None
    }
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

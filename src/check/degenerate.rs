//! Equations that hold for the true motion but do not determine it everywhere.
//!
//! Equations that hold at the true accelerations are the reference's equations combined by a
//! matrix C: their acceleration coefficients are A = C·M (M the mass matrix). They are
//! equivalent to the reference only where C is nonsingular, and must be so over the whole
//! domain: θ̇·(θ̈ + g/l·sin θ) = 0 (the energy law) holds for the motion but says nothing about
//! θ̈ when θ̇ = 0. Sampling at random points never lands on such a set, so det C is evaluated at
//! the sample points, at special points (each velocity 0, each coordinate 0, ±π/2, π, equal
//! parameters of one dimension), and along lines through a sample point in each variable,
//! where a sign change or a minimum that reaches zero is looked for. The factor is named when
//! the answer shows it (a product with a factor free of accelerations), and the energy law is
//! recognised as such.

use std::f64::consts::PI;

use super::common::state_text;
use super::compare::proportional;
use super::points::Filter;
use super::prepare::Prepared;
use super::tolerance;
use super::verdict::{Code, Diagnosis};
use crate::expr::{Id, Node, Program, Style};

/// Grid points on each line scanned through a sample point.
const GRID: usize = 24;
/// Golden-section steps refining a local minimum of |det C| found on a line.
const REFINE: usize = 48;
/// A factor this small relative to its typical size is zero up to rounding.
const NUMERICAL_ZERO: f64 = 1e-12;
/// A value of det C above this fraction of its typical size is not a candidate zero.
const SCREEN: f64 = 1e-3;
/// How many sample points serve as bases for special points and line scans.
const BASES: usize = 2;

/// Why equations that hold for the motion are not equivalent to the reference.
pub(crate) enum Degeneracy {
    /// Row `row` (or the one equation) is the energy law dE/dt = 0.
    EnergyLaw {
        row: Option<usize>,
        velocity: String,
    },
    /// The answer is multiplied by `factor`, which vanishes (or is undefined) at `at`.
    Factor {
        row: Option<usize>,
        factor: String,
        at: String,
        how: Vanishing,
    },
    /// det C vanishes at `at`.
    Vanishes { at: String },
    /// det C changes sign between `at` and `and`, so it vanishes in between.
    SignChange { at: String, and: String },
    /// The answer is undefined at `at`, where the reference determines the accelerations.
    Undefined { at: String },
}

impl Degeneracy {
    /// The sentence for a degeneracy.
    pub(crate) fn details(self) -> Diagnosis {
        let which = |row: Option<usize>| match row {
            Some(i) => format!("equation {}", i + 1),
            None => "your equation".to_string(),
        };
        let message = match self {
            Degeneracy::EnergyLaw {
                row: None,
                velocity,
            } => format!(
                "your equation is the equation of motion multiplied by {velocity}: it is the energy law dE/dt = 0, which holds for the motion but does not determine the acceleration where {velocity} = 0 (at rest, at the turning points)"
            ),
            Degeneracy::EnergyLaw { row, .. } => format!(
                "{} is the energy law dE/dt = 0 (the equations of motion multiplied by the velocities and added): it holds for the motion but does not determine the accelerations where the velocities vanish",
                which(row)
            ),
            Degeneracy::Factor {
                row,
                factor,
                at,
                how,
            } => {
                let how = match how {
                    Vanishing::Zero => "vanishes".to_string(),
                    Vanishing::Undefined => "is undefined".to_string(),
                    Vanishing::Negligible(r) => {
                        format!("becomes negligible ({r:.0e} of its typical size)")
                    }
                };
                format!(
                    "{} is multiplied by {factor}, which {how} at {at}: there it no longer determines the accelerations",
                    which(row)
                )
            }
            Degeneracy::Vanishes { at } => format!(
                "your equations hold for the motion but stop determining the accelerations at {at}: they are the right ones multiplied by something that vanishes there"
            ),
            Degeneracy::SignChange { at, and } => format!(
                "your equations hold for the motion but are the right ones multiplied by something that changes sign between {at} and {and}, so it vanishes in between, where they no longer determine the accelerations"
            ),
            Degeneracy::Undefined { at } => format!(
                "your equations are undefined at {at}, where the right ones determine the accelerations"
            ),
        };
        Diagnosis::new(Code::VanishingFactor, message)
    }
}

/// How a factor fails at the point shown.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Vanishing {
    /// It is 0 there.
    Zero,
    /// It is undefined there.
    Undefined,
    /// It is this fraction (below the tolerance) of its typical size there.
    Negligible(f64),
}

/// What det C is at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Det {
    /// The reference does not determine the accelerations here either (M singular or
    /// undefined): nothing to judge.
    Skip,
    /// The answer is undefined where the reference is defined.
    Undefined,
    Value(f64),
}

/// det C at any point: the answer's acceleration coefficients A and the mass matrix M, each
/// compiled once and evaluated into reused buffers (this runs a few hundred times a check).
struct DetC {
    a: Program,
    m: Option<Program>,
    n: usize,
    /// One equation of a system with several coordinates: `m` holds the reference
    /// equation's acceleration row r, and the factor is a·r / r·r (the answer must be the
    /// reference times a factor that vanishes nowhere).
    projection: bool,
    scratch: std::cell::RefCell<(Vec<f64>, Vec<f64>)>,
}

impl DetC {
    fn new(p: &mut Prepared, res: &[Id]) -> Option<DetC> {
        let coords = p.system.coordinate_syms();
        let n = coords.len();
        let mut roots: Vec<Id> = Vec::new();
        for &r in res {
            for &c in &coords {
                roots.push(p.system.pool.diff(r, c, 2));
            }
        }
        let a = p.system.compile(&roots).ok()?;
        // Divide by det M (without constraints); with constraints A alone is judged.
        let m = if p.system.constraints.is_empty() {
            let entries: Vec<Id> = p.derivation.mass.iter().flatten().copied().collect();
            Some(p.system.compile(&entries).ok()?)
        } else {
            None
        };
        let scratch = (
            a.scratch(),
            m.as_ref().map_or_else(Vec::new, Program::scratch),
        );
        Some(DetC {
            a,
            m,
            n,
            projection: false,
            scratch: std::cell::RefCell::new(scratch),
        })
    }

    /// For one equation `r` of a system with several coordinates, against the reference
    /// equation `reference`.
    fn projection(p: &mut Prepared, r: Id, reference: Id) -> Option<DetC> {
        let coords = p.system.coordinate_syms();
        let row = |p: &mut Prepared, e: Id| -> Vec<Id> {
            coords
                .iter()
                .map(|&c| p.system.pool.diff(e, c, 2))
                .collect()
        };
        let (ra, rr) = (row(p, r), row(p, reference));
        let a = p.system.compile(&ra).ok()?;
        let m = p.system.compile(&rr).ok()?;
        let scratch = (a.scratch(), m.scratch());
        Some(DetC {
            a,
            m: Some(m),
            n: coords.len(),
            projection: true,
            scratch: std::cell::RefCell::new(scratch),
        })
    }

    /// a·r / r·r at `x` (projection mode).
    fn ratio_at(&self, x: &[f64], m: &Program, sa: &mut [f64], sm: &mut [f64]) -> Det {
        if m.run(x, sm).is_err() {
            return Det::Skip;
        }
        let rr: f64 = (0..self.n).map(|j| m.output(j, sm).powi(2)).sum();
        if !rr.is_finite() || rr == 0.0 {
            return Det::Skip;
        }
        if self.a.run(x, sa).is_err() {
            return Det::Undefined;
        }
        let ar: f64 = (0..self.n)
            .map(|j| self.a.output(j, sa) * m.output(j, sm))
            .sum();
        let d = ar / rr;
        if d.is_finite() {
            Det::Value(d)
        } else {
            Det::Undefined
        }
    }

    fn at(&self, x: &[f64]) -> Det {
        let n = self.n;
        let mut guard = self.scratch.borrow_mut();
        let (sa, sm) = &mut *guard;
        if let (true, Some(m)) = (self.projection, &self.m) {
            return self.ratio_at(x, m, sa, sm);
        }
        // The reference first: where M is undefined or singular it does not determine the
        // accelerations either, and there is nothing to judge.
        let det_m = match &self.m {
            Some(m) => {
                if m.run(x, sm).is_err() {
                    return Det::Skip;
                }
                det(n, |i, j| m.output(i * n + j, sm))
            }
            None => 1.0,
        };
        if !det_m.is_finite() || det_m == 0.0 {
            return Det::Skip;
        }
        if self.a.run(x, sa).is_err() {
            return Det::Undefined;
        }
        let d = det(n, |i, j| self.a.output(i * n + j, sa)) / det_m;
        if d.is_finite() {
            Det::Value(d)
        } else {
            Det::Undefined
        }
    }
}

/// The determinant of the n×n matrix with entries `e(i, j)`: by formula up to 3×3 (no
/// allocation), by LU beyond.
fn det(n: usize, e: impl Fn(usize, usize) -> f64) -> f64 {
    match n {
        1 => e(0, 0),
        2 => e(0, 0) * e(1, 1) - e(0, 1) * e(1, 0),
        3 => {
            e(0, 0) * (e(1, 1) * e(2, 2) - e(1, 2) * e(2, 1))
                - e(0, 1) * (e(1, 0) * e(2, 2) - e(1, 2) * e(2, 0))
                + e(0, 2) * (e(1, 0) * e(2, 1) - e(1, 1) * e(2, 0))
        }
        _ => nalgebra::DMatrix::from_fn(n, n, e).determinant(),
    }
}

/// Whether the equations `res` (which hold at the true accelerations, `rows == n`) determine
/// the accelerations everywhere; the reason when they do not.
///
/// One equation of a system with several coordinates (`res.len() == 1 < n`) is judged
/// against `reference`, the part's own reference equation: it must be that equation times a
/// factor that vanishes nowhere.
pub(crate) fn degeneracy(
    p: &mut Prepared,
    res: &[Id],
    reference: Option<Id>,
) -> Option<Degeneracy> {
    let n = p.system.n();
    let det = match (res, reference) {
        _ if res.len() == n => DetC::new(p, res)?,
        ([r], Some(reference)) => DetC::projection(p, *r, reference)?,
        _ => return None,
    };
    let found = probe(p, &det)?;
    Some(explain(p, res, found))
}

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
enum Found {
    /// At this point (zero, or undefined when `undefined`).
    At { x: Vec<f64>, undefined: bool },
    /// Opposite signs at these points.
    Between(Vec<f64>, Vec<f64>),
}

/// Looks for a point where det C vanishes, is undefined, or changes sign.
fn probe(p: &Prepared, det: &DetC) -> Option<Found> {
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

fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let m = v[v.len() / 2];
    (m > 0.0).then_some(m)
}

/// Puts what was found into a reason: the energy law, a named factor, or where.
fn explain(p: &mut Prepared, res: &[Id], found: Found) -> Degeneracy {
    if let Some(d) = energy_law(p, res) {
        return d;
    }
    let (x, y, undefined) = match found {
        Found::At { x, undefined } => (x, None, undefined),
        Found::Between(x, y) => (x, Some(y), false),
    };
    if let Some(f) = vanishing_factor(p, res, &x, y.as_deref()) {
        let vars = p.system.pool.variables(f.factor);
        return Degeneracy::Factor {
            row: f.row,
            factor: p.system.pool.display(f.factor, Style::Unicode),
            at: state_text(p, &f.at, Some(&vars)),
            how: f.how,
        };
    }
    match y {
        Some(y) => Degeneracy::SignChange {
            at: state_text(p, &x, None),
            and: state_text(p, &y, None),
        },
        None if undefined => Degeneracy::Undefined {
            at: state_text(p, &x, None),
        },
        None => Degeneracy::Vanishes {
            at: state_text(p, &x, None),
        },
    }
}

/// The row that is the energy law Σ q̇ᵢ·Eᵢ = 0 (up to a constant factor), if any.
fn energy_law(p: &mut Prepared, res: &[Id]) -> Option<Degeneracy> {
    let coords = p.system.coordinate_syms();
    let equations = p.derivation.equations();
    let terms: Vec<Id> = coords
        .iter()
        .zip(&equations)
        .map(|(&c, &e)| {
            let v = p.system.pool.var(c, 1);
            p.system.pool.mul(v, e)
        })
        .collect();
    let law = p.system.pool.sum(terms);
    let row = res
        .iter()
        .position(|&r| proportional(&p.system, r, law, &p.points, tolerance::SAME))?;
    let velocity = match coords.as_slice() {
        [c] => {
            let v = p.system.pool.var(*c, 1);
            p.system.pool.display(v, Style::Unicode)
        }
        _ => "the velocities".to_string(),
    };
    Some(Degeneracy::EnergyLaw {
        row: (res.len() > 1).then_some(row),
        velocity,
    })
}

/// A factor of an answer's equation that vanishes (or is undefined), and where.
struct VanishingFactor {
    row: Option<usize>,
    factor: Id,
    at: Vec<f64>,
    how: Vanishing,
}

/// A factor of one of the answer's equations, free of accelerations, that vanishes or is
/// undefined at `x` (or changes sign between `x` and `y`, where the zero is then found by
/// bisection).
fn vanishing_factor(
    p: &Prepared,
    res: &[Id],
    x: &[f64],
    y: Option<&[f64]>,
) -> Option<VanishingFactor> {
    for (i, &r) in res.iter().enumerate() {
        let Node::Mul(factors) = p.system.pool.node(r) else {
            continue;
        };
        for &f in factors.iter() {
            // A factor with an acceleration is the equation itself; a number never vanishes.
            let vars = p.system.pool.variables(f);
            if vars.is_empty() || vars.iter().any(|v| v.1 == 2) {
                continue;
            }
            let Ok(prog) = p.system.compile(&[f]) else {
                continue;
            };
            let value = |x: &[f64]| prog.eval(x).ok().map(|v| v[0]);
            let typical = median(
                p.points
                    .points
                    .iter()
                    .filter_map(|s| value(s).map(f64::abs))
                    .collect(),
            )
            .unwrap_or(1.0);
            let at = match (value(x), y) {
                (None, _) => Some(x.to_vec()),
                (Some(h), None) => (h.abs() <= tolerance::SAME * typical).then(|| x.to_vec()),
                (Some(h), Some(y)) => value(y)
                    .filter(|w| w.signum() != h.signum())
                    .map(|_| bisect(&value, x, y)),
            };
            if let Some(at) = at {
                // A sign change through a pole (1/θ̇) leaves a huge value at the bisected
                // point: the factor is undefined there, not zero.
                let how = match value(&at).map(|v| v.abs() / typical) {
                    None => Vanishing::Undefined,
                    Some(r) if r >= 1.0 => Vanishing::Undefined,
                    Some(r) if r <= NUMERICAL_ZERO => Vanishing::Zero,
                    Some(r) => Vanishing::Negligible(r),
                };
                let row = (res.len() > 1).then_some(i);
                return Some(VanishingFactor {
                    row,
                    factor: f,
                    at,
                    how,
                });
            }
        }
    }
    None
}

/// The point on the segment from `x` to `y` where `value` changes sign (bisection).
fn bisect(value: &dyn Fn(&[f64]) -> Option<f64>, x: &[f64], y: &[f64]) -> Vec<f64> {
    let along = |s: f64| -> Vec<f64> { x.iter().zip(y).map(|(a, b)| a + s * (b - a)).collect() };
    let sign_at_x = value(x).map_or(0.0, f64::signum);
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..REFINE {
        let mid = 0.5 * (lo + hi);
        match value(&along(mid)) {
            Some(v) if v.signum() == sign_at_x => lo = mid,
            _ => hi = mid,
        }
    }
    // A zero found by bisection carries rounding noise (θ̇ = −6.7e-16): show it as 0.
    along(0.5 * (lo + hi))
        .into_iter()
        .zip(x.iter().zip(y))
        .map(|(v, (a, b))| {
            if v.abs() <= tolerance::SAME * a.abs().max(b.abs()) {
                0.0
            } else {
                v
            }
        })
        .collect()
}

//! Equilibria for given parameter values: every solution of f(q, q' = 0, t) = 0 inside the
//! coordinate ranges (periodic coordinates modulo 2π), by multi-start Newton with
//! deduplication; stability from the stiffness matrix K = −∂f/∂q. Also the check of a
//! symbolic candidate (x₀ = m g sin α / k) by substitution at random parameter values.

use nalgebra::{DMatrix, DVector};
use rustc_hash::FxHashMap;

use super::derive::Derivation;
use super::error::MechError;
use super::linalg::generalized_eigen;
use super::sample::Sampler;
use super::state::Layout;
use super::system::System;
use crate::expr::{Id, Program};

/// An eigenvalue ω² (or a growth rate, or a frequency) counts as zero below this fraction of
/// the largest one: linear analysis cannot tell the sign of what rounding leaves.
pub(crate) const EIGENVALUE_ZERO: f64 = 1e-9;

/// A Newton root is kept when its residual is within this fraction of (1 + |J|) after the
/// iteration budget (the iteration itself aims at [`NEWTON_TARGET`]).
const NEWTON_ACCEPT: f64 = 1e-9;

/// Residual, relative to (1 + |J|), at which Newton's iteration stops.
const NEWTON_TARGET: f64 = 1e-11;

/// A root may lie this fraction of the range outside a non-periodic coordinate's range
/// (a root found exactly on the edge is not lost to rounding).
const RANGE_MARGIN: f64 = 1e-9;

/// Angles within this of ±π are reported as π (both are one angle; the tolerance is that of
/// [`NEWTON_ACCEPT`]).
const ANGLE_SNAP: f64 = 1e-9;

/// Stability of an equilibrium.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Stability {
    /// Every ω² > 0.
    Stable,
    /// Some ω² < 0.
    Unstable,
    /// No ω² < 0 but some ω² = 0 (linear analysis cannot decide).
    Marginal,
}

impl Stability {
    /// "stable", "unstable" or "marginal".
    pub fn name(self) -> &'static str {
        match self {
            Stability::Stable => "stable",
            Stability::Unstable => "unstable",
            Stability::Marginal => "marginal",
        }
    }
}

/// The equilibria found.
#[derive(Clone, Debug)]
pub struct Equilibria {
    /// Isolated equilibria with their stability, sorted.
    pub points: Vec<(Vec<f64>, Stability)>,
    /// f vanishes on a whole region: equilibria are not isolated (e.g. the bead on the
    /// parabola at ω² = 2ga).
    pub continuum: bool,
}

/// Programs for the static problem: G(q) = f(q, 0, t = 0), J = ∂G/∂q, and M(q, 0).
pub struct Statics {
    program: Program,
    layout: Layout,
    base: Vec<f64>,
}

impl Statics {
    /// Compiles G, J and M with the parameter values `params` (in the system's order).
    pub fn new(sys: &mut System, d: &Derivation, params: &[f64]) -> Result<Statics, MechError> {
        let coords = sys.coordinate_syms();
        let zero = sys.pool.zero();
        let at_rest: FxHashMap<_, _> = coords
            .iter()
            .flat_map(|&c| [((c, 1), zero), ((c, 2), zero)])
            .collect();
        let g: Vec<Id> = d
            .forcing
            .iter()
            .map(|&f| sys.pool.substitute(f, &at_rest))
            .collect();
        let mut roots = g.clone();
        for &gi in &g {
            for &c in &coords {
                roots.push(sys.pool.diff(gi, c, 0));
            }
        }
        for row in &d.mass {
            for &m in row {
                roots.push(sys.pool.substitute(m, &at_rest));
            }
        }
        let program = sys.compile(&roots)?;
        if params.len() != sys.parameters.len() {
            return Err(MechError::ParameterCount {
                expected: sys.parameters.len(),
                given: params.len(),
            });
        }
        let layout = sys.state_layout();
        let base = layout.at_rest(&[], params);
        Ok(Statics {
            program,
            layout,
            base,
        })
    }

    fn eval(
        &self,
        q: &[f64],
        scratch: &mut [f64],
    ) -> Option<(DVector<f64>, DMatrix<f64>, DMatrix<f64>)> {
        let mut x = self.base.clone();
        for (i, &v) in q.iter().enumerate() {
            x[self.layout.q(i)] = v;
        }
        self.program.run(&x, scratch).ok()?;
        let n = self.layout.coordinates();
        let g = DVector::from_fn(n, |i, _| self.program.output(i, scratch));
        let j = DMatrix::from_fn(n, n, |r, c| self.program.output(n + r * n + c, scratch));
        let m = DMatrix::from_fn(n, n, |r, c| {
            self.program.output(n + n * n + r * n + c, scratch)
        });
        Some((g, j, m))
    }

    /// Stability and the generalized eigenvalues ω² (ascending) at `q`.
    pub fn stability(&self, q: &[f64]) -> Result<(Stability, Vec<f64>, DMatrix<f64>), MechError> {
        let mut scratch = self.program.scratch();
        let (_, j, m) = self.eval(q, &mut scratch).ok_or(MechError::Undefined {
            what: "the equations at the equilibrium".into(),
        })?;
        let k = -&j;
        let k = (&k + k.transpose()) * 0.5;
        let (vals, vecs) = generalized_eigen(&k, &m)?;
        let scale = vals.iter().fold(0.0f64, |a, v| a.max(v.abs())).max(1e-300);
        let tol = EIGENVALUE_ZERO * scale;
        let st = if vals.iter().any(|&v| v < -tol) {
            Stability::Unstable
        } else if vals.iter().any(|&v| v.abs() <= tol) || scale <= 1e-250 {
            Stability::Marginal
        } else {
            Stability::Stable
        };
        Ok((st, vals.iter().copied().collect(), vecs))
    }
}

impl System {
    /// All equilibria inside the coordinate ranges for parameter values `params`.
    pub fn equilibria(&mut self, d: &Derivation, params: &[f64]) -> Result<Equilibria, MechError> {
        let statics = Statics::new(self, d, params)?;
        let ranges: Vec<(f64, f64)> = self.coordinates.iter().map(|c| c.range).collect();
        let periodic: Vec<bool> = self.coordinates.iter().map(|c| c.periodic).collect();
        let mut scratch = statics.program.scratch();
        let starts = start_points(&ranges);
        if is_continuum(&statics, &starts, &mut scratch) {
            return Ok(Equilibria {
                points: Vec::new(),
                continuum: true,
            });
        }
        let mut found: Vec<Vec<f64>> = Vec::new();
        for q0 in starts {
            let Some(q) = newton(&statics, q0, &mut scratch) else {
                continue;
            };
            let Some(q) = normalize_root(q, &ranges, &periodic) else {
                continue;
            };
            if !found.iter().any(|p| same_point(p, &q, &periodic)) {
                found.push(q);
            }
        }
        found.sort_by(|a, b| {
            a.iter()
                .zip(b)
                .map(|(x, y)| x.total_cmp(y))
                .find(|o| o.is_ne())
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        let mut points = Vec::with_capacity(found.len());
        for q in found {
            let (st, _, _) = statics.stability(&q)?;
            points.push((q, st));
        }
        Ok(Equilibria {
            points,
            continuum: false,
        })
    }

    /// Whether the candidate equilibrium `point` (one expression per coordinate, in the
    /// parameters) satisfies f(q₀, 0) = 0 at 20 random parameter samples.
    pub fn verify_equilibrium(&mut self, d: &Derivation, point: &[Id]) -> Result<bool, MechError> {
        let coords = self.coordinate_syms();
        let zero = self.pool.zero();
        let mut map: FxHashMap<_, _> = FxHashMap::default();
        for (&c, &v) in coords.iter().zip(point) {
            map.insert((c, 0), v);
            map.insert((c, 1), zero);
            map.insert((c, 2), zero);
        }
        let g: Vec<Id> = d
            .forcing
            .iter()
            .map(|&f| self.pool.substitute(f, &map))
            .collect();
        Ok(g.iter().all(|&gi| self.is_zero(gi)))
    }
}

/// Newton's starting points in `ranges`: a grid (≤ ~400 points) plus seeded random ones.
fn start_points(ranges: &[(f64, f64)]) -> Vec<Vec<f64>> {
    let n = ranges.len();
    let mut sampler = Sampler::new(0x5eed_0003);
    let per_axis = ((400f64).powf(1.0 / n as f64).floor() as usize).clamp(2, 41);
    let mut starts: Vec<Vec<f64>> = Vec::new();
    // The grid grows as per_axis^n: past 512 points (n > 9) only random starts are used.
    let total = per_axis
        .checked_pow(n as u32)
        .filter(|&t| t <= 512)
        .unwrap_or(0);
    for k in 0..total {
        let mut idx = k;
        let mut q = Vec::with_capacity(n);
        for r in ranges {
            let i = idx % per_axis;
            idx /= per_axis;
            q.push(r.0 + (r.1 - r.0) * (i as f64 + 0.5) / per_axis as f64);
        }
        starts.push(q);
    }
    let random = if total == 0 { 256 } else { 64 };
    for _ in 0..random {
        starts.push(ranges.iter().map(|r| sampler.uniform(r.0, r.1)).collect());
    }
    starts
}

/// Whether f ≈ 0 at almost every starting point: the equilibria form a continuum.
fn is_continuum(statics: &Statics, starts: &[Vec<f64>], scratch: &mut [f64]) -> bool {
    let mut zero_at_start = 0;
    let mut defined = 0;
    for q in starts {
        if let Some((g, j, _)) = statics.eval(q, scratch) {
            defined += 1;
            if g.amax() <= 1e-10 * (1.0 + j.amax()) {
                zero_at_start += 1;
            }
        }
    }
    defined > 0 && zero_at_start * 10 >= defined * 9
}

/// A root with periodic coordinates wrapped into (−π, π] and tiny values set to 0; `None`
/// when a non-periodic coordinate lies outside its range.
fn normalize_root(mut q: Vec<f64>, ranges: &[(f64, f64)], periodic: &[bool]) -> Option<Vec<f64>> {
    for i in 0..q.len() {
        if periodic[i] {
            q[i] = wrap_angle(q[i]);
        } else {
            let (lo, hi) = ranges[i];
            let margin = RANGE_MARGIN * (hi - lo);
            // Written as "not inside" so that a NaN is outside too.
            let inside = q[i] >= lo - margin && q[i] <= hi + margin;
            if !inside {
                return None;
            }
        }
        if q[i].abs() < 1e-12 {
            q[i] = 0.0;
        }
    }
    Some(q)
}

/// Whether two roots are one equilibrium (periodic coordinates compared modulo 2π).
fn same_point(a: &[f64], b: &[f64], periodic: &[bool]) -> bool {
    a.iter().zip(b).zip(periodic).all(|((x, y), &per)| {
        let d = if per {
            wrap_angle(x - y).abs()
        } else {
            (x - y).abs()
        };
        d < 1e-6 * (1.0 + x.abs())
    })
}

/// Newton's method with backtracking from `q`; `None` when it does not converge.
fn newton(s: &Statics, mut q: Vec<f64>, scratch: &mut [f64]) -> Option<Vec<f64>> {
    let n = q.len();
    for _ in 0..60 {
        let (g, j, _) = s.eval(&q, scratch)?;
        let scale = 1.0 + j.amax();
        if g.amax() <= NEWTON_TARGET * scale {
            return Some(q);
        }
        let step = j.clone().lu().solve(&(-&g))?;
        if !step.iter().all(|v| v.is_finite()) {
            return None;
        }
        let norm0 = g.norm();
        let mut t = 1.0;
        let mut accepted = false;
        for _ in 0..20 {
            let trial: Vec<f64> = (0..n).map(|i| q[i] + t * step[i]).collect();
            if let Some((g2, _, _)) = s.eval(&trial, scratch)
                && g2.norm() < norm0
            {
                q = trial;
                accepted = true;
                break;
            }
            t *= 0.5;
        }
        if !accepted {
            return None;
        }
        if q.iter().any(|v| v.abs() > 1e6) {
            return None;
        }
    }
    let (g, j, _) = s.eval(&q, scratch)?;
    (g.amax() <= NEWTON_ACCEPT * (1.0 + j.amax())).then_some(q)
}

/// An angle in (−π, π].
pub(crate) fn wrap_angle(x: f64) -> f64 {
    let (pi, tau) = (std::f64::consts::PI, std::f64::consts::TAU);
    let mut y = x.rem_euclid(tau);
    if y > pi {
        y -= tau;
    }
    if (y + pi).abs() < ANGLE_SNAP || (y - pi).abs() < ANGLE_SNAP {
        y = pi;
    }
    y
}

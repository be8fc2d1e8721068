//! Equilibria for given parameter values: every solution of f(q, q' = 0, t) = 0 inside the
//! coordinate ranges (periodic coordinates modulo 2π), by multi-start Newton with
//! deduplication; stability from the stiffness matrix K = −∂f/∂q. Also the check of a
//! symbolic candidate (x₀ = m g sin α / k) by substitution at random parameter values.

use nalgebra::{DMatrix, DVector};
use rustc_hash::FxHashMap;

use super::derive::Derivation;
use super::error::MechError;
use super::linalg::generalized_eigen;
use super::magnitude::{Magnitudes, Sized};
use super::sample::Sampler;
use super::state::Layout;
use super::system::System;
use crate::expr::{Id, Program};

/// An eigenvalue ω² (or a growth rate, or a frequency) counts as zero below this fraction of
/// the largest one: linear analysis cannot tell the sign of what rounding leaves.
pub(crate) const EIGENVALUE_ZERO: f64 = 1e-9;

/// A Newton root is kept when its residual is within this fraction of the force scale (the
/// typical size of the generalized forces' terms over the search range) after the iteration
/// budget (the iteration itself aims at [`NEWTON_TARGET`]). Relative, never absolute: a
/// spring of 1e-12 N/m has forces of 1e-12 N, and its equilibrium is still a single point.
const NEWTON_ACCEPT: f64 = 1e-9;

/// Residual, relative to the force scale, at which Newton's iteration stops.
const NEWTON_TARGET: f64 = 1e-11;

/// Newton's iterates may wander this many range widths away before the start is given up.
const NEWTON_WANDER: f64 = 1e6;

/// A coordinate of a root within this fraction of its range width of 0 is set to 0.
const ROOT_SNAP: f64 = 1e-12;

/// Two roots closer than this fraction of the range width (per coordinate) are one.
const SAME_ROOT: f64 = 1e-6;

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

/// Programs for the static problem: G(q) = f(q, 0, t = 0), J = ∂G/∂q, and M(q, 0); and G
/// and J with the sizes of their terms, which every zero test here is relative to.
pub struct Statics {
    program: Program,
    sizes: Magnitudes,
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
        let sizes = sys.magnitudes(&roots)?;
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
            sizes,
            layout,
            base,
        })
    }

    /// The sample point at rest at `q`.
    fn point(&self, q: &[f64]) -> Vec<f64> {
        let mut x = self.base.clone();
        for (i, &v) in q.iter().enumerate() {
            x[self.layout.q(i)] = v;
        }
        x
    }

    /// G, J and M at `q` with the sizes of their terms (G first, then J and M row-major).
    fn sizes(&self, q: &[f64]) -> Option<Vec<Sized>> {
        self.sizes.eval(&self.point(q))
    }

    /// The size of the generalized forces at `q`: the largest term magnitude among the Gᵢ.
    fn force_size(&self, q: &[f64]) -> Option<f64> {
        let n = self.layout.coordinates();
        let s = self.sizes(q)?;
        Some(s[..n].iter().fold(0.0, |a, v| a.max(v.magnitude)))
    }

    fn eval(
        &self,
        q: &[f64],
        scratch: &mut [f64],
    ) -> Option<(DVector<f64>, DMatrix<f64>, DMatrix<f64>)> {
        let x = self.point(q);
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
        // ω² is zero relative to the larger of the eigenvalues and the size of the terms of
        // K (per unit mass): a stiffness that is rounding left over from cancelling terms
        // is zero however the eigenvalues compare with each other, and a weak but real one
        // (k = 1e-12) is not.
        let scale = vals
            .iter()
            .fold(self.stiffness_size(q, &m), |a, v| a.max(v.abs()));
        let tol = EIGENVALUE_ZERO * scale;
        let st = if vals.iter().any(|&v| v < -tol) {
            Stability::Unstable
        } else if vals.iter().any(|&v| v.abs() <= tol) {
            Stability::Marginal
        } else {
            Stability::Stable
        };
        Ok((st, vals.iter().copied().collect(), vecs))
    }

    /// The size of the terms of K = −J at `q` per unit of mass: maxᵢ Σⱼ |Kᵢⱼ terms| / Mᵢᵢ,
    /// the scale of ω² that rounding in K is measured against (0 when K is exactly 0).
    fn stiffness_size(&self, q: &[f64], m: &DMatrix<f64>) -> f64 {
        let n = self.layout.coordinates();
        let Some(s) = self.sizes(q) else {
            return 0.0;
        };
        (0..n)
            .map(|i| {
                let row: f64 = (0..n).map(|j| s[n + i * n + j].magnitude).sum();
                row / m[(i, i)].abs()
            })
            .filter(|v| v.is_finite())
            .fold(0.0, f64::max)
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
        if let Some(q) = starts.first()
            && starts.iter().all(|q| statics.sizes(q).is_none())
        {
            // Undefined at every start: name what fails rather than find nothing.
            let what = "the equations at rest";
            return Err(self.undefined_at(&statics.sizes, &statics.point(q), what));
        }
        if is_continuum(&statics, &starts) {
            return Ok(Equilibria {
                points: Vec::new(),
                continuum: true,
            });
        }
        let widths = range_widths(&ranges, &periodic);
        let scale = NewtonScale {
            force: force_scale(&statics, &starts),
            limit: NEWTON_WANDER * widths.iter().fold(1.0f64, |a, &w| a.max(w)),
        };
        let mut found: Vec<Vec<f64>> = Vec::new();
        for q0 in starts {
            let Some(q) = newton(&statics, q0, scale, &mut scratch) else {
                continue;
            };
            let Some(q) = normalize_root(q, &ranges, &periodic) else {
                continue;
            };
            if !found.iter().any(|p| same_point(p, &q, &periodic, &widths)) {
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

/// Whether f ≈ 0 at almost every starting point: the equilibria form a continuum. Each
/// force is zero when it is rounding relative to its own terms (the bead on the parabola at
/// ω² = 2ga), never when it is merely small (a spring of 1e-12).
fn is_continuum(statics: &Statics, starts: &[Vec<f64>]) -> bool {
    let n = statics.layout.coordinates();
    let mut zero_at_start = 0;
    let mut defined = 0;
    for q in starts {
        if let Some(s) = statics.sizes(q) {
            defined += 1;
            if s[..n].iter().all(|v| v.negligible()) {
                zero_at_start += 1;
            }
        }
    }
    defined > 0 && zero_at_start * 10 >= defined * 9
}

/// Newton's yardsticks: the typical size of the forces, and how far iterates may wander.
#[derive(Clone, Copy, Debug)]
struct NewtonScale {
    force: f64,
    limit: f64,
}

/// The typical size of the generalized forces over the search range: the median, over the
/// starting points, of the largest term magnitude (a median, so that a pole inside the
/// range does not make every residual look small).
fn force_scale(statics: &Statics, starts: &[Vec<f64>]) -> f64 {
    let mut sizes: Vec<f64> = starts
        .iter()
        .filter_map(|q| statics.force_size(q))
        .filter(|v| v.is_finite() && *v > 0.0)
        .collect();
    if sizes.is_empty() {
        return 0.0;
    }
    sizes.sort_by(f64::total_cmp);
    sizes[sizes.len() / 2]
}

/// The width of each coordinate's range (2π for an angle), kept finite.
fn range_widths(ranges: &[(f64, f64)], periodic: &[bool]) -> Vec<f64> {
    ranges
        .iter()
        .zip(periodic)
        .map(|(&(lo, hi), &per)| {
            let w = if per { std::f64::consts::TAU } else { hi - lo };
            if w.is_finite() && w > 0.0 {
                w
            } else {
                f64::MAX
            }
        })
        .collect()
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
        let width = if periodic[i] {
            std::f64::consts::TAU
        } else {
            (ranges[i].1 - ranges[i].0).min(f64::MAX)
        };
        if q[i].abs() < ROOT_SNAP * width {
            q[i] = 0.0;
        }
    }
    Some(q)
}

/// Whether two roots are one equilibrium (periodic coordinates compared modulo 2π), each
/// coordinate relative to the width of its range.
fn same_point(a: &[f64], b: &[f64], periodic: &[bool], widths: &[f64]) -> bool {
    a.iter()
        .zip(b)
        .zip(periodic.iter().zip(widths))
        .all(|((x, y), (&per, &w))| {
            let d = if per {
                wrap_angle(x - y).abs()
            } else {
                (x - y).abs()
            };
            d < SAME_ROOT * w
        })
}

/// Newton's method with backtracking from `q`; `None` when it does not converge. The
/// residual is measured against the force scale, never against 1.
fn newton(
    s: &Statics,
    mut q: Vec<f64>,
    scale: NewtonScale,
    scratch: &mut [f64],
) -> Option<Vec<f64>> {
    let n = q.len();
    for _ in 0..60 {
        let (g, j, _) = s.eval(&q, scratch)?;
        if g.amax() <= NEWTON_TARGET * scale.force {
            return Some(polish(s, q, &g, &j, scratch));
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
        if q.iter().any(|v| v.abs() > scale.limit) {
            return None;
        }
    }
    let (g, _, _) = s.eval(&q, scratch)?;
    (g.amax() <= NEWTON_ACCEPT * scale.force).then_some(q)
}

/// One more Newton step from a converged `q`, kept when it does not make the residual
/// worse: the target is relative to the forces over the whole range, so a root that is tiny
/// compared with the range (x₀ = m g sin α / k = 5e-12) still gets its full precision.
fn polish(
    s: &Statics,
    q: Vec<f64>,
    g: &DVector<f64>,
    j: &DMatrix<f64>,
    scratch: &mut [f64],
) -> Vec<f64> {
    let Some(step) = j.clone().lu().solve(&(-g)) else {
        return q;
    };
    let trial: Vec<f64> = q.iter().zip(step.iter()).map(|(a, b)| a + b).collect();
    match s.eval(&trial, scratch) {
        Some((g2, _, _)) if trial.iter().all(|v| v.is_finite()) && g2.amax() <= g.amax() => trial,
        _ => q,
    }
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

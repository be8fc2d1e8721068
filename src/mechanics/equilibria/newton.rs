//! The multi-start Newton search behind [`super::System::equilibria`]: starting points,
//! the iteration and its polish down to full precision (degenerate roots included), and
//! what counts as one root.

use nalgebra::{DMatrix, DVector};

use super::Statics;
use crate::mechanics::sample::Sampler;

/// A Newton root is kept when its residual is within this fraction of the force scale (the
/// typical size of the generalized forces' terms over the search range) after the iteration
/// budget (the iteration itself aims at [`NEWTON_TARGET`]). Relative, never absolute: a
/// spring of 1e-12 N/m has forces of 1e-12 N, and its equilibrium is still a single point.
pub(super) const NEWTON_ACCEPT: f64 = 1e-9;

/// Residual, relative to the force scale, at which Newton's iteration stops.
pub(super) const NEWTON_TARGET: f64 = 1e-11;

/// Newton's iterates may wander this many range widths away before the start is given up.
pub(super) const NEWTON_WANDER: f64 = 1e6;

/// A coordinate of a root within this fraction of its range width of 0 is set to 0.
pub(super) const ROOT_SNAP: f64 = 1e-12;

/// Two roots closer than this fraction of the range width (per coordinate) are one.
pub(super) const SAME_ROOT: f64 = 1e-6;

/// A root may lie this fraction of the range outside a non-periodic coordinate's range
/// (a root found exactly on the edge is not lost to rounding).
pub(super) const RANGE_MARGIN: f64 = 1e-9;

/// Newton steps at most in [`polish`] (a root of multiplicity m gains (m−1)/m a step).
pub(super) const POLISH_STEPS: usize = 200;

/// Singular values of J below this fraction of the largest are taken as zero in a step.
pub(super) const PSEUDO_INVERSE_CUT: f64 = 1e-13;

/// Angles within this of ±π are reported as π (both are one angle; the tolerance is that of
/// [`NEWTON_ACCEPT`]).
pub(super) const ANGLE_SNAP: f64 = 1e-9;

/// Newton's starting points in `ranges`: a grid (≤ ~400 points) plus seeded random ones.
pub(super) fn start_points(ranges: &[(f64, f64)]) -> Vec<Vec<f64>> {
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
pub(super) fn is_continuum(statics: &Statics, starts: &[Vec<f64>]) -> bool {
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
pub(super) struct NewtonScale {
    pub(super) force: f64,
    pub(super) limit: f64,
}

/// The typical size of the generalized forces over the search range: the median, over the
/// starting points, of the largest term magnitude (a median, so that a pole inside the
/// range does not make every residual look small).
pub(super) fn force_scale(b: Block, starts: &[Vec<f64>]) -> f64 {
    let mut sizes: Vec<f64> = starts
        .iter()
        .filter_map(|q| b.statics.force_size(q, b.active))
        .filter(|v| v.is_finite() && *v > 0.0)
        .collect();
    if sizes.is_empty() {
        return 0.0;
    }
    crate::sort::sort_by(&mut sizes, f64::total_cmp);
    sizes[sizes.len() / 2]
}

/// The width of each coordinate's range (2π for an angle), kept finite.
pub(super) fn range_widths(ranges: &[(f64, f64)], periodic: &[bool]) -> Vec<f64> {
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
pub(super) fn normalize_root(
    mut q: Vec<f64>,
    ranges: &[(f64, f64)],
    periodic: &[bool],
) -> Option<Vec<f64>> {
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
pub(super) fn same_point(a: &[f64], b: &[f64], periodic: &[bool], widths: &[f64]) -> bool {
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

/// The equations of one block of coordinates that decouple from the rest (all of them
/// when the system does not decouple): Gᵢ and ∂Gᵢ/∂qⱼ for i, j in the block. The other
/// coordinates stay where they are; the block's forces do not depend on them.
#[derive(Clone, Copy)]
pub(super) struct Block<'a> {
    pub(super) statics: &'a Statics,
    pub(super) active: &'a [usize],
}

impl Block<'_> {
    /// The block's G and J at `q`.
    fn eval(&self, q: &[f64], scratch: &mut [f64]) -> Option<(DVector<f64>, DMatrix<f64>)> {
        let (g, j, _) = self.statics.eval(q, scratch)?;
        let a = self.active;
        let gs = DVector::from_fn(a.len(), |r, _| g[a[r]]);
        let js = DMatrix::from_fn(a.len(), a.len(), |r, c| j[(a[r], a[c])]);
        Some((gs, js))
    }

    /// `q` moved by `t` times `step` (one entry per coordinate of the block).
    fn moved(&self, q: &[f64], step: &DVector<f64>, t: f64) -> Vec<f64> {
        let mut out = q.to_vec();
        for (k, &i) in self.active.iter().enumerate() {
            out[i] += t * step[k];
        }
        out
    }
}

/// The pseudo-inverse step −J⁺G, not LU: J is exactly singular along a free direction (a
/// cyclic x, a chain's translation), and the step there is simply zero.
fn step_of(g: &DVector<f64>, j: &DMatrix<f64>) -> Option<DVector<f64>> {
    let svd = j.clone().svd(true, true);
    let cut = PSEUDO_INVERSE_CUT * svd.singular_values.max();
    let step = svd.solve(&(-g), cut).ok()?;
    step.iter().all(|v| v.is_finite()).then_some(step)
}

/// Newton's method with backtracking from `q` on the block `b`; `None` when it does not
/// converge. The residual is measured against the force scale, never against 1.
pub(super) fn newton(
    b: Block,
    mut q: Vec<f64>,
    scale: NewtonScale,
    scratch: &mut [f64],
) -> Option<Vec<f64>> {
    for _ in 0..60 {
        let (g, j) = b.eval(&q, scratch)?;
        if g.amax() <= NEWTON_TARGET * scale.force {
            return Some(polish(b, q, &g, &j, scratch));
        }
        let step = step_of(&g, &j)?;
        let norm0 = g.norm();
        let mut t = 1.0;
        let mut accepted = false;
        for _ in 0..20 {
            let trial = b.moved(&q, &step, t);
            if let Some((g2, _)) = b.eval(&trial, scratch)
                && g2.norm() < norm0
            {
                q = trial;
                accepted = true;
                break;
            }
            t *= 0.5;
        }
        if !accepted || q.iter().any(|v| v.abs() > scale.limit) {
            return None;
        }
    }
    let (g, _) = b.eval(&q, scratch)?;
    (g.amax() <= NEWTON_ACCEPT * scale.force).then_some(q)
}

/// A root with each coordinate near 0 set to 0 where that leaves the residual no larger:
/// at a degenerate root (the rotating hoop at the critical ω, where the force is
/// sin θ (cos θ − 1) and rounds to 0 already at θ = 1e-8) the exact root is preferred to
/// wherever rounding stopped the iteration; a simple root near 0 (x₀ = 5e-12) keeps its
/// value, since 0 leaves a larger residual there.
pub(super) fn snap_to_zero(
    b: Block,
    mut q: Vec<f64>,
    widths: &[f64],
    scratch: &mut [f64],
) -> Vec<f64> {
    let Some((mut g, _)) = b.eval(&q, scratch) else {
        return q;
    };
    for &i in b.active {
        if q[i] == 0.0 || q[i].abs() >= SAME_ROOT * widths[i] {
            continue;
        }
        let mut trial = q.clone();
        trial[i] = 0.0;
        if let Some((g2, _)) = b.eval(&trial, scratch)
            && g2.amax() <= g.amax()
        {
            (q, g) = (trial, g2);
        }
    }
    q
}

/// Newton steps from a converged `q` while they make the residual smaller (at most
/// [`POLISH_STEPS`]): the target is relative to the forces over the whole range, so a root
/// that is tiny compared with the range (x₀ = m g sin α / k = 5e-12) still gets its full
/// precision, and a degenerate root (V = x⁴, where Newton only gains a factor 2/3 a step)
/// is followed down to 0 rather than left at ±1e-4 by every start.
fn polish(
    b: Block,
    mut q: Vec<f64>,
    g: &DVector<f64>,
    j: &DMatrix<f64>,
    scratch: &mut [f64],
) -> Vec<f64> {
    let (mut g, mut j) = (g.clone(), j.clone());
    for _ in 0..POLISH_STEPS {
        if g.amax() == 0.0 {
            break;
        }
        let Some(step) = step_of(&g, &j) else {
            break;
        };
        let trial = b.moved(&q, &step, 1.0);
        match b.eval(&trial, scratch) {
            Some((g2, j2)) if trial.iter().all(|v| v.is_finite()) && g2.amax() < g.amax() => {
                (q, g, j) = (trial, g2, j2);
            }
            _ => break,
        }
    }
    q
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

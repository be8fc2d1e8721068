//! What an equilibrium is beyond a point: one of a continuum (a cyclic x; a free chain that
//! can translate), found as the directions along which every force stays zero; or a
//! degenerate point, where K has a zero eigenvalue along a direction that is not free, so
//! the small oscillations are not harmonic (V = x⁴; the rotating hoop at the critical ω).

use nalgebra::DVector;

use super::Statics;
use super::newton::{NEWTON_ACCEPT, SAME_ROOT, same_point};
use crate::mechanics::equilibria::EIGENVALUE_ZERO;

/// Steps along a candidate free direction at which the forces must still vanish, as
/// fractions of the narrowest range width: a continuum holds far from the root, a
/// degenerate minimum only at it.
const FREE_STEPS: [f64; 4] = [-0.3, -0.07, 0.05, 0.25];

/// Entries of a free direction this close to a whole number (after scaling its largest to
/// 1) are that number.
const DIRECTION_SNAP: f64 = 1e-9;

/// What is known about one equilibrium beyond its position and stability.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Shape {
    /// Directions along which the equilibrium is one of a continuum (every force stays
    /// zero), each scaled so that its largest entry is 1: (1, 0) for a cyclic x, (1, 1, 1)
    /// for a chain's translation. Empty for an isolated equilibrium.
    pub(crate) free: Vec<Vec<f64>>,
    /// K has a zero eigenvalue along a direction that is not free: the restoring force is
    /// not linear in the displacement (V = x⁴), so the small oscillations there are not
    /// harmonic and linear analysis cannot decide stability.
    pub(crate) degenerate: bool,
    /// The coordinates whose velocities lose their inertia here (the mass matrix is
    /// singular: the spherical pendulum's φ at θ = 0, a longitude at a pole). The chart is
    /// singular, not the physics; small oscillations need coordinates regular here.
    pub(crate) singular_chart: Vec<usize>,
}

impl Shape {
    /// Whether direction `i` alone (a coordinate axis) is free: "x arbitrary".
    pub fn coordinate_free(&self, i: usize) -> bool {
        self.free
            .iter()
            .any(|v| v.iter().enumerate().all(|(j, &x)| (j == i) == (x != 0.0)))
    }
}

/// The shape of the equilibrium at `q`: the null space of J there, each null direction
/// tested for whether the forces vanish along it (`widths`: the coordinates' range widths;
/// `force`: the search's force scale).
pub(super) fn shape_at(s: &Statics, q: &[f64], widths: &[f64], force: f64) -> Shape {
    let n = q.len();
    let mut scratch = s.program.scratch();
    let Some((_, j, m)) = s.eval(q, &mut scratch) else {
        return Shape::default();
    };
    let singular_chart = singular_coordinates(&m);
    let sizes = s.sizes(q);
    let term_size = sizes
        .as_ref()
        .map(|v| {
            v[n..n + n * n]
                .iter()
                .fold(0.0f64, |a, x| a.max(x.magnitude))
        })
        .unwrap_or(0.0);
    let svd = j.clone().svd(false, true);
    let Some(vt) = svd.v_t else {
        return Shape::default();
    };
    let scale = svd.singular_values.iter().fold(term_size, |a, &x| a.max(x));
    let step = widths.iter().fold(f64::MAX, |a, &w| a.min(w)).min(1e6);
    let mut shape = Shape {
        singular_chart,
        ..Shape::default()
    };
    for k in 0..n {
        if svd.singular_values[k] > EIGENVALUE_ZERO * scale {
            continue;
        }
        let v: Vec<f64> = vt.row(k).iter().copied().collect();
        if !null_along(&j, sizes.as_deref(), &v) {
            // Small only beside stiffer directions (a spring of 1e-12 next to one of 1):
            // a weak restoring force is still a linear one.
            continue;
        }
        if free_along(s, q, &v, step, force, &mut scratch) {
            shape.free.push(clean_direction(&v));
        } else {
            shape.degenerate = true;
        }
    }
    shape
}

/// The coordinates along which the mass matrix `m` has lost rank: a null direction of `m`
/// (eigenvalue below [`EIGENVALUE_ZERO`] of the largest), named by its large components.
fn singular_coordinates(m: &nalgebra::DMatrix<f64>) -> Vec<usize> {
    let sym = (m + m.transpose()) * 0.5;
    if !sym.iter().all(|x| x.is_finite()) {
        return Vec::new();
    }
    let eig = sym.symmetric_eigen();
    let big = eig.eigenvalues.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    let mut out = Vec::new();
    for (k, &v) in eig.eigenvalues.iter().enumerate() {
        if v.abs() > EIGENVALUE_ZERO * big {
            continue;
        }
        let col = eig.eigenvectors.column(k);
        let top = col.amax();
        for (i, x) in col.iter().enumerate() {
            if x.abs() > 0.1 * top && !out.contains(&i) {
                out.push(i);
            }
        }
    }
    crate::sort::sort_unstable(&mut out);
    out
}

/// Whether J v vanishes relative to the size of the terms it is made of (Σⱼ |Jᵢⱼ terms| |vⱼ|):
/// rounding left over from cancelling terms (a chain's translation, the hoop at the
/// critical spin) or exactly zero (V = x⁴ at 0), never merely small.
fn null_along(
    j: &nalgebra::DMatrix<f64>,
    sizes: Option<&[crate::mechanics::magnitude::Sized]>,
    v: &[f64],
) -> bool {
    let n = v.len();
    let Some(sz) = sizes else {
        return false;
    };
    (0..n).all(|r| {
        let jv: f64 = (0..n).map(|c| j[(r, c)] * v[c]).sum();
        let size: f64 = (0..n)
            .map(|c| sz[n + r * n + c].magnitude * v[c].abs())
            .sum();
        jv.abs() <= EIGENVALUE_ZERO * size
    })
}

/// Whether every force stays zero (rounding relative to its terms, or below the search's
/// acceptance) at q + s v for each of [`FREE_STEPS`].
fn free_along(
    s: &Statics,
    q: &[f64],
    v: &[f64],
    step: f64,
    force: f64,
    scratch: &mut [f64],
) -> bool {
    let n = q.len();
    FREE_STEPS.iter().all(|&f| {
        let p: Vec<f64> = q.iter().zip(v).map(|(a, b)| a + f * step * b).collect();
        let (Some((g, _, _)), Some(sz)) = (s.eval(&p, scratch), s.sizes(&p)) else {
            return false;
        };
        (0..n).all(|i| sz[i].negligible() || g[i].abs() <= NEWTON_ACCEPT * force)
    })
}

/// A direction scaled so that its largest entry is +1, rounding-level entries set to 0.
fn clean_direction(v: &[f64]) -> Vec<f64> {
    let big = v
        .iter()
        .fold(0.0f64, |a, &x| if x.abs() > a.abs() { x } else { a });
    if big == 0.0 {
        return v.to_vec();
    }
    v.iter()
        .map(|&x| {
            let y = x / big;
            // Whole entries (0, ±1: a coordinate, a translation) are shown whole.
            if (y - y.round()).abs() < DIRECTION_SNAP {
                y.round()
            } else {
                y
            }
        })
        .collect()
}

/// `q` with its components along the free directions removed (the family's point nearest
/// the origin: x = 0 for a cyclic x), or `q` itself when that point is not an equilibrium
/// (the family is not straight).
pub(super) fn representative(s: &Statics, q: &[f64], shape: &Shape, force: f64) -> Vec<f64> {
    if shape.free.is_empty() {
        return q.to_vec();
    }
    let basis = orthonormal(&shape.free);
    let mut p = DVector::from_column_slice(q);
    for b in &basis {
        let c = p.dot(b);
        p -= b * c;
    }
    let p: Vec<f64> = p
        .iter()
        .map(|&x| if x.abs() < 1e-12 { 0.0 } else { x })
        .collect();
    let mut scratch = s.program.scratch();
    let n = q.len();
    match (s.eval(&p, &mut scratch), s.sizes(&p)) {
        (Some((g, _, _)), Some(sz))
            if (0..n).all(|i| sz[i].negligible() || g[i].abs() <= NEWTON_ACCEPT * force) =>
        {
            p
        }
        _ => q.to_vec(),
    }
}

/// Whether `b` lies on the family through `a` (their difference is along `a`'s free
/// directions, within `tol` per coordinate).
pub(super) fn on_family(a: &[f64], shape: &Shape, b: &[f64], tol: &[f64]) -> bool {
    if shape.free.is_empty() {
        return false;
    }
    let mut d = DVector::from_iterator(a.len(), a.iter().zip(b).map(|(x, y)| y - x));
    for e in &orthonormal(&shape.free) {
        let c = d.dot(e);
        d -= e * c;
    }
    d.iter().zip(tol).all(|(x, t)| x.abs() < *t)
}

/// The roots `found` grouped into equilibria: each with its shape, a continuum's roots
/// (a free chain's x₁ = x₂ = x₃ = −9.5, −8.5, …) kept once, at its representative point.
pub(super) fn group(
    s: &Statics,
    found: Vec<Vec<f64>>,
    periodic: &[bool],
    widths: &[f64],
    force: f64,
) -> Vec<(Vec<f64>, Shape)> {
    let tol: Vec<f64> = widths.iter().map(|w| SAME_ROOT * w).collect();
    let mut out: Vec<(Vec<f64>, Shape)> = Vec::new();
    for q in found {
        if out.iter().any(|(a, sh)| on_family(a, sh, &q, &tol)) {
            continue;
        }
        let shape = shape_at(s, &q, widths, force);
        let rep = representative(s, &q, &shape, force);
        if out
            .iter()
            .any(|(a, _)| same_point(a, &rep, periodic, widths))
        {
            continue;
        }
        out.push((rep, shape));
    }
    out
}

/// Gram–Schmidt on the free directions.
fn orthonormal(vs: &[Vec<f64>]) -> Vec<DVector<f64>> {
    let mut out: Vec<DVector<f64>> = Vec::new();
    for v in vs {
        let mut w = DVector::from_column_slice(v);
        for e in &out {
            let c = w.dot(e);
            w -= e * c;
        }
        let norm = w.norm();
        if norm > 1e-12 {
            out.push(w / norm);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_coordinate_axis_is_recognised() {
        let s = Shape {
            free: vec![vec![1.0, 0.0]],
            ..Shape::default()
        };
        assert!(s.coordinate_free(0));
        assert!(!s.coordinate_free(1));
        let chain = Shape {
            free: vec![vec![1.0, 1.0, 1.0]],
            ..Shape::default()
        };
        assert!(!chain.coordinate_free(0));
    }

    #[test]
    fn directions_are_scaled_to_a_largest_entry_of_one() {
        let r = 1.0 / 3f64.sqrt();
        assert_eq!(clean_direction(&[-r, -r, -r]), vec![1.0, 1.0, 1.0]);
        assert_eq!(clean_direction(&[1e-17, -0.5]), vec![0.0, 1.0]);
    }

    #[test]
    fn points_on_a_translation_family_are_one() {
        let s = Shape {
            free: vec![vec![1.0, 1.0]],
            ..Shape::default()
        };
        assert!(on_family(&[0.0, 0.0], &s, &[3.0, 3.0], &[1e-6, 1e-6]));
        assert!(!on_family(&[0.0, 0.0], &s, &[3.0, 2.0], &[1e-6, 1e-6]));
    }
}

#[cfg(test)]
mod chart_tests {
    use super::*;

    #[test]
    fn a_pole_names_the_coordinate_that_lost_its_inertia() {
        // Spherical pendulum at θ = 0: M = diag(m l², m l² sin²θ) = diag(1, 0).
        let m = nalgebra::DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 0.0]);
        assert_eq!(singular_coordinates(&m), vec![1]);
        let fine = nalgebra::DMatrix::from_row_slice(2, 2, &[1.0, 0.0, 0.0, 2.0]);
        assert!(singular_coordinates(&fine).is_empty());
    }
}

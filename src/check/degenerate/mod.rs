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
//!
//! Files: [`det`] evaluates det C at a point; [`search`] looks for where it vanishes (sample
//! points, special points, line scans); [`explain`] turns what was found into a reason.

mod det;
mod explain;
mod search;

pub(crate) use explain::Degeneracy;

use self::det::DetC;
use self::explain::explain;
use self::search::probe;
use super::prepare::Prepared;
use crate::expr::Id;

/// Whether the equations `res` (which hold at the true accelerations, `rows == n`) determine
/// the accelerations everywhere; the reason when they do not.
///
/// One equation of a system with several coordinates (`res.len() == 1 < n`) is judged
/// against `reference`, the part's own reference equation: it must be that equation times a
/// factor that vanishes nowhere. Without a reference (the bank verifying a part's own
/// reference equation) it is judged against the one Euler–Lagrange equation it is a multiple
/// of, when it is one (`r·(m r̈ − m r φ̇² + k/r²) = 0` against the radial equation); a
/// genuine combination of several is not judged.
pub(crate) fn degeneracy(
    p: &mut Prepared,
    res: &[Id],
    reference: Option<Id>,
) -> Option<Degeneracy> {
    let n = p.system.n();
    let reference = match (res, reference) {
        _ if res.len() == n => None,
        ([_], Some(reference)) => Some(reference),
        ([r], None) => Some(multiple_of(p, *r)?),
        _ => return None,
    };
    let found = {
        let det = match (res, reference) {
            ([r], Some(reference)) => DetC::projection(p, *r, reference)?,
            _ => DetC::new(p, res)?,
        };
        // `det` borrows the system; the search only reads it.
        let shared: &Prepared = det.prepared();
        probe(shared, &det)?
    };
    Some(explain(p, res, found))
}

/// The Euler–Lagrange equation whose acceleration row is parallel to `r`'s at every sample
/// point where both are defined (so `r` is a function times that equation), if exactly one is.
fn multiple_of(p: &mut Prepared, r: Id) -> Option<Id> {
    let coords = p.system.coordinate_syms();
    let equations = p.derivation.equations();
    let n = coords.len();
    let mut roots = Vec::with_capacity((equations.len() + 1) * n);
    for &e in std::iter::once(&r).chain(&equations) {
        for &c in &coords {
            roots.push(p.system.pool.diff(e, c, 2));
        }
    }
    let vals = super::compare::values(&p.system, &roots, &p.points).ok()?;
    let parallel = |v: &[f64], i: usize| -> bool {
        let a = &v[..n];
        let m = &v[(i + 1) * n..(i + 2) * n];
        let dot: f64 = a.iter().zip(m).map(|(x, y)| x * y).sum();
        let aa: f64 = a.iter().map(|x| x * x).sum();
        let mm: f64 = m.iter().map(|x| x * x).sum();
        // |a|²|m|² − (a·m)² is the squared area between the rows: zero when parallel (a zero
        // row of `r` is parallel to anything, which is what a vanishing factor looks like).
        (aa * mm - dot * dot).abs() <= 1e-9 * (aa * mm).max(f64::MIN_POSITIVE)
    };
    let mut found = None;
    for (i, &e) in equations.iter().enumerate() {
        let mut seen = 0;
        let all = vals.iter().flatten().all(|v| {
            seen += 1;
            parallel(v, i)
        });
        if all && seen > 0 {
            if found.is_some() {
                return None;
            }
            found = Some(e);
        }
    }
    found
}

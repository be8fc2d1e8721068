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

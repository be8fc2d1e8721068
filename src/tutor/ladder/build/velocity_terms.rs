//! Whether a frequencies part's equilibrium has terms linear in the velocities (a rotating
//! frame, a magnetic field): there the linearized motion is M q'' + G q' + K q = 0, and the
//! ladder's M q'' + K q = 0 and det(K − ω² M) steps would drop G.

use rustc_hash::FxHashMap;

use super::statics::{point_of, second};
use crate::expr::{Id, Sym};
use crate::problem::{Part, Problem};
use crate::tutor::ladder::step::LadderError;

/// Whether G = ∂²L/∂q'∂q − (∂²L/∂q'∂q)ᵀ is nonzero at rest at the point of `freq`.
pub(super) fn gyroscopic_at(problem: &Problem, freq: &Part) -> Result<bool, LadderError> {
    let mut sys = problem.system.clone();
    sys.substitute_parameters(&freq.substitute)?;
    let point = point_of(&mut sys, freq)?;
    let coords = sys.coordinate_syms();
    let zero = sys.pool.zero();
    let at_rest: FxHashMap<(Sym, u8), Id> = coords
        .iter()
        .zip(&point)
        .flat_map(|(&c, &q0)| [((c, 0), q0), ((c, 1), zero)])
        .collect();
    let l = sys.lagrangian;
    for &ci in &coords {
        for &cj in &coords {
            let a = second(&mut sys, l, (ci, 1), (cj, 0), &at_rest);
            let b = second(&mut sys, l, (cj, 1), (ci, 0), &at_rest);
            let g = sys.pool.sub(a, b);
            if !sys.is_zero(g) {
                return Ok(true);
            }
        }
    }
    Ok(false)
}

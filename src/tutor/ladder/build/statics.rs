//! The statics the ladder's later steps stand on: the expansion point a part names, the
//! displacement q − q₀ from it, the second derivatives of L there (M and −K at rest), and the
//! point written out for a prompt.

use rustc_hash::FxHashMap;

use super::super::step::LadderError;
use crate::expr::{Id, Style, Sym, read_expr};
use crate::mechanics::System;
use crate::problem::Part;

/// q − q₀ (just q when q₀ is 0).
pub(super) fn displacement(sys: &mut System, c: Sym, q0: Id) -> Id {
    let q = sys.pool.var(c, 0);
    sys.pool.sub(q, q0)
}

/// M = ∂²L/∂q'∂q' and ∂²L/∂q∂q (that is −K) at rest at `point`.
pub(super) fn mass_and_stiffness(sys: &mut System, point: &[Id]) -> (Vec<Vec<Id>>, Vec<Vec<Id>>) {
    let coords = sys.coordinate_syms();
    let zero = sys.pool.zero();
    let mut at_rest: FxHashMap<(Sym, u8), Id> = FxHashMap::default();
    for (&c, &q0) in coords.iter().zip(point) {
        at_rest.insert((c, 0), q0);
        at_rest.insert((c, 1), zero);
    }
    let l = sys.lagrangian;
    let (mut m, mut k) = (Vec::new(), Vec::new());
    for &ci in &coords {
        let mut mr = Vec::new();
        let mut kr = Vec::new();
        for &cj in &coords {
            mr.push(second(sys, l, (ci, 1), (cj, 1), &at_rest));
            kr.push(second(sys, l, (ci, 0), (cj, 0), &at_rest));
        }
        m.push(mr);
        k.push(kr);
    }
    (m, k)
}

/// ∂²L/∂a∂b evaluated at `at`, simplified.
pub(in crate::tutor::ladder) fn second(
    sys: &mut System,
    l: Id,
    a: (Sym, u8),
    b: (Sym, u8),
    at: &FxHashMap<(Sym, u8), Id>,
) -> Id {
    let d = sys.pool.diff(l, a.0, a.1);
    let d = sys.pool.diff(d, b.0, b.1);
    let d = sys.pool.substitute(d, at);
    sys.simplify(d)
}

/// The equilibrium of a frequencies part, one expression per coordinate (0 where unnamed).
pub(in crate::tutor::ladder) fn point_of(
    sys: &mut System,
    part: &Part,
) -> Result<Vec<Id>, LadderError> {
    let ctx = sys.context();
    let names: Vec<String> = sys.coordinates.iter().map(|c| c.name.clone()).collect();
    let mut point = Vec::new();
    for name in &names {
        let id = match part.at.iter().find(|(n, _)| n == name) {
            None => sys.pool.zero(),
            Some((_, text)) => {
                read_expr(text, &ctx, &mut sys.pool).map_err(|_| LadderError::BadPoint {
                    part: part.id.clone(),
                    text: text.clone(),
                })?
            }
        };
        point.push(id);
    }
    Ok(point)
}

/// The point `θ₁ = 0, θ₂ = 0` in Unicode.
pub(super) fn at_text(sys: &System, point: &[Id]) -> String {
    sys.coordinates
        .iter()
        .zip(point)
        .map(|(c, &v)| {
            let name = sys.pool.var_name(c.sym, 0, Style::Unicode);
            format!("{name} = {}", sys.pool.unicode(v))
        })
        .collect::<Vec<_>>()
        .join(", ")
}

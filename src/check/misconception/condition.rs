//! `lost-root` for an equilibrium condition (an `equation` part whose reference has no
//! accelerations): the student's condition is the reference divided by a factor that vanishes
//! at an equilibrium (r, sin θ, cos θ), so that equilibrium no longer satisfies it.

use super::super::compare::{proportional, values};
use super::super::prepare::Prepared;
use super::super::tolerance;
use super::super::verdict::{Code, Diagnosis};
use super::numeric::equal;
use super::roots::factors;
use crate::expr::{Func, Id, Node, Sym};
use rustc_hash::FxHashMap;

/// `lost-root` when the student's one residual `res`, times a candidate divisor, is the
/// reference condition up to a nonzero constant or parameter factor (the checker's own test),
/// and the divisor's zero is an equilibrium the student's condition misses.
pub fn lost_root(p: &mut Prepared, res: &[Id]) -> Option<Diagnosis> {
    let &[s] = res else { return None };
    let reference = (*p.condition.get()?)?;
    for sym in p.system.coordinate_syms() {
        for f in factors(p, sym) {
            let times = p.system.pool.mul(s, f);
            if !proportional(&p.system, times, reference, &p.points, tolerance::SAME) {
                continue;
            }
            let Some(root) = zero_of(p, f) else { continue };
            if loses(p, (s, reference), sym, root) {
                return Some(message(p, f));
            }
        }
    }
    None
}

/// A value of the coordinate where the divisor `f` vanishes: 0 for q and sin q, π/2 for cos q.
fn zero_of(p: &mut Prepared, f: Id) -> Option<Id> {
    match p.system.pool.node(f) {
        Node::Var(..) | Node::Func(Func::Sin, _) => Some(p.system.pool.zero()),
        Node::Func(Func::Cos, _) => {
            let pi = p.system.pool.pi();
            let two = p.system.pool.int(2);
            Some(p.system.pool.div(pi, two))
        }
        _ => None,
    }
}

/// Whether at q = `root` the reference condition holds (an equilibrium) but the student's
/// does not (finite and nonzero at some sample point): the root really is lost.
fn loses(p: &mut Prepared, (s, reference): (Id, Id), sym: Sym, root: Id) -> bool {
    let mut map = FxHashMap::default();
    map.insert((sym, 0), root);
    let r0 = p.system.pool.substitute(reference, &map);
    let zero = p.system.pool.zero();
    if !equal(p, r0, zero, false) {
        return false;
    }
    let s0 = p.system.pool.substitute(s, &map);
    values(&p.system, &[s0], &p.points).is_ok_and(|v| {
        v.iter()
            .flatten()
            .any(|x| x[0].is_finite() && x[0].abs() > 1e-9)
    })
}

/// The sentence, in the student's terms: the divisor and the equilibria it loses.
fn message(p: &Prepared, f: Id) -> Diagnosis {
    let shown = p.system.pool.unicode(f);
    let text = if matches!(p.system.pool.node(f), Node::Var(..)) {
        format!(
            "lost root: you divided the condition by {shown}, which loses the equilibrium {shown} = 0 (the condition holds there too); dividing an equation by a factor loses the zeros of that factor"
        )
    } else {
        format!(
            "lost roots: you divided the condition by {shown}, which loses the equilibria where {shown} = 0 (the condition holds there too); dividing an equation by a factor loses the zeros of that factor"
        )
    };
    Diagnosis::new(Code::LostRoot, text)
}

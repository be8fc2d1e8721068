//! Wrong equations of motion generated from the physics: the Euler–Lagrange equations with the
//! product/chain-rule terms of d/dt ∂L/∂q̇ dropped (`derivative-rule`), with a conserved
//! momentum put into L before differentiating (`premature-substitution`), and in another sign
//! convention (`convention`). Answers are compared through the accelerations each implies.

use super::super::generated::{Candidate, Motion};
use super::super::prepare::Prepared;
use super::super::prepare::true_accelerations;
use super::super::verdict::{Code, Diagnosis};
use super::energies;
use super::numeric::{accelerations, differ, full_rank, holds_at};
use crate::expr::Id;
use crate::problem::{Part, PartKind};
use rustc_hash::FxHashMap;
use std::sync::Arc;

/// Most coordinates for which wrong systems are generated (each costs a derivation).
const MAX_COORDINATES: usize = 6;

/// Most coordinates for which every subset of wrong equations is tried (2ⁿ − 1 systems).
const MAX_SUBSET_COORDINATES: usize = 3;

/// The first generated wrong system of equations the student's equations `res` follow.
pub fn diagnose(part: &Part, p: &mut Prepared, res: &[Id]) -> Option<Diagnosis> {
    if !p.system.constraints.is_empty() || res.is_empty() || p.system.n() > MAX_COORDINATES {
        return None;
    }
    let truth = true_accelerations(p).ok()?;
    let cands = generated(p, &truth);
    for (c, acc) in cands.iter() {
        let follows = match part.kind {
            PartKind::Equations => res.iter().all(|&r| holds_at(p, r, acc)) && full_rank(p, res),
            _ => res.len() == 1 && holds_at(p, res[0], acc) && !holds_at(p, res[0], &truth),
        };
        if follows {
            return Some(c.diagnosis());
        }
    }
    None
}

/// The generated wrong systems that differ from the `truth`, with their accelerations: made
/// on the part's first wrong equations, then kept (they do not depend on the answer).
fn generated(p: &mut Prepared, truth: &[Option<Vec<f64>>]) -> Arc<[Motion]> {
    if let Some(g) = &p.generated.motion {
        return g.clone();
    }
    let mut cands = derivative_rule(p);
    cands.extend(premature_substitution(p));
    cands.extend(convention(p));
    let mut kept = Vec::with_capacity(cands.len());
    for c in cands {
        let acc = accelerations(p, &c.answer);
        if differ(&acc, truth) {
            kept.push((c, acc));
        }
    }
    let g: Arc<[Motion]> = kept.into();
    p.generated.motion = Some(g.clone());
    g
}

/// The Euler–Lagrange residuals of `l` (with the system's generalized forces).
pub fn euler_lagrange(p: &mut Prepared, l: Id) -> Vec<Id> {
    let coords = p.system.coordinate_syms();
    let forces = p.system.forces.clone();
    coords
        .iter()
        .zip(forces)
        .map(|(&c, q)| {
            let pm = p.system.pool.diff(l, c, 1);
            let dp = p.system.pool.dt(pm, &coords);
            let dl = p.system.pool.diff(l, c, 0);
            let e = p.system.pool.sub(dp, dl);
            p.system.pool.sub(e, q)
        })
        .collect()
}

/// d/dt ∂L/∂q̇ taken as Σⱼ ∂²L/∂q̇∂q̇ⱼ·q̈ⱼ only, for every non-empty subset of the coordinates'
/// equations (a student may slip in one equation and not the other).
fn derivative_rule(p: &mut Prepared) -> Vec<Candidate<Vec<Id>>> {
    let n = p.system.n();
    if n == 0 || n > MAX_SUBSET_COORDINATES {
        return Vec::new();
    }
    let l = p.system.lagrangian;
    let right = euler_lagrange(p, l);
    let coords = p.system.coordinate_syms();
    let mut wrong = Vec::with_capacity(n);
    let mut depends = Vec::new();
    for (i, &c) in coords.iter().enumerate() {
        let pm = p.system.pool.diff(l, c, 1);
        let mut inertia = Vec::new();
        for &d in &coords {
            let m = p.system.pool.diff(pm, d, 1);
            for v in p.system.pool.variables(m) {
                if v.1 == 0 && coords.contains(&v.0) && !depends.contains(&v.0) {
                    depends.push(v.0);
                }
            }
            let acc = p.system.pool.var(d, 2);
            inertia.push(p.system.pool.mul(m, acc));
        }
        let dp = p.system.pool.sum(inertia);
        let dl = p.system.pool.diff(l, c, 0);
        let e = p.system.pool.sub(dp, dl);
        wrong.push(p.system.pool.sub(e, p.system.forces[i]));
    }
    if depends.is_empty() {
        // Constant coefficients: d/dt ∂L/∂q̇ has no product- or chain-rule terms to lose.
        return Vec::new();
    }
    let names: Vec<String> = depends
        .iter()
        .map(|&s| {
            let v = p.system.pool.var(s, 0);
            p.system.pool.unicode(v)
        })
        .collect();
    let rate = p.system.pool.var(depends[0], 1);
    let rate = p.system.pool.unicode(rate);
    let message = format!(
        "derivative rule: in d/dt ∂L/∂q̇ the coefficients of the velocities change in time too (they depend on {}), so the product and chain rules add terms (d/dt f({}) = f′({})·{rate}); you differentiated only the velocities",
        names.join(", "),
        names[0],
        names[0]
    );
    (1..(1usize << n))
        .filter(|mask| (0..n).all(|i| mask & (1 << i) == 0 || wrong[i] != right[i]))
        .map(|mask| {
            let sys = (0..n)
                .map(|i| {
                    if mask & (1 << i) != 0 {
                        wrong[i]
                    } else {
                        right[i]
                    }
                })
                .collect();
            Candidate::new(Code::DerivativeRule, message.clone(), sys)
        })
        .collect()
}

/// For each cyclic coordinate c whose momentum is linear in ċ: ċ replaced in L by the
/// conserved p_c before differentiating (the Routhian with the wrong sign), p_c put back after.
fn premature_substitution(p: &mut Prepared) -> Vec<Candidate<Vec<Id>>> {
    let l = p.system.lagrangian;
    let right = euler_lagrange(p, l);
    let coords = p.system.coordinate_syms();
    let mut out = Vec::new();
    for (k, &c) in coords.iter().enumerate() {
        let dl = p.system.pool.diff(l, c, 0);
        let pc = p.system.pool.diff(l, c, 1);
        let a = p.system.pool.diff(pc, c, 1);
        let velocity_free = p.system.pool.variables(a).iter().all(|v| v.1 == 0);
        if !p.system.pool.is_zero(dl)
            || !p.system.pool.is_zero(p.system.forces[k])
            || !velocity_free
            || p.system.pool.is_zero(a)
        {
            continue;
        }
        // ċ = (P − b)/a with b = p_c − a·ċ, P a fresh constant standing for p_c.
        let cdot = p.system.pool.var(c, 1);
        let acd = p.system.pool.mul(a, cdot);
        let b = p.system.pool.sub(pc, acd);
        let psym = p.system.pool.symbol("conserved momentum (premature)");
        let pv = p.system.pool.var(psym, 0);
        let num = p.system.pool.sub(pv, b);
        let cdot_of_p = p.system.pool.div(num, a);
        let mut map = FxHashMap::default();
        map.insert((c, 1), cdot_of_p);
        let routh = p.system.pool.substitute(l, &map);
        let mut back = FxHashMap::default();
        back.insert((psym, 0), pc);
        let mut sys = right.clone();
        for (i, &q) in coords.iter().enumerate() {
            if i == k {
                continue;
            }
            let pm = p.system.pool.diff(routh, q, 1);
            let dp = p.system.pool.dt(pm, &coords);
            let dq = p.system.pool.diff(routh, q, 0);
            let e = p.system.pool.sub(dp, dq);
            let e = p.system.pool.sub(e, p.system.forces[i]);
            sys[i] = p.system.pool.substitute(e, &back);
        }
        let cv = p.system.pool.var(c, 0);
        let name = p.system.pool.unicode(cv);
        let rate = p.system.pool.unicode(cdot);
        out.push(Candidate::new(
            Code::PrematureSubstitution,
            format!(
                "the term that comes from {rate} has the wrong sign, which is what putting the conserved momentum p_{name} into L before differentiating gives (a premature substitution), if that is what you did: ∂/∂q must be taken with {rate} held fixed, not p_{name}. Substitute p_{name} only into the finished equations (or use the Routhian R = L − p_{name}·{rate})"
            ),
            sys,
        ));
    }
    out
}

/// The equations of the same system in another common convention: angles from the horizontal,
/// or y pointing down (when gravity is not the whole potential, where that is a plain sign
/// error).
fn convention(p: &mut Prepared) -> Vec<Candidate<Vec<Id>>> {
    let l = p.system.lagrangian;
    let right = euler_lagrange(p, l);
    let mut out = Vec::new();
    if let Some((map, message)) = energies::angle_from_horizontal(p) {
        let sys = right
            .iter()
            .map(|&e| p.system.pool.substitute(e, &map))
            .collect();
        out.push(Candidate::new(Code::Convention, message, sys));
    }
    for (map, message) in energies::rotation_sense(p) {
        let l2 = p.system.pool.substitute(l, &map);
        let sys = euler_lagrange(p, l2);
        out.push(Candidate::new(Code::Convention, message, sys));
    }
    if let Some((flipped, message)) = energies::gravity_flipped(p) {
        // L' = L + 2·V_gravity: the gravity term of V with the other sign.
        let two = p.system.pool.int(2);
        let extra = p.system.pool.mul(two, flipped);
        let l2 = p.system.pool.add(l, extra);
        let sys = euler_lagrange(p, l2);
        out.push(Candidate::new(Code::Convention, message, sys));
    }
    out
}

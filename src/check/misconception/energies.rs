//! Wrong energies generated from the physics: heights measured wrongly in V (`pe-geometry`),
//! the energy function taken as T + V where they differ (`h-vs-e`), and the same quantity in
//! another sign convention (`convention`).

use super::super::generated::Candidate;
use super::super::prepare::Prepared;
use super::super::verdict::{Code, Diagnosis};
use super::numeric::{distinct, equal};
use crate::expr::{Id, Node, Sym};
use crate::mechanics::Body;
use crate::problem::{Part, PartKind, Quantity};
use rustc_hash::FxHashMap;

/// The first generated wrong answer the expression `s` equals.
pub fn diagnose(part: &Part, p: &mut Prepared, s: Id, reference: Id) -> Option<Diagnosis> {
    let lagrangian = part.kind == PartKind::Lagrangian || part.quantity == Quantity::Lagrangian;
    let loose = part.up_to_constant || lagrangian;
    let mut cands: Vec<Candidate<Id>> = Vec::new();
    if part.quantity == Quantity::EnergyFunction {
        cands.extend(h_vs_e(p));
    }
    if matches!(part.quantity, Quantity::Potential | Quantity::Lagrangian)
        && part.substitute.is_empty()
    {
        for c in pe_geometry(p) {
            let answer = if part.quantity == Quantity::Lagrangian {
                // L' = L + V − V'.
                let v = p.system.potential?;
                let d = p.system.pool.sub(v, c.answer);
                p.system.pool.add(reference, d)
            } else {
                c.answer
            };
            cands.push(Candidate { answer, ..c });
        }
    }
    cands.extend(convention(part, p, reference));
    // T + V for a Lagrangian is told as `t-plus-v`; never as something else.
    let tv = match (p.system.kinetic, p.system.potential) {
        (Some(t), Some(v)) if lagrangian => Some(p.system.pool.add(t, v)),
        _ => None,
    };
    cands
        .into_iter()
        .filter(|c| c.code == Code::HVsE || distinct(p, c.answer, reference))
        .filter(|c| tv.is_none_or(|tv| !equal(p, c.answer, tv, true)))
        // T + V plus a constant is still T + V for h (the zero of V is free there too).
        .find(|c| equal(p, s, c.answer, loose || c.code == Code::HVsE))
        .map(|c| c.diagnosis())
}

/// T + V where the energy function h differs from it.
fn h_vs_e(p: &mut Prepared) -> Option<Candidate<Id>> {
    let (t, v) = (p.system.kinetic?, p.system.potential?);
    let tv = p.system.pool.add(t, v);
    let coords = p.system.coordinate_syms();
    let l = p.system.lagrangian;
    let mut sum = Vec::new();
    for &c in &coords {
        let pm = p.system.pool.diff(l, c, 1);
        let qd = p.system.pool.var(c, 1);
        sum.push(p.system.pool.mul(qd, pm));
    }
    let s = p.system.pool.sum(sum);
    let h = p.system.pool.sub(s, l);
    if !distinct(p, tv, h) {
        return None;
    }
    let time = p.system.pool.time();
    let conserved = if p.system.pool.variables(l).iter().any(|v| v.0 == time) {
        ""
    } else {
        " (it is h, not T + V, that is conserved here)"
    };
    Some(Candidate::new(
        Code::HVsE,
        format!(
            "h is not E here: the energy function h = Σ q̇ ∂L/∂q̇ − L equals T + V only when T is a quadratic form in the velocities; here T has terms that are not (the frame or a constraint moves), so compute h from its definition{conserved}"
        ),
        tv,
    ))
}

/// The symbol of the gravity parameter `g`, when the system has one.
fn gravity_sym(p: &Prepared) -> Option<Sym> {
    p.system
        .parameters
        .iter()
        .find(|x| x.name == "g")
        .map(|x| x.sym)
}

/// The gravity part of V (V minus V with g = 0), with the `convention` sentence for y pointing
/// down — only when V has other, coordinate-dependent parts too: flipping all of V is a plain
/// sign error and is told as one.
pub fn gravity_flipped(p: &mut Prepared) -> Option<(Id, String)> {
    let g = gravity_sym(p)?;
    let (vg, rest) = gravity_part(p, g)?;
    let coords = p.system.coordinate_syms();
    let depends = |p: &Prepared, e: Id| {
        p.system
            .pool
            .variables(e)
            .iter()
            .any(|x| coords.contains(&x.0))
    };
    if !depends(p, vg) || !depends(p, rest) {
        return None;
    }
    Some((
        vg,
        "convention: your answer is right with the height measured downward (y pointing down); the potential energy of gravity is m·g·h with h measured upward, so it stays incorrect here".into(),
    ))
}

/// A substitution of variables (symbol, derivative order) by expressions.
pub type Substitution = FxHashMap<(Sym, u8), Id>;

/// θ → π/2 − θ for every angle (and θ̇ → −θ̇, θ̈ → −θ̈): the angles measured from the
/// perpendicular axis (the map is its own inverse, so the sentence names no direction); with
/// its `convention` sentence. `None` without angle coordinates.
pub fn angle_from_horizontal(p: &mut Prepared) -> Option<(Substitution, String)> {
    let angles: Vec<Sym> = p
        .system
        .coordinates
        .iter()
        .filter(|c| c.periodic)
        .map(|c| c.sym)
        .collect();
    let first = *angles.first()?;
    let pi = p.system.pool.pi();
    let half = p.system.pool.ratio(1, 2);
    let right = p.system.pool.mul(half, pi);
    let mut map = FxHashMap::default();
    for &a in &angles {
        let q = p.system.pool.var(a, 0);
        map.insert((a, 0), p.system.pool.sub(right, q));
        for o in 1..3u8 {
            let d = p.system.pool.var(a, o);
            map.insert((a, o), p.system.pool.neg(d));
        }
    }
    let q = p.system.pool.var(first, 0);
    let name = p.system.pool.unicode(q);
    Some((
        map,
        format!(
            "convention: your answer is right for {name} measured from the perpendicular axis (from the horizontal instead of the vertical, or the reverse: {name} → π/2 − {name}); use the angle as the problem's statement defines it"
        ),
    ))
}

/// Ω → −Ω for every rate (a parameter of dimension T⁻¹) with which a body's position turns
/// in time: the frame or the body turning the other way, which is the same as describing it in
/// axes of the other handedness (x and y exchanged, or one axis reversed). One substitution
/// per rate, with its `convention` sentence; none where no position depends on t.
pub fn rotation_sense(p: &mut Prepared) -> Vec<(Substitution, String)> {
    let time = p.system.pool.time();
    let positions: Vec<Id> = p
        .system
        .bodies
        .iter()
        .flat_map(|b| match b {
            Body::Point { position, .. } => position.clone(),
            Body::Rigid(r) => r.position.clone(),
            Body::Rotor { .. } => Vec::new(),
        })
        .collect();
    let mut out = Vec::new();
    let per_time = crate::expr::Dimension::parse("T^-1").ok();
    let rates: Vec<Sym> = p
        .system
        .parameters
        .iter()
        .filter(|x| x.dimension.is_some() && x.dimension == per_time)
        .map(|x| x.sym)
        .collect();
    for rate in rates {
        let turns = positions.iter().any(|&x| {
            let vars = p.system.pool.variables(x);
            vars.iter().any(|v| v.0 == time) && vars.iter().any(|v| v.0 == rate)
        });
        if !turns {
            continue;
        }
        let w = p.system.pool.var(rate, 0);
        let mut map = FxHashMap::default();
        map.insert((rate, 0), p.system.pool.neg(w));
        let name = p.system.pool.unicode(w);
        out.push((
            map,
            format!(
                "convention: your answer is right for a rotation the other way ({name} → −{name}; the same as axes of the other handedness, x and y exchanged or one axis reversed); use the sense of rotation and the axes the problem's statement fixes"
            ),
        ));
    }
    out
}

/// The part's quantity in another convention: angles from the horizontal, a rotation the
/// other way, y pointing down.
fn convention(part: &Part, p: &mut Prepared, reference: Id) -> Vec<Candidate<Id>> {
    let mut out = Vec::new();
    if let Some((map, message)) = angle_from_horizontal(p) {
        let c = p.system.pool.substitute(reference, &map);
        out.push(Candidate::new(Code::Convention, message, c));
    }
    for (map, message) in rotation_sense(p) {
        let c = p.system.pool.substitute(reference, &map);
        out.push(Candidate::new(Code::Convention, message, c));
    }
    let sign = match part.quantity {
        Quantity::Potential | Quantity::EnergyFunction => 1,
        Quantity::Lagrangian => -1,
        _ => return out,
    };
    if let Some((vg, message)) = gravity_flipped(p) {
        let k = p.system.pool.int(-2 * sign);
        let d = p.system.pool.mul(k, vg);
        let c = p.system.pool.add(reference, d);
        out.push(Candidate::new(Code::Convention, message, c));
    }
    out
}

/// Point masses with their mass and height along the gravity axis (the axis on which
/// Σ m·g·r[axis] is the gravity part of V). Empty when there is no such axis.
fn heights(p: &mut Prepared) -> Vec<(Id, Id)> {
    let Some(g) = gravity_sym(p) else {
        return Vec::new();
    };
    let Some((vg, _)) = gravity_part(p, g) else {
        return Vec::new();
    };
    let gv = p.system.pool.var(g, 0);
    let bodies = p.system.bodies.clone();
    for axis in 0..3 {
        let mut hs = Vec::new();
        for b in &bodies {
            if let Body::Point { mass, position } = b
                && let Some(&h) = position.get(axis)
            {
                hs.push((*mass, h));
            }
        }
        if hs.is_empty() {
            continue;
        }
        let terms: Vec<Id> = hs
            .iter()
            .map(|&(m, h)| p.system.pool.product([m, gv, h]))
            .collect();
        let sum = p.system.pool.sum(terms);
        if equal(p, sum, vg, true) {
            return hs;
        }
    }
    Vec::new()
}

/// The gravity part of V and the rest.
fn gravity_part(p: &mut Prepared, g: Sym) -> Option<(Id, Id)> {
    let v = p.system.potential?;
    let zero = p.system.pool.zero();
    let mut map = FxHashMap::default();
    map.insert((g, 0), zero);
    let rest = p.system.pool.substitute(v, &map);
    Some((p.system.pool.sub(v, rest), rest))
}

/// V with one body's height measured wrongly: from another, moving body; in the wrong
/// direction (with two or more moving masses); or as the product of its drops.
fn pe_geometry(p: &mut Prepared) -> Vec<Candidate<Id>> {
    let hs = heights(p);
    let (Some(g), Some(v)) = (gravity_sym(p), p.system.potential) else {
        return Vec::new();
    };
    let gv = p.system.pool.var(g, 0);
    let coords = p.system.coordinate_syms();
    let moves = |p: &Prepared, e: Id| {
        p.system
            .pool
            .variables(e)
            .iter()
            .any(|x| coords.contains(&x.0))
    };
    let moving = hs.iter().filter(|(_, h)| moves(p, *h)).count();
    let mut out = Vec::new();
    for (i, &(m, h)) in hs.iter().enumerate() {
        let name = p.system.pool.unicode(m);
        let mut alts: Vec<(Id, String)> = Vec::new();
        for &(mj, hj) in &hs[..i] {
            if moves(p, hj) {
                let nj = p.system.pool.unicode(mj);
                alts.push((
                    p.system.pool.sub(h, hj),
                    format!("potential-energy geometry: the height of {name} must be measured from one fixed level, but you measured it from {nj}, which moves; heights add along the chain"),
                ));
            }
        }
        if moving >= 2 && moves(p, h) {
            alts.push((
                p.system.pool.neg(h),
                format!("potential-energy geometry: gravity acts on each mass through its own height above one fixed level; the height of {name} is taken in the wrong direction — check which way {name} moves when the coordinate grows"),
            ));
        }
        let x = p.system.pool.expand(h);
        if let Node::Add(t) = p.system.pool.node(x) {
            let t = t.to_vec();
            let prod = p.system.pool.product(t);
            let message = format!(
                "potential-energy geometry: the height of {name} is the sum of the drops along the chain; you multiplied them instead of adding"
            );
            alts.push((prod, message.clone()));
            alts.push((p.system.pool.neg(prod), message));
        }
        for (h2, message) in alts {
            // V' = V + m·g·(h' − h).
            let dh = p.system.pool.sub(h2, h);
            let dv = p.system.pool.product([m, gv, dh]);
            let answer = p.system.pool.add(v, dv);
            out.push(Candidate::new(Code::PeGeometry, message, answer));
        }
    }
    out
}

//! Wrong list items generated from the physics: a frequency with the wrong inertia
//! (`effective-mass`), a frequency about another equilibrium (`expansion-point`), and
//! equilibria lost by dividing the equilibrium condition by a factor (`lost-root`).

use super::super::compare::{Sampled, equal_sampled};
use super::super::generated::{Candidate, Frequency};
use super::super::prepare::Prepared;
use super::super::verdict::{Code, Diagnosis};
use super::numeric::equal;
use crate::expr::{Func, Id, Node, read_expr};
use crate::mechanics::Body;
use crate::problem::{Part, PartKind, Problem};
use rustc_hash::FxHashMap;
use std::sync::Arc;

/// The first documented mistake a student's list follows.
pub fn diagnose(
    problem: &Problem,
    part: &Part,
    p: &mut Prepared,
    items: &[Vec<Id>],
) -> Option<Diagnosis> {
    let refs: Vec<Vec<Id>> = p.reference.get()?.clone();
    match part.kind {
        PartKind::Frequencies => frequency(problem, part, p, items, &refs),
        PartKind::Equilibria => super::roots::lost_root(p, items, &refs),
        _ => None,
    }
}

/// A student frequency that is no reference item but a generated wrong one. Each item, each
/// reference item and each generated frequency is evaluated at the sample points once, not
/// once per comparison.
fn frequency(
    problem: &Problem,
    part: &Part,
    p: &mut Prepared,
    items: &[Vec<Id>],
    refs: &[Vec<Id>],
) -> Option<Diagnosis> {
    let q0 = match &p.generated.at {
        Some(q0) => q0.clone(),
        None => {
            let q0: Option<Arc<[Id]>> = at_point(part, p).map(Into::into);
            p.generated.at = Some(q0.clone());
            q0
        }
    }?;
    // Single-value items and references, sampled (`None`: several values, or unevaluable).
    let single = |p: &Prepared, it: &[Id]| match it {
        &[s] => sample(p, s),
        _ => None,
    };
    let refs = match &p.generated.references {
        Some(r) => r.clone(),
        None => {
            let r: Arc<[Option<Sampled>]> = refs.iter().map(|r| single(p, r)).collect();
            p.generated.references = Some(r.clone());
            r
        }
    };
    let mine: Vec<Option<Sampled>> = items.iter().map(|it| single(p, it)).collect();
    // The wrong inertia replaces a right frequency; with every right one listed, an extra
    // item is a different slip, so effective-mass would mislead.
    let all_listed = refs
        .iter()
        .all(|r| mine.iter().any(|s| same(p, s.as_ref(), r.as_ref())));
    let effective = if all_listed {
        None
    } else {
        Some(match &p.generated.effective_mass {
            Some(c) => c.clone(),
            None => {
                let made = effective_mass(part, p, &q0);
                let c = sampled(part, p, made);
                p.generated.effective_mass = Some(c.clone());
                c
            }
        })
    };
    let expansion = match &p.generated.expansion_point {
        Some(c) => c.clone(),
        None => {
            let made = expansion_point(problem, p, &q0);
            let c = sampled(part, p, made);
            p.generated.expansion_point = Some(c.clone());
            c
        }
    };
    let cands = effective
        .iter()
        .flat_map(|c| c.iter())
        .chain(expansion.iter());
    let half = num_rational::BigRational::new(1.into(), 2.into());
    for (it, s) in items.iter().zip(&mine) {
        let &[id] = it.as_slice() else { continue };
        if refs.iter().any(|r| same(p, s.as_ref(), r.as_ref())) {
            continue;
        }
        // `√(x)` written out: its radicand, compared with ω² itself.
        let radicand = match p.system.pool.node(id) {
            Node::Pow(base, e) if matches!(p.system.pool.node(*e), Node::Num(h) if *h == half) => {
                Some(sample(p, *base))
            }
            _ => None,
        };
        if let Some(f) = cands
            .clone()
            .find(|f| follows(part, p, s.as_ref(), radicand.as_ref(), f))
        {
            return Some(f.candidate.diagnosis());
        }
    }
    None
}

/// `e` evaluated at the sample points; `None` where it cannot be.
fn sample(p: &Prepared, e: Id) -> Option<Sampled> {
    Sampled::of(&p.system, e, &p.points).ok()
}

/// Whether two sampled values are equal at the sample points ([`equal`]'s test).
fn same(p: &Prepared, a: Option<&Sampled>, b: Option<&Sampled>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => equal_sampled(a, b, p.tolerance),
        _ => false,
    }
}

/// The candidates sampled: each ω², and for a part asking for ω its square root.
fn sampled(part: &Part, p: &mut Prepared, cands: Vec<Candidate<Id>>) -> Arc<[Frequency]> {
    cands
        .into_iter()
        .map(|c| {
            let root = (!part.squared).then(|| p.system.pool.sqrt(c.answer));
            Frequency {
                squared: sample(p, c.answer),
                root: root.and_then(|w| sample(p, w)),
                candidate: c,
            }
        })
        .collect()
}

/// The part's `at` point, one value per coordinate.
fn at_point(part: &Part, p: &mut Prepared) -> Option<Vec<Id>> {
    let coords = p.system.coordinates.clone();
    coords
        .iter()
        .map(|c| {
            let (_, text) = part.at.iter().find(|(n, _)| *n == c.name)?;
            read_expr(text, &p.context, &mut p.system.pool).ok()
        })
        .collect()
}

/// M and K of the linearised equations about `q0`.
fn mass_and_stiffness(p: &mut Prepared, q0: &[Id]) -> (Vec<Vec<Id>>, Vec<Vec<Id>>) {
    let coords = p.system.coordinate_syms();
    let l = p.system.lagrangian;
    let zero = p.system.pool.zero();
    let mut rest = FxHashMap::default();
    for &c in &coords {
        rest.insert((c, 1), zero);
    }
    let l0 = p.system.pool.substitute(l, &rest);
    let mut at = rest.clone();
    for (&c, &v) in coords.iter().zip(q0) {
        at.insert((c, 0), v);
    }
    let (mut m, mut k) = (Vec::new(), Vec::new());
    for &a in &coords {
        let (mut mr, mut kr) = (Vec::new(), Vec::new());
        let la = p.system.pool.diff(l, a, 1);
        let l0a = p.system.pool.diff(l0, a, 0);
        for &b in &coords {
            let mab = p.system.pool.diff(la, b, 1);
            mr.push(p.system.pool.substitute(mab, &at));
            let kab = p.system.pool.diff(l0a, b, 0);
            let kab = p.system.pool.neg(kab);
            kr.push(p.system.pool.substitute(kab, &at));
        }
        m.push(mr);
        k.push(kr);
    }
    (m, k)
}

/// Whether the student's item `s` is the generated frequency `f` whose square is ω²: ω² itself
/// for a `squared` part; ω, or the square root of exactly ω² written out (`radicand`: about
/// an unstable point ω² < 0 and the root is undefined everywhere, yet it is the mistake),
/// otherwise.
fn follows(
    part: &Part,
    p: &Prepared,
    s: Option<&Sampled>,
    radicand: Option<&Option<Sampled>>,
    f: &Frequency,
) -> bool {
    if part.squared {
        return same(p, s, f.squared.as_ref());
    }
    same(p, s, f.root.as_ref()) || radicand.is_some_and(|r| same(p, r.as_ref(), f.squared.as_ref()))
}

/// ω² = `k/m` (compared with the student's items by [`follows`]).
fn item(p: &mut Prepared, k: Id, m: Id) -> Id {
    p.system.pool.div(k, m)
}

/// ω² = K/m with a body's mass (or the total mass) for the inertia (one coordinate); ω² =
/// Kᵢᵢ/Mᵢᵢ ignoring the coupling of the coordinates through M (several).
fn effective_mass(part: &Part, p: &mut Prepared, q0: &[Id]) -> Vec<Candidate<Id>> {
    let (m, k) = mass_and_stiffness(p, q0);
    let n = m.len();
    let mut out = Vec::new();
    if n == 1 {
        let masses = body_masses(part, p);
        let total = p.system.pool.sum(masses.clone());
        let cv = p.system.pool.var(p.system.coordinates[0].sym, 0);
        let name = p.system.pool.unicode(cv);
        let mut all = masses;
        if all.len() > 1 {
            all.push(total);
        }
        for mass in all {
            let shown = p.system.pool.unicode(mass);
            let c = item(p, k[0][0], mass);
            out.push(Candidate::new(
                Code::EffectiveMass,
                format!("effective mass: ω² is the stiffness divided by the inertia that multiplies the acceleration in the linearised equation (the coefficient of {name}̈, from T), not the mass {shown}"),
                c,
            ));
        }
        return out;
    }
    let coupled = (0..n).any(|i| (0..n).any(|j| i != j && !p.system.pool.is_zero(m[i][j])));
    if !coupled {
        return out;
    }
    for i in 0..n {
        if p.system.pool.is_zero(k[i][i]) {
            continue;
        }
        let cv = p.system.pool.var(p.system.coordinates[i].sym, 0);
        let name = p.system.pool.unicode(cv);
        let c = item(p, k[i][i], m[i][i]);
        out.push(Candidate::new(
            Code::EffectiveMass,
            format!("effective mass: the coordinates are coupled through the kinetic energy (the other bodies move too), so the inertia for {name} is not its own diagonal entry of M alone; solve det(K − ω²M) = 0 with the whole mass matrix"),
            c,
        ));
    }
    out
}

/// The masses of the point bodies, with the part's substitutions applied.
fn body_masses(part: &Part, p: &mut Prepared) -> Vec<Id> {
    let mut map = FxHashMap::default();
    for (name, text) in &part.substitute {
        let s = p
            .system
            .pool
            .symbol(&crate::expr::names::normalize(name.trim()));
        let Ok(v) = read_expr(text, &p.context, &mut p.system.pool) else {
            return Vec::new();
        };
        map.insert((s, 0), v);
    }
    let bodies = p.system.bodies.clone();
    bodies
        .iter()
        .filter_map(|b| match b {
            Body::Point { mass, .. } => Some(p.system.pool.substitute(*mass, &map)),
            Body::Rotor { .. } | Body::Rigid(_) => None,
        })
        .collect()
}

/// ω about another equilibrium (one coordinate): the top and bottom of an angle and the
/// problem's own stated equilibria, each checked to be one.
fn expansion_point(problem: &Problem, p: &mut Prepared, q0: &[Id]) -> Vec<Candidate<Id>> {
    let [q0] = q0 else { return Vec::new() };
    let coord = p.system.coordinates[0].clone();
    let mut points = Vec::new();
    if coord.periodic {
        points.push(p.system.pool.zero());
        points.push(p.system.pool.pi());
    }
    for eq in problem
        .parts
        .iter()
        .filter(|x| x.kind == PartKind::Equilibria)
    {
        for a in &eq.answers {
            let body = a.split_once('=').map_or(a.as_str(), |(_, r)| r);
            if let Ok(id) = read_expr(body, &p.context, &mut p.system.pool) {
                points.push(id);
            }
        }
    }
    let sym = coord.sym;
    let mut out = Vec::new();
    for pt in points {
        if same_point(p, coord.periodic, pt, *q0) || !is_equilibrium(p, sym, pt) {
            continue;
        }
        let (m, k) = mass_and_stiffness(p, &[pt]);
        let c = item(p, k[0][0], m[0][0]);
        let cv = p.system.pool.var(sym, 0);
        let (name, at) = (p.system.pool.unicode(cv), p.system.pool.unicode(pt));
        out.push(Candidate::new(
            Code::ExpansionPoint,
            format!("expansion point: that is the frequency of small oscillations about {name} = {at}, another equilibrium; linearise about the equilibrium the question asks for"),
            c,
        ));
    }
    out
}

/// Whether two angles (or values) are the same point at every sample.
fn same_point(p: &mut Prepared, periodic: bool, a: Id, b: Id) -> bool {
    if !periodic {
        return equal(p, a, b, false);
    }
    let d = p.system.pool.sub(a, b);
    let c = p.system.pool.func(Func::Cos, d);
    let one = p.system.pool.one();
    equal(p, c, one, false)
}

/// Whether ∂L/∂q vanishes at rest at q = `pt` at every sample point (relative to its terms).
fn is_equilibrium(p: &mut Prepared, sym: crate::expr::Sym, pt: Id) -> bool {
    let zero = p.system.pool.zero();
    let mut map = FxHashMap::default();
    map.insert((sym, 1), zero);
    map.insert((sym, 2), zero);
    map.insert((sym, 0), pt);
    let l = p.system.lagrangian;
    let f = p.system.pool.diff(l, sym, 0);
    let f = p.system.pool.substitute(f, &map);
    equal(p, f, zero, false)
}

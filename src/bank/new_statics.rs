//! The equilibria and frequencies parts of a drafted problem (`problems new`), stated only in
//! closed form: each coordinate of each equilibrium is 0 (π, ±π/2 for an angle), free (`any`),
//! or the root of a force at rest linear in that coordinate alone (a hanging spring's m g/k).
//! The engine's numeric search is run at generic parameter values and at every corner of the
//! parameters' ranges, and the points must be the same closed forms with the same stability at
//! all of them: equilibria that appear in one regime only (the rotating hoop's side points,
//! when R ω² > g) are left out with the reason, for the instructor to state with an `assume`.

use rustc_hash::FxHashMap;

use super::new_types::{Candidate, Field, LeftOut, Widened};
use crate::expr::eval::eval_tree;
use crate::expr::{Id, Sym};
use crate::mechanics::equilibria::Stability;
use crate::mechanics::{Derivation, System};

/// Corners of the parameters' ranges searched at most (beyond 6 parameters, the corners of the
/// first 6, the others at generic values).
const MAX_CORNERS: usize = 64;

/// An equilibrium as one closed form per coordinate (`None`: free), with its stability.
type Point = (Vec<Option<Id>>, Stability);

/// Adds the equilibria and frequencies parts to `parts`, or says in `left` why not; returns
/// the coordinate ranges widened to hold the stated points.
pub(super) fn statics(
    sys: &mut System,
    d: &Derivation,
    parts: &mut Vec<Candidate>,
    left: &mut Vec<LeftOut>,
) -> Vec<Widened> {
    let mut leave = |reason: String| {
        for part in ["equilibria", "frequencies"] {
            left.push(LeftOut {
                part: part.into(),
                reason: reason.clone(),
            });
        }
    };
    let closed = closed_forms(sys, d);
    let widened = widen(sys, &closed);
    for &(i, r) in &widened {
        sys.coordinates[i].range = r;
    }
    let mut reference: Option<(Vec<f64>, Vec<Point>)> = None;
    for values in samples(sys) {
        let points = match points_at(sys, d, &closed, &values) {
            Ok(p) => p,
            Err(why) => {
                leave(why);
                return Vec::new();
            }
        };
        match &reference {
            None => reference = Some((values, points)),
            Some((first, r)) if *r != points => {
                leave(format!(
                    "the equilibria change with the parameters ({} at {}, {} at {}): state those of one regime by hand, with an `assume`",
                    r.len(),
                    shown(sys, first),
                    points.len(),
                    shown(sys, &values)
                ));
                return Vec::new();
            }
            Some(_) => {}
        }
    }
    let Some((_, points)) = reference else {
        return widened;
    };
    equilibria_part(sys, &points, parts);
    frequencies_part(sys, d, &points, parts, left);
    widened
}

/// The equilibria at parameter values `values`, each recognised as closed forms, sorted; or
/// why they cannot be stated.
fn points_at(
    sys: &mut System,
    d: &Derivation,
    closed: &[Vec<Id>],
    values: &[f64],
) -> Result<Vec<Point>, String> {
    let found = sys.equilibria(d, values).map_err(|e| e.to_string())?;
    if found.continuum {
        return Err(format!(
            "the equilibria form a continuum (every point of a region) at {}, which no list states",
            shown(sys, values)
        ));
    }
    let value_of: FxHashMap<Sym, f64> = sys
        .parameters
        .iter()
        .zip(values)
        .map(|(p, v)| (p.sym, *v))
        .collect();
    let at = |e: Id| {
        eval_tree(&sys.pool, e, &|s, _| {
            value_of.get(&s).copied().unwrap_or(0.0)
        })
    };
    let mut points = Vec::with_capacity(found.points.len());
    for ((q, st), shape) in found.points.iter().zip(&found.shapes) {
        let mut point = Vec::with_capacity(q.len());
        for (i, &qi) in q.iter().enumerate() {
            if shape.coordinate_free(i) {
                point.push(None);
                continue;
            }
            let periodic = sys.coordinates[i].periodic;
            let hit = closed[i].iter().copied().find(|&c| {
                let v = at(c);
                let mut diff = (qi - v).abs();
                if periodic {
                    diff = diff.rem_euclid(std::f64::consts::TAU);
                    diff = diff.min(std::f64::consts::TAU - diff);
                }
                diff <= 1e-6 * v.abs().max(1.0)
            });
            let Some(c) = hit else {
                let name = &sys.coordinates[i].name;
                return Err(format!(
                    "an equilibrium has {name} ≈ {qi:.6} at {}, not 0, ±π/2, π or the root of a force linear in {name}: no closed form is found, so state the equilibria by hand",
                    shown(sys, values)
                ));
            };
            point.push(Some(c));
        }
        points.push((point, *st));
    }
    points.sort_by_key(|(p, _)| p.clone());
    Ok(points)
}

/// "m = 1, g = 9.81": parameter values for a message.
fn shown(sys: &System, values: &[f64]) -> String {
    let pairs: Vec<String> = sys
        .parameters
        .iter()
        .zip(values)
        .map(|(p, v)| format!("{} = {}", p.name, (v * 1e4).round() / 1e4))
        .collect();
    if pairs.is_empty() {
        "every parameter value".into()
    } else {
        pairs.join(", ")
    }
}

/// Generic parameter values (each at an irrational fraction of its range, so that no two
/// masses are equal by accident: an Atwood machine with m1 = m2 is in equilibrium everywhere),
/// then (near) the corners of the ranges. A statement holds for generic values: a coincidence
/// of measure zero (m1 = m2 exactly) is not the problem's.
fn samples(sys: &System) -> Vec<Vec<f64>> {
    let params = &sys.parameters;
    let generic: Vec<f64> = params
        .iter()
        .enumerate()
        .map(|(j, p)| {
            let f = (0.618_033_988_75 * (j as f64 + 1.0)).fract();
            p.range.0 + f * (p.range.1 - p.range.0)
        })
        .collect();
    let k = params.len().min(MAX_CORNERS.trailing_zeros() as usize);
    let mut out = vec![generic.clone()];
    for corner in 0..(1usize << k) {
        let mut v = generic.clone();
        for (j, x) in v.iter_mut().enumerate().take(k) {
            // Just inside each corner, by a different fraction for each parameter: at the
            // corner itself two masses of one range would be equal.
            let (lo, hi) = params[j].range;
            let inset = (0.01 + 0.007 * j as f64) * (hi - lo);
            *x = if (corner >> j) & 1 == 1 {
                hi - inset
            } else {
                lo + inset
            };
        }
        out.push(v);
    }
    out
}

/// The `equations` of equilibria: `theta = pi`, `x = any, s = 0`; `none` without any.
fn text(sys: &System, point: &[Option<Id>], free: &str) -> Vec<(String, String)> {
    point
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let v = c.map_or(free.to_string(), |c| sys.pool.plain(c));
            (sys.coordinates[i].name.clone(), v)
        })
        .collect()
}

/// The equilibria part: the points with their stability (required), or `none`.
fn equilibria_part(sys: &System, points: &[Point], parts: &mut Vec<Candidate>) {
    let hints = [
        "At an equilibrium the velocities and accelerations vanish: every ∂L/∂q (with the generalized forces) is zero.",
        "An equilibrium is stable where the potential is a minimum: every ω² of the small oscillations is positive.",
    ];
    if points.is_empty() {
        parts.push(Candidate::one(
            "equilibria",
            "equilibria",
            "Find every equilibrium (answer `none` if there is none).",
            "none".into(),
            &hints[..1],
        ));
        return;
    }
    let answer = points
        .iter()
        .map(|(p, _)| {
            text(sys, p, "any")
                .iter()
                .map(|(n, v)| format!("{n} = {v}"))
                .collect::<Vec<_>>()
                .join(", ")
        })
        .collect();
    let stability = points.iter().map(|(_, s)| s.name().to_string()).collect();
    let mut eq = Candidate::one(
        "equilibria",
        "equilibria",
        "Find every equilibrium and say whether it is stable.",
        String::new(),
        &hints,
    )
    .with("stability", Field::Strs(stability))
    .with("require_stability", Field::Bool(true));
    eq.answer = answer;
    eq.many = true;
    parts.push(eq);
}

/// The frequencies part about the first stable equilibrium, in closed form.
fn frequencies_part(
    sys: &mut System,
    d: &Derivation,
    points: &[Point],
    parts: &mut Vec<Candidate>,
    left: &mut Vec<LeftOut>,
) {
    let mut leave = |reason: &str| {
        left.push(LeftOut {
            part: "frequencies".into(),
            reason: reason.to_string(),
        })
    };
    let Some((point, _)) = points.iter().find(|(_, s)| *s == Stability::Stable) else {
        leave("no equilibrium is stable: there are no small oscillations to state");
        return;
    };
    let zero = sys.pool.zero();
    let ids: Vec<Id> = point.iter().map(|c| c.unwrap_or(zero)).collect();
    let m = match sys.symbolic_modes(d, &ids) {
        Ok(m) => m,
        Err(e) => return leave(&e.to_string()),
    };
    if m.omega_squared.is_empty() {
        return leave(
            "the characteristic polynomial does not factor into pieces of degree ≤ 2 in ω²: no closed form",
        );
    }
    let omegas = m
        .omega_squared
        .iter()
        .map(|&w2| {
            if sys.is_zero(w2) {
                "0".to_string()
            } else {
                // √(ω²) as written, `sqrt(g/l)`, reads better than the simplifier's √g/√l.
                format!("sqrt({})", sys.pool.plain(w2))
            }
        })
        .collect();
    let at = text(sys, point, "0");
    let shown: Vec<String> = at.iter().map(|(n, v)| format!("{n} = {v}")).collect();
    let mut f = Candidate::one(
        "frequencies",
        "frequencies",
        &format!(
            "Find the angular frequencies of small oscillations about {}.",
            shown.join(", ")
        ),
        String::new(),
        &[
            "Expand about the equilibrium: T with the mass matrix there, V to second order.",
            "Solve det(K − ω² M) = 0 for ω²; a free coordinate gives ω = 0.",
        ],
    )
    .with("at", Field::Map(at));
    f.answer = omegas;
    f.many = true;
    parts.push(f);
}

/// Closed-form candidates for each coordinate at an equilibrium: 0 (and π, ±π/2 for an
/// angle), and the root of the force at rest when it is linear in that coordinate alone.
fn closed_forms(sys: &mut System, d: &Derivation) -> Vec<Vec<Id>> {
    let coords: Vec<Sym> = sys.coordinates.iter().map(|c| c.sym).collect();
    let zero = sys.pool.zero();
    let at_rest: FxHashMap<_, _> = coords
        .iter()
        .flat_map(|&c| [((c, 1), zero), ((c, 2), zero)])
        .collect();
    let mut out = Vec::with_capacity(coords.len());
    for (i, &c) in coords.iter().enumerate() {
        let mut list = vec![zero];
        if sys.coordinates[i].periodic {
            let pi = sys.pool.pi();
            let half = sys.pool.ratio(1, 2);
            let half_pi = sys.pool.product([half, pi]);
            let minus_half_pi = sys.pool.neg(half_pi);
            list.extend([pi, half_pi, minus_half_pi]);
        }
        let g = sys.pool.substitute(d.forcing[i], &at_rest);
        let only_this = sys
            .pool
            .variables(g)
            .iter()
            .all(|(s, _)| *s == c || !coords.contains(s));
        let b = sys.pool.diff(g, c, 0);
        let b = sys.simplify(b);
        let b2 = sys.pool.diff(b, c, 0);
        if only_this && !sys.is_zero(b) && sys.is_zero(b2) {
            let at_zero: FxHashMap<_, _> = [((c, 0), zero)].into_iter().collect();
            let a = sys.pool.substitute(g, &at_zero);
            let r = sys.pool.div(a, b);
            let r = sys.pool.neg(r);
            let r = sys.simplify(r);
            if !list.contains(&r) {
                list.push(r);
            }
        }
        out.push(list);
    }
    out
}

/// For each coordinate that is not an angle, a range wide enough to hold its closed-form
/// candidates at every corner of the parameters' ranges (the search, here and in the
/// verifier, looks for equilibria inside the range), when the default is not.
fn widen(sys: &System, closed: &[Vec<Id>]) -> Vec<Widened> {
    let corners = samples(sys);
    let mut out = Vec::new();
    for (i, list) in closed.iter().enumerate() {
        if sys.coordinates[i].periodic {
            continue;
        }
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for &c in list {
            for values in &corners {
                let value = |s: Sym, _: u8| {
                    sys.parameters
                        .iter()
                        .position(|p| p.sym == s)
                        .map_or(0.0, |j| values[j])
                };
                let v = eval_tree(&sys.pool, c, &value);
                if v.is_finite() {
                    lo = lo.min(v);
                    hi = hi.max(v);
                }
            }
        }
        let (dlo, dhi) = sys.coordinates[i].range;
        if lo < dlo || hi > dhi {
            let margin = 1.0 + 0.25 * (hi - lo);
            let r = (
                ((lo - margin).min(dlo)).floor(),
                ((hi + margin).max(dhi)).ceil(),
            );
            out.push((i, r));
        }
    }
    out
}

//! Laws every bank and corpus problem obeys, in both directions (issue 19's quality bar):
//! the equations of motion scaled row by row by the mass matrix's diagonal (a factor that
//! vanishes only where that direction is singular: m r² on Kepler's φ equation) are right;
//! times a velocity, or times a factor vanishing at a regular state, they are wrong; L plus a
//! total time derivative dF(q, t)/dt, and h plus a constant, are right.

use lagrange::expr::{Id, Pool, Sym};
use lagrange::problem::{PartKind, Problem, Quantity};
use lagrange::{Checker, Code, Status};
use rustc_hash::FxHashMap;

/// The built-in problems and the corpus's systems written from the docs alone.
fn problems() -> Vec<Problem> {
    let mut out = lagrange::bank::embedded::bank().problems;
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/corpus/problems");
    out.extend(
        lagrange::bank::load_dir(&dir)
            .expect("corpus problems")
            .problems,
    );
    out
}

/// The problem's Euler–Lagrange equations, each row as plain text, with its mass matrix's
/// diagonal; None for a system with constraints or forces (its equations are not M q̈ = f of
/// L alone) or one that does not derive.
fn equations(p: &Problem) -> Option<(Vec<String>, Vec<String>)> {
    if !p.system.constraints.is_empty() {
        return None;
    }
    let mut sys = p.system.clone();
    if sys.forces.iter().any(|&f| !sys.pool.is_zero(f)) {
        return None;
    }
    let d = sys.derive().ok()?;
    let rows = d.equations().iter().map(|&e| sys.pool.plain(e)).collect();
    let diag = (0..d.mass.len())
        .map(|i| sys.pool.plain(d.mass[i][i]))
        .collect();
    Some((rows, diag))
}

/// The id of the problem's `equations` part asking for the full equations, if it has one: not
/// a linearized part (`about`, whose answer is the equations expanded to first order) nor a
/// numeric one (`values`), which these laws do not describe.
fn equations_part(p: &Problem) -> Option<&str> {
    p.parts
        .iter()
        .find(|part| {
            part.kind == PartKind::Equations
                && part.substitute.is_empty()
                && part.about.is_none()
                && part.units.is_none()
        })
        .map(|part| part.id.as_str())
}

fn join(rows: &[String]) -> String {
    rows.iter()
        .map(|r| format!("{r} = 0"))
        .collect::<Vec<_>>()
        .join("; ")
}

#[test]
fn equations_scaled_by_the_mass_diagonal_are_right() {
    let mut tried = 0;
    let mut wrong = Vec::new();
    for p in problems() {
        let (Some(part), Some((rows, diag))) = (equations_part(&p), equations(&p)) else {
            continue;
        };
        let mut checker = Checker::new(&p);
        let scaled: Vec<String> = rows
            .iter()
            .zip(&diag)
            .map(|(r, m)| format!("({m})*({r})"))
            .collect();
        for answer in [join(&rows), join(&scaled)] {
            tried += 1;
            let v = checker.check(part, &answer).expect("checks");
            if v.status != Status::Correct {
                wrong.push(format!("{}/{part}: {answer}\n    {:?}", p.id, v.diagnoses));
            }
        }
    }
    assert!(tried >= 10, "only {tried} systems");
    assert!(wrong.is_empty(), "refused:\n{}", wrong.join("\n"));
}

#[test]
fn equations_times_a_velocity_or_a_regular_zero_are_wrong() {
    let mut tried = 0;
    let mut missed = Vec::new();
    for p in problems() {
        let (Some(part), Some((rows, _))) = (equations_part(&p), equations(&p)) else {
            continue;
        };
        let mut checker = Checker::new(&p);
        for (i, c) in p.system.coordinates.iter().enumerate() {
            // A velocity, and a factor of the coordinate that vanishes at a generic state
            // (0.3 ± π/2 for an angle, the middle of the sampled range otherwise), where every
            // one of these systems is regular.
            let mid = 0.5 * (c.range.0 + c.range.1) + 0.1234;
            let factors = [
                format!("{}'", c.name),
                if c.periodic {
                    format!("cos({} - 0.3)", c.name)
                } else {
                    format!("({} - {mid})", c.name)
                },
            ];
            for f in factors {
                let mut bad = rows.clone();
                bad[i] = format!("({f})*({})", rows[i]);
                let answer = join(&bad);
                tried += 1;
                let v = checker.check(part, &answer).expect("checks");
                let named = v.diagnoses.iter().any(|d| d.code == Code::VanishingFactor);
                if v.status != Status::Incorrect || !named {
                    missed.push(format!("{}/{part}: {answer}\n    {:?}", p.id, v.diagnoses));
                }
            }
        }
    }
    assert!(tried >= 30, "only {tried} cases");
    assert!(missed.is_empty(), "not refused:\n{}", missed.join("\n"));
}

/// `e` with every velocity and acceleration set to 0: a function of the coordinates and t.
fn at_rest(pool: &mut Pool, e: Id, coords: &[Sym]) -> Id {
    let zero = pool.zero();
    let mut map: FxHashMap<(Sym, u8), Id> = FxHashMap::default();
    for &c in coords {
        map.insert((c, 1), zero);
        map.insert((c, 2), zero);
    }
    pool.substitute(e, &map)
}

#[test]
fn a_total_time_derivative_and_a_constant_change_nothing() {
    let mut tried = 0;
    let mut wrong = Vec::new();
    for p in problems() {
        let mut sys = p.system.clone();
        let coords: Vec<Sym> = sys.coordinates.iter().map(|c| c.sym).collect();
        let mut checker = Checker::new(&p);
        for part in &p.parts {
            if !part.substitute.is_empty() {
                continue;
            }
            let Some(reference) = part.answers.first() else {
                continue;
            };
            let answer = match (part.kind, part.quantity) {
                // F = t·L(q, 0, t): energy times time, so dF/dt is an energy.
                (PartKind::Lagrangian, _) => {
                    let rest = at_rest(&mut sys.pool, sys.lagrangian, &coords);
                    if sys.pool.is_zero(rest) {
                        continue;
                    }
                    format!("{reference} + d/dt(t*({}))", sys.pool.plain(rest))
                }
                // A constant of the dimension of energy: L at rest with every coordinate and t
                // at 0 (0 keeps every dimension; skipped where that is 0 or undefined).
                (PartKind::Expression, Quantity::EnergyFunction) => {
                    let rest = at_rest(&mut sys.pool, sys.lagrangian, &coords);
                    let zero = sys.pool.zero();
                    let mut map: FxHashMap<(Sym, u8), Id> = FxHashMap::default();
                    for &c in &coords {
                        map.insert((c, 0), zero);
                    }
                    map.insert((sys.pool.time(), 0), zero);
                    let c = sys.pool.substitute(rest, &map);
                    let text = sys.pool.plain(c);
                    if sys.pool.is_zero(c) || text.contains("undefined") || text.contains("/0") {
                        continue;
                    }
                    format!("{reference} + 3*({})", sys.pool.plain(c))
                }
                _ => continue,
            };
            tried += 1;
            let v = checker.check(&part.id, &answer).expect("checks");
            if v.status != Status::Correct {
                wrong.push(format!(
                    "{}/{}: {answer}\n    {:?}",
                    p.id, part.id, v.diagnoses
                ));
            }
        }
    }
    assert!(tried >= 20, "only {tried} cases");
    assert!(wrong.is_empty(), "refused:\n{}", wrong.join("\n"));
}

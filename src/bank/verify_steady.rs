//! Verification of steady-motion parts: the coordinates `at` names stay put at the stated
//! values while the one it leaves out (which must be cyclic) moves uniformly at the stated
//! rate; every equation of motion must then hold, at parameter samples that respect the
//! problem's assumptions.

use super::FindingCode;
use rustc_hash::FxHashMap;

use super::verify_failed::{Check, Failed, check_dimension};
use crate::check::compare::{parameter_text, values};
use crate::check::points::PointSet;
use crate::check::prepare::{Prepared, equilibrium_of, read_one};
use crate::expr::{Dimension, Id};
use crate::mechanics::sample::seed_from;
use crate::problem::{Part, Problem};

/// Parameter samples for a steady motion.
const STEADY_SAMPLES: usize = 20;

/// An equation counts as satisfied when its residual is this fraction of the size of its
/// parts (the forces at rest and what the motion adds to them).
const STEADY_TOLERANCE: f64 = 1e-9;

pub(super) fn verify_steady(problem: &Problem, part: &Part, p: &mut Prepared) -> Check {
    // With constraints the forcing alone is not the equation of motion (the multipliers'
    // forces are missing from it): the check below would prove nothing.
    if !p.system.constraints.is_empty() {
        return Err(Failed::new(
            FindingCode::Unprovable,
            "a steady-motion part is proved for systems without constraints: write the system in independent coordinates".into(),
        ));
    }
    let c = moving_coordinate(part, p)?;
    let name = p.system.coordinates[c].name.clone();
    if !p.system.is_zero(p.derivation.steps[c].force) || !p.system.is_zero(p.system.forces[c]) {
        return Err(Failed::new(
            FindingCode::NotCyclic,
            format!(
                "{name} is not cyclic (L depends on it, or a force acts on it): it cannot move uniformly while the others stay put"
            ),
        ));
    }
    let stated = read_one(p, &part.answers[0])?;
    if p.system.coordinates[c].periodic {
        let want = Dimension::new(0, 0, if part.squared { -2 } else { -1 });
        check_dimension(problem, p, stated, Some(want))?;
    }
    let rate = if part.squared {
        p.system.pool.sqrt(stated)
    } else {
        stated
    };
    let at = equilibrium_of(p, part)?;
    let moving = residuals(p, &at, c, rate);
    let zero = p.system.pool.zero();
    let still = residuals(p, &at, c, zero);
    let samples = PointSet::draw(
        &p.system,
        &p.assumptions,
        seed_from(&[&problem.id, &part.id, "steady"]),
        STEADY_SAMPLES,
    )
    .map_err(|e| Failed::new(FindingCode::Sampling, e.to_string()))?;
    let roots: Vec<Id> = moving.iter().chain(&still).copied().collect();
    let vals = values(&p.system, &roots, &samples)
        .map_err(|e| Failed::new(FindingCode::Sampling, e.to_string()))?;
    let n = moving.len();
    let mut defined = 0;
    for (k, v) in vals.iter().enumerate() {
        let Some(v) = v else { continue };
        if v.iter().any(|x| !x.is_finite()) {
            continue;
        }
        defined += 1;
        for i in 0..n {
            let scale = v[n + i].abs().max((v[i] - v[n + i]).abs());
            if v[i].abs() > STEADY_TOLERANCE * scale {
                let params = samples.params(&p.system, k).to_vec();
                return Err(Failed::new(
                    FindingCode::NotSteady,
                    format!(
                        "for {} the equation of {} does not hold in the stated steady motion (residual {:.3e})",
                        parameter_text(&p.system, &params),
                        p.system.coordinates[i].name,
                        v[i]
                    ),
                ));
            }
        }
    }
    if defined == 0 {
        return Err(Failed::new(
            FindingCode::Sampling,
            "the stated steady motion is undefined at every parameter sample".into(),
        ));
    }
    Ok(())
}

/// The one coordinate `at` leaves out: the one that moves.
fn moving_coordinate(part: &Part, p: &Prepared) -> Result<usize, Failed> {
    let named = |c: &str| {
        part.at
            .iter()
            .any(|(k, _)| crate::expr::names::normalize(k.trim()) == c)
    };
    let free: Vec<usize> = (0..p.system.n())
        .filter(|&i| !named(&p.system.coordinates[i].name))
        .collect();
    match free[..] {
        [c] => Ok(c),
        _ => Err(Failed::new(
            FindingCode::BadSteady,
            format!(
                "a steady-motion part gives in `at` every coordinate but the one that moves; here {} are left out",
                free.len()
            ),
        )),
    }
}

/// The forcing f of M q'' = f with the other coordinates at `at`, at rest, and coordinate
/// `c` moving at `rate` (no accelerations: in a steady motion M q'' = 0).
fn residuals(p: &mut Prepared, at: &[Id], c: usize, rate: Id) -> Vec<Id> {
    let zero = p.system.pool.zero();
    let mut map: FxHashMap<_, _> = FxHashMap::default();
    for (j, coord) in p.system.coordinates.iter().enumerate() {
        if j != c {
            map.insert((coord.sym, 0), at[j]);
        }
        map.insert((coord.sym, 1), if j == c { rate } else { zero });
        map.insert((coord.sym, 2), zero);
    }
    p.derivation
        .forcing
        .clone()
        .iter()
        .map(|&f| p.system.pool.substitute(f, &map))
        .collect()
}

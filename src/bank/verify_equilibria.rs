//! Verification of equilibria parts: each stated point is an equilibrium with the right
//! dimensions, none is listed twice, and for every parameter sample the engine finds none
//! missing, none spurious and the stated stabilities.

use super::verify_failed::{Check, Failed, check_dimension};
use crate::check::compare::{fmt_value, parameter_text, values};
use crate::check::points::PointSet;
use crate::check::prepare::{Prepared, read_point, same_coordinate};
use crate::check::tolerance;
use crate::expr::Id;
use crate::mechanics::sample::seed_from;
use crate::problem::{Part, Problem};

/// Parameter samples for equilibria (each runs a multi-start search).
const EQUILIBRIUM_SAMPLES: usize = 6;

/// What comparing the stated equilibria with the engine's, for one parameter sample, found.
enum EquilibriumFinding {
    /// Every point is an equilibrium.
    Continuum,
    /// The engine finds an equilibrium at `at` that the answer lacks.
    Missing { at: String },
    /// Stated item `item` has stability `want` but is `is`.
    Stability {
        item: String,
        want: String,
        is: &'static str,
    },
    /// Stated item `item` is not among the engine's equilibria.
    Spurious { item: String },
}

impl EquilibriumFinding {
    /// The finding as a failed verification, for the parameters `pstr`.
    fn details(self, pstr: &str) -> Failed {
        match self {
            EquilibriumFinding::Continuum => Failed::new(
                "not-isolated",
                format!(
                    "for {pstr} every point is an equilibrium; restrict the parameters with `assume`"
                ),
            ),
            EquilibriumFinding::Missing { at } => Failed::new(
                "missing-equilibrium",
                format!(
                    "the physics also has an equilibrium at {at} (for {pstr}), which the answer does not list"
                ),
            ),
            EquilibriumFinding::Stability { item, want, is } => Failed::new(
                "wrong-stability",
                format!("`{item}` is stated {want}, but it is {is} (for {pstr})"),
            ),
            EquilibriumFinding::Spurious { item } => Failed::new(
                "spurious-equilibrium",
                format!("`{item}` is not among the equilibria the engine finds for {pstr}"),
            ),
        }
    }
}

/// Reads the stated equilibria and checks each one's dimensions, that the forces vanish
/// there, and that the stabilities are as many as the equilibria.
fn stated_equilibria(
    problem: &Problem,
    part: &Part,
    p: &mut Prepared,
) -> Result<Vec<Vec<Id>>, Failed> {
    let stated: Vec<Vec<Id>> = part
        .answers
        .iter()
        .map(|a| read_point(p, a))
        .collect::<Result<_, _>>()?;
    for (item, point) in part.answers.iter().zip(&stated) {
        for (i, &v) in point.iter().enumerate() {
            let want = problem.dims.get(&p.system.coordinates[i].name);
            check_dimension(problem, p, v, want)?;
        }
        if !p
            .system
            .verify_equilibrium(&p.derivation, point)
            .map_err(|e| Failed::new("unusable", e.to_string()))?
        {
            return Err(Failed::new(
                "spurious-equilibrium",
                format!(
                    "`{item}` is not an equilibrium: the generalized forces do not vanish there"
                ),
            ));
        }
    }
    if !part.stability.is_empty() && part.stability.len() != stated.len() {
        return Err(Failed::new(
            "bad-stability",
            format!(
                "{} stabilities for {} equilibria",
                part.stability.len(),
                stated.len()
            ),
        ));
    }
    Ok(stated)
}

/// Compares the stated equilibria (values `stated_pts`) with those the engine finds for
/// `params`.
fn compare_equilibria(
    part: &Part,
    p: &mut Prepared,
    params: &[f64],
    stated_pts: &[&[f64]],
) -> Result<Option<EquilibriumFinding>, Failed> {
    let found = p
        .system
        .equilibria(&p.derivation, params)
        .map_err(|e| Failed::new("unusable", e.to_string()))?;
    if found.continuum {
        return Ok(Some(EquilibriumFinding::Continuum));
    }
    let coords = p.system.coordinates.clone();
    let same = |s: &[f64], q: &[f64]| {
        s.iter()
            .zip(q)
            .enumerate()
            .all(|(i, (a, b))| same_coordinate(coords[i].periodic, *a, *b))
    };
    for (q, st) in &found.points {
        match stated_pts.iter().position(|s| same(s, q)) {
            None => {
                let at = coords
                    .iter()
                    .zip(q)
                    .map(|(c, x)| format!("{} = {}", c.name, fmt_value(*x)))
                    .collect::<Vec<_>>()
                    .join(", ");
                return Ok(Some(EquilibriumFinding::Missing { at }));
            }
            Some(j) => {
                // The full linearization (velocity terms included), as `modes` reports it.
                let st = p
                    .system
                    .modes_at(&p.derivation, params, q)
                    .map_or(*st, |m| m.stability);
                if let Some(want) = part.stability.get(j)
                    && want != st.name()
                {
                    return Ok(Some(EquilibriumFinding::Stability {
                        item: part.answers[j].clone(),
                        want: want.clone(),
                        is: st.name(),
                    }));
                }
            }
        }
    }
    let in_range = |q: &[f64]| {
        q.iter().enumerate().all(|(i, x)| {
            coords[i].periodic
                || (coords[i].range.0 - tolerance::RANGE_SLACK
                    ..=coords[i].range.1 + tolerance::RANGE_SLACK)
                    .contains(x)
        })
    };
    Ok(stated_pts
        .iter()
        .position(|s| in_range(s) && !found.points.iter().any(|(q, _)| same(s, q)))
        .map(|j| EquilibriumFinding::Spurious {
            item: part.answers[j].clone(),
        }))
}

pub(super) fn verify_equilibria(problem: &Problem, part: &Part, p: &mut Prepared) -> Check {
    let stated = stated_equilibria(problem, part, p)?;
    let samples = PointSet::draw(
        &p.system,
        &p.assumptions,
        seed_from(&[&problem.id, &part.id, "equilibria"]),
        EQUILIBRIUM_SAMPLES,
    )
    .map_err(|e| Failed::new("sampling", e.to_string()))?;
    let flat: Vec<Id> = stated.iter().flatten().copied().collect();
    let vals =
        values(&p.system, &flat, &samples).map_err(|e| Failed::new("sampling", e.to_string()))?;
    let n = p.system.n();
    for (k, v) in vals.iter().enumerate() {
        let Some(v) = v else { continue };
        let params = samples.params(&p.system, k).to_vec();
        let stated_pts: Vec<&[f64]> = v.chunks(n).collect();
        if let Some(f) = repeated_equilibrium(part, p, &stated_pts) {
            return Err(f);
        }
        if let Some(f) = compare_equilibria(part, p, &params, &stated_pts)? {
            return Err(f.details(&parameter_text(&p.system, &params)));
        }
    }
    Ok(())
}

/// Two stated equilibria that are the same point (θ = π and θ = −π for a periodic θ): a
/// student listing each point once would be graded as missing one.
fn repeated_equilibrium(part: &Part, p: &Prepared, stated_pts: &[&[f64]]) -> Option<Failed> {
    let coords = &p.system.coordinates;
    for (i, a) in stated_pts.iter().enumerate() {
        for (j, b) in stated_pts.iter().enumerate().skip(i + 1) {
            let same = a
                .iter()
                .zip(b.iter())
                .enumerate()
                .all(|(c, (x, y))| same_coordinate(coords[c].periodic, *x, *y));
            if same {
                return Some(Failed::new(
                    "duplicate-equilibrium",
                    format!(
                        "`{}` and `{}` are the same equilibrium (an angle is periodic): list each point once",
                        part.answers[i], part.answers[j]
                    ),
                ));
            }
        }
    }
    None
}

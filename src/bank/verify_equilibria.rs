//! Verification of equilibria parts: each stated point is an equilibrium with the right
//! dimensions, none is listed twice, and for every parameter sample the engine finds none
//! missing, none spurious and the stated stabilities.

use super::FindingCode;
use super::verify_failed::{Check, Failed, check_dimension};
use crate::check::compare::{fmt_value, parameter_text, values};
use crate::check::points::PointSet;
use crate::check::prepare::{Prepared, read_point_any, same_coordinate};
use crate::check::tolerance;
use crate::expr::Id;
use crate::mechanics::Coordinate;
use crate::mechanics::equilibria::{Equilibria, Shape};
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
    /// Stated item `item` is one of a continuum along `coordinate`, stated as a point.
    NotIsolated { item: String, coordinate: String },
    /// The engine finds a continuum along a direction that is not one coordinate (a free
    /// chain's translation), which an answer cannot state point by point.
    Family { at: String, direction: String },
}

impl EquilibriumFinding {
    /// The finding as a failed verification, for the parameters `pstr`.
    fn details(self, pstr: &str) -> Failed {
        match self {
            EquilibriumFinding::Continuum => Failed::new(
                FindingCode::NotIsolated,
                format!(
                    "for {pstr} every point is an equilibrium; restrict the parameters with `assume`"
                ),
            ),
            EquilibriumFinding::Missing { at } => Failed::new(
                FindingCode::MissingEquilibrium,
                format!(
                    "the physics also has an equilibrium at {at} (for {pstr}), which the answer does not list"
                ),
            ),
            EquilibriumFinding::Stability { item, want, is } => Failed::new(
                FindingCode::WrongStability,
                format!("`{item}` is stated {want}, but it is {is} (for {pstr})"),
            ),
            EquilibriumFinding::NotIsolated { item, coordinate } => Failed::new(
                FindingCode::NotIsolated,
                format!(
                    "`{item}` is one of a continuum of equilibria (for {pstr}): {coordinate} is arbitrary there; state it as `{coordinate} = any`"
                ),
            ),
            EquilibriumFinding::Family { at, direction } => Failed::new(
                FindingCode::NotIsolated,
                format!(
                    "the equilibria through {at} form a continuum along ({direction}) (for {pstr}), which an equilibria part cannot state point by point: fix the free motion (a coordinate relative to another) or ask for the frequencies at one point"
                ),
            ),
            EquilibriumFinding::Spurious { item } => Failed::new(
                FindingCode::SpuriousEquilibrium,
                format!("`{item}` is not among the equilibria the engine finds for {pstr}"),
            ),
        }
    }
}

/// The stated points (one expression per coordinate) and which coordinates are `any`.
type StatedItems = (Vec<Vec<Id>>, Vec<Vec<bool>>);

/// Reads the stated equilibria and checks each one's dimensions, that the forces vanish
/// there, and that the stabilities are as many as the equilibria.
fn stated_equilibria(
    problem: &Problem,
    part: &Part,
    p: &mut Prepared,
) -> Result<StatedItems, Failed> {
    let (stated, free): (Vec<Vec<Id>>, Vec<Vec<bool>>) = part
        .answers
        .iter()
        .map(|a| read_point_any(p, a))
        .collect::<Result<Vec<_>, _>>()?
        .into_iter()
        .unzip();
    for (item, point) in part.answers.iter().zip(&stated) {
        for (i, &v) in point.iter().enumerate() {
            let want = problem.dims.get(&p.system.coordinates[i].name);
            check_dimension(problem, p, v, want)?;
        }
        let samples = p.points.points.clone();
        if !p
            .system
            .verify_equilibrium_at(&p.derivation, point, &samples)
            .map_err(|e| Failed::new(FindingCode::Unusable, e.to_string()))?
        {
            let at = super::verify_failed::equilibrium_failure(p, point)
                .map(|w| format!(" ({w})"))
                .unwrap_or_default();
            return Err(Failed::new(
                FindingCode::SpuriousEquilibrium,
                format!(
                    "`{item}` is not an equilibrium: the generalized forces do not vanish there{at}"
                ),
            ));
        }
    }
    if !part.stability.is_empty() && part.stability.len() != stated.len() {
        return Err(Failed::new(
            FindingCode::BadStability,
            format!(
                "{} stabilities for {} equilibria",
                part.stability.len(),
                stated.len()
            ),
        ));
    }
    Ok((stated, free))
}

/// The stated points for one parameter sample: values, and which coordinates are `any`.
struct StatedPoints<'a> {
    values: Vec<&'a [f64]>,
    free: &'a [Vec<bool>],
}

/// Compares the stated equilibria with those the engine finds for `params`.
fn compare_equilibria(
    part: &Part,
    p: &mut Prepared,
    params: &[f64],
    stated: &StatedPoints,
) -> Result<Option<EquilibriumFinding>, Failed> {
    let found = match p.system.equilibria(&p.derivation, params) {
        // No equilibrium found: right for an answer of `none`; otherwise each stated point
        // in range is spurious.
        Err(crate::mechanics::MechError::NoEquilibrium) => {
            return Ok(stated.values.first().map(|_| EquilibriumFinding::Spurious {
                item: part.answers[0].clone(),
            }));
        }
        other => other.map_err(|e| Failed::new(FindingCode::Unusable, e.to_string()))?,
    };
    if found.continuum {
        return Ok(Some(EquilibriumFinding::Continuum));
    }
    let coords = p.system.coordinates.clone();
    let matches = |j: usize, q: &[f64], shape: &Shape, strict: bool| {
        stated_matches(&coords, stated, j, q, shape, strict)
    };
    for ((q, st), shape) in found.points.iter().zip(&found.shapes) {
        if let Some(f) = unstatable_family(p, q, shape) {
            return Ok(Some(f));
        }
        let Some(j) = (0..stated.values.len()).find(|&j| matches(j, q, shape, true)) else {
            if let Some(j) = (0..stated.values.len()).find(|&j| matches(j, q, shape, false))
                && let Some(i) = (0..q.len()).find(|&i| shape.coordinate_free(i))
            {
                return Ok(Some(EquilibriumFinding::NotIsolated {
                    item: part.answers[j].clone(),
                    coordinate: coords[i].name.clone(),
                }));
            }
            let at = point_text(p, q, shape);
            return Ok(Some(EquilibriumFinding::Missing { at }));
        };
        // The full linearization (velocity terms included), as `modes` reports it, at an
        // isolated point; on a continuum the search's stability, judged across it (the free
        // direction is not an instability: the cart at rest anywhere with θ = 0 is stable).
        let isolated = (0..q.len()).all(|i| !shape.coordinate_free(i));
        let st = if isolated {
            p.system
                .modes_at(&p.derivation, params, q)
                .map_or(*st, |m| m.stability)
        } else {
            *st
        };
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
    Ok(first_spurious(part, &coords, stated, &found))
}

/// Whether stated point `j` names the engine's equilibrium `q`: each coordinate agrees, a
/// coordinate stated `any` exactly where the engine finds it free alone; leniently (not
/// `strict`), ignoring the coordinates the engine finds free, so that a continuum stated
/// as a point can be named as such.
fn stated_matches(
    coords: &[Coordinate],
    stated: &StatedPoints,
    j: usize,
    q: &[f64],
    shape: &Shape,
    strict: bool,
) -> bool {
    (0..q.len()).all(|i| {
        let (any, free) = (stated.free[j][i], shape.coordinate_free(i));
        match (any, free) {
            (_, true) if !strict => true,
            (true, true) => true,
            (true, false) | (false, true) => false,
            (false, false) => same_coordinate(coords[i].periodic, stated.values[j][i], q[i]),
        }
    })
}

/// A stated point in range that the engine does not find is spurious; points outside the
/// search range are not held against the answer, since the search never looked there.
fn first_spurious(
    part: &Part,
    coords: &[Coordinate],
    stated: &StatedPoints,
    found: &Equilibria,
) -> Option<EquilibriumFinding> {
    let in_range = |q: &[f64]| {
        q.iter().enumerate().all(|(i, x)| {
            coords[i].periodic
                || (coords[i].range.0 - tolerance::RANGE_SLACK
                    ..=coords[i].range.1 + tolerance::RANGE_SLACK)
                    .contains(x)
        })
    };
    (0..stated.values.len())
        .find(|&j| {
            in_range(stated.values[j])
                && !found
                    .points
                    .iter()
                    .zip(&found.shapes)
                    .any(|((q, _), sh)| stated_matches(coords, stated, j, q, sh, true))
        })
        .map(|j| EquilibriumFinding::Spurious {
            item: part.answers[j].clone(),
        })
}

/// A continuum along a direction that is not a single coordinate, as a finding.
fn unstatable_family(p: &Prepared, q: &[f64], shape: &Shape) -> Option<EquilibriumFinding> {
    let d = shape
        .free
        .iter()
        .find(|d| d.iter().filter(|&&x| x != 0.0).count() > 1)?;
    Some(EquilibriumFinding::Family {
        at: point_text(p, q, shape),
        direction: d
            .iter()
            .map(|x| fmt_value(*x))
            .collect::<Vec<_>>()
            .join(", "),
    })
}

/// `x arbitrary, theta = 0`: the engine's equilibrium as text.
fn point_text(p: &Prepared, q: &[f64], shape: &Shape) -> String {
    p.system
        .coordinates
        .iter()
        .zip(q)
        .enumerate()
        .map(|(i, (c, x))| {
            if shape.coordinate_free(i) {
                format!("{} arbitrary", c.name)
            } else {
                format!("{} = {}", c.name, fmt_value(*x))
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

pub(super) fn verify_equilibria(problem: &Problem, part: &Part, p: &mut Prepared) -> Check {
    let (stated, free) = stated_equilibria(problem, part, p)?;
    let samples = PointSet::draw(
        &p.system,
        &p.assumptions,
        seed_from(&[&problem.id, &part.id, "equilibria"]),
        EQUILIBRIUM_SAMPLES,
    )
    .map_err(|e| Failed::new(FindingCode::Sampling, e.to_string()))?;
    let flat: Vec<Id> = stated.iter().flatten().copied().collect();
    let vals = values(&p.system, &flat, &samples)
        .map_err(|e| Failed::new(FindingCode::Sampling, e.to_string()))?;
    let n = p.system.n();
    for (k, v) in vals.iter().enumerate() {
        let Some(v) = v else { continue };
        let params = samples.params(&p.system, k).to_vec();
        let stated_pts: Vec<&[f64]> = v.chunks(n).collect();
        if let Some(f) = repeated_equilibrium(part, p, &stated_pts) {
            return Err(f);
        }
        let pts = StatedPoints {
            values: stated_pts,
            free: &free,
        };
        if let Some(f) = compare_equilibria(part, p, &params, &pts)? {
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
                    FindingCode::DuplicateEquilibrium,
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

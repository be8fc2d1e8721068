//! What `modes` adds about equilibria beyond their modes: the point given checked and read
//! in the parameters, continua shown as "x arbitrary", singular charts and degenerate points
//! explained, and what the search covered.

use std::fmt::{self, Write as _};

use super::{EquilibriumModes, ModesError, ModesOptions, SearchCoverage, point};
use crate::check::compare::fmt_value;
use crate::expr::{Id, Style};
use crate::mechanics::equilibria::Coverage;
use crate::mechanics::modes::Modes;
use crate::mechanics::{Derivation, MechError, System};
use crate::report::Formula;
use crate::report::Paint;

/// [`MechError::NotAnEquilibrium`] when the forces at rest at the point given do not vanish
/// for every value of the parameters.
pub(super) fn check_symbolic_point(
    sys: &mut System,
    d: &Derivation,
    ids: &[Id],
    opts: &ModesOptions,
) -> Result<(), ModesError> {
    sys.refuse_explicit_time(d)?;
    if sys.verify_equilibrium(d, ids)? {
        return Ok(());
    }
    let point = opts
        .at
        .iter()
        .flatten()
        .map(|(n, v)| format!("{} = {}", n.trim(), v.trim()))
        .collect::<Vec<_>>()
        .join(", ");
    Err(MechError::NotAnEquilibrium {
        point,
        forces:
            "the generalized forces at rest there do not vanish for every value of the parameters"
                .into(),
    }
    .into())
}

/// The given equilibrium with the parameter values substituted (`r = l0 + m*g/k`).
pub(super) fn given_point(
    sys: &mut System,
    given: &[(String, String)],
    values: &rustc_hash::FxHashMap<(crate::expr::Sym, u8), Id>,
) -> Result<Vec<Id>, ModesError> {
    let ids = point(sys, given)?;
    Ok(ids
        .into_iter()
        .map(|e| sys.pool.substitute(e, values))
        .collect())
}

/// The search's coverage, coordinates by their labels.
pub(super) fn search_coverage(c: &Coverage, labels: &[String]) -> SearchCoverage {
    SearchCoverage {
        blocks: c
            .blocks
            .iter()
            .map(|b| b.iter().filter_map(|&i| labels.get(i).cloned()).collect())
            .collect(),
        starts: c.starts.clone(),
    }
}

/// An equilibrium where the coordinates are singular: no modes (the chart's linearization
/// says nothing), stability undecided.
pub(super) fn chart_modes(q: &[f64]) -> Modes {
    crate::mechanics::modes::empty(q)
}

/// The equilibrium as `x arbitrary, θ = 0` (a coordinate free alone is arbitrary).
pub(super) fn point_text(labels: &[Formula], m: &EquilibriumModes, style: Style) -> Vec<String> {
    labels
        .iter()
        .zip(&m.coordinates)
        .enumerate()
        .map(|(i, (n, v))| {
            let alone = m
                .free
                .iter()
                .any(|d| d.iter().enumerate().all(|(j, &x)| (j == i) == (x != 0.0)));
            if alone {
                format!("{} arbitrary", n.get(style))
            } else {
                format!("{} = {}", n.get(style), fmt_value(*v))
            }
        })
        .collect()
}

/// What the equilibrium is beyond a point: one of a continuum not along a single
/// coordinate, or degenerate.
pub(super) fn write_shape(m: &EquilibriumModes, paint: &dyn Paint, o: &mut String) -> fmt::Result {
    for d in &m.free {
        if d.iter().filter(|&&x| x != 0.0).count() > 1 {
            let dir: Vec<String> = d.iter().map(|x| fmt_value(*x)).collect();
            writeln!(
                o,
                "  one of a continuum of equilibria: every point along ({}) from here is one",
                dir.join(", ")
            )?;
        }
    }
    if !m.singular_chart.is_empty() {
        writeln!(
            o,
            "  {} the mass matrix is singular here: the velocity of {} has no inertia at this point (like a longitude at a pole), so these coordinates cannot describe small motions about it; the point is an equilibrium, but its stability and frequencies need coordinates that are regular here (e.g. Cartesian ones)",
            paint.warn("singular coordinates:"),
            m.singular_chart.join(", ")
        )?;
    }
    if m.not_harmonic {
        writeln!(
            o,
            "  {} ω² = 0 along a direction that is not free: the restoring force is not linear in the displacement, so the motion is not a harmonic oscillation and linear analysis cannot decide stability",
            paint.warn("not harmonic:")
        )?;
    }
    Ok(())
}

/// How sure the list is: what the search covered, and that it is a search.
pub(super) fn write_coverage(c: &SearchCoverage, found: usize, o: &mut String) -> fmt::Result {
    let starts: usize = c.starts.iter().sum();
    if c.blocks.len() > 1 {
        let blocks: Vec<String> = c
            .blocks
            .iter()
            .map(|b| format!("{{{}}}", b.join(", ")))
            .collect();
        writeln!(
            o,
            "search: the equations at rest decouple into {} blocks {}, each searched on its own ({starts} Newton starts in all); the {found} listed are every combination of the blocks' equilibria found in the ranges",
            c.blocks.len(),
            blocks.join(" ")
        )?;
    } else {
        writeln!(
            o,
            "search: {starts} Newton starts over the coordinate ranges"
        )?;
    }
    writeln!(
        o,
        "(a numerical search finds the equilibria it converges to: one outside the ranges, or between the starts, may be missing)"
    )
}

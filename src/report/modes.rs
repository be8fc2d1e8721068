//! [`ModesReport`]: what `modes` shows — equilibria, their stability, frequencies, growth
//! rates and mode shapes, and optionally the characteristic polynomial and ω² in closed
//! form — built by [`modes()`] from a system and [`ModesOptions`], rendered by
//! [`ModesReport::render`].
//!
//! The serialized fields are in alphabetical order, the order of the JSON the command has
//! always printed.

use std::collections::BTreeMap;

use serde::{Serialize, Serializer};

use super::Formula;
use crate::expr::{Id, ParseError, Program, read_expr};
use crate::mechanics::equilibria::{Coverage, Shape, Stability, across_family};

mod render;
mod shown;

use crate::mechanics::modes::Modes;
use crate::mechanics::{Derivation, MechError, System};
use shown::{chart_modes, check_symbolic_point, given_point, search_coverage};

/// What to analyse. Names and values are as a person typed them; values are expressions.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ModesOptions {
    /// The search range given to every non-periodic coordinate first (a typed Lagrangian has
    /// no ranges of its own); `None` keeps the system's ranges.
    pub default_range: Option<(f64, f64)>,
    /// Search ranges of named coordinates, applied after `default_range`.
    pub ranges: Vec<(String, f64, f64)>,
    /// Parameter values, `name = expression`; an expression may use other parameters, which
    /// then stay symbolic.
    pub params: Vec<(String, String)>,
    /// Only this equilibrium, one `coordinate = expression` per coordinate.
    pub at: Option<Vec<(String, String)>>,
    /// Also the characteristic polynomial and ω² in closed form (needs `at`).
    pub symbolic: bool,
    /// Steady motions: fixed momenta `p_phi = value` of cyclic coordinates; the analysis is
    /// of the Routhian (see `report::steady`).
    pub steady: Vec<(String, String)>,
}

/// Why the modes could not be reported.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum ModesError {
    /// The system itself could not be analysed.
    #[error(transparent)]
    Mech(#[from] MechError),
    /// The equilibrium given names no value for this coordinate.
    #[error("the equilibrium gives no value for `{name}`")]
    MissingPointValue {
        /// The coordinate.
        name: String,
    },
    /// The equilibrium given is not numeric, but every parameter has a number.
    #[error("the equilibrium's values must be numbers here")]
    PointNotNumeric,
    /// A value of the equilibrium given did not read. The face labels the value as its user
    /// gave it (a command line, by the flag that gave it).
    #[error("cannot read the equilibrium's value of `{coordinate}`: {error}")]
    PointValue {
        /// The coordinate, as named in the equilibrium given.
        coordinate: String,
        /// The value as given.
        source_text: String,
        /// Why it did not read.
        error: Box<ParseError>,
    },
    /// A parameter's value is undefined (`g=0/0`) or not finite (`g=log(0)`).
    #[error("the value of `{name}`, {text}, is undefined")]
    UndefinedValue {
        /// The parameter.
        name: String,
        /// Its value as given.
        text: String,
    },
    /// Closed forms were asked for without an equilibrium to expand about.
    #[error("the closed forms need the equilibrium")]
    SymbolicNeedsPoint,
    /// The steady-motion reduction failed.
    #[error(transparent)]
    Steady(#[from] crate::mechanics::steady::SteadyError),
    /// The equilibrium search does not follow constraints: the point must be given.
    #[error(
        "with constraints the equilibria are not searched for (the search would ignore the constraints)"
    )]
    ConstrainedNeedsPoint,
    /// The closed forms do not include constraints.
    #[error(
        "the closed forms ignore constraints, so they would be wrong here; the numeric modes are linearized on the constraints"
    )]
    SymbolicConstrained,
}

/// A `name=value` item that is not one.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("`{0}` should look like name=value")]
pub struct BadAssignment(pub String);

/// Comma-separated `name=value` pairs, trimmed; empty items are skipped. Names are read as in
/// expressions (`θ₁=0.1` names `theta1`; see [`crate::expr::spelled`]).
pub fn assignments(text: &str) -> Result<Vec<(String, String)>, BadAssignment> {
    text.split(',')
        .map(str::trim)
        .filter(|x| !x.is_empty())
        .map(|item| {
            item.split_once('=')
                .map(|(a, b)| (crate::expr::spelled(a), b.trim().to_string()))
                .ok_or_else(|| BadAssignment(item.to_string()))
        })
        .collect()
}

/// Everything `modes` shows.
#[derive(Clone, Debug, Serialize)]
#[non_exhaustive]
pub struct ModesReport {
    /// det(K − ω²M), when closed forms were asked for.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) characteristic_polynomial: Option<Formula>,
    /// How many holonomic constraints the modes were linearized on.
    pub(crate) constraints: usize,
    /// Every point of the search range is an equilibrium.
    pub(crate) continuum: bool,
    /// The equilibria analysed.
    pub equilibria: Vec<EquilibriumModes>,
    /// What the search covered, when the equilibria were searched for (not given).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub search: Option<SearchCoverage>,
    /// ω² in closed form, when closed forms were asked for (empty: not given for this size).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub omega_squared: Option<Vec<Formula>>,
    /// The Routhian and the cyclic velocities, for steady motions.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub(crate) steady: Option<super::steady::SteadyNote>,
    /// How the text shows each coordinate.
    #[serde(skip)]
    pub(crate) coordinate_labels: Vec<Formula>,
    /// Gyroscopic terms entered the characteristic polynomial: det(K − ω²M − iωC).
    #[serde(skip)]
    pub(crate) gyroscopic_closed_form: bool,
}

/// What the equilibrium search covered: the list is a search's, not a proof.
#[derive(Clone, Debug, Serialize)]
pub struct SearchCoverage {
    /// Blocks of coordinates whose equations at rest decouple, each searched on its own.
    pub blocks: Vec<Vec<String>>,
    /// Newton starts in each block.
    pub(crate) starts: Vec<usize>,
}

/// A damped oscillation.
#[derive(Clone, Copy, Debug, Serialize)]
pub struct DampedMode {
    /// The decay rate γ = −Re λ.
    pub(crate) decay_rate: f64,
    /// The damping ratio ζ = γ/|λ|.
    pub(crate) damping_ratio: f64,
    /// The damped angular frequency ω_d = Im λ.
    pub(crate) frequency: f64,
}

/// One equilibrium and its small oscillations.
#[derive(Clone, Debug, Serialize)]
pub struct EquilibriumModes {
    /// Damped oscillations (with damping terms).
    pub(crate) damped: Vec<DampedMode>,
    /// Symmetric velocity terms (friction, drag) survive.
    pub(crate) damping: bool,
    /// Decay rates of the modes that decay without oscillating.
    pub(crate) decay_rates: Vec<f64>,
    /// Directions along which a displacement is not restored (ω = 0), largest component 1.
    pub(crate) free_directions: Vec<Vec<f64>>,
    /// Undamped oscillation frequencies ω, 0 for each free motion.
    pub frequencies: Vec<f64>,
    /// Growth rates of unstable directions.
    pub growth_rates: Vec<f64>,
    /// Gyroscopic (antisymmetric velocity) terms survive: rotating frames, magnetic fields.
    pub(crate) gyroscopic: bool,
    /// The mode shapes, one per mode.
    pub(crate) modes: Vec<Vec<f64>>,
    /// ω² of each mode.
    pub omega_squared: Vec<f64>,
    /// The equilibrium, by coordinate name (a coordinate listed in `free` alone is
    /// arbitrary; its value here is the representative one).
    pub(crate) point: BTreeMap<String, f64>,
    /// For a steady motion: the velocity of each cyclic coordinate, `phi'` and its value.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub rates: Vec<(String, f64)>,
    /// Directions along which this equilibrium is one of a continuum (empty: isolated).
    pub free: Vec<Vec<f64>>,
    /// ω² = 0 along a direction that is not free: the small oscillations are not harmonic.
    pub not_harmonic: bool,
    /// Coordinates whose velocities lose their inertia here (a singular chart): no modes.
    pub singular_chart: Vec<String>,
    /// Stable, unstable or marginal.
    #[serde(serialize_with = "stability_name")]
    pub stability: Stability,
    /// Whether it is stable.
    pub(crate) stable: bool,
    /// The equilibrium in coordinate order.
    #[serde(skip)]
    pub coordinates: Vec<f64>,
    /// A description of each mode ("in phase, θ₂/θ₁ = 1.414214"), in Unicode.
    #[serde(skip)]
    pub(crate) descriptions: Vec<String>,
}

fn stability_name<S: Serializer>(s: &Stability, ser: S) -> Result<S::Ok, S::Error> {
    ser.serialize_str(s.name())
}

/// Finds the equilibria of `sys` (or takes the one given) and their normal modes, with the
/// closed forms when asked. `sys` itself is left unchanged.
pub fn modes(sys: &System, opts: &ModesOptions) -> Result<ModesReport, ModesError> {
    let mut sys = sys.clone();
    set_ranges(&mut sys, opts)?;
    let (mut sys, steady) = super::steady::reduce(sys, &opts.steady)?;
    let params: Vec<(String, String)> = opts.params.iter().chain(&opts.steady).cloned().collect();
    let values = sys.substitute_parameters(&params)?;
    check_values(&sys, &values, &params)?;
    // Parameters declared but not used by L (a bank problem's `l` for its equal-length
    // part) need no value.
    sys.drop_unused_parameters();
    let d = sys.derive()?;
    let coordinate_labels: Vec<Formula> = sys
        .coordinates
        .clone()
        .iter()
        .map(|c| {
            let v = sys.pool.var(c.sym, 0);
            Formula::new(&sys.pool, v)
        })
        .collect();
    let at = match &opts.at {
        Some(given) => Some(given_point(&mut sys, given, &values)?),
        None => None,
    };
    let mut equilibria = Vec::new();
    let mut continuum = false;
    let mut search = None;
    if sys.parameters.is_empty() {
        (equilibria, continuum, search) = numeric_report(
            &mut sys,
            &d,
            at.as_deref(),
            steady.as_ref(),
            &values,
            &coordinate_labels,
        )?;
    } else if !opts.symbolic {
        return Err(MechError::MissingValue {
            name: sys.parameters[0].name.clone(),
        }
        .into());
    }
    if opts.symbolic && !sys.constraints.is_empty() {
        return Err(ModesError::SymbolicConstrained);
    }
    let symbolic = match (&at, opts.symbolic) {
        (Some(ids), true) => {
            check_symbolic_point(&mut sys, &d, ids, opts)?;
            Some(sys.symbolic_modes(&d, ids)?)
        }
        (None, true) => return Err(ModesError::SymbolicNeedsPoint),
        _ => None,
    };
    let pool = &sys.pool;
    Ok(ModesReport {
        characteristic_polynomial: symbolic
            .as_ref()
            .map(|s| Formula::factored(pool, &s.characteristic_shown)),
        constraints: sys.constraints.len(),
        continuum,
        search,
        equilibria,
        omega_squared: symbolic.as_ref().map(|s| {
            s.omega_squared_shown
                .iter()
                .map(|w| Formula::factored(pool, w))
                .collect()
        }),
        steady,
        coordinate_labels,
        gyroscopic_closed_form: symbolic.as_ref().is_some_and(|s| s.gyroscopic),
    })
}

/// The equilibria as reported, whether they fill the range, and what the search covered.
type NumericReport = (Vec<EquilibriumModes>, bool, Option<SearchCoverage>);

/// The numeric half of the report, possible only once every parameter has a number: the
/// modes at each equilibrium (with a steady motion's cyclic velocities) in the report's terms.
fn numeric_report(
    sys: &mut System,
    d: &Derivation,
    at: Option<&[Id]>,
    steady: Option<&super::steady::SteadyNote>,
    values: &rustc_hash::FxHashMap<(crate::expr::Sym, u8), Id>,
    labels: &[Formula],
) -> Result<NumericReport, ModesError> {
    let unicode: Vec<String> = labels.iter().map(|l| l.unicode.clone()).collect();
    let names: Vec<String> = sys.coordinates.iter().map(|c| c.name.clone()).collect();
    let (found, continuum, coverage) = numeric_modes(sys, d, at)?;
    let search = coverage.map(|c| search_coverage(&c, &unicode));
    let mut equilibria: Vec<EquilibriumModes> = found
        .iter()
        .map(|(m, shape)| equilibrium(m, shape, &names, &unicode))
        .collect();
    if let Some(note) = steady {
        let points: Vec<Vec<f64>> = found.iter().map(|(m, _)| m.point.clone()).collect();
        let rates = super::steady::rates_at(note, sys, values, &points);
        for (e, r) in equilibria.iter_mut().zip(rates) {
            e.rates = r;
        }
    }
    Ok((equilibria, continuum, search))
}

/// A constant value that does not evaluate to a finite number is its own error, rather than
/// an undefined L reported as a degenerate system.
fn check_values(
    sys: &System,
    values: &rustc_hash::FxHashMap<(crate::expr::Sym, u8), Id>,
    given: &[(String, String)],
) -> Result<(), ModesError> {
    for (&(sym, _), &v) in values {
        let finite = sys.pool.variables(v).is_empty().then(|| constant(sys, v));
        if sys.pool.is_undefined(v) || finite.is_some_and(|x| !x.is_some_and(f64::is_finite)) {
            let name = sys.pool.name(sym).to_string();
            let text = given
                .iter()
                .find(|(n, _)| crate::expr::names::normalize(n.trim()) == name)
                .map_or_else(String::new, |(_, t)| t.clone());
            return Err(ModesError::UndefinedValue { name, text });
        }
    }
    Ok(())
}

/// Applies the default and the named search ranges.
fn set_ranges(sys: &mut System, opts: &ModesOptions) -> Result<(), MechError> {
    if let Some(range) = opts.default_range {
        for c in sys.coordinates.iter_mut().filter(|c| !c.periodic) {
            c.range = range;
        }
    }
    for (name, lo, hi) in &opts.ranges {
        let c = sys
            .coordinates
            .iter_mut()
            .find(|c| c.name == name.trim())
            .ok_or_else(|| MechError::UnknownCoordinate {
                name: name.trim().into(),
            })?;
        c.range = (*lo, *hi);
    }
    Ok(())
}

/// The given equilibrium, one expression per coordinate.
fn point(sys: &mut System, given: &[(String, String)]) -> Result<Vec<Id>, ModesError> {
    let names: Vec<String> = sys.coordinates.iter().map(|c| c.name.clone()).collect();
    let ctx = sys.open_context();
    let mut point = vec![None; names.len()];
    for (name, v) in given {
        let k = names
            .iter()
            .position(|n| *n == crate::expr::names::normalize(name))
            .ok_or(MechError::UnknownCoordinate { name: name.clone() })?;
        let value = read_expr(v, &ctx, &mut sys.pool).map_err(|error| ModesError::PointValue {
            coordinate: name.clone(),
            source_text: v.clone(),
            error: Box::new(error),
        })?;
        point[k] = Some(value);
    }
    point
        .into_iter()
        .zip(names)
        .map(|(p, name)| p.ok_or(ModesError::MissingPointValue { name }))
        .collect()
}

/// The modes found with their shapes, whether the equilibria fill the range, and what the
/// search covered (none when the point was given).
type NumericModes = (Vec<(Modes, Shape)>, bool, Option<Coverage>);

/// The numeric modes at the given point, or at every equilibrium found; and whether the
/// equilibria form a continuum.
fn numeric_modes(
    sys: &mut System,
    d: &Derivation,
    at: Option<&[Id]>,
) -> Result<NumericModes, ModesError> {
    if let Some(ids) = at {
        let q: Vec<f64> = ids
            .iter()
            .map(|&e| constant(sys, e).ok_or(ModesError::PointNotNumeric))
            .collect::<Result<_, _>>()?;
        sys.check_equilibrium(d, &[], &q)?;
        let shape = sys.equilibrium_shape(d, &[], &q)?;
        if !shape.singular_chart.is_empty() {
            return Ok((vec![(chart_modes(&q), shape)], false, None));
        }
        let mut m = sys.modes_at(d, &[], &q)?;
        m.stability = across_family(m.stability, &shape);
        return Ok((vec![(m, shape)], false, None));
    }
    if !sys.constraints.is_empty() {
        return Err(ModesError::ConstrainedNeedsPoint);
    }
    let eq = sys.equilibria(d, &[])?;
    if !eq.continuum && eq.points.is_empty() {
        return Err(MechError::NoEquilibrium.into());
    }
    let mut found = Vec::with_capacity(eq.points.len());
    for ((q, _), shape) in eq.points.into_iter().zip(eq.shapes) {
        if !shape.singular_chart.is_empty() {
            found.push((chart_modes(&q), shape));
            continue;
        }
        let mut m = sys.modes_at(d, &[], &q)?;
        m.stability = across_family(m.stability, &shape);
        found.push((m, shape));
    }
    Ok((found, eq.continuum, Some(eq.coverage)))
}

/// The value of a constant expression.
fn constant(sys: &System, e: Id) -> Option<f64> {
    if !sys.pool.variables(e).is_empty() {
        return None;
    }
    Program::compile(&sys.pool, &[e], &[])
        .ok()?
        .eval(&[])
        .ok()
        .map(|v| v[0])
}

fn equilibrium(m: &Modes, shape: &Shape, names: &[String], labels: &[String]) -> EquilibriumModes {
    EquilibriumModes {
        damped: m
            .damped
            .iter()
            .map(|d| DampedMode {
                decay_rate: d.decay_rate,
                damping_ratio: d.damping_ratio,
                frequency: d.frequency,
            })
            .collect(),
        damping: m.damping,
        decay_rates: m.decay_rates.clone(),
        free_directions: m.free_directions.clone(),
        frequencies: m.frequencies.clone(),
        growth_rates: m.growth_rates.clone(),
        gyroscopic: m.gyroscopic,
        modes: m.modes.iter().map(|x| x.shape.clone()).collect(),
        omega_squared: m.modes.iter().map(|x| x.omega_squared).collect(),
        point: point_map(names, &m.point),
        stability: m.stability,
        stable: m.stability == Stability::Stable,
        free: shape.free.clone(),
        not_harmonic: shape.degenerate,
        singular_chart: shape
            .singular_chart
            .iter()
            .filter_map(|&i| labels.get(i).cloned())
            .collect(),
        coordinates: m.point.clone(),
        rates: Vec::new(),
        descriptions: m.describe(labels),
    }
}

/// Each coordinate's value at the point, by name (a repeated name keeps its last value, as
/// `collect` does). Inserted one by one rather than collected: collecting a `BTreeMap` sorts,
/// one more copy of the standard sort in the page's WebAssembly module.
fn point_map(names: &[String], values: &[f64]) -> BTreeMap<String, f64> {
    let mut point = BTreeMap::new();
    for (name, value) in names.iter().zip(values) {
        point.insert(name.clone(), *value);
    }
    point
}

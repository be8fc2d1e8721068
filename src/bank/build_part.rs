//! The checks of a problem file's parts and names: ids (problem and part), reserved parameter
//! names, a part's kind, answers, tolerance and weight, quantity and multiplier.

use crate::expr::Dimension;
use crate::mechanics::System;
use crate::problem::{Part, PartKind, Quantity, is_none_answer};

use super::FindingCode;
use super::schema::{AnswerSpec, PartSpec};

/// Smallest and largest relative tolerance a part may set: below 1e-15 is under the rounding
/// of f64; above 1e-2 a wrong answer (a constant off by 1 %, or `0` at 100 %) would pass.
const MIN_TOLERANCE: f64 = 1e-15;
const MAX_TOLERANCE: f64 = 1e-2;
/// Largest weight of a part.
const MAX_POINTS: f64 = 1e6;

/// Why `name` cannot be a parameter's name: it would read as time, π or a function.
pub(super) fn reserved(name: &str) -> Option<String> {
    crate::mechanics::system::check_coordinate_name(name)
        .err()
        .map(|e| e.reason())
}

/// An id is used on the command line and printed in reports: it must be non-empty and made
/// of letters, digits, `-`, `_` and `.` only (no spaces, control or invisible characters).
pub(super) fn check_id(id: &str, what: &str) -> Result<(), String> {
    const MAX_ID: usize = 100;
    if id.is_empty() {
        return Err(format!("the {what} id is empty"));
    }
    if id.chars().count() > MAX_ID {
        return Err(format!("the {what} id is longer than {MAX_ID} characters"));
    }
    if let Some(c) = id
        .chars()
        .find(|&c| !(c.is_alphanumeric() || matches!(c, '-' | '_' | '.')))
    {
        return Err(format!(
            "the {what} id `{}` has the {}; an id is letters, digits, `-`, `_` and `.`",
            crate::expr::error::visible(id),
            crate::expr::error::describe_char(c)
        ));
    }
    Ok(())
}

/// The part's tolerance and weight, each checked to be a number in its range (a NaN, a
/// negative or a huge tolerance would let `check` accept wrong answers).
fn tolerance_and_points(sp: &PartSpec) -> Result<(f64, f64), (FindingCode, String)> {
    let tolerance = match sp.tolerance {
        None => crate::check::tolerance::TOLERANCE,
        Some(t) if (MIN_TOLERANCE..=MAX_TOLERANCE).contains(&t) => t,
        Some(t) => {
            return Err((
                FindingCode::BadTolerance,
                format!(
                    "tolerance = {t:?}: a relative tolerance lies between {MIN_TOLERANCE:e} and {MAX_TOLERANCE:e} (default 1e-9); a larger one would accept wrong answers"
                ),
            ));
        }
    };
    let points = match sp.points {
        None => 1.0,
        Some(p) if (0.0..=MAX_POINTS).contains(&p) => p,
        Some(p) => {
            return Err((
                FindingCode::BadPoints,
                format!("points = {p:?}: a part's weight is a number from 0 to {MAX_POINTS:e}"),
            ));
        }
    };
    Ok((tolerance, points))
}

pub(super) fn build_part(
    sp: &PartSpec,
    line: usize,
    sys: &System,
) -> Result<Part, (FindingCode, String)> {
    let kind = PartKind::parse(&sp.kind).ok_or_else(|| {
        (FindingCode::BadKind, format!("unknown part kind `{}` (expression, lagrangian, equation, equations, equilibria, frequencies, values, constraint-force, steady-motion)", sp.kind))
    })?;
    let answers = answers_of(sp, kind)?;
    let quantity = quantity_of(sp, sys)?;
    let (tolerance, points) = tolerance_and_points(sp)?;
    let up_to_constant = match sp.up_to.as_deref() {
        None => false,
        Some("constant") => true,
        Some(other) => {
            return Err((
                FindingCode::BadUpTo,
                format!("up_to = \"{other}\" (only \"constant\")"),
            ));
        }
    };
    let dimension = sp
        .dimension
        .as_deref()
        .map(Dimension::parse)
        .transpose()
        .map_err(|e| (FindingCode::BadDimension, e.to_string()))?;
    let same_motion = match sp.accept.as_deref() {
        None => false,
        Some("same-motion") if kind == PartKind::Lagrangian || quantity == Quantity::Lagrangian => {
            true
        }
        Some("same-motion") => {
            return Err((
                FindingCode::BadAccept,
                "accept = \"same-motion\" applies to a Lagrangian part only".into(),
            ));
        }
        Some(other) => {
            return Err((
                FindingCode::BadAccept,
                format!("accept = \"{other}\" (only \"same-motion\", on a Lagrangian part)"),
            ));
        }
    };
    if sp.require_stability && kind != PartKind::Equilibria {
        return Err((
            FindingCode::BadRequireStability,
            "require_stability applies to an equilibria part only".into(),
        ));
    }
    if sp.require_stability && sp.stability.len() != answers.len() {
        return Err((
            FindingCode::BadRequireStability,
            "require_stability needs the stability of every stated point: give `stability`, one word per answer item".into(),
        ));
    }
    for s in &sp.stability {
        if !matches!(s.as_str(), "stable" | "unstable" | "marginal") {
            return Err((
                FindingCode::BadStability,
                format!("stability `{s}` (use stable, unstable or marginal)"),
            ));
        }
    }
    let extra = super::build_linearized::options(sp, kind, quantity, sys)?;
    Ok(Part {
        id: sp.id.clone(),
        kind,
        prompt: sp.prompt.clone(),
        answers,
        hints: sp.hints.clone(),
        points,
        substitute: sp
            .substitute
            .iter()
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect(),
        at: sp.at.iter().map(|(k, v)| (k.clone(), v.clone())).collect(),
        up_to_constant,
        wrong: sp.wrong.clone(),
        tolerance,
        stability: sp.stability.clone(),
        quantity,
        dimension,
        squared: sp.squared,
        same_motion,
        require_stability: sp.require_stability,
        // Read by the builder, which holds the system mutably.
        assumptions: Vec::new(),
        about: extra.about,
        omit_zero_modes: extra.omit_zero_modes,
        growth: extra.growth,
        // Set by `build_numeric`, which knows the parameters' dimensions.
        units: None,
        values: Vec::new(),
        answers_with_units: Vec::new(),
        line,
        numbers: sp.numbers,
    })
}

/// The reference answers; `none` (alone) states an empty list, for a list part only.
fn answers_of(sp: &PartSpec, kind: PartKind) -> Result<Vec<String>, (FindingCode, String)> {
    let mut answers = match &sp.answer {
        AnswerSpec::One(s) => vec![s.clone()],
        AnswerSpec::Many(v) => v.clone(),
    };
    if answers.is_empty() {
        return Err((
            FindingCode::NoAnswer,
            "the part has an empty answer (an empty list is written `none`)".into(),
        ));
    }
    // `none` states an empty list, explicitly: an omission is never read as one.
    let list = matches!(
        kind,
        PartKind::Equilibria | PartKind::Frequencies | PartKind::Values
    );
    if answers.len() == 1 && is_none_answer(&answers[0]) {
        if !list {
            return Err((
                FindingCode::NoAnswer,
                format!("`none` answers a list part, not a {} part", kind.name()),
            ));
        }
        answers.clear();
    }
    Ok(answers)
}

/// The quantity an expression part asks for: stated, or implied by the part's id.
fn quantity_of(sp: &PartSpec, sys: &System) -> Result<Quantity, (FindingCode, String)> {
    let coordinate = match &sp.coordinate {
        None => 0,
        Some(c) => sys
            .coordinates
            .iter()
            .position(|x| x.name == crate::expr::names::normalize(c))
            .ok_or_else(|| {
                (
                    FindingCode::BadCoordinate,
                    format!("`{c}` is not a coordinate"),
                )
            })?,
    };
    let q = sp.quantity.as_deref().unwrap_or(match sp.id.as_str() {
        "kinetic" => "kinetic",
        "potential" => "potential",
        "lagrangian" => "lagrangian",
        "momentum" => "momentum",
        "energy-function" => "energy-function",
        "tension" | "constraint-force" => "multiplier",
        "cyclic" => "cyclic",
        _ => "none",
    });
    let quantity = match q {
        "kinetic" => Quantity::Kinetic,
        "potential" => Quantity::Potential,
        "lagrangian" => Quantity::Lagrangian,
        "momentum" => Quantity::Momentum(coordinate),
        "energy-function" => Quantity::EnergyFunction,
        "multiplier" => Quantity::Multiplier(sp.multiplier.unwrap_or(1).saturating_sub(1)),
        "acceleration" => Quantity::Acceleration(coordinate),
        "cyclic" if sp.kind == "values" => Quantity::Cyclic,
        "cyclic" => {
            return Err((
                FindingCode::BadQuantity,
                "`cyclic` is the quantity of a `values` part (the names of the cyclic coordinates)"
                    .into(),
            ));
        }
        "none" => Quantity::None,
        other => {
            return Err((
                FindingCode::BadQuantity,
                format!("unknown quantity `{other}`"),
            ));
        }
    };
    check_multiplier(sp.multiplier, quantity, sys.constraints.len())?;
    Ok(quantity)
}

/// The `multiplier` key and a multiplier quantity fit the problem's constraints: a multiplier
/// exists only for a constraint, numbered from 1, and the key only on a multiplier part.
fn check_multiplier(
    key: Option<usize>,
    quantity: Quantity,
    constraints: usize,
) -> Result<(), (FindingCode, String)> {
    let bad = |m: String| Err((FindingCode::BadMultiplier, m));
    match quantity {
        Quantity::Multiplier(_) if constraints == 0 => bad(
            "the problem has no constraints, so there is no multiplier to ask for: add `constraints`, or choose another quantity".into(),
        ),
        _ if key == Some(0) => bad("multiplier = 0: multipliers are numbered from 1".into()),
        Quantity::Multiplier(j) if j >= constraints => bad(format!(
            "multiplier = {}: the problem has {constraints} constraint(s)",
            j + 1
        )),
        Quantity::Multiplier(_) => Ok(()),
        _ if key.is_some() => bad(
            "`multiplier` applies only to a multiplier part (a constraint force, or quantity = \"multiplier\")".into(),
        ),
        _ => Ok(()),
    }
}

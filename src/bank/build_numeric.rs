//! Numeric parts: `values` give every parameter a number, with a unit in square brackets
//! (`l = "50 [cm]"`, converted to SI and checked against the parameter's dimension), and the
//! answers are numbers with units (`"4.43 [rad/s]"`). The part's system is the problem's with
//! those numbers substituted, so verification proves the stated number against the physics,
//! within the tolerance the part must state.

use crate::check::units::{UnitError, convert};
use crate::expr::{Context, Dimension, Dimensions, Pool, read_expr};
use crate::mechanics::System;
use crate::problem::{Part, PartKind, Quantity};

use super::FindingCode;
use super::build_reader::Builder;
use super::finding::{Finding, line_of};
use super::schema::{BoundSpec, ProblemFile};

/// Makes the parts with `values` numeric (in file order, as `parts` are).
pub(super) fn numeric(
    b: &Builder,
    pf: &ProblemFile,
    parts: &mut [Part],
    system: &System,
    dims: &Dimensions,
) -> Result<(), Finding> {
    for (sp, part) in pf.parts.iter().zip(parts.iter_mut()) {
        if sp.get_ref().values.is_empty() {
            continue;
        }
        let line = line_of(b.text, sp.span().start);
        let fail = |m: String| Finding {
            part: Some(part.id.clone()),
            ..b.fail(line, FindingCode::BadValues, m)
        };
        let sp = sp.get_ref();
        if sp.tolerance.is_none() {
            return Err(fail(
                "a numeric part states the relative tolerance it accepts (`tolerance = 1e-3` for about three significant digits)".into(),
            ));
        }
        let want = answer_dimension(part, system, dims).map_err(fail)?;
        let mut values = Vec::new();
        let mut shown = Vec::new();
        for (name, value) in &sp.values {
            let norm = crate::expr::names::normalize(name);
            let Some(d) = dims
                .get(&norm)
                .filter(|_| system.parameters.iter().any(|p| p.name == norm))
            else {
                return Err(fail(format!(
                    "`values` names `{name}`, which is not a parameter"
                )));
            };
            let text = match value {
                BoundSpec::Number(v) if v.is_finite() => format!("{v}"),
                BoundSpec::Number(v) => {
                    return Err(fail(format!("`{name} = {v}` is not a finite number")));
                }
                BoundSpec::Text(t) => t.clone(),
            };
            let si = si_number(&text, d).map_err(|m| fail(format!("`{name} = {text}`: {m}")))?;
            values.push((norm, si));
            shown.push((name.clone(), text));
        }
        let unset: Vec<&str> = system
            .parameters
            .iter()
            .map(|p| p.name.as_str())
            .filter(|n| {
                !values.iter().any(|(v, _)| v == n)
                    && !part
                        .substitute
                        .iter()
                        .any(|(s, _)| crate::expr::names::normalize(s) == *n)
            })
            .collect();
        if !unset.is_empty() {
            return Err(fail(format!(
                "a numeric part gives every parameter a number: {} {} none",
                unset.join(", "),
                if unset.len() == 1 { "has" } else { "have" }
            )));
        }
        part.answers_with_units = part.answers.clone();
        for a in &mut part.answers {
            let c = convert(a, want)
                .map_err(|e| fail(format!("the answer `{a}`: {}", unit_message(&e))))?;
            *a = c.text;
        }
        part.substitute.extend(values);
        part.units = Some(want);
        part.values = shown;
    }
    Ok(())
}

/// The dimension a numeric part's answer has: a frequency's (T⁻¹, T⁻² squared), the
/// quantity's, or the part's `dimension`.
fn answer_dimension(part: &Part, system: &System, dims: &Dimensions) -> Result<Dimension, String> {
    let t = Dimension::new(0, 0, 1);
    let coord = |i: usize| dims.get(&system.coordinates[i].name);
    let d = match (part.kind, part.quantity) {
        (PartKind::Frequencies, _) if part.squared => Some(Dimension::new(0, 0, -2)),
        (PartKind::Frequencies, _) => Some(Dimension::new(0, 0, -1)),
        (PartKind::Expression | PartKind::ConstraintForce, _) if part.dimension.is_some() => {
            part.dimension
        }
        (
            PartKind::Expression,
            Quantity::Kinetic
            | Quantity::Potential
            | Quantity::Lagrangian
            | Quantity::EnergyFunction,
        ) => Some(Dimension::energy()),
        (PartKind::Expression, Quantity::Momentum(i)) => {
            coord(i).map(|d| Dimension::energy() * t / d)
        }
        (PartKind::Expression, Quantity::Acceleration(i)) => coord(i).map(|d| d / (t * t)),
        (PartKind::Expression | PartKind::ConstraintForce, _) => {
            return Err("say the answer's dimension with `dimension` (e.g. \"M L T^-2\"), so that its units can be checked".into());
        }
        (kind, _) => {
            return Err(format!(
                "a numeric part is a frequencies or an expression part, not {}",
                kind.name()
            ));
        }
    };
    d.ok_or_else(|| "the answer's dimension is unknown: state it with `dimension`".to_string())
}

/// A parameter's value in SI: a number, optionally with a unit in brackets of the
/// parameter's dimension; nothing but numbers.
fn si_number(text: &str, dim: Dimension) -> Result<String, String> {
    let c = convert(text, dim).map_err(|e| unit_message(&e))?;
    let mut pool = Pool::new();
    read_expr(&c.text, &Context::new(), &mut pool).map_err(|e| format!("not a number ({e})"))?;
    Ok(c.text)
}

/// A unit error in words.
pub(crate) fn unit_message(e: &UnitError) -> String {
    match e {
        UnitError::Unreadable(m) => m.clone(),
        UnitError::Dimension {
            item,
            unit,
            have,
            want,
        } => format!("`{item}`: the unit {unit} has dimension {have}, but {want} is needed"),
    }
}

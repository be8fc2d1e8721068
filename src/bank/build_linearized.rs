//! The part options of the parts instructors ask for beyond the basic kinds: a linearized
//! answer (`about`, the point to expand about), a frequencies list without its zero modes
//! (`omit_zero_modes`) and the growth rates at an unstable equilibrium (`growth`). Each is
//! checked here to apply to its part's kind and to name real coordinates.

use crate::mechanics::System;
use crate::problem::{PartKind, Quantity};

use super::FindingCode;
use super::schema::{BoundSpec, PartSpec};

/// A part's linearization point and frequency options, checked.
pub(super) struct Options {
    pub(crate) about: Option<Vec<(String, String)>>,
    pub(crate) omit_zero_modes: bool,
    pub(crate) growth: bool,
}

/// Reads and checks `about`, `omit_zero_modes` and `growth`.
pub(super) fn options(
    sp: &PartSpec,
    kind: PartKind,
    quantity: Quantity,
    sys: &System,
) -> Result<Options, (FindingCode, String)> {
    let about = match &sp.about {
        None => None,
        Some(map) => Some(about_of(map, kind, quantity, sys)?),
    };
    if (sp.omit_zero_modes || sp.growth) && kind != PartKind::Frequencies {
        let key = if sp.growth {
            "growth"
        } else {
            "omit_zero_modes"
        };
        return Err((
            FindingCode::BadFrequencyOption,
            format!("`{key}` applies to a frequencies part only"),
        ));
    }
    if sp.omit_zero_modes && sp.growth {
        return Err((
            FindingCode::BadFrequencyOption,
            "`growth` lists only the growing modes, so `omit_zero_modes` says nothing there: drop it".into(),
        ));
    }
    Ok(Options {
        about,
        omit_zero_modes: sp.omit_zero_modes,
        growth: sp.growth,
    })
}

/// The expansion point: every key a coordinate, every value a finite number or an expression
/// (read with the part, where a bad one is reported), on a part whose answer can be expanded.
fn about_of(
    map: &std::collections::BTreeMap<String, BoundSpec>,
    kind: PartKind,
    quantity: Quantity,
    sys: &System,
) -> Result<Vec<(String, String)>, (FindingCode, String)> {
    let bad = |m: String| Err((FindingCode::BadAbout, m));
    // A quantity of the motion's energy or its equations: what "to second order" means for.
    let expandable = match kind {
        PartKind::Equation | PartKind::Equations | PartKind::Lagrangian => true,
        PartKind::Expression => matches!(
            quantity,
            Quantity::Kinetic
                | Quantity::Potential
                | Quantity::Lagrangian
                | Quantity::EnergyFunction
        ),
        _ => false,
    };
    if !expandable {
        return bad(format!(
            "`about` linearizes an energy (quantity kinetic, potential, lagrangian, energy-function) or equations of motion; a {} part has nothing to expand",
            kind.name()
        ));
    }
    let mut out = Vec::new();
    for (name, value) in map {
        let norm = crate::expr::names::normalize(name);
        if !sys.coordinates.iter().any(|c| c.name == norm) {
            return bad(format!("`about` names `{name}`, which is not a coordinate"));
        }
        let text = match value {
            BoundSpec::Number(v) if v.is_finite() => format!("{v}"),
            BoundSpec::Number(v) => return bad(format!("`{name} = {v}` is not a finite point")),
            BoundSpec::Text(t) => t.clone(),
        };
        out.push((norm, text));
    }
    Ok(out)
}

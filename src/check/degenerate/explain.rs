//! Naming a degeneracy: the energy law, a factor of the answer that vanishes (or is undefined)
//! where the zero was found, or just where; and the sentence for each ([`Degeneracy`]).

use super::det::median;
use super::search::Found;
use crate::check::common::state_text;
use crate::check::compare::proportional;
use crate::check::prepare::Prepared;
use crate::check::tolerance;
use crate::check::verdict::{Code, Diagnosis};
use crate::expr::{Id, Node, Style};

/// A factor this small relative to its typical size is zero up to rounding.
const NUMERICAL_ZERO: f64 = 1e-12;

/// Why equations that hold for the motion are not equivalent to the reference.
pub(crate) enum Degeneracy {
    /// Row `row` (or the one equation) is the energy law dE/dt = 0.
    EnergyLaw {
        row: Option<usize>,
        velocity: String,
    },
    /// The answer is multiplied by `factor`, which vanishes (or is undefined) at `at`.
    Factor {
        row: Option<usize>,
        factor: String,
        at: String,
        how: Vanishing,
    },
    /// det C vanishes at `at`.
    Vanishes { at: String },
    /// The answer is undefined at `at`, where the reference determines the accelerations.
    Undefined { at: String },
}

impl Degeneracy {
    /// The sentence for a degeneracy.
    pub(crate) fn details(self) -> Diagnosis {
        let which = |row: Option<usize>| match row {
            Some(i) => format!("equation {}", i + 1),
            None => "your equation".to_string(),
        };
        let message = match self {
            Degeneracy::EnergyLaw {
                row: None,
                velocity,
            } => format!(
                "your equation is the equation of motion multiplied by {velocity}: it is the energy law dE/dt = 0, which holds for the motion but does not determine the acceleration where {velocity} = 0 (at rest, at the turning points)"
            ),
            Degeneracy::EnergyLaw { row, .. } => format!(
                "{} is the energy law dE/dt = 0 (the equations of motion multiplied by the velocities and added): it holds for the motion but does not determine the accelerations where the velocities vanish",
                which(row)
            ),
            Degeneracy::Factor {
                row,
                factor,
                at,
                how,
            } => {
                let how = match how {
                    Vanishing::Zero => "vanishes".to_string(),
                    Vanishing::Rounding => {
                        "vanishes (to within 1e-12 of its typical size, the limit of the arithmetic)"
                            .to_string()
                    }
                    Vanishing::Undefined => "is undefined".to_string(),
                    Vanishing::Negligible(r) => {
                        format!("becomes negligible ({r:.0e} of its typical size)")
                    }
                };
                format!(
                    "{} is multiplied by {factor}, which {how} at {at}: there it no longer determines the accelerations",
                    which(row)
                )
            }
            Degeneracy::Vanishes { at } => format!(
                "your equations hold for the motion but stop determining the accelerations at {at}: they are the right ones multiplied by something that vanishes there"
            ),
            Degeneracy::Undefined { at } => format!(
                "your equations are undefined at {at}, where the right ones determine the accelerations"
            ),
        };
        Diagnosis::new(Code::VanishingFactor, message)
    }
}

/// How a factor fails at the point shown.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Vanishing {
    /// It is 0 there.
    Zero,
    /// It is 0 up to rounding there (below 1e-12 of its typical size, not exactly 0).
    Rounding,
    /// It is undefined there.
    Undefined,
    /// It is this fraction (below the tolerance) of its typical size there.
    Negligible(f64),
}

/// Puts what was found into a reason: the energy law, a named factor, or where.
pub(super) fn explain(p: &mut Prepared, res: &[Id], found: Found) -> Degeneracy {
    if let Some(d) = energy_law(p, res) {
        return d;
    }
    let Found::At { x, undefined } = found;
    if let Some(f) = vanishing_factor(p, res, &x) {
        let vars = p.system.pool.variables(f.factor);
        return Degeneracy::Factor {
            row: f.row,
            factor: p.system.pool.display(f.factor, Style::Unicode),
            at: state_text(p, &f.at, Some(&vars)),
            how: f.how,
        };
    }
    if undefined {
        Degeneracy::Undefined {
            at: state_text(p, &x, None),
        }
    } else {
        Degeneracy::Vanishes {
            at: state_text(p, &x, None),
        }
    }
}

/// The row that is the energy law Σ q̇ᵢ·Eᵢ = 0 (up to a constant factor), if any.
fn energy_law(p: &mut Prepared, res: &[Id]) -> Option<Degeneracy> {
    let coords = p.system.coordinate_syms();
    let equations = p.derivation.equations();
    let terms: Vec<Id> = coords
        .iter()
        .zip(&equations)
        .map(|(&c, &e)| {
            let v = p.system.pool.var(c, 1);
            p.system.pool.mul(v, e)
        })
        .collect();
    let law = p.system.pool.sum(terms);
    let row = res
        .iter()
        .position(|&r| proportional(&p.system, r, law, &p.points, tolerance::SAME))?;
    let velocity = match coords.as_slice() {
        [c] => {
            let v = p.system.pool.var(*c, 1);
            p.system.pool.display(v, Style::Unicode)
        }
        _ => "the velocities".to_string(),
    };
    Some(Degeneracy::EnergyLaw {
        row: (res.len() > 1).then_some(row),
        velocity,
    })
}

/// A factor of an answer's equation that vanishes (or is undefined), and where.
struct VanishingFactor {
    row: Option<usize>,
    factor: Id,
    at: Vec<f64>,
    how: Vanishing,
}

/// A factor of one of the answer's equations, free of accelerations, that vanishes or is
/// undefined at `x` (or within rounding of it: a zero found by bisection).
fn vanishing_factor(p: &Prepared, res: &[Id], x: &[f64]) -> Option<VanishingFactor> {
    for (i, &r) in res.iter().enumerate() {
        let Node::Mul(factors) = p.system.pool.node(r) else {
            continue;
        };
        for &f in factors.iter() {
            // A factor with an acceleration is the equation itself; a number never vanishes.
            let vars = p.system.pool.variables(f);
            if vars.is_empty() || vars.iter().any(|v| v.1 == 2) {
                continue;
            }
            let Ok(prog) = p.system.compile(&[f]) else {
                continue;
            };
            let value = |x: &[f64]| prog.eval(x).ok().map(|v| v[0]);
            let typical = median(
                p.points
                    .points
                    .iter()
                    .filter_map(|s| value(s).map(f64::abs))
                    .collect(),
            )
            .unwrap_or(1.0);
            let at = match value(x) {
                None => Some(x.to_vec()),
                Some(h) => (h.abs() <= tolerance::SAME * typical).then(|| rounded(x, &value)),
            };
            if let Some(at) = at {
                // A sign change through a pole (1/θ̇) leaves a huge value at the bisected
                // point: the factor is undefined there, not zero.
                let how = match value(&at).map(|v| v.abs() / typical) {
                    None => Vanishing::Undefined,
                    Some(r) if r >= 1.0 => Vanishing::Undefined,
                    Some(0.0) => Vanishing::Zero,
                    Some(r) if r <= NUMERICAL_ZERO => Vanishing::Rounding,
                    Some(r) => Vanishing::Negligible(r),
                };
                let row = (res.len() > 1).then_some(i);
                return Some(VanishingFactor {
                    row,
                    factor: f,
                    at,
                    how,
                });
            }
        }
    }
    None
}

/// `x` with each entry that is 0 up to rounding (a zero found by bisection carries noise,
/// θ̇ = −6.7e-16) shown as 0, when the factor is no larger there.
fn rounded(x: &[f64], value: &dyn Fn(&[f64]) -> Option<f64>) -> Vec<f64> {
    let Some(here) = value(x).map(f64::abs) else {
        return x.to_vec();
    };
    let mut out = x.to_vec();
    for k in 0..out.len() {
        if out[k] != 0.0 && out[k].abs() <= 1e-12 {
            let keep = out[k];
            out[k] = 0.0;
            if value(&out).is_none_or(|v| v.abs() > here.max(f64::MIN_POSITIVE)) {
                out[k] = keep;
            }
        }
    }
    out
}

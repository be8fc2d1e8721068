//! What a Lagrangian part accepts: L = T − V up to an added constant and up to a total time
//! derivative dF(q, t)/dt (another gauge: the same L, with momenta shifted by ∂F/∂q). A
//! constant factor (2L, and V − T = −L) gives the same equations of motion but is not the
//! Lagrangian asked for — its momenta and its energy function h are scaled too — so it is a
//! `constant-factor` (or `sign-error`) unless the part opts in with `accept = "same-motion"`.

use super::compare::{Relation, fmt_value, relate};
use super::diagnose::nice_fraction;
use super::prepare::Prepared;
use super::tolerance;
use super::verdict::{Code, Diagnosis};
use crate::expr::Id;
use crate::problem::{Part, PartKind, Quantity};

/// Whether `part` asks for the Lagrangian (a `lagrangian` part, or an expression part whose
/// quantity is L).
pub(super) fn asks_lagrangian(part: &Part) -> bool {
    part.kind == PartKind::Lagrangian || part.quantity == Quantity::Lagrangian
}

/// How a student's L that is not the reference up to a constant relates to it through the
/// motion it gives.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Motion {
    /// The same Euler–Lagrange expressions: L differs by a total time derivative.
    Gauge,
    /// `f` times the reference's Euler–Lagrange expressions (f ≠ 1): the same motion,
    /// another Lagrangian; `derivative` when a total time derivative is added to f·L as well.
    Scaled { f: f64, derivative: bool },
}

/// The Euler–Lagrange expressions d/dt ∂L/∂q̇ − ∂L/∂q of `l`, one per coordinate.
fn euler_lagrange(p: &mut Prepared, l: Id) -> Vec<Id> {
    let coords = p.system.coordinate_syms();
    coords
        .iter()
        .map(|&c| {
            let pm = p.system.pool.diff(l, c, 1);
            let dp = p.system.pool.dt(pm, &coords);
            let dl = p.system.pool.diff(l, c, 0);
            p.system.pool.sub(dp, dl)
        })
        .collect()
}

/// The one constant factor between the Euler–Lagrange expressions of `a` and those of `b`
/// (1 when they are equal), or `None` when they are not so related.
fn motion_factor(p: &mut Prepared, a: Id, b: Id) -> Option<f64> {
    let (ea, eb) = (euler_lagrange(p, a), euler_lagrange(p, b));
    let mut factor: Option<f64> = None;
    for (x, y) in ea.into_iter().zip(eb) {
        let f = match relate(&p.system, x, y, &p.points, tolerance::SAME).ok()? {
            Relation::Equal => 1.0,
            Relation::Factor(f) => f,
            _ => return None,
        };
        if factor.is_some_and(|g| (g - f).abs() > tolerance::NUMBER * f.abs().max(1.0)) {
            return None;
        }
        factor = Some(f);
    }
    factor
}

/// How `s` relates to the reference L through the motion (`None`: another motion). `factor`
/// is the constant factor between the two Lagrangians themselves, when the comparison found
/// one.
pub(super) fn motion(
    p: &mut Prepared,
    s: Id,
    reference: Id,
    factor: Option<f64>,
) -> Option<Motion> {
    if let Some(f) = factor {
        return Some(Motion::Scaled {
            f,
            derivative: false,
        });
    }
    let f = motion_factor(p, s, reference)?;
    Some(if (f - 1.0).abs() <= tolerance::NUMBER {
        Motion::Gauge
    } else {
        Motion::Scaled {
            f,
            derivative: true,
        }
    })
}

/// The note on an L accepted for giving the reference's motion.
pub(super) fn accepted(m: Motion) -> Diagnosis {
    match m {
        Motion::Gauge => Diagnosis::new(
            Code::TotalDerivative,
            "your L differs from T − V by a total time derivative dF/dt (another gauge): it gives the same equations of motion, and the momenta that follow from it differ by ∂F/∂q",
        ),
        Motion::Scaled { f, .. } => Diagnosis::new(
            Code::EquivalentLagrangian,
            format!(
                "your L gives {} times the equations of motion of T − V; this part accepts any Lagrangian with the right motion",
                shown(f)
            ),
        ),
    }
}

/// Why an L with the reference's motion but another scale is not the Lagrangian asked for:
/// `sign-error` for V − T, `constant-factor` otherwise.
pub(super) fn refused(m: Motion) -> Option<Diagnosis> {
    let Motion::Scaled { f, derivative } = m else {
        return None;
    };
    let what = if derivative {
        format!(
            "your L is {} times T − V plus a total time derivative",
            shown(f)
        )
    } else if (f + 1.0).abs() <= tolerance::NUMBER {
        "your L is V − T, the negative of T − V".to_string()
    } else {
        format!("your L is {} times T − V", shown(f))
    };
    let code = if (f + 1.0).abs() <= tolerance::NUMBER {
        Code::SignError
    } else {
        Code::ConstantFactor
    };
    Some(Diagnosis::new(
        code,
        format!(
            "{what}: it gives the same equations of motion, but it is not the Lagrangian asked for — the momenta ∂L/∂q̇ and the energy function h it gives are {} times the right ones. L = T − V (an added constant is free)",
            shown(f)
        ),
    ))
}

/// A factor as a fraction when it is one (`2`, `−1`, `1/2`), else a decimal.
fn shown(f: f64) -> String {
    nice_fraction(f).unwrap_or_else(|| fmt_value(f))
}

//! Linearized parts (`about = { theta = 0 }`): the system a part is checked against is
//! replaced by its Taylor polynomial about the point — T, V and L to second order in the
//! displacements q − q₀ and the velocities q̇, the generalized forces to first — so that the
//! reference, the truth verification proves it against and the true accelerations a student's
//! equations must give are all those of the linearized motion. A wrong answer is expanded in
//! turn, to tell a student who did not expand, or expanded to another order.

use super::compare::{Relation, relate};
use super::prepare::{Prepared, residuals};
use super::taylor::{ORDER, taylor};
use super::tolerance;
use super::verdict::{Code, Diagnosis, Status, Verdict};
use crate::expr::{Id, read_expr};
use crate::problem::{Part, PartKind, Quantity};

/// Why an answer to a linearized part is wrong, when it is about the expansion: right but not
/// expanded (the full V, sin θ kept), the second-order term dropped, or terms beyond second
/// order kept. Added to a wrong verdict; nothing for other parts.
pub(super) fn diagnose(part: &Part, p: &mut Prepared, input: &str, v: &mut Verdict) {
    let Some(point) = p.expansion.as_ref().map(|f| f.point.clone()) else {
        return;
    };
    if v.status == Status::Correct || v.status == Status::Invalid {
        return;
    }
    let at = at_text(p, &point);
    let d = match part.kind {
        PartKind::Equation | PartKind::Equations => equations(part, p, input, &point, &at),
        _ => expression(part, p, input, &point, &at),
    };
    if let Some(d) = d {
        // The expansion is the mistake: the term-level findings only say it again, worse.
        v.diagnoses.retain(|x| {
            !matches!(
                x.code,
                Code::NotEqual
                    | Code::MissingTerm
                    | Code::ExtraTerm
                    | Code::WrongFactor
                    | Code::WrongEquation
                    | Code::RightInLimit
                    | Code::SmallAngle
            )
        });
        v.diagnoses.push(d);
    }
}

/// `θ = 0, x = 0`: the expansion point as a student reads it.
fn at_text(p: &Prepared, point: &[Id]) -> String {
    let pool = &p.system.pool;
    p.system
        .coordinates
        .iter()
        .zip(point)
        .map(|(c, &v)| {
            format!(
                "{} = {}",
                crate::expr::names::unicode_name(&c.name),
                pool.unicode(v)
            )
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// Whether `a` and `b` are the same answer to this part (up to the constant it allows).
fn same(part: &Part, p: &Prepared, a: Id, b: Id) -> bool {
    let free_constant = part.up_to_constant
        || part.kind == PartKind::Lagrangian
        || matches!(
            part.quantity,
            Quantity::Lagrangian | Quantity::EnergyFunction
        );
    match relate(&p.system, a, b, &p.points, tolerance::SAME) {
        Ok(Relation::Equal) => true,
        Ok(Relation::UpToConstant(_)) => free_constant,
        _ => false,
    }
}

fn expression(
    part: &Part,
    p: &mut Prepared,
    input: &str,
    point: &[Id],
    at: &str,
) -> Option<Diagnosis> {
    let s = match crate::expr::read(input, &p.context, &mut p.system.pool).ok()? {
        crate::expr::Reading::Expr(e, _) => e,
        crate::expr::Reading::Equation { rhs, .. } => rhs,
        _ => return None,
    };
    let reference = read_expr(&part.answers[0], &p.context, &mut p.system.pool).ok()?;
    let s2 = taylor(&mut p.system, s, point, ORDER);
    if same(part, p, s2, reference) {
        // Right to second order: what it has beyond is the mistake.
        return Some(if super::limits::has_function_of_coordinate(p, s) {
            Diagnosis::new(
                Code::NotExpanded,
                format!(
                    "your answer is right but not expanded: this part asks for its Taylor polynomial to second order about {at} (cos θ ≈ 1 − θ²/2, sin θ ≈ θ; keep terms up to second order in the displacements and velocities)"
                ),
            )
        } else {
            Diagnosis::new(
                Code::ExpansionOrder,
                format!(
                    "your answer keeps terms beyond second order about {at}: this part asks for the expansion to second order, so drop the higher powers"
                ),
            )
        });
    }
    for k in (0..ORDER).rev() {
        let low = taylor(&mut p.system, reference, point, k);
        if same(part, p, s, low) {
            let missing = p.system.pool.sub(reference, low);
            let missing = p.system.simplify(missing);
            return Some(Diagnosis::new(
                Code::ExpansionOrder,
                format!(
                    "your answer stops at order {k} about {at}: the second-order term {} is missing (this part asks for the expansion to second order)",
                    p.system.pool.unicode(missing)
                ),
            ));
        }
    }
    None
}

fn equations(
    part: &Part,
    p: &mut Prepared,
    input: &str,
    point: &[Id],
    at: &str,
) -> Option<Diagnosis> {
    let res = residuals(p, &[input.to_string()]).ok()?;
    let linear: Vec<Id> = res
        .iter()
        .map(|&r| taylor(&mut p.system, r, point, ORDER - 1))
        .collect();
    if linear == res {
        return None;
    }
    let system = part.kind == PartKind::Equations;
    match super::equations::equations_hold(p, &linear, system) {
        Ok(None) => Some(Diagnosis::new(
            Code::NotExpanded,
            format!(
                "your equation{} linearize{} to the right ones, but {} not linearized: this part asks for the equations of motion linearized about {at} (sin θ ≈ θ, cos θ ≈ 1, and drop products of small quantities such as θ̇² and θ·θ̈)",
                if system { "s" } else { "" },
                if system { "" } else { "s" },
                if system { "they are" } else { "it is" },
            ),
        )),
        _ => None,
    }
}

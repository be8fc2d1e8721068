//! Verification: every stated answer of a problem is proved against the physics before a
//! student sees it — dimensions, the Lagrangian from bodies against the stated one, equations
//! of motion through their accelerations, equilibria (none missing, none spurious, stated
//! stability), frequencies from the eigen-solver, and the energy function, momenta, T, V and
//! constraint forces; and every `wrong` example must indeed be wrong. This file holds the entry
//! point and the per-part dispatch; each kind of part is proved in its own `verify_*` sibling.

use super::FindingCode;
use super::finding::Finding;
use super::verify_equilibria::verify_equilibria;
use super::verify_expression::{verify_equations, verify_expression, verify_values};
use super::verify_frequencies::verify_frequencies;
use super::verify_steady::verify_steady;
use crate::check::compare::{Relation, relate};
use crate::check::points::PointSet;
use crate::check::prepare::{POINTS, prepare};
use crate::check::tolerance;
use crate::expr::Dimension;
use crate::mechanics::sample::seed_from;
use crate::problem::{Part, PartKind, Problem, Quantity};

/// Verifies a problem; an empty list means every stated answer holds. A problem with
/// variants is proved for each student's numbers too (`verify_variants.rs`).
pub fn verify(problem: &Problem) -> Vec<Finding> {
    let mut out = verify_one(problem);
    // `verify_one` is passed in so that the variants' file does not import this one.
    out.extend(super::verify_variants::verify_variants(problem, verify_one));
    out
}

/// Verifies a problem as it stands (with its parameters' ranges, pinned or not).
pub(super) fn verify_one(problem: &Problem) -> Vec<Finding> {
    let mut out = Vec::new();
    let whole = |line: usize, code: FindingCode, message: String| Finding {
        file: problem.file.clone(),
        problem: Some(problem.id.clone()),
        part: None,
        line,
        code,
        message,
    };
    let sys = &problem.system;
    let energy = Dimension::energy();
    for (what, e) in [
        ("L", Some(sys.lagrangian)),
        ("T", sys.kinetic),
        ("V", sys.potential),
    ] {
        let Some(e) = e else { continue };
        match sys.pool.dimension(e, &problem.dims) {
            Ok(Some(d)) if d != energy && !sys.pool.is_zero(e) => out.push(whole(
                problem.lagrangian_line,
                FindingCode::Dimension,
                format!(
                    "{what} = {} has dimension {d}, not an energy (M L² T⁻²)",
                    sys.pool.unicode(e)
                ),
            )),
            Err(err) => out.push(whole(
                problem.lagrangian_line,
                FindingCode::Dimension,
                format!("{what}: {err}"),
            )),
            _ => {}
        }
    }
    if let Some(stated) = problem.stated_lagrangian
        && stated != sys.lagrangian
    {
        let mut s = sys.clone();
        match PointSet::draw(
            &s,
            &problem.assumptions,
            seed_from(&[&problem.id, "lagrangian"]),
            POINTS,
        )
        .and_then(|pts| relate(&s, stated, s.lagrangian, &pts, tolerance::SAME))
        {
            Ok(Relation::Equal | Relation::UpToConstant(_)) => {}
            Ok(_) => {
                let derived = s.simplify(s.lagrangian);
                out.push(whole(
                    problem.lagrangian_line,
                    FindingCode::LagrangianMismatch,
                    format!(
                        "the stated L = {} is not the L of the bodies, {}",
                        s.pool.unicode(stated),
                        s.pool.unicode(derived)
                    ),
                ));
            }
            Err(e) => out.push(whole(
                problem.lagrangian_line,
                FindingCode::Sampling,
                e.to_string(),
            )),
        }
    }
    for part in &problem.parts {
        if let Err(f) = verify_part(problem, part) {
            out.push(f);
        }
    }
    out
}

fn verify_part(problem: &Problem, part: &Part) -> Result<(), Finding> {
    let fail = |code: FindingCode, message: String| Finding {
        file: problem.file.clone(),
        problem: Some(problem.id.clone()),
        part: Some(part.id.clone()),
        line: part.line,
        code,
        message,
    };
    // A part the engine derives nothing for would be "proved" without any check.
    if let Some(why) = unprovable(part) {
        return Err(fail(FindingCode::Unprovable, why));
    }
    // A prompt that asks about stability is answered in full only with it.
    if part.kind == PartKind::Equilibria && part.prompt_asks_stability() && !part.require_stability
    {
        return Err(fail(
            FindingCode::StabilityNotRequired,
            "the prompt asks about stability, but the part does not require it: an answer without any stability would get full marks; set `require_stability = true` (with `stability`, one word per point)".into(),
        ));
    }
    let mut p = prepare(problem, part).map_err(|e| fail(FindingCode::Unusable, e.to_string()))?;
    let physics = match part.kind {
        PartKind::Expression | PartKind::Lagrangian | PartKind::ConstraintForce => {
            verify_expression(problem, part, &mut p).map_err(|f| fail(f.code, f.message))
        }
        PartKind::Equation | PartKind::Equations => {
            verify_equations(part, &mut p).map_err(|f| fail(f.code, f.message))
        }
        PartKind::Equilibria => {
            verify_equilibria(problem, part, &mut p).map_err(|f| fail(f.code, f.message))
        }
        PartKind::Frequencies => {
            verify_frequencies(problem, part, &mut p).map_err(|f| fail(f.code, f.message))
        }
        PartKind::Values => verify_values(part, &mut p).map_err(|f| fail(f.code, f.message)),
        PartKind::SteadyMotion => {
            verify_steady(problem, part, &mut p).map_err(|f| fail(f.code, f.message))
        }
    };
    physics?;
    // The checker must accept the reference as written and reject every `wrong` example.
    let reference = part.reference_text(p.system.n());
    let v = crate::check::answer::check_prepared(problem, part, &mut p, &reference);
    if v.status != crate::check::Status::Correct {
        let why: Vec<String> = v.diagnoses.iter().map(|d| d.message.clone()).collect();
        return Err(fail(
            FindingCode::ReferenceRejected,
            format!(
                "the checker does not accept the reference answer `{reference}`: {}",
                why.join("; ")
            ),
        ));
    }
    for w in &part.wrong {
        let v = crate::check::answer::check_prepared(problem, part, &mut p, w);
        // A `wrong` example that cannot be checked proves nothing: it is a typo in the file.
        if v.status == crate::check::Status::Invalid {
            let why: Vec<String> = v.diagnoses.iter().map(|d| d.message.clone()).collect();
            return Err(fail(
                FindingCode::UnreadableWrong,
                format!(
                    "the `wrong` example `{w}` cannot be checked: {}",
                    why.join("; ")
                ),
            ));
        }
        if v.status == crate::check::Status::Correct {
            return Err(fail(
                FindingCode::WrongAccepted,
                format!("the `wrong` example `{w}` is in fact correct"),
            ));
        }
    }
    Ok(())
}

/// Why a part the engine derives nothing for cannot be proved (it would pass unchecked).
fn unprovable(part: &Part) -> Option<String> {
    let needs_quantity = matches!(
        part.kind,
        PartKind::Expression | PartKind::Lagrangian | PartKind::ConstraintForce | PartKind::Values
    );
    if part.quantity != Quantity::None || !needs_quantity {
        return None;
    }
    let known = if part.kind == PartKind::Values {
        "cyclic"
    } else {
        "kinetic, potential, lagrangian, momentum, energy-function, multiplier, acceleration"
    };
    Some(format!(
        "verification cannot prove this {} part: say what it is with `quantity` ({known})",
        part.kind.name()
    ))
}

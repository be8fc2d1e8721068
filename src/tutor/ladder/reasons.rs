//! The tutor's own reasons for a wrong step, on top of the checker's: a step's
//! [`Pitfall`]s (the answer a known mistake gives, with its sentence), a differentiation left
//! to the tool (`d/dt(…)` of the step's input), and a position judged component by component
//! in the order the step asks.

use crate::check::compare::{Relation, proportional, relate};
use crate::check::prepare::Prepared;
use crate::check::{Code, Diagnosis, Status, Verdict, tolerance};
use crate::expr::{Id, Reading, read, read_equation, read_expr};
use crate::problem::PartKind;
use crate::tutor::ladder::step::{Pitfall, Step};

/// Whether `step` asks the student to differentiate (so `d/dt(…)` typed in the answer leaves
/// the step's work to the tool).
pub(super) fn asks_to_differentiate(step: &Step) -> bool {
    let kind = step.id.split(':').next().unwrap_or_default();
    matches!(
        kind,
        "momentum-rate" | "speed-squared" | "angular-speed-squared"
    )
}

/// Whether `input`, squared, is the step's reference: the speed given where its square is
/// asked (`l θ'` for l²θ̇²).
pub(super) fn is_root_of_reference(p: &mut Prepared, step: &Step, input: &str) -> bool {
    let ctx = p.context.clone();
    let (Ok(a), Some(Ok(b))) = (
        read_expr(input, &ctx, &mut p.system.pool),
        step.part
            .answers
            .first()
            .map(|t| read_expr(t, &ctx, &mut p.system.pool)),
    ) else {
        return false;
    };
    let square = p.system.pool.mul(a, a);
    matches!(
        relate(&p.system, square, b, &p.points, tolerance::SAME),
        Ok(Relation::Equal)
    )
}

/// Whether `input` writes a time derivative with the `d/dt(…)` operator.
pub(super) fn uses_dt(input: &str) -> bool {
    let flat: String = input.chars().filter(|c| !c.is_whitespace()).collect();
    flat.contains("d/dt")
}

/// Turns an answer that leaves the differentiation to the tool into an unchecked one.
pub(super) fn refuse_dt(v: &mut Verdict) {
    v.status = Status::Invalid;
    v.score = 0.0;
    v.diagnoses = vec![Diagnosis::new(
        Code::WrongKind,
        "this step asks you to carry out the differentiation: write the derivative itself, without d/dt(…)",
    )];
}

/// The first pitfall of `step` that `input` is, judged on `p`'s points.
pub(super) fn pitfall<'s>(p: &mut Prepared, step: &'s Step, input: &str) -> Option<&'s Pitfall> {
    step.pitfalls
        .iter()
        .find(|f| matches_pitfall(p, step.part.kind, input, f))
}

/// Whether `input` is the wrong answer `f`: the same expression, or equations each a constant
/// multiple of one of `f`'s (in any order).
fn matches_pitfall(p: &mut Prepared, kind: PartKind, input: &str, f: &Pitfall) -> bool {
    let ctx = p.context.clone();
    match kind {
        PartKind::Expression => {
            let (Ok(a), Some(Ok(b))) = (
                read_expr(input, &ctx, &mut p.system.pool),
                f.answers
                    .first()
                    .map(|t| read_expr(t, &ctx, &mut p.system.pool)),
            ) else {
                return false;
            };
            matches!(
                relate(&p.system, a, b, &p.points, tolerance::SAME),
                Ok(Relation::Equal)
            )
        }
        PartKind::Equation | PartKind::Equations => {
            let Some(mine) = residuals(p, input) else {
                return false;
            };
            let mut theirs = Vec::new();
            for t in &f.answers {
                let Ok((l, r)) = read_equation(t, &ctx, &mut p.system.pool) else {
                    return false;
                };
                theirs.push(p.system.pool.sub(l, r));
            }
            mine.len() == theirs.len()
                && mine.iter().all(|&a| {
                    theirs
                        .iter()
                        .any(|&b| proportional(&p.system, a, b, &p.points, tolerance::SAME))
                })
        }
        _ => false,
    }
}

/// The residuals lhs − rhs of the equations of `input`.
fn residuals(p: &mut Prepared, input: &str) -> Option<Vec<Id>> {
    let ctx = p.context.clone();
    let reading = read(input, &ctx, &mut p.system.pool).ok()?;
    let items = match reading {
        Reading::System(items, _) | Reading::List(items, _) => items,
        one => vec![one],
    };
    items
        .into_iter()
        .map(|r| match r {
            Reading::Expr(e, _) => Some(e),
            Reading::Equation { lhs, rhs, .. } => Some(p.system.pool.sub(lhs, rhs)),
            _ => None,
        })
        .collect()
}

/// A position's component verdicts in order, each prefixed by its axis: the score is the
/// share of components right where they belong, and each wrong one says why.
pub(super) fn by_component(v: &mut Verdict, components: &[Verdict]) {
    const AXES: [&str; 3] = ["x", "y", "z"];
    let right = components
        .iter()
        .filter(|c| c.status == Status::Correct)
        .count();
    v.score = right as f64 / components.len().max(1) as f64;
    let mut diagnoses = Vec::new();
    for (i, c) in components.iter().enumerate() {
        if c.status == Status::Correct {
            continue;
        }
        let axis = AXES.get(i).copied().unwrap_or("a");
        for d in &c.diagnoses {
            diagnoses.push(Diagnosis::new(
                d.code,
                format!("{axis} component: {}", d.message),
            ));
        }
    }
    if !diagnoses.is_empty() {
        v.diagnoses = diagnoses;
    }
}

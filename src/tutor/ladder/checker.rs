//! Judging an answer to one rung: [`StepChecker`] prepares each step once and checks answers
//! against it ([`check_step`] for a single answer); a position is also checked component by
//! component in order.

use std::borrow::Cow;
use std::collections::hash_map::Entry;

use rustc_hash::FxHashMap;

use super::reasons;
use super::step::Step;
use crate::check::answer::check_prepared;
use crate::check::prepare::{Prepared, prepare};
use crate::check::{self, CheckError, Code, Diagnosis, Status, Verdict};
use crate::problem::{PartKind, Problem};

/// Checks `input` against one step. A position is also checked component by component, in
/// order (the list checker alone would accept x and y exchanged).
pub fn check_step(problem: &Problem, step: &Step, input: &str) -> Result<Verdict, CheckError> {
    StepChecker::new(problem).check(step, input)
}

/// Checks answers to the steps of one problem's ladder, preparing each step once (the first
/// answer to a step samples its points and derives what it needs; later answers reuse that).
/// This is what a session keeps while a student climbs the ladder.
pub struct StepChecker<'a> {
    problem: Cow<'a, Problem>,
    /// Per step id: the problem as the step sees it (when it is judged against its own
    /// system) and the prepared part.
    prepared: FxHashMap<String, (Option<Problem>, Prepared)>,
}

impl<'a> StepChecker<'a> {
    /// A checker for the steps of `problem`'s ladder.
    pub fn new(problem: &'a Problem) -> Self {
        StepChecker {
            problem: Cow::Borrowed(problem),
            prepared: FxHashMap::default(),
        }
    }

    /// A checker that owns its problem (what a session keeps while the bank it borrows from
    /// is its own).
    pub fn owned(problem: Problem) -> StepChecker<'static> {
        StepChecker {
            problem: Cow::Owned(problem),
            prepared: FxHashMap::default(),
        }
    }

    /// The problem whose ladder this checker judges.
    pub fn problem(&self) -> &Problem {
        &self.problem
    }

    /// Checks `input` against `step` (a step of this problem's ladder). Errors are usage
    /// errors (a part that cannot be prepared), never a judgement of the input.
    pub fn check(&mut self, step: &Step, input: &str) -> Result<Verdict, CheckError> {
        let problem: &Problem = &self.problem;
        let (own, prepared) = match self.prepared.entry(step.id.clone()) {
            Entry::Occupied(o) => o.into_mut(),
            Entry::Vacant(v) => {
                let own = step.against.as_ref().map(|sys| {
                    let mut own = problem.clone();
                    own.system = (**sys).clone();
                    own
                });
                let prepared = prepare(own.as_ref().unwrap_or(problem), &step.part)?;
                v.insert((own, prepared))
            }
        };
        let judged = own.as_ref().unwrap_or(problem);
        let mut v = check_prepared(judged, &step.part, prepared, input);
        if reasons::asks_to_differentiate(step) && reasons::uses_dt(input) {
            reasons::refuse_dt(&mut v);
            return Ok(v);
        }
        // Another coordinate's equation holds for the motion too, but is not this step's.
        let judged_wrong =
            |f: &&super::Pitfall| v.status == Status::Incorrect || f.code == Code::WrongEquation;
        if v.status != Status::Invalid
            && let Some(f) = reasons::pitfall(prepared, step, input).filter(judged_wrong)
        {
            v.status = Status::Incorrect;
            v.score = 0.0;
            v.diagnoses = vec![Diagnosis::new(f.code, f.message.clone())];
        }
        let kind = step.id.split(':').next().unwrap_or_default();
        if v.status == Status::Incorrect
            && matches!(kind, "speed-squared" | "angular-speed-squared")
            && reasons::is_root_of_reference(prepared, step, input)
        {
            let what = if kind == "speed-squared" {
                "the speed"
            } else {
                "the angular speed"
            };
            v.score = 0.0;
            v.diagnoses = vec![Diagnosis::new(
                Code::WrongFactor,
                format!("that is {what}; this step asks for its square"),
            )];
        }
        if step.id.starts_with("position:") {
            if v.status == Status::Correct {
                order_of_components(problem, step, input, &mut v)?;
            } else if v.status == Status::Incorrect
                && let Some(each) = components(problem, step, input)?
            {
                // A vector in a stated order: each component is judged in its place.
                reasons::by_component(&mut v, &each);
                if other_axes(problem, step, input)? {
                    v.diagnoses = vec![Diagnosis::new(Code::Convention, axes_message(problem))];
                }
            }
        }
        Ok(v)
    }
}

/// Each component of a position checked against the step's component in the same place
/// (`None` when the answer has another number of components).
fn components(
    problem: &Problem,
    step: &Step,
    input: &str,
) -> Result<Option<Vec<Verdict>>, CheckError> {
    let items = split_top_level(input);
    if items.len() != step.part.answers.len() {
        return Ok(None);
    }
    let mut out = Vec::new();
    for (item, answer) in items.iter().zip(&step.part.answers) {
        let mut part = step.part.clone();
        part.kind = PartKind::Expression;
        part.answers = vec![answer.clone()];
        out.push(check::check(problem, &part, item)?);
    }
    Ok(Some(out))
}

/// Turns a correct but reordered position into an incorrect one.
fn order_of_components(
    problem: &Problem,
    step: &Step,
    input: &str,
    v: &mut Verdict,
) -> Result<(), CheckError> {
    let items = split_top_level(input);
    if items.len() != step.part.answers.len() {
        return Ok(());
    }
    for (i, (item, answer)) in items.iter().zip(&step.part.answers).enumerate() {
        let mut part = step.part.clone();
        part.kind = PartKind::Expression;
        part.answers = vec![answer.clone()];
        let c = check::check(problem, &part, item)?;
        if c.status != Status::Correct {
            v.status = Status::Incorrect;
            v.score = 0.0;
            // The same point in axes named or ordered otherwise: a convention, not a slip.
            v.diagnoses.push(Diagnosis::new(
                Code::Convention,
                format!(
                    "{} (the right components in another order: component {} should be {})",
                    axes_message(problem),
                    i + 1,
                    answer
                ),
            ));
            return Ok(());
        }
    }
    Ok(())
}

/// The sentence of a position right in other axes: the axes the step uses.
fn axes_message(problem: &Problem) -> String {
    match problem.axes.as_str() {
        "" => "convention: your position is right in other axes (rotated, reflected or reordered, or with another phase of the rotation); use the axes of the problem's statement".into(),
        a => format!(
            "convention: your position is right in other axes (rotated, reflected or reordered, or with another phase of the rotation); this step uses: {a}"
        ),
    }
}

/// Whether a wrong position is the reference in other axes about the same origin: the same
/// distance from the origin and the same speed at every sample point (a constant rotation or
/// reflection of the axes, their order, a phase of the rotation or its sense keep both), with
/// as many components.
fn other_axes(problem: &Problem, step: &Step, input: &str) -> Result<bool, CheckError> {
    let items = split_top_level(input);
    let answers = &step.part.answers;
    if items.len() != answers.len() || items.iter().any(|x| x.is_empty()) {
        return Ok(false);
    }
    let square = |xs: &[&str], rate: bool| -> String {
        xs.iter()
            .map(|x| {
                if rate {
                    format!("(d/dt({x}))^2")
                } else {
                    format!("({x})^2")
                }
            })
            .collect::<Vec<_>>()
            .join(" + ")
    };
    let reference: Vec<&str> = answers.iter().map(String::as_str).collect();
    for rate in [false, true] {
        let mut part = step.part.clone();
        part.kind = PartKind::Expression;
        part.answers = vec![square(&reference, rate)];
        let c = check::check(problem, &part, &square(&items, rate))?;
        if c.status != Status::Correct {
            return Ok(false);
        }
    }
    Ok(true)
}

/// Splits `a, b, (c, d)` at the commas outside brackets (also `;`).
fn split_top_level(input: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let (mut depth, mut start) = (0i32, 0usize);
    let trimmed = input.trim();
    let inner = match (trimmed.strip_prefix('('), trimmed.strip_suffix(')')) {
        (Some(_), Some(_)) if trimmed.len() >= 2 => &trimmed[1..trimmed.len() - 1],
        _ => trimmed,
    };
    for (i, ch) in inner.char_indices() {
        match ch {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            ',' | ';' if depth == 0 => {
                out.push(inner[start..i].trim());
                start = i + ch.len_utf8();
            }
            _ => {}
        }
    }
    out.push(inner[start..].trim());
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splits_at_top_level_commas() {
        assert_eq!(split_top_level("(a, f(b, c))"), vec!["a", "f(b, c)"]);
        assert_eq!(split_top_level("x; y"), vec!["x", "y"]);
    }
}

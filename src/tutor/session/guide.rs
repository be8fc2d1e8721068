//! The guided derivation: `:tutor` walks the open problem's derivation ladder step by step,
//! with answers to steps, `:show`, `:back` and `:hint` there.

use super::replies::{no_problem, not_in_tutor};
use super::{Session, Tutor};
use crate::check::Status;
use crate::tutor::ladder::{StepChecker, ladder};
use crate::tutor::response::{
    HintReply, Response, StepPrompt, StepSolutionReply, StepVerdictReply,
};

/// The tutor: `:tutor`, answers to steps, `:show`, `:back` and `:hint` there.
impl Session {
    /// Whether answers go to the guided derivation (after `:tutor`, until `:back` or the
    /// last step).
    pub fn in_tutor(&self) -> bool {
        self.tutor_ref().is_some_and(|t| t.active)
    }

    /// The current tutor step's id, while in the tutor.
    pub fn current_step(&self) -> Option<&str> {
        let t = self.tutor_ref().filter(|t| t.active)?;
        t.steps.get(t.current).map(|s| s.id.as_str())
    }

    fn tutor_ref(&self) -> Option<&Tutor> {
        self.open.as_ref()?.tutor.as_ref()
    }

    /// `:tutor`: builds the ladder on first use, then asks the current step (from the first
    /// step again once the ladder was climbed to the end).
    pub(super) fn tutor(&mut self) -> Vec<Response> {
        let Some(o) = self.open.as_mut() else {
            return vec![no_problem()];
        };
        let problem = &self.bank.problems[o.problem];
        if o.tutor.is_none() {
            match ladder(problem) {
                Ok(steps) if !steps.is_empty() => {
                    o.tutor = Some(Tutor {
                        attempts: vec![0; steps.len()],
                        hints: vec![0; steps.len()],
                        steps,
                        checker: StepChecker::owned(problem.clone()),
                        current: 0,
                        active: false,
                    });
                }
                Ok(_) => {
                    let msg = format!("`{}` has no derivation to walk through", problem.id);
                    return vec![Response::error("no-ladder", msg, None)];
                }
                Err(e) => {
                    let msg = format!("cannot build the derivation of `{}`: {e}", problem.id);
                    return vec![Response::error("no-ladder", msg, None)];
                }
            }
        }
        let Some(t) = o.tutor.as_mut() else {
            return vec![no_problem()];
        };
        if t.current >= t.steps.len() {
            t.current = 0;
        }
        t.active = true;
        step_prompt(&problem.id, t, t.current, None)
            .map(Response::Step)
            .into_iter()
            .collect()
    }

    /// An answer to the current step: its verdict, with `next` when it is correct. After the
    /// last step the tutor is left (answers go to the parts again).
    pub(super) fn step_answer(&mut self, input: &str) -> Vec<Response> {
        let Some(o) = self.open.as_mut() else {
            return vec![no_problem()];
        };
        let pid = self.bank.problems[o.problem].id.clone();
        let Some(t) = o.tutor.as_mut().filter(|t| t.active) else {
            return vec![not_in_tutor()];
        };
        let Some(step) = t.steps.get(t.current) else {
            return vec![not_in_tutor()];
        };
        let verdict = match t.checker.check(step, input) {
            Ok(v) => v,
            Err(e) => {
                let msg = format!("step `{}` cannot be checked: {e}", step.id);
                return vec![Response::error(e.code(), msg, None)];
            }
        };
        let (index, id) = (t.current, step.id.clone());
        if verdict.status != Status::Invalid
            && let Some(a) = t.attempts.get_mut(index)
        {
            *a = a.saturating_add(1);
        }
        let next = (verdict.status == Status::Correct).then(|| advance(&pid, t));
        vec![Response::StepVerdict(StepVerdictReply {
            verdict,
            step: id,
            number: index + 1,
            total: t.steps.len(),
            attempts: t.attempts.get(index).copied().unwrap_or(0),
            next,
        })]
    }

    /// `:show`: the current step's reference (plain and Unicode), then the next step.
    pub(super) fn show(&mut self) -> Vec<Response> {
        let Some(o) = self.open.as_mut() else {
            return vec![no_problem()];
        };
        let problem = &self.bank.problems[o.problem];
        let Some(t) = o.tutor.as_mut().filter(|t| t.active) else {
            return vec![not_in_tutor()];
        };
        let Some(step) = t.steps.get(t.current) else {
            return vec![not_in_tutor()];
        };
        let answer = step.reference_text(problem.system.n());
        let unicode = t
            .checker
            .check(step, &answer)
            .map(|v| v.reading.unicode)
            .unwrap_or_default();
        let (index, id) = (t.current, step.id.clone());
        let next = advance(&problem.id, t);
        vec![Response::StepSolution(StepSolutionReply {
            problem: problem.id.clone(),
            step: id,
            number: index + 1,
            total: t.steps.len(),
            answer,
            unicode,
            next,
        })]
    }

    /// `:back`: leaves the tutor; the current part is asked again.
    pub(super) fn back(&mut self) -> Vec<Response> {
        if !self.in_tutor() {
            return vec![not_in_tutor()];
        }
        self.leave_tutor_then(|s| s.prompt().into_iter().collect())
    }

    /// Leaves the tutor (keeping its place), then carries out `then`.
    pub(super) fn leave_tutor_then(
        &mut self,
        then: impl FnOnce(&mut Self) -> Vec<Response>,
    ) -> Vec<Response> {
        if let Some(t) = self.open.as_mut().and_then(|o| o.tutor.as_mut()) {
            t.active = false;
        }
        then(self)
    }

    /// `:hint` in the tutor: the current step's next hint (generated from the step's
    /// physics); once none remain, `hint` is null and `:show` reveals the step.
    pub(super) fn step_hint(&mut self) -> Vec<Response> {
        let pid = self.current_problem().unwrap_or_default().to_string();
        let Some(t) = self
            .open
            .as_mut()
            .and_then(|o| o.tutor.as_mut())
            .filter(|t| t.active)
        else {
            return vec![not_in_tutor()];
        };
        let Some(step) = t.steps.get(t.current) else {
            return vec![not_in_tutor()];
        };
        let total = step.part.hints.len();
        let given = t.hints.get(t.current).copied().unwrap_or(0);
        let hint = step.part.hints.get(given).cloned();
        if hint.is_some()
            && let Some(h) = t.hints.get_mut(t.current)
        {
            *h += 1;
        }
        vec![Response::Hint(HintReply {
            problem: pid,
            part: step.id.clone(),
            number: if hint.is_some() {
                given + 1
            } else {
                given.min(total)
            },
            remaining: if hint.is_some() {
                total.saturating_sub(given + 1)
            } else {
                0
            },
            hint,
            reveal: ":show",
        })]
    }
}

/// Moves `t` past its current step; the step now asked (`None` after the last, when the tutor
/// is left).
fn advance(problem: &str, t: &mut Tutor) -> Option<StepPrompt> {
    t.current = (t.current + 1).min(t.steps.len());
    let next = step_prompt(problem, t, t.current, None);
    if next.is_none() {
        t.active = false;
    }
    next
}

/// Step `index` of `t` as asked.
fn step_prompt(problem: &str, t: &Tutor, index: usize, note: Option<String>) -> Option<StepPrompt> {
    let step = t.steps.get(index)?;
    Some(StepPrompt {
        problem: problem.to_string(),
        step: step.id.clone(),
        number: index + 1,
        total: t.steps.len(),
        prompt: step.prompt.clone(),
        note,
    })
}

#[cfg(test)]
mod tests {
    use super::super::tests::pendulum;
    use super::*;

    #[test]
    fn the_tutor_ends_after_its_last_step_and_starts_again() {
        let mut s = pendulum();
        s.handle(":open simple-pendulum");
        let total = match s.handle(":tutor").first() {
            Some(Response::Step(p)) => p.total,
            other => panic!("{other:?}"),
        };
        for _ in 1..total {
            s.handle(":show");
        }
        assert!(s.in_tutor());
        let last = s.handle(":show");
        assert!(matches!(&last[0], Response::StepSolution(r) if r.next.is_none()));
        assert!(!s.in_tutor() && s.current_step().is_none());
        // Answers go to the parts again; `:tutor` starts from the first step.
        assert!(matches!(&s.handle("x")[0], Response::Verdict(_)));
        assert!(matches!(&s.handle(":tutor")[0], Response::Step(p) if p.number == 1));
    }

    #[test]
    fn opening_a_problem_leaves_the_tutor_and_its_ladder() {
        let mut s = pendulum();
        s.handle(":open simple-pendulum");
        s.handle(":tutor");
        s.handle(":show");
        assert_eq!(s.current_step(), Some("speed-squared:1"));
        s.handle(":open simple-pendulum");
        assert!(!s.in_tutor());
        assert!(matches!(&s.handle(":tutor")[0], Response::Step(p) if p.step == "position:1"));
    }
}

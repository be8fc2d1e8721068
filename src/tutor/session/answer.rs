//! Answers to the current part and what helps with it: the check (each part prepared once),
//! follow-through from the student's own earlier answers, `:hint` (the problem file's hints,
//! then hints generated from the physics) and `:solution` with its worked derivation.

use super::Session;
use super::replies::no_problem;
use crate::check::answer::check_prepared;
use crate::check::prepare::prepare;
use crate::check::{Status, Verdict};
use crate::problem::{Part, PartKind, Problem, Quantity};
use crate::report;
use crate::report::problems::terminal_math;
use crate::tutor::follow::{Earlier, apply, follows_from_earlier};
use crate::tutor::ladder::ladder;
use crate::tutor::response::{HintReply, Response, SolutionReply, VerdictReply, WorkedStep};

impl Session {
    pub(super) fn answer(&mut self, input: &str) -> Vec<Response> {
        let mut verdict = match self.check_current(input) {
            Ok(v) => v,
            Err(r) => return vec![*r],
        };
        if verdict.status != Status::Invalid
            && let Some(o) = self.open.as_mut()
            && let Some(index) = o.current
        {
            o.judged.insert(index, (input.to_string(), verdict.clone()));
        }
        if verdict.status == Status::Incorrect {
            self.follow_through(input, &mut verdict);
        }
        let problem_id = verdict.problem.clone();
        let part_id = verdict.part.clone();
        if verdict.status != Status::Invalid {
            let correct = verdict.status == Status::Correct;
            self.progress
                .record_attempt(&problem_id, &part_id, input, correct);
        }
        let attempts = self
            .progress
            .part(&problem_id, &part_id)
            .map_or(0, |p| p.attempts);
        let correct = verdict.status == Status::Correct;
        let mut out = vec![Response::Verdict(VerdictReply { verdict, attempts })];
        if correct {
            out.extend(self.next());
        }
        out
    }

    /// Adds `follows-from-earlier` to an incorrect verdict on the current part when the answer
    /// follows from the student's own latest wrong answer to another part of the open problem
    /// (read from the progress, in part order: a later part counts as more recent), or accepts
    /// it when it follows from an L accepted with a total time derivative added.
    fn follow_through(&self, input: &str, verdict: &mut Verdict) {
        let (Some(problem), Some(part)) = (self.problem(), self.part()) else {
            return;
        };
        let earlier: Vec<Earlier> = problem
            .parts
            .iter()
            .filter(|q| q.id != part.id)
            .filter_map(|q| {
                let rec = self.progress.part(&problem.id, &q.id)?;
                Some(Earlier::new(q.id.as_str(), rec.last_answer()?))
            })
            .collect();
        if earlier.is_empty() {
            return;
        }
        let judged = self.open.as_ref().map(|o| &o.judged);
        let known = |e: &Earlier| {
            let index = problem.parts.iter().position(|q| q.id == e.part)?;
            let (answer, v) = judged?.get(&index)?;
            (*answer == e.answer).then(|| v.clone())
        };
        if let Some(d) = follows_from_earlier(problem, part, input, &earlier, &known) {
            apply(verdict, d);
        }
    }

    /// Checks `input` against the current part, preparing the part on first use.
    fn check_current(&mut self, input: &str) -> Result<Verdict, Box<Response>> {
        let Some(o) = self.open.as_mut() else {
            return Err(Box::new(no_problem()));
        };
        let problem = &self.bank.problems[o.problem];
        let Some(index) = o.current else {
            return Err(Box::new(Response::error(
                "no-part",
                "this problem has no part to answer",
                None,
            )));
        };
        let part = &problem.parts[index];
        // A part that accepts numbers is judged with the numbers practised, if any.
        let problem = match &o.pinned {
            Some(pinned) if part.numbers => pinned,
            _ => problem,
        };
        let prepared = o
            .prepared
            .entry(index)
            .or_insert_with(|| prepare(problem, part));
        match prepared {
            Ok(p) => Ok(check_prepared(problem, part, p, input)),
            Err(e) => Err(Box::new(Response::error(
                e.code(),
                format!("part `{}` cannot be checked: {e}", part.id),
                None,
            ))),
        }
    }

    pub(super) fn hint(&mut self) -> Vec<Response> {
        let (Some(problem), Some(part)) = (self.problem(), self.part()) else {
            return vec![self.no_part()];
        };
        let (pid, qid) = (problem.id.clone(), part.id.clone());
        // The file's hints in order, then the physics' (derived only once they are reached).
        let from_file = part.hints.len();
        let total = from_file + physics_hint_count(problem, part);
        let given = self.progress.part(&pid, &qid).map_or(0, |r| r.hints_used);
        let given = usize::try_from(given).unwrap_or(usize::MAX);
        let hint = match part.hints.get(given) {
            Some(h) => Some(terminal_math(h)),
            None if given < total => physics_hints(problem, part).get(given - from_file).cloned(),
            None => None,
        };
        if hint.is_some() {
            let rec = self.progress.part_mut(&pid, &qid);
            rec.hints_used = rec.hints_used.saturating_add(1);
        }
        let reply = HintReply {
            problem: pid,
            part: qid,
            number: if hint.is_some() {
                given + 1
            } else {
                given.min(total)
            },
            remaining: match hint {
                Some(_) => total.saturating_sub(given + 1),
                None => 0,
            },
            hint,
            reveal: ":solution",
        };
        vec![Response::Hint(reply)]
    }

    pub(super) fn solution(&mut self) -> Vec<Response> {
        let (Some(problem), Some(part)) = (self.problem(), self.part()) else {
            return vec![self.no_part()];
        };
        let answer = part.reference_text(problem.system.n());
        let derivation = worked_derivation(problem, part);
        let (pid, qid) = (problem.id.clone(), part.id.clone());
        // The reference read as an answer gives its Unicode form.
        let unicode = self
            .check_current(&answer)
            .map(|v| v.reading.unicode)
            .unwrap_or_default();
        self.progress.part_mut(&pid, &qid).revealed = true;
        vec![Response::Solution(SolutionReply {
            problem: pid,
            part: qid,
            answer,
            unicode,
            derivation,
        })]
    }

    pub(super) fn no_part(&self) -> Response {
        if self.open.is_none() {
            no_problem()
        } else {
            Response::error(
                "no-part",
                "no part is current: `:part ID|N` chooses one",
                None,
            )
        }
    }
}

/// The ladder's steps that lead to `part`, with their results: up to T, V or L for those
/// parts, up to the momenta for a momentum, up to the equations of motion for an equation,
/// and on to the equilibria or the frequencies for those.
fn worked_derivation(problem: &Problem, part: &Part) -> Vec<WorkedStep> {
    let last = match (part.kind, part.quantity) {
        (_, Quantity::Kinetic) => "kinetic",
        (_, Quantity::Potential) => "potential",
        (PartKind::Lagrangian, _) | (_, Quantity::Lagrangian) => "lagrangian",
        (_, Quantity::Momentum(_)) => "momentum:",
        (PartKind::Equation | PartKind::Equations, _) => "eom:",
        (PartKind::Equilibria, _) => "equilibria",
        (PartKind::Frequencies, _) => "frequencies",
        _ => return Vec::new(),
    };
    let Ok(steps) = ladder(problem) else {
        return Vec::new();
    };
    // Through the last step whose id matches (a prefix like `eom:` takes every coordinate).
    let Some(end) = steps.iter().rposition(|s| {
        if last.ends_with(':') {
            s.id.starts_with(last)
        } else {
            s.id == last
        }
    }) else {
        return Vec::new();
    };
    let ctx = problem.context();
    let mut pool = problem.system.pool.clone();
    steps[..=end]
        .iter()
        .map(|s| {
            let answer = s.reference_text(problem.system.n());
            let unicode = crate::expr::read(&answer, &ctx, &mut pool)
                .map(|r| r.unicode(&pool))
                .unwrap_or_default();
            WorkedStep {
                step: s.id.clone(),
                prompt: s.prompt.clone(),
                answer,
                unicode,
            }
        })
        .collect()
}

/// The hint a tutor gives first on `part` (what `:hint` says to a student who has asked for
/// none): the problem file's first hint, else the first one derived from the physics; `None`
/// when the part has none. The grader's feedback quotes it under a wrong answer.
pub fn first_hint(problem: &Problem, part: &Part) -> Option<String> {
    match part.hints.first() {
        Some(h) => Some(terminal_math(h)),
        None => physics_hints(problem, part).into_iter().next(),
    }
}

/// How many hints [`physics_hints`] gives for `part`, without deriving anything.
fn physics_hint_count(problem: &Problem, part: &Part) -> usize {
    if !part.substitute.is_empty() {
        return 0;
    }
    match (part.kind, part.quantity) {
        (_, Quantity::Momentum(_)) => 1,
        (PartKind::Equation | PartKind::Equations, _) => 3 * problem.system.n(),
        _ => 0,
    }
}

/// Hints generated from the physics, after the problem file's: for a momentum part, L and
/// what to differentiate it by; for an equation part, each coordinate's ∂L/∂q̇, its time
/// derivative and ∂L/∂q. None for a part that substitutes parameters (its system differs).
fn physics_hints(problem: &Problem, part: &Part) -> Vec<String> {
    if physics_hint_count(problem, part) == 0 {
        return vec![];
    }
    let Ok(d) = report::derivation(&problem.system) else {
        return vec![];
    };
    if let Quantity::Momentum(i) = part.quantity {
        return d
            .coordinate_labels
            .get(i)
            .map(|(_, v)| {
                let l = &d.lagrangian.unicode;
                format!("L = {l}; differentiate it with respect to {}.", v.unicode)
            })
            .into_iter()
            .collect();
    }
    let mut out = Vec::new();
    for (i, (q, v)) in d.coordinate_labels.iter().enumerate() {
        let (q, v) = (&q.unicode, &v.unicode);
        let at =
            |f: &[crate::report::Formula]| f.get(i).map_or(String::new(), |f| f.unicode.clone());
        out.push(format!("∂L/∂{v} = {}", at(&d.momenta)));
        out.push(format!("d/dt ∂L/∂{v} = {}", at(&d.momenta_dt)));
        out.push(format!(
            "∂L/∂{q} = {}; the equation is d/dt ∂L/∂{v} − ∂L/∂{q} = 0.",
            at(&d.generalized_forces)
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::super::tests::pendulum;
    use super::*;

    #[test]
    fn a_hint_counts_once_and_none_remaining_is_said() {
        let mut s = pendulum();
        s.handle(":open simple-pendulum");
        s.handle(":part lagrangian");
        let hints: Vec<_> = (0..3).flat_map(|_| s.hint()).collect();
        let remaining: Vec<_> = hints
            .iter()
            .filter_map(|r| match r {
                Response::Hint(h) => Some((h.hint.is_some(), h.remaining)),
                _ => None,
            })
            .collect();
        assert_eq!(remaining, [(true, 1), (true, 0), (false, 0)]);
        let used = s
            .progress
            .part("simple-pendulum", "lagrangian")
            .map(|p| p.hints_used);
        assert_eq!(used, Some(2));
    }

    #[test]
    fn follow_through_uses_the_kept_verdict_only_for_the_same_answer() {
        let mut s = pendulum();
        s.handle(":open simple-pendulum");
        s.handle(":part lagrangian");
        s.handle("1/2*m*l^2*theta'^2 - m*g*l*cos(theta)");
        let kept = s.open.as_ref().map(|o| o.judged.len());
        assert_eq!(kept, Some(1));
        // Progress from elsewhere (not judged here) is checked afresh, with the same result.
        let mut fresh = pendulum();
        fresh.progress = s.progress.clone();
        fresh.handle(":open simple-pendulum");
        for t in [&mut s, &mut fresh] {
            t.handle(":part eom");
            let r = t.handle("m*l^2*theta'' - m*g*l*sin(theta) = 0");
            let Some(Response::Verdict(v)) = r.first() else {
                panic!("{r:?}");
            };
            let codes: Vec<_> = v.verdict.diagnoses.iter().map(|d| d.code).collect();
            assert!(
                codes.contains(&crate::check::Code::FollowsFromEarlier),
                "{codes:?}"
            );
        }
    }
}

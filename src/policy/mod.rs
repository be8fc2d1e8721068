//! The grading policy of an assignment: how a verdict becomes a score and which attempt
//! counts. Pure data and arithmetic, shared by every face that grades (today `grade`; the
//! browser page and an LMS plug-in could offer the same rules without copying them):
//!
//! - partial credit per diagnosis code (a sign error earns half): a wrong answer earns the
//!   highest credit among its codes, or its own partial score (a list partly right) if higher;
//! - follow-through credit: a wrong answer that follows from the student's own wrong answer
//!   to another part earns a set fraction (the checking itself is [`crate::tutor::follow`]);
//! - a penalty per extra attempt, a fraction of the part's points taken from the score of the
//!   second attempt, twice from the third…, never below zero;
//! - the best or the last attempt counts.
//!
//! [`Assignment`] reads all of it, with the problems, parts, points and the course seed, from
//! an assignment file (TOML); [`Decision`] is an instructor's decision on one answer.

mod assignment;
mod decision;

pub use assignment::{Assignment, AssignmentError, ProblemEntry};
pub use decision::Decision;

use crate::check::{Code, Status};

/// Which of a student's attempts at a part counts.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Attempts {
    /// The last one, in the order the answers were given (file order).
    #[default]
    Last,
    /// The highest-scoring one after the attempt penalty (the later of equals).
    Best,
}

impl Attempts {
    /// `last` or `best`, as the assignment file spells it.
    pub fn name(self) -> &'static str {
        match self {
            Attempts::Last => "last",
            Attempts::Best => "best",
        }
    }
}

/// How answers are scored and which attempt counts. The default is what `grade` does with no
/// option: the checker's score, no code credit, no penalty, no follow-through, the last attempt.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Policy {
    /// Which attempt counts.
    pub attempts: Attempts,
    /// The fraction of a part's points lost per attempt after the first (0 ≤ p ≤ 1).
    pub(crate) penalty: f64,
    /// The credit, as a fraction of the points, of a wrong answer that follows from the
    /// student's own earlier wrong answer; `None`: no follow-through.
    pub follow_through: Option<f64>,
    /// Partial credit per diagnosis code, as a fraction of the points, sorted by code.
    pub(crate) credit: Vec<(Code, f64)>,
}

impl Policy {
    /// The fraction of the points an answer earns from its verdict: a right answer its score
    /// (1, or less for a list partly right); any other the larger of its own score and the
    /// highest credit among its codes (several codes: the highest applies).
    pub fn answer_fraction(&self, status: Status, score: f64, codes: &[Code]) -> f64 {
        if status == Status::Correct {
            return score;
        }
        codes
            .iter()
            .filter_map(|c| self.credit_of(*c))
            .fold(score, f64::max)
    }

    /// The credit set for one code, if any.
    pub fn credit_of(&self, code: Code) -> Option<f64> {
        self.credit
            .binary_search_by_key(&code, |(c, _)| *c)
            .ok()
            .map(|i| self.credit[i].1)
    }

    /// The fraction a wrong answer earns when it follows from the student's own earlier
    /// answer: the larger of its own fraction and the follow-through credit (`None` when
    /// follow-through is off).
    pub fn follow_through_fraction(&self, own: f64) -> Option<f64> {
        self.follow_through.map(|c| own.max(c))
    }

    /// The score attempt number `attempt` (1-based) keeps of `score`, on a part worth
    /// `points`: the penalty times the points is taken once per earlier attempt, down to 0.
    pub fn attempt_score(&self, score: f64, points: f64, attempt: usize) -> f64 {
        let extra = attempt.saturating_sub(1) as f64;
        if self.penalty == 0.0 || extra == 0.0 {
            return score;
        }
        (score - self.penalty * points * extra).max(0.0)
    }

    /// Which attempt counts, given each attempt's score in order (before the penalty) on a
    /// part worth `points`: its index and the score it counts for (after the penalty).
    /// `None` for no attempt.
    pub fn counted(
        &self,
        scores: impl IntoIterator<Item = f64>,
        points: f64,
    ) -> Option<(usize, f64)> {
        let mut chosen: Option<(usize, f64)> = None;
        for (i, s) in scores.into_iter().enumerate() {
            let s = self.attempt_score(s, points, i + 1);
            let better = match (self.attempts, chosen) {
                (_, None) | (Attempts::Last, _) => true,
                // The later of equals: a student who repeats a right answer is not penalised
                // for having given it first.
                (Attempts::Best, Some((_, c))) => c <= s,
            };
            if better {
                chosen = Some((i, s));
            }
        }
        chosen
    }

    /// A stable one-line description (the run id hashes it; two policies that score
    /// differently describe differently).
    pub fn describe(&self) -> String {
        let credit: Vec<String> = (self.credit.iter())
            .map(|(c, f)| format!("{c}={f}"))
            .collect();
        format!(
            "attempts={} penalty={} follow-through={:?} credit={}",
            self.attempts.name(),
            self.penalty,
            self.follow_through,
            credit.join(",")
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn policy() -> Policy {
        Policy {
            attempts: Attempts::Best,
            penalty: 0.1,
            follow_through: Some(0.5),
            credit: vec![(Code::SignError, 0.5), (Code::ConstantFactor, 0.25)],
        }
    }

    #[test]
    fn the_highest_credit_of_several_codes_applies() {
        let p = policy();
        let codes = [Code::ConstantFactor, Code::SignError];
        assert_eq!(p.answer_fraction(Status::Incorrect, 0.0, &codes), 0.5);
        assert_eq!(
            p.answer_fraction(Status::Incorrect, 0.0, &[Code::NotEqual]),
            0.0
        );
        // A list two-thirds right keeps its own score over a smaller credit.
        assert_eq!(
            p.answer_fraction(Status::Incorrect, 2.0 / 3.0, &[Code::ConstantFactor]),
            2.0 / 3.0
        );
        // A right answer is never lowered by a credit.
        assert_eq!(p.answer_fraction(Status::Correct, 1.0, &[]), 1.0);
    }

    #[test]
    fn the_penalty_is_taken_once_per_earlier_attempt_and_never_below_zero() {
        let p = policy();
        assert_eq!(p.attempt_score(2.0, 2.0, 1), 2.0);
        assert!((p.attempt_score(2.0, 2.0, 3) - 1.6).abs() < 1e-12);
        assert_eq!(p.attempt_score(0.5, 2.0, 4), 0.0);
    }

    #[test]
    fn best_takes_the_highest_after_the_penalty_and_last_the_last() {
        let mut p = policy();
        // 0, then 1 at the second attempt (0.9 after the penalty), then 1 at the third (0.8).
        assert_eq!(p.counted([0.0, 1.0, 1.0], 1.0), Some((1, 0.9)));
        p.attempts = Attempts::Last;
        let (i, s) = p.counted([0.0, 1.0, 1.0], 1.0).unwrap();
        assert_eq!(i, 2);
        assert!((s - 0.8).abs() < 1e-12);
        assert_eq!(p.counted(std::iter::empty(), 1.0), None);
        // Without a penalty, the later of equal scores counts.
        p.attempts = Attempts::Best;
        p.penalty = 0.0;
        assert_eq!(p.counted([1.0, 0.0, 1.0], 1.0), Some((2, 1.0)));
    }

    #[test]
    fn follow_through_credit_never_lowers_a_partial_score() {
        let p = policy();
        assert_eq!(p.follow_through_fraction(0.0), Some(0.5));
        assert_eq!(p.follow_through_fraction(0.75), Some(0.75));
        assert_eq!(Policy::default().follow_through_fraction(0.0), None);
    }
}

//! What judging gives: every row's [`Outcome`] (status, score, codes, message), the
//! representatives checked ([`Rep`]) and their readings, held in [`Judged`] in a form small
//! enough for a class of all-different answers (one representative per row): a
//! representative's outcome is made when asked for, not kept.

use std::borrow::Cow;
use std::sync::Arc;

use lagrange::check::{Code, Status as Checked};
use lagrange::policy::Decision;
use rustc_hash::FxHashMap;

use super::Slim;

/// The status column of results.csv.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Status {
    Correct,
    Incorrect,
    /// The answer could not be read (or is too long to read).
    Invalid,
    /// The row could not be graded at all (bad line, unknown problem or part, empty answer).
    Error,
}

impl From<Checked> for Status {
    fn from(s: Checked) -> Status {
        match s {
            Checked::Correct => Status::Correct,
            Checked::Incorrect => Status::Incorrect,
            Checked::Invalid => Status::Invalid,
        }
    }
}

impl Status {
    /// The name written in results.csv and the summary.
    pub fn name(self) -> &'static str {
        match self {
            Status::Correct => "correct",
            Status::Incorrect => "incorrect",
            Status::Invalid => "invalid",
            Status::Error => "error",
        }
    }
}

/// One checked representative: the verdict every row of its canonical form shares. Kept
/// small (no text of its own: its reading, message and grouping key are in [`Judged`]'s
/// words, its codes shared), since a class of all-different answers keeps one per row
/// (issue 20 §5).
pub struct Rep {
    /// The problem's index in the bank (for a part that accepts numbers, the problem pinned
    /// to the student's numbers).
    pub problem: u32,
    /// The part's index in the problem.
    pub part: u32,
    /// The answer checked (the first spelling of the form in input order), as its index in
    /// [`Table::answers`].
    pub answer: u32,
    /// The bank problem its rows count for (the first of its id: a pinned problem counts as
    /// the bank's own).
    pub counted_as: u32,
    /// The verdict's score times the part's points, by the policy.
    pub score: f64,
    /// The verdict ([`Slim`]: what grading reads of it), or why the part could not be
    /// checked.
    pub verdict: Result<Slim, std::sync::Arc<str>>,
}

impl Rep {
    /// [`Rep::outcome`] without its codes and message.
    fn brief(&self, r: usize) -> Brief {
        let status = match &self.verdict {
            Ok(v) => Status::from(v.status),
            Err(_) => Status::Error,
        };
        Brief {
            status,
            score: self.score,
            target: Some((self.counted_as as usize, self.part as usize)),
            rep: Some(r),
        }
    }

    /// The outcome every row of this representative shares (`r`: its index; `lists`: the
    /// run's code lists).
    fn outcome(&self, r: usize, lists: &[Arc<[Code]>]) -> Outcome {
        let codes = match &self.verdict {
            Ok(v) => lists
                .get(v.codes as usize)
                .cloned()
                .unwrap_or_else(no_codes),
            Err(_) => no_codes(),
        };
        // The verdict's first message (or the error) is read through `Judged::message`.
        Outcome::new(self.brief(r), codes, None)
    }
}

/// What a row is given: shared by every row with the same representative (and the same
/// follow-through question), or a row's own (an error, an answer too long to read).
#[derive(Clone, Debug)]
pub struct Outcome {
    /// The status column.
    pub status: Status,
    /// The verdict's score times the part's points (follow-through credit included).
    pub score: f64,
    /// The diagnosis codes, most specific first (`follows-from-earlier` leading); shared with
    /// the verdict's own (a class of all-different answers has an outcome per row).
    pub codes: Arc<[Code]>,
    /// The first diagnosis, or why the row is an error or unread; `None`: the first
    /// diagnosis of the representative's verdict, or why it could not be checked (not copied:
    /// a class of all-different answers has as many outcomes as rows). See
    /// [`Judged::message`].
    pub message: Option<String>,
    /// `(problem, part)` indices into the bank, for rows that name a real part.
    pub target: Option<(usize, usize)>,
    /// The representative whose verdict this is.
    pub rep: Option<usize>,
    /// The instructor's decision that replaced the checker's (`--overrides`), if any.
    pub decision: Option<Decision>,
}

impl Outcome {
    /// An outcome with `brief`'s status, score, target and representative, `codes` and
    /// `message` (`None`: its representative's), decided by no one.
    pub(in crate::grade) fn new(
        brief: Brief,
        codes: Arc<[Code]>,
        message: Option<String>,
    ) -> Outcome {
        Outcome {
            status: brief.status,
            score: brief.score,
            codes,
            message,
            target: brief.target,
            rep: brief.rep,
            decision: None,
        }
    }

    /// What the passes over every row read of it.
    fn brief(&self) -> Brief {
        Brief {
            status: self.status,
            score: self.score,
            target: self.target,
            rep: self.rep,
        }
    }
}

/// What the passes over every row read of an outcome ([`Judged::brief`]): an [`Outcome`]
/// without its codes and message.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Brief {
    /// The status column.
    pub status: Status,
    /// The score (follow-through credit and decisions included).
    pub score: f64,
    /// `(problem, part)` indices into the bank, for rows that name a real part.
    pub target: Option<(usize, usize)>,
    /// The representative whose verdict this is.
    pub rep: Option<usize>,
}

/// The outcome of one row of the input.
#[derive(Clone, Copy, Debug)]
pub struct Graded {
    /// Its outcome in [`Judged::outcomes`].
    pub outcome: u32,
    /// Whether this row is the student's answer that counts for the part.
    pub counts: bool,
}

/// Every row's outcome (same order as the input) and the representatives checked.
///
/// Outcomes are numbered: `0..reps.len()` are the representatives' own (made when asked for,
/// not kept: a class of all-different answers has one per row), the others are kept
/// ([`Judged::add`]: rows' errors, overrides, follow-through).
pub struct Judged {
    /// One entry per input row, in input order.
    pub rows: Vec<Graded>,
    /// The outcomes after the representatives' own.
    pub(in crate::grade) kept: Vec<Outcome>,
    /// The answers actually checked.
    pub reps: Vec<Rep>,
    /// The representatives' readings and first messages ([`Judged::reading`],
    /// [`Judged::said`]), in memory or in a temporary file.
    words: super::words::Store,
    /// The code lists of the verdicts, by number ([`Slim::codes`]).
    code_lists: Vec<Arc<[Code]>>,
    /// The score a counted row counts for when the attempt penalty lowers it below its
    /// outcome's (few rows: only later attempts, only with a penalty).
    pub penalised: FxHashMap<u32, f64>,
}

impl Judged {
    /// The bank problem that judged an outcome: for a part that accepts numbers, the one
    /// pinned to the student's numbers (the outcome's `target` names its bank problem).
    pub fn judged_with(&self, o: &Outcome) -> Option<usize> {
        o.rep.map(|r| self.reps[r].problem as usize)
    }

    /// How many outcomes there are (the numbers [`Judged::outcome_at`] takes).
    pub fn outcome_count(&self) -> usize {
        self.reps.len() + self.kept.len()
    }

    /// Outcome `k`.
    pub fn outcome_at(&self, k: u32) -> Cow<'_, Outcome> {
        let k = k as usize;
        match k.checked_sub(self.reps.len()) {
            None => Cow::Owned(self.reps[k].outcome(k, &self.code_lists)),
            Some(i) => Cow::Borrowed(&self.kept[i]),
        }
    }

    /// Every outcome's [`Brief`], in number order.
    pub fn briefs(&self) -> impl Iterator<Item = Brief> + '_ {
        (0..self.outcome_count() as u32).map(|k| self.brief_at(k))
    }

    /// Every outcome, in number order.
    pub fn outcomes(&self) -> impl Iterator<Item = Cow<'_, Outcome>> {
        (0..self.outcome_count() as u32).map(|k| self.outcome_at(k))
    }

    /// Row `i`'s outcome.
    pub fn outcome(&self, i: usize) -> Cow<'_, Outcome> {
        self.outcome_at(self.rows[i].outcome)
    }

    /// Outcome `k` without its codes and message: what the passes over every row read, made
    /// without touching the shared code lists (a row's outcome is asked for several times).
    pub fn brief_at(&self, k: u32) -> Brief {
        let k = k as usize;
        match k.checked_sub(self.reps.len()) {
            None => self.reps[k].brief(k),
            Some(i) => self.kept[i].brief(),
        }
    }

    /// Row `i`'s outcome without its codes and message ([`Judged::brief_at`]).
    pub fn brief(&self, i: usize) -> Brief {
        self.brief_at(self.rows[i].outcome)
    }

    /// How a representative's answer was read (Unicode; empty when it could not be).
    pub fn reading(&self, rep: usize) -> Cow<'_, str> {
        self.words.reading(rep)
    }

    /// An outcome's message (results.csv's `message`).
    pub fn message<'s>(&'s self, o: &'s Outcome) -> Cow<'s, str> {
        match (&o.message, o.rep) {
            (Some(m), _) => Cow::Borrowed(m),
            (None, Some(r)) => match &self.reps[r].verdict {
                Ok(v) => self.said(v),
                Err(e) => Cow::Borrowed(e),
            },
            (None, None) => Cow::Borrowed(""),
        }
    }

    /// Why some words were lost (grading's temporary file could not be written or read
    /// back), if they were: outputs made since must not be written.
    pub fn lost(&self) -> Option<String> {
        self.words.lost()
    }

    /// The score row `i` counts for in the gradebook (after the attempt penalty).
    pub fn counted_score(&self, i: usize) -> f64 {
        match self.penalised.get(&(i as u32)) {
            Some(&s) => s,
            None => self.brief(i).score,
        }
    }

    /// Adds an outcome; its number.
    pub(in crate::grade) fn add(&mut self, o: Outcome) -> u32 {
        self.kept.push(o);
        (self.outcome_count() - 1) as u32
    }

    /// Representatives of problem 0, part 0 that could not be checked, one per answer given
    /// (for tests of what is made from them).
    #[cfg(test)]
    pub fn unchecked(answers: impl Iterator<Item = u32>) -> Judged {
        let mut judged = Judged::with_capacity(0, 0);
        for answer in answers {
            let rep = Rep {
                problem: 0,
                part: 0,
                answer,
                counted_as: 0,
                score: 0.0,
                verdict: Err(Arc::from("")),
            };
            let words = super::Words {
                reading: String::new(),
                message: String::new(),
                fingerprint: 0,
            };
            judged.push(rep, &words);
        }
        judged
    }

    /// A verdict's codes, most specific first.
    pub fn codes(&self, v: &Slim) -> &[Code] {
        self.code_lists.get(v.codes as usize).map_or(&[], |c| c)
    }

    /// Sets the code lists the verdicts' numbers name (once they are all checked).
    pub(in crate::grade) fn set_codes(&mut self, lists: Vec<Arc<[Code]>>) {
        self.code_lists = lists;
    }

    /// What a verdict said: its first diagnosis's message (empty without one).
    pub fn said(&self, v: &Slim) -> Cow<'_, str> {
        self.words.message(v.message)
    }

    /// No outcome yet, room for `reps` representatives and `text` bytes of readings and as
    /// many of messages (reserved, not touched: only what is written takes memory).
    pub(in crate::grade) fn with_capacity(reps: usize, text: usize) -> Judged {
        Judged::with_words(reps, super::words::Store::memory(reps, text))
    }

    /// No outcome yet, room for `reps` representatives, their words kept in `words`.
    pub(in crate::grade) fn with_words(reps: usize, words: super::words::Store) -> Judged {
        Judged {
            rows: Vec::new(),
            kept: Vec::new(),
            reps: Vec::with_capacity(reps),
            words,
            code_lists: Vec::new(),
            penalised: FxHashMap::default(),
        }
    }

    /// Representative `rep`'s grouping key in the summary, if the checker gave one.
    pub fn fingerprint(&self, rep: usize) -> Option<u128> {
        self.words.fingerprint(rep)
    }

    /// Adds a checked representative and its words.
    pub(in crate::grade) fn push(&mut self, mut rep: Rep, words: &super::Words) {
        let message = self.words.push(words);
        if let Ok(v) = &mut rep.verdict {
            v.message = message;
        }
        self.reps.push(rep);
    }
}

/// No diagnosis codes: one shared empty list (rows that are errors have no codes each).
pub fn no_codes() -> Arc<[Code]> {
    static EMPTY: std::sync::OnceLock<Arc<[Code]>> = std::sync::OnceLock::new();
    EMPTY.get_or_init(|| Arc::from([])).clone()
}

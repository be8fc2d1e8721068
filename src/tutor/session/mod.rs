//! The practice session: the state machine behind the REPL's commands. It holds the bank, the
//! student's [`Progress`], the open problem and its current part, and answers each input line
//! with [`Response`]s — data only, never printed. Answers are checked against the open
//! problem with each part prepared once; unreadable input never counts as an attempt.
//!
//! An incorrect answer to a part gets follow-through: the student's latest answers to the
//! open problem's other parts (from the progress) are passed to the follow-through check, so
//! a wrong EOM that follows from their own wrong L is diagnosed `follows-from-earlier`. The
//! verdicts on those earlier answers given in this session are kept and not checked again.
//! A part that accepts numbers is judged with the numbers practised (`:variant`).
//!
//! `:tutor` walks the open problem's derivation ladder (one [`StepChecker`] per open problem,
//! kept across `:back`/`:tutor`): answers go to the current step, a correct one (or `:show`)
//! moves on and names the next step, and the tutor is left after the last step or on `:back`,
//! `:part`, `:next` or `:skip`. In the tutor `:hint` reveals nothing (it asks the step again
//!
//! The session's concepts live in files of their own: answers to parts with their hints and
//! solutions (`answer`), the guided derivation (`guide`), `:read`/`:derive`/`:modes`
//! (`analysis`), `:simulate` (`simulate`) and the replies shared by them (`replies`, a leaf). This file holds the state,
//! the command dispatch, completion and moving between problems and parts.

mod analysis;
mod answer;
pub use answer::first_hint;
mod guide;
mod replies;
mod simulate;

use rustc_hash::FxHashMap;

use crate::bank::Bank;
use crate::check::prepare::Prepared;
use crate::check::{CheckError, Verdict};
use crate::problem::{Part, Problem};
use crate::report::problems::{problem_sheet, terminal_math};
use crate::tutor::command::{COMMANDS, Command, did_you_mean, parse};
use crate::tutor::ladder::{Step, StepChecker};
use crate::tutor::progress::Progress;
use crate::tutor::response::{
    DoneReply, PartEntry, PartPrompt, PartsReply, ProblemEntry, ProblemsReply, ProgressReply,
    Response, StatementReply,
};
use analysis::analyse_typed;
use replies::{help, no_problem, solution_in_tutor, visible};

/// The open problem: its index in the bank, its current part and its prepared parts.
struct Open {
    problem: usize,
    current: Option<usize>,
    /// Prepared parts by part index, built on first use (a failure is kept, not retried).
    prepared: FxHashMap<usize, Result<Prepared, CheckError>>,
    /// The guided derivation, built on the first `:tutor` and kept while the problem is open
    /// (so its checker prepares each step once, however often the student comes back).
    tutor: Option<Tutor>,
    /// Per part index, the student's latest checked answer there and its verdict (before
    /// follow-through), so follow-through does not check an earlier answer again.
    judged: FxHashMap<usize, (String, Verdict)>,
    /// The problem with the practised numbers (`:variant`), which judges the parts that
    /// accept numbers.
    pinned: Option<Box<Problem>>,
}

/// The guided derivation of the open problem: its ladder, one [`StepChecker`] and where the
/// student is on it.
struct Tutor {
    steps: Vec<Step>,
    checker: StepChecker<'static>,
    /// The step asked (`steps.len()` once the last is done).
    current: usize,
    /// Checked attempts per step, this session.
    attempts: Vec<u32>,
    /// Hints given per step, this session.
    hints: Vec<usize>,
    /// Whether answers go to the tutor (between `:tutor` and `:back` or the last step).
    active: bool,
}

/// A student's practice session over a bank.
///
/// ```
/// use lagrange::tutor::{Progress, Response, Session};
///
/// let mut s = Session::new(lagrange::embedded::bank(), Progress::new());
/// s.handle(":open simple-pendulum");
/// assert_eq!(s.current_part(), Some("kinetic"));
/// let r = s.handle("1/2*m*l^2*theta'^2");
/// assert!(matches!(&r[0], Response::Verdict(v) if v.verdict.score == 1.0));
/// assert_eq!(s.current_part(), Some("potential"));
/// ```
pub struct Session {
    bank: Bank,
    progress: Progress,
    open: Option<Open>,
}

impl Session {
    /// A session over `bank`, continuing `progress`; no problem is open.
    pub fn new(bank: Bank, progress: Progress) -> Session {
        Session {
            bank,
            progress,
            open: None,
        }
    }

    /// Answers one input line (a command or an answer); a blank line gives no response.
    pub fn handle(&mut self, line: &str) -> Vec<Response> {
        match parse(line) {
            Ok(cmd) => self.execute(cmd),
            Err(e) => {
                // The suggestion goes in its own slot only (the face shows it once).
                match &e {
                    crate::tutor::command::CommandError::Unknown {
                        name,
                        suggestion: Some(s),
                    } => {
                        let message = format!("there is no command `:{}`", visible(name));
                        vec![Response::error(e.code(), message, Some(format!(":{s}")))]
                    }
                    _ => vec![Response::error(e.code(), e.to_string(), None)],
                }
            }
        }
    }

    /// Carries out one command.
    pub fn execute(&mut self, cmd: Command) -> Vec<Response> {
        match cmd {
            Command::Empty => vec![],
            Command::Answer(a) if self.in_tutor() => self.step_answer(&a),
            Command::Answer(a) => self.answer(&a),
            Command::Problems => vec![Response::Problems(ProblemsReply {
                problems: self.entries(),
            })],
            Command::Open(id) => self.open(&id),
            Command::Parts => self.parts(),
            Command::Part(id) if self.in_tutor() => self.leave_tutor_then(|s| s.select(&id)),
            Command::Part(id) => self.select(&id),
            Command::Next | Command::Skip if self.in_tutor() => self.leave_tutor_then(Self::next),
            Command::Next | Command::Skip => self.next(),
            Command::Hint if self.in_tutor() => self.step_hint(),
            Command::Hint => self.hint(),
            Command::Solution if self.in_tutor() => vec![solution_in_tutor()],
            Command::Solution => self.solution(),
            Command::Tutor => self.tutor(),
            Command::Show => self.show(),
            Command::Back => self.back(),
            Command::Progress => vec![self.progress_reply()],
            Command::Help(topic) => vec![help(topic.as_deref())],
            Command::Quit => vec![Response::Quit],
            Command::Read(expr) => vec![self.read(&expr)],
            Command::Derive(l) if l.is_empty() => vec![self.analyse_and_reveal(false)],
            Command::Modes(l) if l.is_empty() => vec![self.analyse_and_reveal(true)],
            Command::Derive(l) => vec![analyse_typed(&l, false)],
            Command::Modes(l) => vec![analyse_typed(&l, true)],
            Command::Simulate(args) => vec![self.simulate(&args)],
            Command::Variant => self.variant(),
        }
    }

    /// The student's progress (the face saves it).
    pub fn progress(&self) -> &Progress {
        &self.progress
    }

    /// The session's progress, ending the session.
    pub fn into_progress(self) -> Progress {
        self.progress
    }

    /// The bank.
    pub fn bank(&self) -> &Bank {
        &self.bank
    }

    /// The open problem.
    pub fn problem(&self) -> Option<&Problem> {
        self.open
            .as_ref()
            .and_then(|o| self.bank.problems.get(o.problem))
    }

    /// The open problem's id.
    pub fn current_problem(&self) -> Option<&str> {
        self.problem().map(|p| p.id.as_str())
    }

    /// The current part.
    pub fn part(&self) -> Option<&Part> {
        let o = self.open.as_ref()?;
        self.bank.problems.get(o.problem)?.parts.get(o.current?)
    }

    /// The current part's id.
    pub fn current_part(&self) -> Option<&str> {
        self.part().map(|p| p.id.as_str())
    }

    /// Command names with their colon (`:open`, …), for completion.
    pub fn command_names(&self) -> Vec<String> {
        COMMANDS.iter().map(|c| format!(":{}", c.name)).collect()
    }

    /// The bank's problem ids, for completion.
    pub fn problem_ids(&self) -> Vec<&str> {
        self.bank.problems.iter().map(|p| p.id.as_str()).collect()
    }

    /// The open problem's part ids, for completion (empty when none is open).
    pub fn part_ids(&self) -> Vec<&str> {
        self.problem()
            .map(|p| p.parts.iter().map(|q| q.id.as_str()).collect())
            .unwrap_or_default()
    }

    /// The open problem's coordinate and parameter names, for completion.
    pub fn symbol_names(&self) -> Vec<&str> {
        let Some(p) = self.problem() else {
            return vec![];
        };
        let sys = &p.system;
        let coords = sys.coordinates.iter().map(|c| sys.pool.name(c.sym));
        let params = sys.parameters.iter().map(|q| sys.pool.name(q.sym));
        coords.chain(params).collect()
    }

    /// Completion of the word that ends `line` (the text before the cursor): command names
    /// after a leading `:`, problem ids after `:open `, part ids after `:part `, command names
    /// after `:help `, and otherwise the open problem's coordinates and parameters. Returns
    /// the byte offset where the word starts and the candidates it begins, sorted.
    pub fn complete(&self, line: &str) -> (usize, Vec<String>) {
        let start = line
            .char_indices()
            .rev()
            .find(|(_, c)| !(c.is_alphanumeric() || matches!(c, '_' | '-' | ':')))
            .map_or(0, |(i, c)| i + c.len_utf8());
        let word = &line[start..];
        let head = line[..start].trim_start();
        let candidates: Vec<String> = if head.is_empty() && word.starts_with(':') {
            self.command_names()
        } else if head == ":open " {
            self.problem_ids().into_iter().map(str::to_string).collect()
        } else if head == ":part " {
            self.part_ids().into_iter().map(str::to_string).collect()
        } else if head == ":help " || head == "help " {
            COMMANDS.iter().map(|c| c.name.to_string()).collect()
        } else {
            self.symbol_names()
                .into_iter()
                .map(str::to_string)
                .collect()
        };
        let mut found: Vec<String> = candidates
            .into_iter()
            .filter(|c| c.starts_with(word))
            .collect();
        crate::sort::sort(&mut found);
        found.dedup();
        // A unique command is completed with the space its argument follows, as shells do.
        if head.is_empty()
            && word.starts_with(':')
            && let [only] = found.as_mut_slice()
        {
            only.push(' ');
        }
        (start, found)
    }

    fn open(&mut self, id: &str) -> Vec<Response> {
        let Some(index) = self.bank.problems.iter().position(|p| p.id == id) else {
            let suggestion = did_you_mean(id, self.bank.problems.iter().map(|p| p.id.as_str()));
            // A suggestion is shown from its own slot, not repeated in the message.
            let hint = match &suggestion {
                Some(_) => "",
                None => " — `:problems` lists them",
            };
            let message = format!("there is no problem `{}`{hint}", visible(id));
            return vec![Response::error("unknown-problem", message, suggestion)];
        };
        let problem = &self.bank.problems[index];
        let current = self
            .first_unsolved(problem, 0)
            .or((!problem.parts.is_empty()).then_some(0));
        let seed = (self.progress.problems.get(&problem.id)).and_then(|p| p.variant_seed);
        let variant = seed.and_then(|s| crate::problem::variant::pick_own(problem, s));
        let sheet = match &variant {
            Some(v) => crate::report::sheets::variant_sheet(problem, false, v),
            None => problem_sheet(problem, false),
        };
        self.open = Some(Open {
            problem: index,
            current,
            prepared: FxHashMap::default(),
            tutor: None,
            judged: FxHashMap::default(),
            pinned: variant.map(|v| Box::new(problem.pinned(&v))),
        });
        let mut out = vec![Response::Statement(StatementReply {
            sheet,
            current: self.current_part().map(str::to_string),
        })];
        out.extend(self.prompt());
        out
    }

    /// `:variant`: fresh numbers for the open problem — the next seed of a SplitMix64 sequence
    /// from the last one, kept in the progress — and its statement with them. The first time,
    /// the sequence starts from the learner's seed (drawn once per progress file) mixed with
    /// the FNV-1a hash of the problem id, so learners practise different numbers; without a
    /// learner seed, from the hash alone.
    fn variant(&mut self) -> Vec<Response> {
        let Some(problem) = self.problem() else {
            return vec![no_problem()];
        };
        if problem.variants.is_empty() {
            return vec![Response::error(
                "no-variants",
                "this problem's numbers do not vary: it is the same for everyone",
                None,
            )];
        }
        let id = problem.id.clone();
        let learner = self.progress.learner_seed;
        let record = self.progress.problems.entry(id.clone()).or_default();
        let mut state = record
            .variant_seed
            .unwrap_or_else(|| first_variant_state(learner, &id));
        record.variant_seed = Some(crate::problem::variant::splitmix64(&mut state));
        self.open(&id)
    }

    /// The first unsolved part at or after `from`, wrapping round.
    fn first_unsolved(&self, problem: &Problem, from: usize) -> Option<usize> {
        let n = problem.parts.len();
        (0..n)
            .map(|k| (from + k) % n)
            .find(|&i| !self.progress.is_solved(&problem.id, &problem.parts[i].id))
    }

    /// The current part's prompt, if a part is current.
    fn prompt(&self) -> Option<Response> {
        let (problem, part) = (self.problem()?, self.part()?);
        let number = self.open.as_ref()?.current? + 1;
        Some(Response::Part(PartPrompt {
            problem: problem.id.clone(),
            part: part.id.clone(),
            number,
            part_kind: part.kind.name().to_string(),
            prompt: match crate::check::units::answer_form(part) {
                Some(form) => format!("{} ({form})", terminal_math(&part.prompt)),
                None => terminal_math(&part.prompt),
            },
            solved: self.progress.is_solved(&problem.id, &part.id),
        }))
    }

    fn select(&mut self, which: &str) -> Vec<Response> {
        let Some(problem) = self.problem() else {
            return vec![no_problem()];
        };
        let by_id = problem.parts.iter().position(|p| p.id == which);
        let by_number = which
            .parse::<usize>()
            .ok()
            .filter(|&n| n >= 1 && n <= problem.parts.len())
            .map(|n| n - 1);
        let Some(index) = by_id.or(by_number) else {
            let suggestion = did_you_mean(which, problem.parts.iter().map(|p| p.id.as_str()));
            let ids: Vec<&str> = problem.parts.iter().map(|p| p.id.as_str()).collect();
            let message = format!(
                "`{}` has no part `{}`; its parts are {} (or 1–{})",
                problem.id,
                visible(which),
                ids.join(", "),
                ids.len()
            );
            return vec![Response::error("unknown-part", message, suggestion)];
        };
        if let Some(o) = self.open.as_mut() {
            o.current = Some(index);
        }
        self.prompt().into_iter().collect()
    }

    fn next(&mut self) -> Vec<Response> {
        let Some(problem) = self.problem() else {
            return vec![no_problem()];
        };
        let from = self
            .open
            .as_ref()
            .and_then(|o| o.current)
            .map_or(0, |c| c + 1);
        let next = self.first_unsolved(problem, from);
        let done = DoneReply {
            problem: problem.id.clone(),
            parts: problem.parts.len(),
        };
        if let Some(o) = self.open.as_mut() {
            o.current = next.or(o.current);
        }
        match next {
            Some(_) => self.prompt().into_iter().collect(),
            None => vec![Response::Done(done)],
        }
    }

    fn parts(&self) -> Vec<Response> {
        let Some(problem) = self.problem() else {
            return vec![no_problem()];
        };
        let current = self.open.as_ref().and_then(|o| o.current);
        let parts = problem
            .parts
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let rec = self
                    .progress
                    .part(&problem.id, &p.id)
                    .cloned()
                    .unwrap_or_default();
                PartEntry {
                    number: i + 1,
                    id: p.id.clone(),
                    part_kind: p.kind.name().to_string(),
                    current: current == Some(i),
                    solved: rec.solved,
                    attempts: rec.attempts,
                    hints_used: rec.hints_used,
                    revealed: rec.revealed,
                }
            })
            .collect();
        vec![Response::Parts(PartsReply {
            problem: problem.id.clone(),
            parts,
        })]
    }

    /// Each problem of the bank with its progress.
    fn entries(&self) -> Vec<ProblemEntry> {
        self.bank
            .problems
            .iter()
            .map(|p| {
                let recs: Vec<_> = p
                    .parts
                    .iter()
                    .filter_map(|q| self.progress.part(&p.id, &q.id))
                    .collect();
                ProblemEntry {
                    id: p.id.clone(),
                    title: p.title.clone(),
                    solved: recs.iter().filter(|r| r.solved).count(),
                    parts: p.parts.len(),
                    attempts: recs.iter().map(|r| r.attempts).fold(0, u32::saturating_add),
                    hints_used: recs
                        .iter()
                        .map(|r| r.hints_used)
                        .fold(0, u32::saturating_add),
                    revealed: recs.iter().filter(|r| r.revealed).count(),
                }
            })
            .collect()
    }

    fn progress_reply(&self) -> Response {
        let problems = self.entries();
        Response::Progress(ProgressReply {
            solved: problems.iter().map(|p| p.solved).sum(),
            parts: problems.iter().map(|p| p.parts).sum(),
            problems,
        })
    }
}

/// Where a problem's `:variant` sequence starts: the learner's seed mixed with the problem id's
/// FNV-1a hash through one SplitMix64 step (so that nearby learner seeds start far apart), or
/// the hash alone for a progress without a learner seed.
fn first_variant_state(learner: Option<u64>, id: &str) -> u64 {
    let hash = crate::problem::variant::fnv1a64(id.as_bytes());
    match learner {
        Some(seed) => {
            let mut state = seed ^ hash;
            crate::problem::variant::splitmix64(&mut state)
        }
        None => hash,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bank::embedded;

    pub(super) fn pendulum() -> Session {
        let mut bank = Bank::default();
        bank.problems.extend(embedded::problem("simple-pendulum"));
        Session::new(bank, Progress::new())
    }

    #[test]
    fn first_unsolved_wraps_round() {
        let mut s = pendulum();
        let Some(p) = s.bank.problems.first().cloned() else {
            panic!("no pendulum");
        };
        assert_eq!(s.first_unsolved(&p, 3), Some(3));
        s.progress.record_attempt(&p.id, "momentum", "x", true);
        assert_eq!(s.first_unsolved(&p, 3), Some(4));
        for q in &p.parts[4..] {
            s.progress.record_attempt(&p.id, &q.id, "x", true);
        }
        assert_eq!(s.first_unsolved(&p, 5), Some(0));
    }

    #[test]
    fn completion_by_position() {
        let mut s = pendulum();
        assert_eq!(s.complete(":op"), (0, vec![":open ".to_string()]));
        assert_eq!(
            s.complete(":open simple"),
            (6, vec!["simple-pendulum".to_string()])
        );
        assert_eq!(
            s.complete("th").1,
            Vec::<String>::new(),
            "nothing open: no symbols"
        );
        s.handle(":open simple-pendulum");
        assert_eq!(s.complete("1/2*m*th"), (6, vec!["theta".to_string()]));
        assert_eq!(s.complete(":part mo").1, ["momentum"]);
        assert_eq!(s.complete(":help hi").1, ["hint"]);
        assert_eq!(s.complete("θ + l").1, ["l"]);
    }
}

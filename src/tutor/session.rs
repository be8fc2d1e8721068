//! The practice session: the state machine behind the REPL's commands. It holds the bank, the
//! student's [`Progress`], the open problem and its current part, and answers each input line
//! with [`Response`]s — data only, never printed. Answers are checked against the open
//! problem with each part prepared once; unreadable input never counts as an attempt.
//!
//! An incorrect answer to a part gets follow-through: the student's latest answers to the
//! open problem's other parts (from the progress) are passed to the follow-through check, so
//! a wrong EOM that follows from their own wrong L is diagnosed `follows-from-earlier`. The
//! verdicts on those earlier answers given in this session are kept and not checked again.
//!
//! `:tutor` walks the open problem's derivation ladder (one [`StepChecker`] per open problem,
//! kept across `:back`/`:tutor`): answers go to the current step, a correct one (or `:show`)
//! moves on and names the next step, and the tutor is left after the last step or on `:back`,
//! `:part`, `:next` or `:skip`. In the tutor `:hint` reveals nothing (it asks the step again
//! with a pointer to `:show`) and `:solution` is refused in favour of `:show`.

use rustc_hash::FxHashMap;

use super::command::{COMMANDS, Command, command_info, did_you_mean, parse};
use super::follow::{Earlier, follows_from_earlier};
use super::ladder::{Step, StepChecker, ladder};
use super::progress::Progress;
use super::response::WorkedStep;
use super::response::{
    AnalysisReply, AnalysisReport, DoneReply, HelpEntry, HelpReply, HintReply, PartEntry,
    PartPrompt, PartsReply, ProblemEntry, ProblemsReply, ProgressReply, Response, SolutionReply,
    StatementReply, StepPrompt, StepSolutionReply, StepVerdictReply, VerdictReply,
};
use crate::bank::Bank;
use crate::check::answer::check_prepared;
use crate::check::prepare::{Prepared, prepare};
use crate::check::{CheckError, Status, Verdict};
use crate::problem::{Part, PartKind, Problem, Quantity};
use crate::report::problems::{problem_sheet, terminal_math};
use crate::report::{self, ModesOptions, ReadOptions, reading};

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
                let suggestion = match &e {
                    super::command::CommandError::Unknown { suggestion, .. } => {
                        suggestion.as_ref().map(|s| format!(":{s}"))
                    }
                    _ => None,
                };
                vec![Response::error(e.code(), e.to_string(), suggestion)]
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
            Command::Derive(l) if l.is_empty() => vec![self.analyse(false)],
            Command::Modes(l) if l.is_empty() => vec![self.analyse(true)],
            Command::Derive(l) => vec![analyse_typed(&l, false)],
            Command::Modes(l) => vec![analyse_typed(&l, true)],
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
        found.sort();
        found.dedup();
        (start, found)
    }

    fn open(&mut self, id: &str) -> Vec<Response> {
        let Some(index) = self.bank.problems.iter().position(|p| p.id == id) else {
            let suggestion = did_you_mean(id, self.bank.problems.iter().map(|p| p.id.as_str()));
            let hint = match &suggestion {
                Some(s) => format!(" — did you mean `{s}`?"),
                None => " — `:problems` lists them".to_string(),
            };
            let message = format!("there is no problem `{}`{hint}", visible(id));
            return vec![Response::error("unknown-problem", message, suggestion)];
        };
        let problem = &self.bank.problems[index];
        let current = self
            .first_unsolved(problem, 0)
            .or((!problem.parts.is_empty()).then_some(0));
        let sheet = problem_sheet(problem, false);
        self.open = Some(Open {
            problem: index,
            current,
            prepared: FxHashMap::default(),
            tutor: None,
            judged: FxHashMap::default(),
        });
        let mut out = vec![Response::Statement(StatementReply {
            sheet,
            current: self.current_part().map(str::to_string),
        })];
        out.extend(self.prompt());
        out
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
            prompt: terminal_math(&part.prompt),
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

    fn answer(&mut self, input: &str) -> Vec<Response> {
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
    /// (read from the progress, in part order: a later part counts as more recent).
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
            verdict.diagnoses.push(d);
            verdict.sort();
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

    fn hint(&mut self) -> Vec<Response> {
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
        };
        vec![Response::Hint(reply)]
    }

    fn solution(&mut self) -> Vec<Response> {
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

    /// `:read EXPR`: read with the open problem's coordinates and parameter dimensions (or
    /// with every name open when no problem is).
    fn read(&self, expr: &str) -> Response {
        let mut opts = ReadOptions::default();
        if let Some(p) = self.problem() {
            opts.coords = p
                .system
                .coordinates
                .iter()
                .map(|c| c.name.clone())
                .collect();
            // Every symbol's dimension as the problem declares it (angles: none).
            let names = p.system.coordinates.iter().map(|c| &c.name);
            let names = names.chain(p.system.parameters.iter().map(|q| &q.name));
            opts.dims = names
                .filter_map(|n| Some((n.clone(), p.dims.get(n)?)))
                .collect();
        }
        match reading(expr, &opts) {
            Ok(r) => Response::Analysis(AnalysisReply {
                of: "read".to_string(),
                report: AnalysisReport::Read(Box::new(r)),
                note: None,
            }),
            Err(e) => Response::error("syntax", format!("`{}`: {e}", visible(expr)), None),
        }
    }

    /// `:derive` or `:modes` on the open problem's system.
    fn analyse(&self, modes: bool) -> Response {
        let Some(p) = self.problem() else {
            return no_problem();
        };
        // Numeric modes need numbers: each parameter at the middle of its sampling range.
        let params: Vec<(String, String)> = p
            .system
            .parameters
            .iter()
            .map(|q| (q.name.clone(), format!("{}", (q.range.0 + q.range.1) / 2.0)))
            .collect();
        let note = (modes && !params.is_empty()).then(|| {
            let shown: Vec<String> = params.iter().map(|(n, v)| format!("{n} = {v}")).collect();
            format!(
                "parameters at the middle of their ranges: {}",
                shown.join(", ")
            )
        });
        let opts = ModesOptions {
            params,
            ..ModesOptions::default()
        };
        analysis_response(&p.system, modes, &opts, note)
    }

    fn no_part(&self) -> Response {
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
    fn tutor(&mut self) -> Vec<Response> {
        let Some(o) = self.open.as_mut() else {
            return vec![no_problem()];
        };
        let problem = &self.bank.problems[o.problem];
        if o.tutor.is_none() {
            match ladder(problem) {
                Ok(steps) if !steps.is_empty() => {
                    o.tutor = Some(Tutor {
                        attempts: vec![0; steps.len()],
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
    fn step_answer(&mut self, input: &str) -> Vec<Response> {
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
    fn show(&mut self) -> Vec<Response> {
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
    fn back(&mut self) -> Vec<Response> {
        if !self.in_tutor() {
            return vec![not_in_tutor()];
        }
        self.leave_tutor_then(|s| s.prompt().into_iter().collect())
    }

    /// Leaves the tutor (keeping its place), then carries out `then`.
    fn leave_tutor_then(&mut self, then: impl FnOnce(&mut Self) -> Vec<Response>) -> Vec<Response> {
        if let Some(t) = self.open.as_mut().and_then(|o| o.tutor.as_mut()) {
            t.active = false;
        }
        then(self)
    }

    /// `:hint` in the tutor reveals nothing: it asks the current step again, with a pointer to
    /// `:show` (which reveals the step) and `:back`. The ladder's steps are already the small
    /// steps a hint would suggest.
    fn step_hint(&self) -> Vec<Response> {
        let Some(t) = self.tutor_ref().filter(|t| t.active) else {
            return vec![not_in_tutor()];
        };
        let note = "the tutor gives no hints beyond the step itself: `:show` reveals this \
                    step's answer and moves on, `:back` returns to the parts";
        let pid = self.current_problem().unwrap_or_default();
        step_prompt(pid, t, t.current, Some(note.to_string()))
            .map(Response::Step)
            .into_iter()
            .collect()
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

fn not_in_tutor() -> Response {
    Response::error(
        "not-in-tutor",
        "the tutor is not running: `:tutor` starts the guided derivation of the open problem",
        None,
    )
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
    steps[..=end]
        .iter()
        .map(|s| WorkedStep {
            step: s.id.clone(),
            prompt: s.prompt.clone(),
            answer: s.reference_text(problem.system.n()),
        })
        .collect()
}

fn solution_in_tutor() -> Response {
    Response::error(
        "in-tutor",
        "in the tutor, `:show` reveals the current step; `:back` returns to the parts",
        None,
    )
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

fn no_problem() -> Response {
    Response::error(
        "no-problem-open",
        "no problem is open: `:open ID` opens one (`:problems` lists them)",
        None,
    )
}

/// `:derive L` / `:modes L` on a typed Lagrangian, with optional `--coords q1,q2` (else the
/// names that appear with a time derivative) and, for modes, `--params m=1,k=2`.
fn analyse_typed(text: &str, modes: bool) -> Response {
    let (l, coords, params) = split_flags(text);
    let coords: Vec<String> = match coords {
        Some(c) => c
            .split(',')
            .map(|x| x.trim().to_string())
            .filter(|x| !x.is_empty())
            .collect(),
        None => moving_names(l),
    };
    if coords.is_empty() {
        return Response::error(
            "no-coordinates",
            "no coordinate: write the velocities with a prime (x') or add --coords x,y",
            None,
        );
    }
    let names: Vec<&str> = coords.iter().map(String::as_str).collect();
    let sys = match crate::mechanics::System::from_lagrangian(l, &names) {
        Ok(sys) => sys,
        Err(e) => return Response::error(e.code(), e.to_string(), None),
    };
    let mut opts = ModesOptions {
        default_range: Some((-10.0, 10.0)),
        ..ModesOptions::default()
    };
    if modes {
        match params.map(report::modes::assignments).transpose() {
            Ok(p) => opts.params = p.unwrap_or_default(),
            Err(e) => return Response::error("bad-params", e.to_string(), None),
        }
    }
    analysis_response(&sys, modes, &opts, None)
}

/// The derivation or the modes of `sys` as an analysis response (or why not).
fn analysis_response(
    sys: &crate::mechanics::System,
    modes: bool,
    opts: &ModesOptions,
    note: Option<String>,
) -> Response {
    let report = if modes {
        report::modes(sys, opts)
            .map(|r| AnalysisReport::Modes(Box::new(r)))
            .map_err(|e| e.to_string())
    } else {
        report::derivation(sys)
            .map(|r| AnalysisReport::Derive(Box::new(r)))
            .map_err(|e| e.to_string())
    };
    match report {
        Ok(report) => Response::Analysis(AnalysisReply {
            of: if modes { "modes" } else { "derive" }.to_string(),
            report,
            note,
        }),
        Err(e) => Response::error("analysis", e, None),
    }
}

/// The Lagrangian and the values of `--coords` and `--params` in `:derive L --coords x`.
fn split_flags(text: &str) -> (&str, Option<&str>, Option<&str>) {
    let mut l = text;
    let mut coords = None;
    let mut params = None;
    // Flags come after the Lagrangian, in any order.
    while let Some(i) = l.rfind(" --") {
        let (head, flag) = (&l[..i], &l[i + 3..]);
        match flag.split_once(char::is_whitespace) {
            Some(("coords", v)) => coords = Some(v.trim()),
            Some(("params", v)) => params = Some(v.trim()),
            _ => break,
        }
        l = head;
    }
    (l.trim(), coords, params)
}

/// The names that appear with a time derivative in `l` (its coordinates, by the notation).
fn moving_names(l: &str) -> Vec<String> {
    let mut pool = crate::expr::Pool::new();
    let Ok(e) = crate::expr::read_expr(l, &crate::expr::Context::open(), &mut pool) else {
        return Vec::new();
    };
    let mut names: Vec<String> = pool
        .variables(e)
        .into_iter()
        .filter(|v| v.1 >= 1)
        .map(|v| pool.name(v.0).to_string())
        .collect();
    names.sort();
    names.dedup();
    names
}

/// Help on every command, or on one (an unknown one gets did-you-mean).
fn help(topic: Option<&str>) -> Response {
    let entry = |c: &super::command::CommandInfo| HelpEntry {
        usage: c.usage.to_string(),
        summary: c.summary.to_string(),
    };
    match topic {
        None => Response::Help(HelpReply {
            commands: COMMANDS.iter().map(entry).collect(),
        }),
        Some(t) => match command_info(t) {
            Some(c) => Response::Help(HelpReply {
                commands: vec![entry(c)],
            }),
            None => {
                let name = t.trim_start_matches(':');
                let s = did_you_mean(name, COMMANDS.iter().map(|c| c.name));
                let msg = format!("there is no command `:{}`", visible(name));
                Response::error("unknown-command", msg, s.map(|s| format!(":{s}")))
            }
        },
    }
}

/// User text as shown in a message: control characters made visible.
fn visible(s: &str) -> String {
    crate::expr::error::visible(s)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bank::embedded;

    fn pendulum() -> Session {
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
        assert_eq!(s.complete(":op"), (0, vec![":open".to_string()]));
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

    #[test]
    fn help_on_one_command_and_an_unknown_one() {
        assert!(matches!(help(Some(":open")), Response::Help(h) if h.commands.len() == 1));
        assert!(matches!(help(None), Response::Help(h) if h.commands.len() == COMMANDS.len()));
        let r = help(Some("hitn"));
        assert!(matches!(r, Response::Error(e) if e.suggestion.as_deref() == Some(":hint")));
    }

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

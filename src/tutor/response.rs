//! What a practice session answers, as data: one [`Response`] per thing to show, serialised
//! with a `"kind"` tag (`verdict`, `statement`, `part`, `hint`, …) so the REPL renders it,
//! the JSON-lines protocol prints it and a browser face reads it, all from one type.

use serde::Serialize;

use crate::check::Verdict;
use crate::report::problems::ProblemSheet;
use crate::report::{DerivationReport, ModesReport, ReadReport};

/// One thing a session answers with.
#[derive(Clone, Debug, Serialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Response {
    /// The verdict on an answer to the current part.
    Verdict(VerdictReply),
    /// An opened problem's statement and parts.
    Statement(StatementReply),
    /// The part now current and its question.
    Part(PartPrompt),
    /// Every part of the open problem is solved.
    Done(DoneReply),
    /// A hint for the current part.
    Hint(HintReply),
    /// The reference answer of the current part.
    Solution(SolutionReply),
    /// The bank, with the student's progress on each problem.
    Problems(ProblemsReply),
    /// The open problem's parts and their state.
    Parts(PartsReply),
    /// The student's progress over the bank, with totals.
    Progress(ProgressReply),
    /// The commands, or one command's usage.
    Help(HelpReply),
    /// An analysis (`:read`, `:derive`, `:modes`): the same report the CLI command gives.
    Analysis(AnalysisReply),
    /// A command or answer that could not be carried out (never counts as an attempt).
    Error(ErrorReply),
    /// The session ends.
    Quit,
    /// A tutor step (`:tutor`, or `:hint` in the tutor): what the guided derivation asks now.
    Step(StepPrompt),
    /// The verdict on an answer to the current tutor step. Serialised with `"kind": "verdict"`
    /// and the fields of a part's verdict, but `"step"` in place of `"part"`.
    #[serde(rename = "verdict")]
    StepVerdict(StepVerdictReply),
    /// The current tutor step's reference answer (`:show`), after which the tutor moves on.
    StepSolution(StepSolutionReply),
}

/// A verdict: the fields of `lagrange check --json` (its `problem` and `part` included), plus
/// the part's attempts so far.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct VerdictReply {
    /// The checker's verdict.
    #[serde(flatten)]
    pub verdict: Verdict,
    /// Checked attempts at this part, this one included (an invalid answer is not one).
    pub attempts: u32,
}

/// An opened problem.
#[derive(Clone, Debug, Serialize)]
pub struct StatementReply {
    /// The statement, symbols and parts (no reference answers).
    #[serde(flatten)]
    pub sheet: ProblemSheet,
    /// The part made current (the first unsolved one).
    pub current: Option<String>,
}

/// A part's question.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PartPrompt {
    /// The problem id.
    pub problem: String,
    /// The part id.
    pub part: String,
    /// Its 1-based number.
    pub number: usize,
    /// What kind of answer it asks for (`expression`, `equation`, …).
    pub part_kind: String,
    /// The question, with inline math made readable on a terminal.
    pub prompt: String,
    /// Whether it is already solved.
    pub solved: bool,
}

/// Every part of the open problem is solved.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct DoneReply {
    /// The problem id.
    pub problem: String,
    /// How many parts it has (all solved).
    pub parts: usize,
}

/// A hint, or the news that none remain.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct HintReply {
    /// The problem id.
    pub problem: String,
    /// The part id.
    pub part: String,
    /// The hint; `None` when every hint has been given.
    pub hint: Option<String>,
    /// Its 1-based number among the part's hints (the count given, when none remain).
    pub number: usize,
    /// Hints still to come.
    pub remaining: usize,
    /// The command that reveals the answer once the hints run out: `:solution` for a part,
    /// `:show` for a tutor step.
    pub reveal: &'static str,
}

/// A part's reference answer.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SolutionReply {
    /// The problem id.
    pub(crate) problem: String,
    /// The part id.
    pub(crate) part: String,
    /// The answer as a student would type it.
    pub answer: String,
    /// The answer as read, in Unicode (empty if it cannot be read).
    pub unicode: String,
    /// The worked derivation: the tutor's steps that lead to this part, with their results
    /// (empty when the ladder cannot be built or no step leads there).
    pub derivation: Vec<WorkedStep>,
}

/// One step of a worked derivation: its id, question and result.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct WorkedStep {
    /// The step id (as in the tutor).
    pub(crate) step: String,
    /// The question.
    pub prompt: String,
    /// The result, as a student would type it.
    pub answer: String,
    /// The result read back, in Unicode as every other formula is shown (empty if it
    /// cannot be read).
    pub unicode: String,
}

/// One problem of the bank with the student's progress on it.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ProblemEntry {
    /// Its id.
    pub id: String,
    /// Its title.
    pub title: String,
    /// Parts solved.
    pub solved: usize,
    /// Parts in all.
    pub parts: usize,
    /// Checked attempts over its parts.
    pub attempts: u32,
    /// Hints used over its parts.
    pub hints_used: u32,
    /// Parts whose answer was revealed.
    pub revealed: usize,
}

/// The bank.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ProblemsReply {
    /// Every problem, in bank order.
    pub problems: Vec<ProblemEntry>,
}

/// One part of the open problem and its state.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct PartEntry {
    /// Its 1-based number.
    pub number: usize,
    /// Its id.
    pub id: String,
    /// Its kind.
    pub part_kind: String,
    /// Whether it is the current part.
    pub current: bool,
    /// Solved.
    pub solved: bool,
    /// Checked attempts.
    pub attempts: u32,
    /// Hints used.
    pub hints_used: u32,
    /// Answer revealed.
    pub revealed: bool,
}

/// The open problem's parts.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct PartsReply {
    /// The problem id.
    pub problem: String,
    /// Its parts, in order.
    pub parts: Vec<PartEntry>,
}

/// Progress over the bank.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ProgressReply {
    /// Every problem, in bank order.
    pub problems: Vec<ProblemEntry>,
    /// Parts solved over the bank.
    pub solved: usize,
    /// Parts in the bank.
    pub parts: usize,
}

/// One command's help.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct HelpEntry {
    /// Its usage, e.g. `:open ID`.
    pub usage: String,
    /// What it does.
    pub summary: String,
}

/// The commands' help.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct HelpReply {
    /// The commands asked about (all of them for a bare `:help`).
    pub commands: Vec<HelpEntry>,
}

/// An analysis and its report.
#[derive(Clone, Debug, Serialize)]
pub struct AnalysisReply {
    /// Which: `read`, `derive`, `modes` or `simulate`.
    pub of: String,
    /// The report (rendered by the face with the report's own `render`).
    pub report: AnalysisReport,
    /// What the analysis assumed, e.g. the parameter values `:modes` used.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// The report of an analysis, serialised as the report itself.
#[derive(Clone, Debug, Serialize)]
#[serde(untagged)]
pub enum AnalysisReport {
    /// How an expression is read (`:read`).
    Read(Box<ReadReport>),
    /// The derivation of the open problem (`:derive`).
    Derive(Box<DerivationReport>),
    /// The equilibria and normal modes of the open problem (`:modes`).
    Modes(Box<ModesReport>),
    /// An integrated motion of the open problem (`:simulate`; the face draws its chart).
    Simulate(Box<crate::report::SimulationReport>),
}

/// Something that could not be done.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct ErrorReply {
    /// A stable kebab-case code (`unknown-command`, `unknown-problem`, `no-problem-open`, …).
    pub code: String,
    /// What went wrong, for the student.
    pub message: String,
    /// The likeliest meant name, if any.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub suggestion: Option<String>,
}

/// A step of the guided derivation (the ladder of `tutor::ladder`).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StepPrompt {
    /// The problem id.
    pub(crate) problem: String,
    /// The step id (`kinetic`, `momentum:theta`, `eom:theta`, …; stable).
    pub step: String,
    /// Its 1-based number in the ladder.
    pub number: usize,
    /// How many steps the ladder has.
    pub total: usize,
    /// The question, a plain sentence.
    pub prompt: String,
    /// A remark about the tutor (e.g. that `:hint` reveals nothing there), when there is one.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

/// The verdict on an answer to a tutor step.
///
/// Serialised as the checker's verdict (the fields of `lagrange check --json`) without
/// `"part"`, plus `"step"`, `"number"`, `"total"`, `"attempts"` and, on a correct answer,
/// `"next"`: the next step (`null` after the last).
#[derive(Clone, Debug, PartialEq)]
pub struct StepVerdictReply {
    /// The checker's verdict (its `part` is the step id; not serialised).
    pub verdict: Verdict,
    /// The step id.
    pub step: String,
    /// Its 1-based number in the ladder.
    pub number: usize,
    /// How many steps the ladder has.
    pub(crate) total: usize,
    /// Checked attempts at this step in this session, this one included.
    pub attempts: u32,
    /// On a correct answer, the step now asked (`Some(None)` after the last); `None` otherwise.
    pub next: Option<Option<StepPrompt>>,
}

impl Serialize for StepVerdictReply {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::Error;
        let value = serde_json::to_value(&self.verdict).map_err(S::Error::custom)?;
        let serde_json::Value::Object(mut map) = value else {
            return Err(S::Error::custom("a verdict serialises as an object"));
        };
        map.remove("part");
        let mut put = |k: &str, v: serde_json::Result<serde_json::Value>| {
            v.map(|v| map.insert(k.to_string(), v))
                .map_err(S::Error::custom)
        };
        put("step", serde_json::to_value(&self.step))?;
        put("number", serde_json::to_value(self.number))?;
        put("total", serde_json::to_value(self.total))?;
        put("attempts", serde_json::to_value(self.attempts))?;
        if let Some(next) = &self.next {
            put("next", serde_json::to_value(next))?;
        }
        map.serialize(serializer)
    }
}

/// A tutor step's reference answer, revealed by `:show`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct StepSolutionReply {
    /// The problem id.
    pub(crate) problem: String,
    /// The step revealed.
    pub step: String,
    /// Its 1-based number in the ladder.
    pub number: usize,
    /// How many steps the ladder has.
    pub total: usize,
    /// The reference as a student would type it.
    pub answer: String,
    /// The reference as read, in Unicode (empty if it cannot be read).
    pub unicode: String,
    /// The step now asked (`null` after the last).
    pub next: Option<StepPrompt>,
}

impl Response {
    /// An error response.
    pub fn error(code: &str, message: impl Into<String>, suggestion: Option<String>) -> Response {
        Response::Error(ErrorReply {
            code: code.to_string(),
            message: message.into(),
            suggestion,
        })
    }

    /// The `"kind"` tag of this response.
    pub fn kind(&self) -> &'static str {
        match self {
            Response::Verdict(_) => "verdict",
            Response::Statement(_) => "statement",
            Response::Part(_) => "part",
            Response::Done(_) => "done",
            Response::Hint(_) => "hint",
            Response::Solution(_) => "solution",
            Response::Problems(_) => "problems",
            Response::Parts(_) => "parts",
            Response::Progress(_) => "progress",
            Response::Help(_) => "help",
            Response::Analysis(_) => "analysis",
            Response::Error(_) => "error",
            Response::Quit => "quit",
            Response::Step(_) => "step",
            Response::StepVerdict(_) => "verdict",
            Response::StepSolution(_) => "step-solution",
        }
    }
}

/// One JSON object for one input line, as the REPL's `--json` protocol writes it
/// (docs/repl-protocol.md): the first response, with any others in `"more"`; a line that gives
/// no response (a blank line) gives `{"kind":"none"}`. `extend` may add fields to each
/// response's object (a browser face adds the drawing data a simulation skips), so every face
/// builds the same shape from this one place.
pub fn json_object(
    responses: &[Response],
    mut extend: impl FnMut(&Response, &mut serde_json::Map<String, serde_json::Value>),
) -> serde_json::Result<serde_json::Value> {
    let mut object = |r: &Response| {
        let mut value = serde_json::to_value(r)?;
        if let serde_json::Value::Object(map) = &mut value {
            extend(r, map);
        }
        Ok::<_, serde_json::Error>(value)
    };
    let Some((first, rest)) = responses.split_first() else {
        return Ok(serde_json::json!({"kind": "none"}));
    };
    let mut value = object(first)?;
    if !rest.is_empty()
        && let serde_json::Value::Object(map) = &mut value
    {
        let more = rest
            .iter()
            .map(&mut object)
            .collect::<serde_json::Result<Vec<_>>>()?;
        map.insert("more".into(), serde_json::Value::Array(more));
    }
    Ok(value)
}

/// [`json_object`] as one line of text, with nothing added: what `lagrange repl --json` prints.
pub fn json_line(responses: &[Response]) -> serde_json::Result<String> {
    serde_json::to_string(&json_object(responses, |_, _| {})?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tagged_by_kind() {
        let r = Response::error("unknown-command", "no", Some("hint".into()));
        let json = serde_json::to_value(&r).unwrap_or_default();
        assert_eq!(json["kind"], r.kind());
        assert_eq!(json["suggestion"], "hint");
        let q = serde_json::to_value(Response::Quit).unwrap_or_default();
        assert_eq!(q, serde_json::json!({"kind": "quit"}));
    }

    #[test]
    fn a_step_verdict_has_step_not_part_and_next_only_when_given() {
        let verdict = Verdict {
            problem: "p".into(),
            part: "kinetic".into(),
            status: crate::check::Status::Correct,
            score: 1.0,
            reading: Default::default(),
            diagnoses: vec![],
            seed: 0,
            parse_error: None,
        };
        let mut reply = StepVerdictReply {
            verdict,
            step: "kinetic".into(),
            number: 3,
            total: 13,
            attempts: 1,
            next: Some(None),
        };
        let json = serde_json::to_value(Response::StepVerdict(reply.clone())).unwrap_or_default();
        assert_eq!(json["kind"], "verdict");
        assert_eq!(json["step"], "kinetic");
        assert!(json.get("part").is_none(), "{json}");
        assert_eq!(json.get("next"), Some(&serde_json::Value::Null));
        reply.next = None;
        let json = serde_json::to_value(Response::StepVerdict(reply)).unwrap_or_default();
        assert!(json.get("next").is_none(), "{json}");
    }
}

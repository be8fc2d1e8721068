//! One input line of a practice session as a [`Command`]: a line starting with `:` is a
//! command (`help`, `hint`, `quit` and `exit` also work without the colon); any other line is
//! an answer. The table [`COMMANDS`] gives each command's usage and summary, for `:help`, for
//! completion and for "did you mean".

/// What one input line asks for.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Command {
    /// `:problems` — the bank with each problem's progress.
    Problems,
    /// `:open ID` — open a problem.
    Open(String),
    /// `:part ID|N` — make a part current, by id or 1-based number.
    Part(String),
    /// `:parts` — the open problem's parts and their state.
    Parts,
    /// `:next` — the next unsolved part.
    Next,
    /// `:skip` — leave the current part unsolved and go to the next part.
    Skip,
    /// `:hint` — the next hint of the current part.
    Hint,
    /// `:solution` — the reference answer (marks the part revealed).
    Solution,
    /// `:tutor` — start the guided derivation.
    Tutor,
    /// `:show` — reveal the current tutor step.
    Show,
    /// `:back` — leave the tutor.
    Back,
    /// `:read EXPR` — how an expression is read.
    Read(String),
    /// `:derive [L]` — the derivation of the open problem, or of a typed Lagrangian.
    Derive(String),
    /// `:modes [L]` — equilibria and normal modes of the open problem, or of a typed Lagrangian.
    Modes(String),
    /// `:simulate [--init …] [--t-end T] [--params …]` — integrate the open problem's motion.
    Simulate(String),
    /// `:progress` — the student's progress over the bank.
    Progress,
    /// `:variant` — practise the open problem with fresh numbers (one with variants).
    Variant,
    /// `:help [COMMAND]` — the commands, or one command's usage.
    Help(Option<String>),
    /// `:quit` / `:exit` — end the session.
    Quit,
    /// A blank line: nothing to do.
    Empty,
    /// Any other line: an answer to the current part.
    Answer(String),
}

/// Whether a command takes an argument.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arg {
    /// No argument.
    None,
    /// A required argument.
    Required,
    /// An optional argument.
    Optional,
}

/// A command's name, usage and one-line summary.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CommandInfo {
    /// The name without the colon, e.g. `open`.
    pub(crate) name: &'static str,
    /// The usage line, e.g. `:open ID`.
    pub usage: &'static str,
    /// What it does.
    pub summary: &'static str,
    /// Its argument.
    pub(crate) arg: Arg,
}

const fn info(
    name: &'static str,
    usage: &'static str,
    arg: Arg,
    summary: &'static str,
) -> CommandInfo {
    CommandInfo {
        name,
        usage,
        summary,
        arg,
    }
}

/// Every command, in the order `:help` lists them.
pub const COMMANDS: &[CommandInfo] = &[
    info(
        "problems",
        ":problems",
        Arg::None,
        "the problems, with your progress on each",
    ),
    info(
        "open",
        ":open ID",
        Arg::Required,
        "open a problem: its statement and parts",
    ),
    info(
        "part",
        ":part ID|N",
        Arg::Required,
        "answer another part of the open problem",
    ),
    info(
        "parts",
        ":parts",
        Arg::None,
        "the open problem's parts and where you are",
    ),
    info("next", ":next", Arg::None, "go to the next unsolved part"),
    info(
        "skip",
        ":skip",
        Arg::None,
        "leave this part for now and go to the next one",
    ),
    info(
        "hint",
        ":hint",
        Arg::None,
        "the next hint for the current part",
    ),
    info(
        "solution",
        ":solution",
        Arg::None,
        "the reference answer (marks the part revealed)",
    ),
    info(
        "tutor",
        ":tutor",
        Arg::None,
        "be walked through the derivation step by step",
    ),
    info(
        "show",
        ":show",
        Arg::None,
        "in the tutor: reveal the current step and move on",
    ),
    info("back", ":back", Arg::None, "leave the tutor"),
    info(
        "read",
        ":read EXPR",
        Arg::Required,
        "show how an expression is read",
    ),
    info(
        "derive",
        ":derive [L]",
        Arg::Optional,
        "derive the equations of motion",
    ),
    info(
        "modes",
        ":modes [L]",
        Arg::Optional,
        "equilibria and normal modes",
    ),
    info(
        "simulate",
        ":simulate [--init …] [--t-end T] [--params …]",
        Arg::Optional,
        "integrate the open problem's motion from its suggested start (or --init, --params; --t-end up to 1000): a chart of q(t) and a summary",
    ),
    info(
        "progress",
        ":progress",
        Arg::None,
        "your progress over the whole bank",
    ),
    info(
        "variant",
        ":variant",
        Arg::None,
        "practise the open problem with fresh numbers (a problem whose numbers vary by student)",
    ),
    info(
        "help",
        ":help [COMMAND]",
        Arg::Optional,
        "the commands, or how to use one",
    ),
    info("quit", ":quit", Arg::None, "end the session (also :exit)"),
    info("exit", ":exit", Arg::None, "end the session (also :quit)"),
];

/// The entry of [`COMMANDS`] named `name` (with or without its colon).
pub fn command_info(name: &str) -> Option<&'static CommandInfo> {
    let name = name.trim().trim_start_matches(':');
    COMMANDS.iter().find(|c| c.name == name)
}

/// Why a line is not a valid command.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum CommandError {
    /// No command has this name.
    #[error("there is no command `:{}`{}", crate::expr::error::visible(.name), suggestion_text(.suggestion))]
    Unknown {
        name: String,
        suggestion: Option<String>,
    },
    /// The command needs an argument.
    #[error("`:{name}` needs an argument: {usage}")]
    MissingArgument { name: String, usage: String },
    /// The command takes no argument.
    #[error("`:{name}` takes no argument: {usage}")]
    UnexpectedArgument { name: String, usage: String },
}

fn suggestion_text(s: &Option<String>) -> String {
    match s {
        Some(s) => format!(" — did you mean `:{s}`?"),
        None => " — `:help` lists the commands".to_string(),
    }
}

impl CommandError {
    /// A stable kebab-case code, e.g. `unknown-command`.
    pub fn code(&self) -> &'static str {
        match self {
            CommandError::Unknown { .. } => "unknown-command",
            CommandError::MissingArgument { .. } => "missing-argument",
            CommandError::UnexpectedArgument { .. } => "unexpected-argument",
        }
    }
}

/// The words that are commands without a colon.
const BARE: [&str; 4] = ["help", "hint", "quit", "exit"];

/// Reads one input line.
pub fn parse(line: &str) -> Result<Command, CommandError> {
    let line = line.trim();
    if line.is_empty() {
        return Ok(Command::Empty);
    }
    let (word, rest) = match line.split_once(char::is_whitespace) {
        Some((w, r)) => (w, r.trim()),
        None => (line, ""),
    };
    if let Some(name) = word.strip_prefix(':') {
        return command(name, rest);
    }
    // `help`, `hint`, `quit`, `exit` work bare; `help open` too. Nothing else is a command.
    if BARE.contains(&word) && (rest.is_empty() || word == "help") {
        return command(word, rest);
    }
    Ok(Command::Answer(line.to_string()))
}

fn command(name: &str, rest: &str) -> Result<Command, CommandError> {
    let Some(info) = command_info(name) else {
        let suggestion = did_you_mean(name, COMMANDS.iter().map(|c| c.name));
        return Err(CommandError::Unknown {
            name: name.to_string(),
            suggestion,
        });
    };
    match (info.arg, rest.is_empty()) {
        (Arg::Required, true) => {
            return Err(CommandError::MissingArgument {
                name: info.name.to_string(),
                usage: info.usage.to_string(),
            });
        }
        (Arg::None, false) => {
            return Err(CommandError::UnexpectedArgument {
                name: info.name.to_string(),
                usage: info.usage.to_string(),
            });
        }
        _ => {}
    }
    let arg = rest.to_string();
    Ok(match info.name {
        "problems" => Command::Problems,
        "open" => Command::Open(arg),
        "part" => Command::Part(arg),
        "parts" => Command::Parts,
        "next" => Command::Next,
        "skip" => Command::Skip,
        "hint" => Command::Hint,
        "solution" => Command::Solution,
        "tutor" => Command::Tutor,
        "show" => Command::Show,
        "back" => Command::Back,
        "read" => Command::Read(arg),
        "derive" => Command::Derive(arg),
        "modes" => Command::Modes(arg),
        "simulate" => Command::Simulate(arg),
        "progress" => Command::Progress,
        "variant" => Command::Variant,
        "help" => Command::Help((!arg.is_empty()).then_some(arg)),
        _ => Command::Quit,
    })
}

pub use crate::diagnostic::did_you_mean;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn commands_and_answers() {
        assert_eq!(
            parse(":open simple-pendulum"),
            Ok(Command::Open("simple-pendulum".into()))
        );
        assert_eq!(parse("  hint "), Ok(Command::Hint));
        assert_eq!(parse("exit"), Ok(Command::Quit));
        assert_eq!(parse(":exit"), Ok(Command::Quit));
        assert_eq!(parse("help open"), Ok(Command::Help(Some("open".into()))));
        assert_eq!(parse(":help"), Ok(Command::Help(None)));
        assert_eq!(parse(":derive"), Ok(Command::Derive(String::new())));
        assert_eq!(parse(":read  m*g*l "), Ok(Command::Read("m*g*l".into())));
        assert_eq!(parse(""), Ok(Command::Empty));
        assert_eq!(
            parse("m*l^2*theta'"),
            Ok(Command::Answer("m*l^2*theta'".into()))
        );
        // `hint` followed by more is an answer (the bare words are whole lines).
        assert_eq!(parse("hint + 1"), Ok(Command::Answer("hint + 1".into())));
    }

    #[test]
    fn errors_suggest() {
        let e = parse(":hnit");
        assert_eq!(
            e,
            Err(CommandError::Unknown {
                name: "hnit".into(),
                suggestion: Some("hint".into())
            })
        );
        assert!(
            e.err()
                .is_some_and(|e| e.to_string().contains("did you mean `:hint`"))
        );
        assert!(matches!(
            parse(":open"),
            Err(CommandError::MissingArgument { .. })
        ));
        assert!(matches!(
            parse(":hint 2"),
            Err(CommandError::UnexpectedArgument { .. })
        ));
        assert_eq!(
            did_you_mean("pendulum", ["atwood", "simple-pendulum"].into_iter()),
            Some("simple-pendulum".into())
        );
        assert_eq!(did_you_mean("zzzz", ["atwood"].into_iter()), None);
    }
}

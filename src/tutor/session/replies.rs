//! Replies shared by the session's files: the errors for no open problem, outside the tutor
//! and `:solution` inside it, `:help`, and user text made visible in messages. A leaf: it
//! imports nothing from the session.

use crate::tutor::command::{COMMANDS, command_info, did_you_mean};
use crate::tutor::response::{HelpEntry, HelpReply, Response};

pub(super) fn not_in_tutor() -> Response {
    Response::error(
        "not-in-tutor",
        "the tutor is not running: `:tutor` starts the guided derivation of the open problem",
        None,
    )
}

pub(super) fn solution_in_tutor() -> Response {
    Response::error(
        "in-tutor",
        "in the tutor, `:show` reveals the current step; `:back` returns to the parts",
        None,
    )
}

pub(super) fn no_problem() -> Response {
    Response::error(
        "no-problem-open",
        "no problem is open: `:open ID` opens one (`:problems` lists them)",
        None,
    )
}

/// Help on every command, or on one (an unknown one gets did-you-mean).
pub(super) fn help(topic: Option<&str>) -> Response {
    let entry = |c: &crate::tutor::command::CommandInfo| HelpEntry {
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
pub(super) fn visible(s: &str) -> String {
    crate::expr::error::visible(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn help_on_one_command_and_an_unknown_one() {
        assert!(matches!(help(Some(":open")), Response::Help(h) if h.commands.len() == 1));
        assert!(matches!(help(None), Response::Help(h) if h.commands.len() == COMMANDS.len()));
        let r = help(Some("hitn"));
        assert!(matches!(r, Response::Error(e) if e.suggestion.as_deref() == Some(":hint")));
    }
}

//! Line editing for a terminal (rustyline): Tab completion through `Session::complete`,
//! matching-bracket highlighting, a greyed hint after the cursor (how the line will be read,
//! or the usage of the command being typed) and a validator that keeps a line with
//! unbalanced brackets open.
//!
//! The hint and the bracket highlighting work on the whole line at every keystroke, so they
//! stop past [`LIVE_HELP_MAX_BYTES`]: a long line pasted without bracketed paste then costs
//! time linear in its length (each character is echoed as typed, issue 20 §6) instead of a
//! reading and a repaint of the whole line per character.

use std::borrow::Cow;
use std::cell::RefCell;
use std::rc::Rc;

use rustyline::completion::Completer;
use rustyline::highlight::{CmdKind, Highlighter, MatchingBracketHighlighter};
use rustyline::hint::Hinter;
use rustyline::validate::{
    MatchingBracketValidator, ValidationContext, ValidationResult, Validator,
};
use rustyline::{Context, Helper};

use lagrange::tutor::Session;
use lagrange::tutor::command::command_info;

/// The longest line that gets a hint and bracket highlighting as it is typed. Beyond it the
/// hint could not be read on one screen line anyway; the line is still read in full on Enter.
pub const LIVE_HELP_MAX_BYTES: usize = 400;

/// The REPL's rustyline helper, sharing the session with the loop.
pub struct ReplHelper {
    /// The session (borrowed only while a line is edited).
    pub session: Rc<RefCell<Session>>,
    brackets: MatchingBracketHighlighter,
    validator: MatchingBracketValidator,
    color: bool,
}

impl ReplHelper {
    /// A helper over `session`; `color` greys the hint.
    pub fn new(session: Rc<RefCell<Session>>, color: bool) -> ReplHelper {
        ReplHelper {
            session,
            brackets: MatchingBracketHighlighter::new(),
            validator: MatchingBracketValidator::new(),
            color,
        }
    }
}

/// What the hint shows for `line`: a command's usage, or how an answer will be read; nothing
/// for a line longer than [`LIVE_HELP_MAX_BYTES`].
pub fn hint_for(session: &Session, line: &str) -> Option<String> {
    let t = line.trim_start();
    if t.is_empty() || line.len() > LIVE_HELP_MAX_BYTES {
        return None;
    }
    if let Some(cmd) = t.strip_prefix(':') {
        let (name, arg) = cmd.split_once(' ').unwrap_or((cmd, ""));
        if name == "read" && !arg.trim().is_empty() {
            return reading_hint(session, arg.trim());
        }
        let info = command_info(name)?;
        // While the name is typed: what follows it in the usage, and what it does.
        let args = info.usage.split_once(' ').map_or("", |(_, a)| a);
        return (!cmd.contains(' ')).then(|| format!(" {args}   — {}", info.summary));
    }
    reading_hint(session, t)
}

/// How `text` is read in the open problem's context, unless that is just `text` again.
fn reading_hint(session: &Session, text: &str) -> Option<String> {
    let problem = session.problem()?;
    let ctx = problem.context();
    let mut pool = problem.system.pool.clone();
    let reading = lagrange::read(text, &ctx, &mut pool).ok()?;
    let shown = reading.unicode(&pool);
    (shown != text).then(|| format!("   ⇒ {shown}"))
}

impl Completer for ReplHelper {
    type Candidate = String;
    fn complete(
        &self,
        line: &str,
        pos: usize,
        _ctx: &Context<'_>,
    ) -> rustyline::Result<(usize, Vec<String>)> {
        let before = line.get(..pos).unwrap_or(line);
        Ok(self.session.borrow().complete(before))
    }
}

impl Hinter for ReplHelper {
    type Hint = String;
    fn hint(&self, line: &str, pos: usize, _ctx: &Context<'_>) -> Option<String> {
        if pos < line.len() {
            return None;
        }
        hint_for(&self.session.borrow(), line)
    }
}

impl Highlighter for ReplHelper {
    fn highlight<'l>(&self, line: &'l str, pos: usize) -> Cow<'l, str> {
        if self.color && line.len() <= LIVE_HELP_MAX_BYTES {
            self.brackets.highlight(line, pos)
        } else {
            Cow::Borrowed(line)
        }
    }
    fn highlight_hint<'h>(&self, hint: &'h str) -> Cow<'h, str> {
        if self.color {
            Cow::Owned(format!("\x1b[2m{hint}\x1b[0m"))
        } else {
            Cow::Borrowed(hint)
        }
    }
    fn highlight_char(&self, line: &str, pos: usize, kind: CmdKind) -> bool {
        // `false` lets rustyline echo the character alone rather than repaint the line.
        self.color
            && line.len() <= LIVE_HELP_MAX_BYTES
            && self.brackets.highlight_char(line, pos, kind)
    }
}

impl Validator for ReplHelper {
    /// A line with an unclosed bracket stays open, and says so (a bare new line would look
    /// hung): how to finish it and how to cancel.
    fn validate(&self, ctx: &mut ValidationContext) -> rustyline::Result<ValidationResult> {
        match self.validator.validate(ctx)? {
            ValidationResult::Incomplete => {
                Ok(ValidationResult::Invalid(Some(continuation(ctx.input()))))
            }
            other => Ok(other),
        }
    }
}

/// What a line with unclosed brackets shows under it.
pub fn continuation(input: &str) -> String {
    let open = input.chars().filter(|c| matches!(c, '(' | '[')).count();
    let closed = input.chars().filter(|c| matches!(c, ')' | ']')).count();
    let n = open.saturating_sub(closed).max(1);
    let what = if n == 1 {
        "a bracket is still open".to_string()
    } else {
        format!("{n} brackets are still open")
    };
    // Short enough for 80 columns with 2 brackets open (the editor would break it mid-word).
    format!("\n  … {what}: type `)` and Enter, or Ctrl-C to cancel the line")
}

impl Helper for ReplHelper {}

#[cfg(test)]
mod tests {
    use super::*;
    use lagrange::tutor::Progress;

    #[test]
    fn hints_usage_and_reading() {
        let mut s = Session::new(lagrange::embedded::bank(), Progress::new());
        let open = hint_for(&s, ":open").unwrap_or_default();
        assert!(open.starts_with(" ID   — "), "{open}");
        assert_eq!(hint_for(&s, "theta'"), None);
        s.handle(":open simple-pendulum");
        let h = hint_for(&s, "1/2 m l^2 theta'^2").unwrap_or_default();
        assert!(h.contains('θ'), "{h}");
        assert_eq!(hint_for(&s, "g"), None);
        let r = hint_for(&s, ":read theta''").unwrap_or_default();
        assert!(r.contains('θ'), "{r}");
    }

    /// Issue 20 §6: a 19 kB line typed (or pasted without bracketed paste) one character at
    /// a time asks for a hint at every character; past the bound the hint costs nothing, so
    /// the whole line costs time linear in its length (it took ~20 s).
    #[test]
    fn hinting_a_long_line_character_by_character_is_linear() {
        let mut s = Session::new(lagrange::embedded::bank(), Progress::new());
        s.handle(":open simple-pendulum");
        let line = "m*l^2*theta'^2 + ".repeat(19_000 / 17);
        let start = std::time::Instant::now();
        let mut hinted = 0;
        for end in 1..=line.len() {
            hinted += usize::from(hint_for(&s, &line[..end]).is_some());
        }
        let took = start.elapsed();
        assert!(hinted > 0 && hinted <= LIVE_HELP_MAX_BYTES, "{hinted}");
        assert!(took.as_secs_f64() < 2.0, "19,000 hints took {took:?}");
    }
}

//! The student's REPL (`lagrange`, `lagrange repl`): a face over `lagrange::tutor::Session`.
//! On a terminal it edits lines with rustyline (see [`editor`]); piped, it reads lines plainly,
//! prints no prompt and no colour, and ends with exit 0 at end of input. With `--json` every
//! input line gets exactly one JSON object (see `docs/repl-protocol.md`). Progress is kept in
//! the data directory (see [`store`]). No mathematics here.

mod editor;
mod render;
mod store;
mod wrap;

use std::cell::RefCell;
use std::io::{BufRead, IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;
use std::rc::Rc;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use clap::Args;
use lagrange::report::{Paint, Plain};
use lagrange::tutor::{Progress, Response, Session};

use crate::face::Terminal;

/// `lagrange repl [PROBLEM] [--json] [--no-save]`.
#[derive(Args, Debug, Default)]
pub struct ReplArgs {
    /// A problem id to open first.
    pub problem: Option<String>,
    /// One JSON object per input line (JSON lines; see docs/repl-protocol.md).
    #[arg(long)]
    pub json: bool,
    /// Keep no progress file.
    #[arg(long)]
    pub no_save: bool,
}

/// How the REPL was asked to run.
pub struct Options {
    /// A problem to open first.
    pub problem: Option<String>,
    /// JSON lines instead of text.
    pub json: bool,
    /// Keep no progress file.
    pub no_save: bool,
    /// The folder of problem files (`--problems`), else the embedded bank.
    pub problems: Option<PathBuf>,
    /// Colour (already resolved from `--color` and NO_COLOR).
    pub color: bool,
}

/// Where responses go: text or JSON lines, and the progress file.
struct Output {
    json: bool,
    color: bool,
    /// The terminal's width in columns, when the text is wrapped to it (interactive only).
    width: Option<usize>,
    store: Option<store::Store>,
}

impl Output {
    /// Prints the responses to `line`, saves progress; `true` when the session ends.
    fn emit(&mut self, line: &str, responses: &[Response], session: &Session) -> bool {
        let text = if self.json {
            json_line(responses).map(|j| j + "\n").unwrap_or_default()
        } else {
            let paint: &dyn Paint = if self.color { &Terminal } else { &Plain };
            let texts: Vec<String> = responses
                .iter()
                .map(|r| match (r, self.width) {
                    // A statement wrapped at the terminal's width is one paragraph per
                    // paragraph of the file, not the file's own line breaks.
                    (Response::Statement(s), Some(_)) => {
                        let mut s = s.clone();
                        s.sheet.statement = wrap::reflow(&s.sheet.statement);
                        render::response(&Response::Statement(s), line, paint, self.color)
                    }
                    _ => render::response(r, line, paint, self.color),
                })
                .collect();
            match self.width {
                Some(w) => wrap::wrap(&texts.concat(), w),
                None => texts.concat(),
            }
        };
        let mut out = std::io::stdout().lock();
        // A closed pipe (`… | head`) just ends the output; anything else is worth a word.
        if let Err(e) = out.write_all(text.as_bytes()).and_then(|()| out.flush())
            && e.kind() != std::io::ErrorKind::BrokenPipe
        {
            eprintln!("warning: cannot write the output: {e}");
        }
        if let Some(s) = &mut self.store
            && let Err(e) = s.save(session.progress())
        {
            eprintln!("warning: could not save progress: {e}");
        }
        responses.iter().any(|r| matches!(r, Response::Quit))
    }
}

// One JSON object per input line: built by the library, shared with the browser face.
pub use lagrange::tutor::response::json_line;

/// Runs the REPL until `:quit`, Ctrl-D or the end of input.
pub fn run(opts: &Options) -> anyhow::Result<ExitCode> {
    let bank = crate::face::load_bank(opts.problems.as_deref()).map_err(anyhow::Error::msg)?;
    let (store, progress) = open_store(opts.no_save);
    let session = Rc::new(RefCell::new(Session::new(bank, progress)));
    let terminal = std::io::stdin().is_terminal();
    let mut out = Output {
        json: opts.json,
        color: opts.color && terminal && !opts.json,
        width: None,
        store,
    };
    if terminal && !out.json {
        println!("lagrange — `:problems` lists the problems, `:help` the commands, Ctrl-D quits.");
    }
    if let Some(id) = &opts.problem {
        let line = format!(":open {id}");
        let r = session.borrow_mut().handle(&line);
        out.emit(&line, &r, &session.borrow());
    }
    if terminal {
        interactive(&session, &mut out)?;
    } else {
        piped(&session, &mut out)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// The progress file (none with `--no-save` or without a data directory) and its progress.
fn open_store(no_save: bool) -> (Option<store::Store>, Progress) {
    if no_save {
        return (None, Progress::new());
    }
    let Some(dir) = store::data_dir() else {
        eprintln!("warning: no data directory; progress will not be saved");
        return (None, Progress::new());
    };
    let (s, progress, warning) = store::Store::open(&dir);
    if let Some(w) = warning {
        eprintln!("{w}");
    }
    (Some(s), progress)
}

/// Lines from a pipe: no prompt, no editing. A line that is not UTF-8 gets an error reply
/// (`not-utf8`) and the session goes on.
fn piped(session: &Rc<RefCell<Session>>, out: &mut Output) -> anyhow::Result<()> {
    for bytes in std::io::stdin().lock().split(b'\n') {
        let mut bytes = bytes?;
        if bytes.last() == Some(&b'\r') {
            bytes.pop();
        }
        let (line, r) = match String::from_utf8(bytes) {
            Ok(line) => {
                let r = session.borrow_mut().handle(&line);
                (line, r)
            }
            Err(e) => {
                let bad = e.utf8_error().valid_up_to();
                let line = String::from_utf8_lossy(e.as_bytes()).into_owned();
                let message = format!(
                    "this line is not UTF-8 (byte {} is 0x{:02X}); it was not read",
                    bad + 1,
                    e.as_bytes()[bad]
                );
                let reply = Response::error("not-utf8", message, None);
                (line, vec![reply])
            }
        };
        if out.emit(&line, &r, &session.borrow()) {
            break;
        }
    }
    Ok(())
}

/// Lines from a terminal, with rustyline: history, completion, hints, validation.
fn interactive(session: &Rc<RefCell<Session>>, out: &mut Output) -> anyhow::Result<()> {
    use rustyline::error::ReadlineError;
    let mut rl =
        rustyline::Editor::<editor::ReplHelper, rustyline::history::DefaultHistory>::new()?;
    rl.set_helper(Some(editor::ReplHelper::new(session.clone(), out.color)));
    let history = store::data_dir().map(|d| d.join("history.txt"));
    if let Some(h) = &history {
        // No history file yet is the normal first run.
        rl.load_history(h).ok();
    }
    loop {
        // The prompt names what a line answers: the tutor's step, else the current part.
        let prompt = {
            let s = session.borrow();
            match (s.current_step(), s.current_part()) {
                (Some(step), _) => format!("tutor {step}> "),
                (None, Some(part)) => format!("{part}> "),
                (None, None) => "> ".to_string(),
            }
        };
        match rl.readline(&prompt) {
            Ok(line) => {
                // The width now (the window may have been resized since the last line).
                out.width = rl.dimensions().map(|(cols, _)| usize::from(cols));
                // A history entry that cannot be added (a duplicate, an empty line) is no error.
                rl.add_history_entry(line.as_str()).ok();
                let r = interruptible(!out.json, || session.borrow_mut().handle(&line));
                if out.emit(&line, &r, &session.borrow()) {
                    break;
                }
            }
            Err(ReadlineError::Interrupted) => continue,
            Err(ReadlineError::Eof) => break,
            Err(e) => return Err(e.into()),
        }
    }
    if let Some(h) = &history {
        let saved = h
            .parent()
            .map_or(Ok(()), std::fs::create_dir_all)
            .map_err(|e| e.to_string())
            .and_then(|()| rl.save_history(h).map_err(|e| e.to_string()));
        if let Err(e) = saved {
            eprintln!(
                "warning: the line history was not saved ({}): {e}",
                h.display()
            );
        }
    }
    Ok(())
}

/// Runs `f` (one command) with Ctrl-C stopping the long library call inside it, such as the
/// integration of `:simulate`, which then answers "interrupted" while the REPL and its
/// history go on. The SIGINT handler is installed only for the call: it sets a flag that the
/// call's progress callback polls (with a bar on stderr for a long call, without `--json`).
fn interruptible<R>(bar: bool, f: impl FnOnce() -> R) -> R {
    let flag = Arc::new(AtomicBool::new(false));
    let id = signal_hook::flag::register(signal_hook::consts::SIGINT, flag.clone()).ok();
    let bar = crate::face::bar::Bar::percent(bar).stopped_by(flag);
    let r = lagrange::progress::with_ambient(Box::new(bar), f);
    if let Some(id) = id {
        signal_hook::low_level::unregister(id);
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn several_responses_make_one_object() {
        let rs = [Response::error("a", "first", None), Response::Quit];
        let j = json_line(&rs).unwrap_or_default();
        assert_eq!(
            j,
            r#"{"code":"a","kind":"error","message":"first","more":[{"kind":"quit"}]}"#
        );
        assert_eq!(json_line(&[]).unwrap_or_default(), r#"{"kind":"none"}"#);
    }
}

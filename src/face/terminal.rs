//! The terminal: colours for every report (through `colored`, which honours `--color` and
//! NO_COLOR) and writing a command's output to standard output.

use colored::Colorize;

use lagrange::report::Paint;

/// Colour for a terminal, through `colored` (which honours `--color` and NO_COLOR).
pub struct Terminal;

impl Paint for Terminal {
    fn heading(&self, text: &str) -> String {
        text.bold().to_string()
    }
    fn good(&self, text: &str) -> String {
        text.green().to_string()
    }
    fn bad(&self, text: &str) -> String {
        text.red().to_string()
    }
    fn warn(&self, text: &str) -> String {
        text.yellow().to_string()
    }
    fn dim(&self, text: &str) -> String {
        text.dimmed().to_string()
    }
}

/// Writes a command's output; a closed pipe (`lagrange … | head`) is not an error.
pub fn emit(text: &str) -> std::io::Result<()> {
    use std::io::Write;
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
    {
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        other => other,
    }
}

//! The `lagrange` command line: a thin clap layer over the library. It parses arguments,
//! calls the library and prints; it holds no mathematics.
//!
//! Exit codes: 0 success, 1 "no" (the input could not be read or is inconsistent),
//! 2 usage or other error.

mod bar;
mod cli;
mod grade;
mod outfile;
mod plot;
mod repl;

use std::process::ExitCode;

fn main() -> ExitCode {
    match cli::run() {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

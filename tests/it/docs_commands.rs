//! Every command the README and `docs/*.md` show is run here, against the built binary, and
//! its output compared with the output the page shows. The convention (also in
//! `docs/development.md`, "Documented commands"):
//!
//! - a fenced block tagged `console` is a transcript: a line starting with `$ ` is a command
//!   (a trailing ` \` continues it on the next line), the lines after it up to the next `$ `
//!   are what it prints (standard output, then standard error); a last line `[exit N]` states
//!   a non-zero exit code;
//! - in the documented output, a line that starts with `…` stands for any number of lines
//!   (none included), and a line that ends with `…` for one line that starts with the text
//!   before it; every other line must be printed exactly (trailing spaces aside);
//! - a command that only sets a shell variable (`$ L="…"`) is kept and run before every later
//!   command of the same page;
//! - each page's commands run in order, with `sh`, in one fresh temporary folder holding an
//!   empty `docs/` and a copy of `examples/`, with the built `lagrange` first on `PATH`,
//!   `NO_COLOR` set and the REPL's progress kept inside the folder — so a command may use a
//!   file an earlier command of its page wrote, and a picture `docs/x.svg` is written there,
//!   never over the committed one;
//! - in a release build a command must take at most 3 s of CPU time (user + system, its
//!   threads included): a slow example is shown at a smaller size;
//! - a `lagrange` command anywhere else in a fenced block (`sh`, `bash`, untagged) is an
//!   error here: a synopsis with placeholders is tagged `text`, and is not run.

use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// The pages whose commands are run: the README and every `docs/*.md`.
fn pages() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut pages: Vec<PathBuf> = std::fs::read_dir(root.join("docs"))
        .expect("docs/")
        .map(|e| e.expect("a docs/ entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .collect();
    pages.sort();
    pages.insert(0, root.join("README.md"));
    pages
}

/// One documented command with what the page says it prints.
#[derive(Debug)]
struct Documented {
    /// The 1-based line of the `$ ` in its page.
    line: usize,
    /// The command, continuation lines joined.
    command: String,
    /// The documented standard output (may be empty: then only the exit code is checked).
    output: Vec<String>,
    /// The documented exit code (`[exit N]`, else 0).
    exit: i32,
}

/// The commands of `text` (one page), or the convention's violations.
fn parse(text: &str) -> Result<Vec<Documented>, Vec<String>> {
    let mut commands: Vec<Documented> = Vec::new();
    let mut problems = Vec::new();
    let mut fence: Option<String> = None;
    let mut continuing = false;
    for (n, raw) in text.lines().enumerate() {
        let line = raw.trim_end();
        if let Some(tag) = line.trim_start().strip_prefix("```") {
            if fence.is_none() {
                fence = Some(tag.trim().to_string());
                continue;
            }
            if tag.trim().is_empty() {
                fence = None;
                continuing = false;
                continue;
            }
        }
        let Some(tag) = fence.as_deref() else {
            continue;
        };
        if tag != "console" {
            let t = line.trim_start();
            if tag != "text" && (t.starts_with("lagrange ") || t.starts_with("$ ")) {
                problems.push(format!(
                    "line {}: a command in a ```{tag} block is not run: tag the block \
                     ```console (a synopsis: ```text)",
                    n + 1
                ));
            }
            continue;
        }
        if continuing {
            let last = commands.last_mut().expect("a command is being continued");
            continuing = line.ends_with(" \\");
            last.command.push(' ');
            last.command
                .push_str(line.trim_start().trim_end_matches(" \\"));
        } else if let Some(command) = line.strip_prefix("$ ") {
            continuing = command.ends_with(" \\");
            commands.push(Documented {
                line: n + 1,
                command: command.trim_end_matches(" \\").to_string(),
                output: Vec::new(),
                exit: 0,
            });
        } else if let Some(last) = commands.last_mut() {
            match line
                .strip_prefix("[exit ")
                .and_then(|r| r.strip_suffix(']'))
            {
                Some(code) => last.exit = code.parse().unwrap_or(-1),
                None => last.output.push(line.to_string()),
            }
        } else {
            problems.push(format!(
                "line {}: a ```console block must start with a `$ ` command",
                n + 1
            ));
        }
    }
    if problems.is_empty() {
        Ok(commands)
    } else {
        Err(problems)
    }
}

/// Whether `command` only sets shell variables (`L="…"`): kept for the later commands.
fn is_assignment(command: &str) -> bool {
    let name_len = command
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(0);
    name_len > 0 && command[name_len..].starts_with('=') && !command.contains("lagrange")
}

/// Whether the printed lines `actual` match the documented `expected` (see the module's
/// convention for `…`).
fn matches(expected: &[String], actual: &[&str]) -> bool {
    let Some((first, rest)) = expected.split_first() else {
        return actual.is_empty();
    };
    let first = first.trim_end();
    if first.trim_start().starts_with('…') {
        return (0..=actual.len()).any(|skip| matches(rest, &actual[skip..]));
    }
    let Some((line, more)) = actual.split_first() else {
        return false;
    };
    let line = line.trim_end();
    let fits = match first.strip_suffix('…') {
        Some(prefix) => line.starts_with(prefix),
        None => line == first,
    };
    fits && matches(rest, more)
}

/// The CPU time (user + system) of the children of a `sh` that ran `times` into `path`.
fn children_cpu(path: &Path) -> Option<Duration> {
    let text = std::fs::read_to_string(path).ok()?;
    // Two lines: the shell's own times, then its children's: "0m1.234s 0m0.056s".
    let children = text.lines().nth(1)?;
    let mut total = 0.0;
    for field in children.split_whitespace() {
        let (minutes, seconds) = field.strip_suffix('s')?.split_once('m')?;
        total += minutes.parse::<f64>().ok()? * 60.0 + seconds.parse::<f64>().ok()?;
    }
    Some(Duration::from_secs_f64(total))
}

/// Runs one command in `dir`; (exit code, stdout, stderr, CPU time).
fn run(dir: &Path, prelude: &str, command: &str) -> (i32, String, String, Option<Duration>) {
    let bin = Path::new(env!("CARGO_BIN_EXE_lagrange"));
    let path = std::env::join_paths(
        std::iter::once(bin.parent().expect("the binary's folder").to_path_buf()).chain(
            std::env::split_paths(&std::env::var_os("PATH").unwrap_or_default()),
        ),
    )
    .expect("a PATH");
    let times = dir.join(".times");
    let script = format!("{prelude}{command}\nstatus=$?\ntimes > .times\nexit $status\n");
    let mut child = Command::new("sh")
        .args(["-c", &script])
        .current_dir(dir)
        .env("PATH", path)
        .env("NO_COLOR", "1")
        .env("LAGRANGE_HOME", dir.join(".lagrange"))
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("sh runs");
    // Read both pipes on threads so a long output cannot block the child; a deadline stops a
    // command that hangs instead of stalling the suite.
    let mut stdout = child.stdout.take().expect("stdout piped");
    let mut stderr = child.stderr.take().expect("stderr piped");
    let out = std::thread::spawn(move || {
        let mut s = String::new();
        std::io::Read::read_to_string(&mut stdout, &mut s).ok();
        s
    });
    let err = std::thread::spawn(move || {
        let mut s = String::new();
        std::io::Read::read_to_string(&mut stderr, &mut s).ok();
        s
    });
    let start = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().expect("wait") {
            break Some(status);
        }
        if start.elapsed() > Duration::from_secs(120) {
            child.kill().ok();
            child.wait().ok();
            break None;
        }
        std::thread::sleep(Duration::from_millis(10));
    };
    let (out, err) = (
        out.join().unwrap_or_default(),
        err.join().unwrap_or_default(),
    );
    let cpu = children_cpu(&times);
    std::fs::remove_file(&times).ok();
    let code = status.and_then(|s| s.code()).unwrap_or(-1);
    (code, out, err, cpu)
}

/// Copies the folder `from` into `to`, recursively.
fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).expect("a folder");
    for entry in std::fs::read_dir(from).expect("a folder to copy") {
        let entry = entry.expect("an entry");
        let target = to.join(entry.file_name());
        if entry.file_type().expect("a file type").is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), target).expect("a copy");
        }
    }
}

#[test]
fn every_documented_command_runs_and_prints_what_its_page_shows() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut failures = Vec::new();
    let mut ran = 0;
    for page in pages() {
        let name = page
            .strip_prefix(root)
            .unwrap_or(&page)
            .display()
            .to_string();
        let text = std::fs::read_to_string(&page).expect("a page");
        let commands = match parse(&text) {
            Ok(commands) => commands,
            Err(problems) => {
                failures.extend(problems.into_iter().map(|p| format!("{name}: {p}")));
                continue;
            }
        };
        if commands.is_empty() {
            continue;
        }
        let dir = crate::helpers::scratch("docs");
        std::fs::create_dir_all(dir.join("docs")).expect("docs/");
        copy_dir(&root.join("examples"), &dir.join("examples"));
        let mut prelude = String::new();
        for doc in commands {
            let at = format!("{name}:{}", doc.line);
            if is_assignment(&doc.command) {
                prelude.push_str(&doc.command);
                prelude.push('\n');
                continue;
            }
            ran += 1;
            let (code, out, err, cpu) = run(&dir, &prelude, &doc.command);
            println!("{at}: {:?} CPU  $ {}", cpu.unwrap_or_default(), doc.command);
            if code != doc.exit {
                failures.push(format!(
                    "{at}: exit {code}, documented {}\n  $ {}\n{out}{err}",
                    doc.exit, doc.command
                ));
                continue;
            }
            // What a console shows: standard output, then standard error.
            let printed = format!("{out}{err}");
            let lines: Vec<&str> = printed.lines().collect();
            if !doc.output.is_empty() && !matches(&doc.output, &lines) {
                failures.push(format!(
                    "{at}: the output differs from the page's\n  $ {}\n--- documented\n{}\n--- printed\n{out}{err}",
                    doc.command,
                    doc.output.join("\n")
                ));
            }
            if cfg!(not(debug_assertions)) && cpu.is_some_and(|t| t > Duration::from_secs(3)) {
                failures.push(format!(
                    "{at}: took {cpu:?} of CPU time (more than 3 s): show it at a smaller size\n  $ {}",
                    doc.command
                ));
            }
        }
    }
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    // The README and the docs show commands: a parser that found none is broken.
    assert!(ran >= 24, "only {ran} documented commands found");
}

#[test]
fn the_convention_reads_transcripts_as_documented() {
    let page = "text\n```console\n$ lagrange a \\\n    --b c\nout 1\n…\nout 9\n[exit 1]\n$ X=\"y\"\n$ lagrange d\n```\n```sh\ncargo test\n```\n";
    let commands = parse(page).expect("a valid page");
    assert_eq!(commands.len(), 3);
    assert_eq!(commands[0].command, "lagrange a --b c");
    assert_eq!(commands[0].line, 3);
    assert_eq!(commands[0].output, ["out 1", "…", "out 9"]);
    assert_eq!(commands[0].exit, 1);
    assert!(is_assignment(&commands[1].command));
    assert!(!is_assignment(&commands[2].command));
    let doc: Vec<String> = ["a", "…", "z", "pre…"].map(String::from).to_vec();
    assert!(matches(&doc, &["a", "z", "prefix"]));
    assert!(matches(&doc, &["a", "b", "c", "z", "pre"]));
    assert!(!matches(&doc, &["a", "z"]));
    assert!(!matches(&doc, &["a", "z", "prefix", "extra"]));
    // A lagrange command outside a console block is refused, a synopsis in `text` is not.
    assert!(parse("```sh\nlagrange check x\n```\n").is_err());
    assert!(parse("```\n$ lagrange check x\n```\n").is_err());
    assert!(parse("```text\nlagrange grade FILE [--out DIR]\n```\n").is_ok());
}

/// The README is a guide a newcomer reads in five minutes: at most 250 lines, every link into
/// `docs/` pointing at a page that exists.
#[test]
fn the_readme_stays_short_and_its_links_resolve() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    for page in pages() {
        let text = std::fs::read_to_string(&page).expect("a page");
        let folder = page.parent().expect("a folder");
        if page.ends_with("README.md") {
            let lines = text.lines().count();
            assert!(
                lines <= 250,
                "README.md has {lines} lines: move detail into docs/"
            );
        }
        // Markdown links and pictures `](target)` to local files.
        for piece in text.split("](").skip(1) {
            let target = piece.split([')', '#']).next().unwrap_or_default();
            if target.is_empty() || target.contains("://") {
                continue;
            }
            assert!(
                folder.join(target).exists(),
                "{}: the link {target} leads nowhere",
                page.strip_prefix(root).unwrap_or(&page).display()
            );
        }
    }
}

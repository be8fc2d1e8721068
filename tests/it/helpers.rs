//! Shared helpers: contexts for the notes' systems, reading, evaluating.

use lagrange::expr::{Context, Id, Pool, Program, Reading, read, read_expr};

/// Coordinates used across the syntax tests.
pub fn mech_ctx() -> Context {
    Context::new()
        .with_coordinates(["theta", "theta1", "theta2", "x", "r"])
        .with_parameters([
            "m", "m1", "m2", "l", "l1", "l2", "g", "k", "a", "b", "omega", "alpha",
        ])
}

/// Reads `src` as an expression in `ctx`, panicking with the error (tests only).
pub fn expr(pool: &mut Pool, src: &str, ctx: &Context) -> Id {
    match read_expr(src, ctx, pool) {
        Ok(id) => id,
        Err(e) => panic!("could not read {src:?}: {e}"),
    }
}

/// Reads `src` in an open context and prints it in plain syntax.
pub fn plain_open(src: &str) -> String {
    let mut pool = Pool::new();
    let e = expr(&mut pool, src, &Context::open());
    pool.plain(e)
}

/// Reads `src` in the mechanics context and prints it in plain syntax.
pub fn plain_mech(src: &str) -> String {
    let mut pool = Pool::new();
    match read(src, &mech_ctx(), &mut pool) {
        Ok(Reading::Expr(e, _)) => pool.plain(e),
        Ok(Reading::Equation { lhs, rhs, .. }) => {
            format!("{} = {}", pool.plain(lhs), pool.plain(rhs))
        }
        Ok(other) => format!("{other:?}"),
        Err(e) => panic!("could not read {src:?}: {e}"),
    }
}

/// Evaluates `e` with named values for its variables (`x'` names a first derivative).
#[allow(dead_code)]
pub fn eval(pool: &Pool, e: Id, values: &[(&str, f64)]) -> Option<f64> {
    let vars = pool.variables(e);
    let mut inputs = Vec::new();
    for &(s, o) in &vars {
        let name = format!("{}{}", pool.name(s), "'".repeat(o as usize));
        inputs.push(values.iter().find(|(n, _)| *n == name)?.1);
    }
    let p = Program::compile(pool, &[e], &vars).ok()?;
    p.eval(&inputs).ok().map(|v| v[0])
}

/// Runs the `lagrange` binary without colour: (exit code, stdout, stderr).
pub fn lagrange(args: &[&str]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_lagrange"))
        .args(args)
        .env("NO_COLOR", "1")
        .output()
        .expect("the binary runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A tutor session on the embedded bank with fresh progress.
pub fn session() -> lagrange::tutor::Session {
    lagrange::tutor::Session::new(lagrange::embedded::bank(), lagrange::tutor::Progress::new())
}

/// The one response of a line that must answer with exactly one.
pub fn one(s: &mut lagrange::tutor::Session, line: &str) -> lagrange::tutor::Response {
    let mut r = s.handle(line);
    assert_eq!(r.len(), 1, "`{line}` gave {r:?}");
    r.remove(0)
}

/// (problem, part, answer, status, the verdict's first code or `None` for none).
pub type VerdictRow<'a> = (
    &'a str,
    &'a str,
    &'a str,
    lagrange::Status,
    Option<lagrange::Code>,
);

/// Checks each row on the built-in bank; fails listing every row that disagrees, with the
/// first diagnosis's message.
pub fn verdict_table(rows: &[VerdictRow]) {
    let bank = lagrange::bank::embedded::bank();
    let mut failures = Vec::new();
    for &(problem, part, answer, status, code) in rows {
        let p = bank.problem(problem).expect("a bank problem");
        let v = lagrange::Checker::new(p)
            .check(part, answer)
            .expect("a part");
        let codes: Vec<lagrange::Code> = v.diagnoses.iter().map(|d| d.code).collect();
        let code_ok = match code {
            Some(c) => codes.first() == Some(&c),
            None => codes.is_empty(),
        };
        if v.status != status || !code_ok {
            failures.push(format!(
                "{problem}/{part} `{answer}`: {:?} {codes:?} ({}), want {status:?} {code:?}",
                v.status,
                v.diagnoses
                    .first()
                    .map_or(String::new(), |d| d.message.clone())
            ));
        }
    }
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

/// A fresh, empty temporary folder that is removed with everything in it when dropped — also
/// when the test fails — so a run of the suite leaves nothing in the system's temp folder.
/// It derefs to its [`Path`](std::path::Path), so `dir.join(…)` and `&dir` work as with a path.
pub struct Scratch(tempfile::TempDir);

/// A new [`Scratch`] folder named `lagrange-{label}-…` (the label says which test left it,
/// should a killed run leave one).
pub fn scratch(label: &str) -> Scratch {
    let dir = tempfile::Builder::new()
        .prefix(&format!("lagrange-{label}-"))
        .tempdir()
        .expect("a temporary folder");
    Scratch(dir)
}

impl std::ops::Deref for Scratch {
    type Target = std::path::Path;
    fn deref(&self) -> &std::path::Path {
        self.0.path()
    }
}

impl AsRef<std::path::Path> for Scratch {
    fn as_ref(&self) -> &std::path::Path {
        self.0.path()
    }
}

impl AsRef<std::ffi::OsStr> for Scratch {
    fn as_ref(&self) -> &std::ffi::OsStr {
        self.0.path().as_os_str()
    }
}

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

/// The numbers of `text`, as ranges of its characters: an optional sign, digits, decimals and
/// an exponent. Digits inside names (`theta1`, `m_2`) are not numbers.
fn number_spans(chars: &[char]) -> Vec<(usize, usize)> {
    let in_name = |j: usize| j > 0 && (chars[j - 1].is_alphanumeric() || chars[j - 1] == '_');
    let digit = |j: usize| chars.get(j).is_some_and(char::is_ascii_digit);
    let digits = |mut j: usize| {
        while digit(j) {
            j += 1;
        }
        j
    };
    let mut spans = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let signed = matches!(chars[i], '-' | '−') && digit(i + 1) && !in_name(i);
        let starts = signed || digit(i) && !in_name(i);
        if !starts {
            i += 1;
            continue;
        }
        let start = i;
        let mut end = digits(i + usize::from(signed));
        if chars.get(end) == Some(&'.') && digit(end + 1) {
            end = digits(end + 1);
        }
        if matches!(chars.get(end), Some('e' | 'E')) {
            let sign = usize::from(matches!(chars.get(end + 1), Some('-' | '+')));
            if digit(end + 1 + sign) {
                end = digits(end + 1 + sign);
            }
        }
        spans.push((start, end));
        i = end;
    }
    spans
}

/// `text` with every number (sign, digits, decimals, exponent) replaced by `#`, so a snapshot
/// pins a summary's wording and layout while the numbers are checked against physics at a
/// tolerance. Digits inside names (`theta1`, `m_2`) are kept.
pub fn mask_numbers(text: &str) -> String {
    let chars: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let mut at = 0;
    for (start, end) in number_spans(&chars) {
        out.extend(&chars[at..start]);
        out.push('#');
        at = end;
    }
    out.extend(&chars[at..]);
    out
}

/// Every number of `text`, in order (those [`mask_numbers`] masks).
fn numbers(text: &str) -> Vec<f64> {
    let chars: Vec<char> = text.chars().collect();
    number_spans(&chars)
        .into_iter()
        .map(|(start, end)| {
            let s: String = chars[start..end].iter().collect();
            s.replace('−', "-").parse().unwrap_or(f64::NAN)
        })
        .collect()
}

/// The numbers of `line` after `key` up to the next `,` or end: `value_after("x = 1.5, y = 2",
/// "y = ")` is 2.0. Panics (a test failure) when the key or its number is missing.
pub fn value_after(line: &str, key: &str) -> f64 {
    let at = line
        .find(key)
        .unwrap_or_else(|| panic!("no `{key}` in {line:?}"));
    let rest = &line[at + key.len()..];
    let end = rest.find([',', ' ', ')']).unwrap_or(rest.len());
    rest[..end]
        .parse()
        .unwrap_or_else(|e| panic!("`{key}` in {line:?}: {e}"))
}

/// Panics unless the SVG `fresh` draws what `committed` does: the same elements, line by line,
/// with the same text and every number within a pixel. A picture's bytes depend on the last
/// bit of each coordinate; what it shows does not.
pub fn assert_svg_agrees(fresh: &str, committed: &str, name: &str) {
    let stale = format!("{name} is stale: rerun its documented command");
    let (a, b): (Vec<&str>, Vec<&str>) = (fresh.lines().collect(), committed.lines().collect());
    assert_eq!(
        a.len(),
        b.len(),
        "{stale}: {} elements, not {}",
        a.len(),
        b.len()
    );
    for (n, (x, y)) in a.iter().zip(&b).enumerate() {
        let (nx, ny) = (numbers(x), numbers(y));
        let near = nx.len() == ny.len() && nx.iter().zip(&ny).all(|(p, q)| (p - q).abs() <= 1.0);
        assert!(
            mask_numbers(x) == mask_numbers(y) && near,
            "{stale}: line {}\n  drawn:     {x}\n  committed: {y}",
            n + 1
        );
    }
}

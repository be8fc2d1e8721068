//! Drafting a proved problem file from a system (`lagrange problems new`): from a Lagrangian or
//! from bodies and potentials, the parts the engine can state — T and V (bodies only: a
//! Lagrangian alone does not fix them), L, the momenta and cyclic coordinates, the equations
//! of motion, the energy function, the equilibria and small-oscillation frequencies where they
//! have a closed form — each answer derived by the engine and then proved by the same
//! verification as every bank file. A part that cannot be stated, or that verification does not
//! prove, is left out with a comment giving the reason. No I/O: the face writes the text.
//!
//! The composing of candidate parts is in `new_parts.rs`, the writing of TOML in
//! `new_toml.rs`.

use super::load::load_str;
use super::new_parts::candidates;
use super::new_toml::{compose, skeleton};
use super::new_types::Candidate;
pub use super::new_types::{Drafted, LeftOut, Param, Spec, Table, Value};
use super::verify::verify;
use crate::diagnostic::Diagnostic;
use crate::expr::{Context, Pool, read_expr};

/// How many times a draft is verified and its failing parts removed before giving up (each
/// round removes at least one part, and a draft has at most a few dozen).
const MAX_ROUNDS: usize = 64;

/// Drafts a problem file from `spec`: every stated part derived by the engine and proved by
/// verification. An error is a system that cannot make a problem file (an unreadable
/// expression, a parameter whose dimension cannot be guessed, L not an energy).
pub fn draft(spec: &Spec) -> Result<Drafted, Diagnostic> {
    super::build_part::check_id(&spec.id, "problem")
        .map_err(|why| Diagnostic::new("bad-id", why, "ids use letters, digits, -, _ and ."))?;
    if spec.coordinates.is_empty() {
        return Err(Diagnostic::new(
            "usage",
            "no coordinate is given",
            "name them with --coords, e.g. --coords theta",
        ));
    }
    if spec.lagrangian.is_some() != spec.bodies.is_empty() {
        return Err(Diagnostic::new(
            "usage",
            "give the system by a Lagrangian or by bodies, one of the two",
            "--lagrangian \"…\", or --point/--rigid with --gravity, --spring or --potential",
        ));
    }
    let params = parameters(spec)?;
    let mut ranges = vec![None; spec.coordinates.len()];
    let base = skeleton(spec, &params, &ranges);
    // TOML puts plain keys before tables: the empty parts go before `[parameters]`.
    let empty = base.replacen("\n[parameters]\n", "parts = []\n\n[parameters]\n", 1);
    let problem = load_str(&format!("{}.toml", spec.id), &empty).map_err(|f| {
        Diagnostic::new(
            f.code.as_str(),
            format!("the drafted file does not load: {}", f.message),
            "check the flags' expressions; `lagrange derive` with the same flags shows the system",
        )
    })?;
    if let Some(f) = verify(&problem).into_iter().next() {
        return Err(Diagnostic::new(
            f.code.as_str(),
            f.message,
            "give each parameter's dimension with --param NAME=DIM (e.g. --param \"k=M T^-2\")",
        ));
    }
    let (mut parts, mut left_out, wider) = candidates(&problem);
    for (i, r) in wider {
        ranges[i] = Some(r);
    }
    let base = skeleton(spec, &params, &ranges);
    for _ in 0..MAX_ROUNDS {
        let text = compose(&base, &parts, &left_out);
        let problem = load_str(&format!("{}.toml", spec.id), &text).map_err(|f| {
            Diagnostic::new(
                f.code.as_str(),
                format!(
                    "the drafted file does not load (line {}): {}",
                    f.line, f.message
                ),
                "this is lagrange's mistake: please report it with the command",
            )
        })?;
        let findings = verify(&problem);
        if findings.is_empty() {
            return Ok(Drafted {
                text,
                stated: parts.iter().map(|p| p.id.clone()).collect(),
                left_out,
            });
        }
        for f in findings {
            let Some(id) = f.part.clone() else {
                return Err(Diagnostic::new(
                    f.code.as_str(),
                    f.message,
                    "check the system's flags",
                ));
            };
            if let Some(k) = parts.iter().position(|p| p.id == id) {
                let removed: Candidate = parts.remove(k);
                left_out.push(LeftOut {
                    part: removed.id,
                    reason: format!("verification did not prove it: [{}] {}", f.code, f.message),
                });
            }
        }
    }
    Err(Diagnostic::new(
        "draft-failed",
        "no draft of this system verifies",
        "this is lagrange's mistake: please report it with the command",
    ))
}

/// The parameters: every name the expressions use that is not a coordinate, `t` or `pi`, with
/// the dimension given for it or guessed from its name, and a sampling range and value.
fn parameters(spec: &Spec) -> Result<Vec<Param>, Diagnostic> {
    let mut pool = Pool::new();
    let ctx = Context::open().with_coordinates(spec.coordinates.iter().map(String::as_str));
    let mut texts: Vec<&str> = spec.lagrangian.iter().map(String::as_str).collect();
    for table in spec.bodies.iter().chain(&spec.potentials) {
        for (_, v) in &table.fields {
            match v {
                Value::Text(t) => texts.push(t),
                Value::List(l) => texts.extend(l.iter().map(String::as_str)),
                Value::Rows(r) => texts.extend(r.iter().flatten().map(String::as_str)),
                Value::Body(_) => {}
            }
        }
    }
    let mut names: Vec<String> = Vec::new();
    for text in texts {
        // An axis name (`y`) is a word, not an expression.
        if matches!(text, "x" | "y" | "z") && !spec.coordinates.iter().any(|c| c == text) {
            continue;
        }
        let id = read_expr(text, &ctx, &mut pool).map_err(|e| {
            Diagnostic::new(
                "syntax",
                format!("`{text}` does not read: {e}"),
                "the expression syntax is that of answers (docs/language.md)",
            )
        })?;
        for (s, _) in pool.variables(id) {
            let name = pool.name(s).to_string();
            let coordinate = spec
                .coordinates
                .iter()
                .any(|c| crate::expr::names::normalize(c) == name);
            if !coordinate && name != "t" && !names.contains(&name) {
                names.push(name);
            }
        }
    }
    names.sort();
    names
        .into_iter()
        .map(|name| {
            let given = spec
                .dimensions
                .iter()
                .find(|(n, _)| *n == name)
                .map(|(_, d)| d.clone());
            let (dim, range, value) = match (given, guess(&name)) {
                (Some(d), guessed) => {
                    let (range, value) = guessed.map_or(((0.5, 2.0), 1.0), |(_, r, v)| (r, v));
                    (d, range, value)
                }
                (None, Some((d, r, v))) => (d.to_string(), r, v),
                (None, None) => {
                    return Err(Diagnostic::new(
                        "unknown-dimension",
                        format!("the dimension of the parameter `{name}` cannot be told from its name"),
                        format!("give it with --param, e.g. --param \"{name}=M L T^-2\" (M, L, T, Q and powers; \"1\" for a pure number)"),
                    ));
                }
            };
            // Numbered twins get distinct values (m1 = 1, m2 = 1.5): a simulation from the
            // values of an Atwood machine with equal masses would not move.
            let n: f64 = crate::expr::names::split_digits(&name).1.parse().unwrap_or(1.0);
            let value = (value * (1.0 + 0.5 * (n - 1.0).clamp(0.0, 4.0))).clamp(range.0, range.1);
            Ok(Param {
                name,
                dimension: dim,
                range,
                value,
            })
        })
        .collect()
}

/// The dimension, sampling range and typical value a parameter's name suggests, after the
/// usual textbook letters: m mass, l length, g gravity, k stiffness, ω a rate, I a moment of
/// inertia, q a charge, B a magnetic field, F a force, α an angle. Trailing digits and `0`
/// are ignored (`m2`, `l0`).
pub fn guess(name: &str) -> Option<(&'static str, (f64, f64), f64)> {
    let (letters, _) = crate::expr::names::split_digits(name);
    let unit = (0.5, 2.0);
    Some(match letters {
        "m" | "M" | "mass" | "mu" => ("M", unit, 1.0),
        "g" => ("L T^-2", (5.0, 15.0), 9.81),
        "k" | "K" | "kappa" => ("M T^-2", unit, 1.0),
        "l" | "L" | "R" | "r" | "a" | "b" | "d" | "h" | "s" | "c" | "ell" | "rho" => {
            ("L", unit, 1.0)
        }
        "omega" | "Omega" | "w" | "W" | "nu" => ("T^-1", unit, 1.0),
        "I" | "J" => ("M L^2", unit, 1.0),
        "q" | "e" | "Q" => ("Q", unit, 1.0),
        "B" => ("M T^-1 Q^-1", unit, 1.0),
        "E" => ("M L T^-2 Q^-1", unit, 1.0),
        "F" | "f" => ("M L T^-2", unit, 1.0),
        _ if crate::mechanics::system::looks_like_angle(letters) => ("1", (0.3, 1.2), 0.5),
        _ => return None,
    })
}

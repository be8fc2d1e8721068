//! What the expression, equation and list checks share, kept in a leaf so that they do not
//! import each other: the verdict skeleton, the verdict on unreadable input, and a sample point as
//! text.

use super::compare::fmt_value;
use super::prepare::Prepared;
use super::verdict::{Code, Diagnosis, ReadAs, Status, Verdict};
use crate::expr::{ParseErrorKind, Sym};
use crate::mechanics::sample::seed_from;
use crate::problem::{Part, Problem};

/// A verdict skeleton.
pub(super) fn verdict(problem: &Problem, part: &Part, status: Status) -> Verdict {
    Verdict {
        problem: problem.id.clone(),
        part: part.id.clone(),
        status,
        score: if status == Status::Correct { 1.0 } else { 0.0 },
        reading: ReadAs::default(),
        diagnoses: Vec::new(),
        seed: seed_from(&[&problem.id, &part.id]),
        parse_error: None,
    }
}

/// The verdict on an input that could not be read.
pub(super) fn invalid_reading(
    problem: &Problem,
    part: &Part,
    e: crate::expr::ParseError,
) -> Verdict {
    let mut v = verdict(problem, part, Status::Invalid);
    let d = match &e.kind {
        ParseErrorKind::UnknownName { name, .. } => {
            match part
                .substitute
                .iter()
                .find(|(k, _)| crate::expr::names::normalize(k) == *name)
            {
                Some((k, val)) => Diagnosis::new(
                    Code::SubstitutedSymbol,
                    format!("this part sets {k} = {val}: write your answer with {val}, not {k}"),
                ),
                None => Diagnosis::new(Code::UnknownSymbol, format!("{}; {}", e.kind, e.help())),
            }
        }
        _ => Diagnosis::new(Code::Syntax, format!("{}; {}", e.kind, e.help())),
    };
    v.diagnoses.push(d);
    v.parse_error = Some(e);
    v
}

/// Sample point `k` as text: `theta = 0.3, m = 1.2`.
pub(super) fn point_text(p: &Prepared, k: usize) -> String {
    let x = &p.points.points[k];
    let at = p.system.state_layout();
    let mut parts = Vec::new();
    for (i, c) in p.system.coordinates.iter().enumerate() {
        parts.push(format!("{} = {}", c.name, fmt_value(x[at.q(i)])));
    }
    for (j, q) in p.system.parameters.iter().enumerate() {
        parts.push(format!("{} = {}", q.name, fmt_value(x[at.param(j)])));
    }
    parts.join(", ")
}

/// The diagnosis of an answer that is undefined everywhere (it contains 1/0, log(−1), …).
pub(super) fn undefined_everywhere() -> Diagnosis {
    Diagnosis::new(
        Code::Undefined,
        "your answer is undefined everywhere: it divides by zero or takes a function outside its domain (such as the log of a negative number), and 0 times an undefined value is still undefined",
    )
}

/// Any point as text, with velocities, in Unicode: `θ = 0.3, θ̇ = 0, m = 1.2`. With `only`,
/// just those variables (what a factor depends on), accelerations and time included when
/// they are among them: a point never omits a variable the expression uses.
pub(super) fn state_text(p: &Prepared, x: &[f64], only: Option<&[(Sym, u8)]>) -> String {
    let at = p.system.state_layout();
    let shown = |s: Sym, order: u8| only.is_none_or(|o| o.contains(&(s, order)));
    let mut slots: Vec<(Sym, u8, usize)> = Vec::new();
    for (i, c) in p.system.coordinates.iter().enumerate() {
        slots.push((c.sym, 0, at.q(i)));
        slots.push((c.sym, 1, at.qdot(i)));
        // An acceleration is shown where the expression uses one (never in a full state).
        if only.is_some_and(|o| o.contains(&(c.sym, 2))) {
            slots.push((c.sym, 2, at.qddot(i)));
        }
    }
    let t = p.system.pool.time();
    if only.is_some_and(|o| o.contains(&(t, 0))) {
        slots.push((t, 0, at.time()));
    }
    for (j, q) in p.system.parameters.iter().enumerate() {
        slots.push((q.sym, 0, at.param(j)));
    }
    slots
        .into_iter()
        .filter(|&(s, o, _)| shown(s, o))
        .map(|(s, o, k)| {
            let name = p.system.pool.var_name(s, o, crate::expr::Style::Unicode);
            format!("{name} = {}", fmt_value(x[k]))
        })
        .collect::<Vec<_>>()
        .join(", ")
}

//! Preparing a part for checking: the system with the part's substitutions, its derivation,
//! seeded sample points that respect the assumptions, and readers for answer items (equations,
//! equilibrium points, frequencies).

use crate::check::points::{Assumption, PointSet};
use crate::expr::{Context, Id, Node, Reading, read, read_equation, read_expr};
use crate::mechanics::equilibria::wrap_angle;
use crate::mechanics::sample::seed_from;
use crate::mechanics::{Derivation, System};
use crate::problem::{Part, PartKind, Problem};

/// Sample points for expressions and equations.
pub const POINTS: usize = 24;

/// An error while checking: a stable code and a message.
pub type Failure = (&'static str, String);

/// A part's system (with its substitutions), its derivation and sample points.
pub struct Prepared {
    pub system: System,
    pub derivation: Derivation,
    pub assumptions: Vec<Assumption>,
    pub points: PointSet,
    pub context: Context,
    /// The true accelerations at each point, computed once (None where undefined).
    pub accelerations: std::cell::OnceCell<Vec<Option<Vec<f64>>>>,
    /// For an `equation` part whose reference has no accelerations: its residual (decided once).
    pub condition: std::cell::OnceCell<Option<Id>>,
    /// The reference answer's items, read once (one id per item; several per equilibrium).
    pub reference: std::cell::OnceCell<Vec<Vec<Id>>>,
}

/// Prepares a part: substitutes, derives and draws points seeded by the problem and part.
pub fn prepare(problem: &Problem, part: &Part) -> Result<Prepared, String> {
    let mut system = problem.system.clone();
    let map = system
        .substitute_parameters(&part.substitute)
        .map_err(|e| e.to_string())?;
    let assumptions: Vec<Assumption> = problem
        .assumptions
        .iter()
        .map(|a| Assumption {
            lhs: system.pool.substitute(a.lhs, &map),
            rhs: system.pool.substitute(a.rhs, &map),
            ..a.clone()
        })
        .collect();
    let derivation = system.derive().map_err(|e| e.to_string())?;
    let context = system.context();
    // Points where the reference answer is undefined are redrawn.
    let mut reference: Vec<Id> = Vec::new();
    for a in &part.answers {
        for piece in a.split(';') {
            let body = match piece.split_once('=') {
                Some((l, r)) if part.kind != PartKind::Equilibria => format!("({l}) - ({r})"),
                Some((_, r)) => r.to_string(),
                None => piece.to_string(),
            };
            if let Ok(id) = read_expr(&body, &context, &mut system.pool) {
                reference.push(id);
            }
        }
    }
    let points = PointSet::draw_defined(
        &system,
        &assumptions,
        &reference,
        seed_from(&[&problem.id, &part.id]),
        POINTS,
    )?;
    Ok(Prepared {
        system,
        derivation,
        assumptions,
        points,
        context,
        accelerations: std::cell::OnceCell::new(),
        condition: std::cell::OnceCell::new(),
        reference: std::cell::OnceCell::new(),
    })
}

pub fn read_one(p: &mut Prepared, src: &str) -> Result<Id, (&'static str, String)> {
    read_expr(src, &p.context, &mut p.system.pool).map_err(|e| {
        let code = if matches!(e.kind, crate::expr::ParseErrorKind::UnknownName { .. }) {
            "undeclared-symbol"
        } else {
            "unreadable"
        };
        (code, format!("`{src}`: {e} ({})", e.help()))
    })
}

/// The residuals `lhs − rhs` of an answer's equations.
pub fn residuals(p: &mut Prepared, items: &[String]) -> Result<Vec<Id>, (&'static str, String)> {
    let mut out = Vec::new();
    for it in items {
        for piece in it.split(';').filter(|s| !s.trim().is_empty()) {
            let (l, r) = read_equation(piece, &p.context, &mut p.system.pool)
                .map_err(|e| ("unreadable", format!("`{piece}`: {e}")))?;
            out.push(p.system.pool.sub(l, r));
        }
    }
    Ok(out)
}

/// Reads an equilibrium item: `pi`, `theta = pi` or `theta1 = 0, theta2 = pi`.
pub fn read_point(p: &mut Prepared, src: &str) -> Result<Vec<Id>, (&'static str, String)> {
    let reading = read(src, &p.context, &mut p.system.pool)
        .map_err(|e| ("unreadable", format!("`{src}`: {e}")))?;
    let n = p.system.n();
    let mut point: Vec<Option<Id>> = vec![None; n];
    let assign =
        |lhs: Id, rhs: Id, point: &mut Vec<Option<Id>>| -> Result<(), (&'static str, String)> {
            match p.system.pool.node(lhs) {
                Node::Var(s, 0) => match p.system.coordinates.iter().position(|c| c.sym == *s) {
                    Some(i) => {
                        point[i] = Some(rhs);
                        Ok(())
                    }
                    None => Err((
                        "unreadable",
                        format!("`{src}`: the left side must be a coordinate"),
                    )),
                },
                _ => Err(("unreadable", format!("`{src}`: write coordinate = value"))),
            }
        };
    match reading {
        Reading::Expr(e, _) if n == 1 => point[0] = Some(e),
        Reading::Equation { lhs, rhs, .. } => assign(lhs, rhs, &mut point)?,
        Reading::List(items, _) => {
            for it in items {
                match it {
                    Reading::Equation { lhs, rhs, .. } => assign(lhs, rhs, &mut point)?,
                    _ => {
                        return Err((
                            "unreadable",
                            format!("`{src}`: write coordinate = value for each coordinate"),
                        ));
                    }
                }
            }
        }
        _ => {
            return Err((
                "unreadable",
                format!("`{src}`: an equilibrium is coordinate = value"),
            ));
        }
    }
    point
        .into_iter()
        .enumerate()
        .map(|(i, v)| {
            v.ok_or((
                "unreadable",
                format!(
                    "`{src}` gives no value for {}",
                    p.system.coordinates[i].name
                ),
            ))
        })
        .collect()
}

/// Whether two coordinate values are the same (modulo 2π for periodic coordinates).
pub fn same_coordinate(periodic: bool, a: f64, b: f64) -> bool {
    let d = if periodic { wrap_angle(a - b) } else { a - b };
    let d = if periodic && (d.abs() - std::f64::consts::PI).abs() < 1e-9 {
        std::f64::consts::PI.min(d.abs())
    } else {
        d
    };
    d.abs() <= 1e-6 * (1.0 + a.abs().max(b.abs()))
}

/// Reads a frequency item, allowing a label: `omega = sqrt(g/l)` or `sqrt(g/l)`.
pub fn read_frequency(p: &mut Prepared, src: &str) -> Result<Id, (&'static str, String)> {
    let body = match src.split_once('=') {
        Some((label, rhs))
            if label
                .trim()
                .chars()
                .all(|c| c.is_alphanumeric() || c == '_' || c == '²' || c == '^') =>
        {
            rhs
        }
        _ => src,
    };
    read_one(p, body)
}

/// The equilibrium a frequencies part is about (`at`, default all coordinates 0).
pub fn equilibrium_of(p: &mut Prepared, part: &Part) -> Result<Vec<Id>, (&'static str, String)> {
    let n = p.system.n();
    let zero = p.system.pool.zero();
    let mut at = vec![zero; n];
    for (name, v) in &part.at {
        let i = p
            .system
            .coordinates
            .iter()
            .position(|c| c.name == crate::expr::names::normalize(name))
            .ok_or((
                "bad-at",
                format!("`at` names `{name}`, which is not a coordinate"),
            ))?;
        at[i] = read_one(p, v)?;
    }
    Ok(at)
}

//! Preparing a part for checking: the system with the part's substitutions, its derivation,
//! seeded sample points that respect the assumptions, and readers for answer items (equations,
//! equilibrium points, frequencies).

use rustc_hash::FxHashMap;

use super::error::CheckError;
use super::points::PointSet;
use super::tolerance;
use crate::expr::{Context, Id, Node, Reading, read, read_equation, read_expr};
use crate::mechanics::accel::Dynamics;
use crate::mechanics::equilibria::wrap_angle;
use crate::mechanics::sample::seed_from;
use crate::mechanics::{Derivation, System};
use crate::problem::{Assumption, Part, PartKind, Problem};

/// Sample points for expressions and equations.
pub const POINTS: usize = 24;

/// A part's system (with its substitutions), its derivation and sample points.
pub struct Prepared {
    pub(crate) system: System,
    pub(crate) derivation: Derivation,
    pub(crate) assumptions: Vec<Assumption>,
    pub(crate) points: PointSet,
    pub(crate) context: Context,
    /// The part's relative tolerance (the documented one unless the part sets its own).
    pub(crate) tolerance: f64,
    /// Whether a product of two velocities in the answer comes from squaring a sum of
    /// velocities (T, L, h, a speed²), so that a missing one is the cross term of that square;
    /// not in a generalized force or a d/dt(∂L/∂q̇), where such products come otherwise.
    pub(crate) squares_velocities: bool,
    /// The true accelerations at each point, computed once (None where undefined).
    pub(crate) accelerations: std::cell::OnceCell<Vec<Option<Vec<f64>>>>,
    /// For an `equation` part whose reference has no accelerations: its residual (decided once).
    pub(crate) condition: std::cell::OnceCell<Option<Id>>,
    /// The reference answer's items, read once (one id per item; several per equilibrium).
    pub(crate) reference: std::cell::OnceCell<Vec<Vec<Id>>>,
    /// For a linearized part (`about`): where `system` was expanded.
    pub(crate) expansion: Option<super::taylor::Expansion>,
    /// The answer being checked, for quoting the student's own terms in diagnoses.
    pub(crate) quotes: Quotes,
    /// The wrong answers generated from the part's physics, made once.
    pub(crate) generated: super::generated::Generated,
    /// The accelerations of the equations linearized about rest at q = 0, at each point, and
    /// the part's reference equations (lhs, rhs) read: made for the first wrong equation
    /// (`equation_diagnosis.rs`), then kept.
    pub(crate) linearized: Option<std::sync::Arc<[Option<Vec<f64>>]>>,
    pub(crate) reference_equations: Option<std::sync::Arc<[(Id, Id)]>>,
    /// The last equation's affine form at the sample points (`residual.rs`): for each point,
    /// the coefficients of q'' and the rest.
    pub(crate) last_affine: Option<AffineForm>,
}

/// An equation and its affine form at each sample point (see [`Prepared::last_affine`]).
pub(crate) type AffineForm = (Id, std::sync::Arc<[Option<(Vec<f64>, f64)>]>);

/// Prepares a part: substitutes, derives and draws points seeded by the problem and part.
pub fn prepare(problem: &Problem, part: &Part) -> Result<Prepared, CheckError> {
    let mut system = problem.system.clone();
    let map = system
        .substitute_parameters(&part.substitute)
        .map_err(|error| CheckError::Substitution { error })?;
    // A linearized part is checked against the expanded system.
    let expansion = match &part.about {
        Some(about) => Some(super::taylor::linearize(&mut system, about)?),
        None => None,
    };
    // The problem's assumptions and the part's own.
    let assumptions: Vec<Assumption> = problem
        .assumptions
        .iter()
        .chain(&part.assumptions)
        .map(|a| Assumption {
            lhs: system.pool.substitute(a.lhs, &map),
            rhs: system.pool.substitute(a.rhs, &map),
            ..a.clone()
        })
        .collect();
    let derivation = system
        .derive()
        .map_err(|error| CheckError::Derivation { error })?;
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
        tolerance: part.tolerance,
        squares_velocities: !part.id.starts_with("generalized-force")
            && !part.id.starts_with("momentum-rate")
            && !matches!(
                part.quantity,
                crate::problem::Quantity::Momentum(_)
                    | crate::problem::Quantity::Acceleration(_)
                    | crate::problem::Quantity::Multiplier(_)
            ),
        accelerations: std::cell::OnceCell::new(),
        condition: std::cell::OnceCell::new(),
        reference: std::cell::OnceCell::new(),
        expansion,
        quotes: Quotes::default(),
        generated: Default::default(),
        linearized: None,
        reference_equations: None,
        last_affine: None,
    })
}

/// Reads one expression item of a reference answer.
pub(crate) fn read_one(p: &mut Prepared, src: &str) -> Result<Id, CheckError> {
    read_expr(src, &p.context, &mut p.system.pool).map_err(|e| CheckError::UnreadableItem {
        src: src.to_string(),
        error: Box::new(e),
    })
}

/// The residuals `lhs − rhs` of an answer's equations.
pub(crate) fn residuals(p: &mut Prepared, items: &[String]) -> Result<Vec<Id>, CheckError> {
    let mut out = Vec::new();
    for it in items {
        for piece in it.split(';').filter(|s| !s.trim().is_empty()) {
            let (l, r) = read_equation(piece, &p.context, &mut p.system.pool).map_err(|e| {
                CheckError::UnreadableEquation {
                    src: piece.to_string(),
                    error: Box::new(e),
                }
            })?;
            out.push(p.system.pool.sub(l, r));
        }
    }
    Ok(out)
}

/// Reads an equilibrium item: `pi`, `theta = pi` or `theta1 = 0, theta2 = pi`; a
/// coordinate stated `any` reads as 0 (see [`read_point_any`] for which ones are).
pub(crate) fn read_point(p: &mut Prepared, src: &str) -> Result<Vec<Id>, CheckError> {
    let marked = any_as_marker(p, src);
    read_point_any(p, &marked).map(|(point, _)| point)
}

/// What a coordinate left arbitrary (`x = any`) is read as when answers are compared: a
/// value no one types for a coordinate (√3·π), so that `any` matches only `any`. Read as 0,
/// a student's single point `x = 0, s = 0` would pass for the continuum `x = any, s = 0` —
/// the point is one of the continuum, but the answer misses that x is free.
const ANY_MARKER: &str = "√3π";

/// `input` with each `= any` read as [`ANY_MARKER`] (unless `any` is a parameter).
pub(crate) fn any_as_marker(p: &Prepared, input: &str) -> String {
    if p.system.parameters.iter().any(|q| q.name == "any") {
        return input.to_string();
    }
    let arbitrary = arbitrary_as_any(input);
    let input = arbitrary.as_str();
    let mut out = String::with_capacity(input.len() + 8);
    let mut rest = input;
    while let Some(k) = rest.find("any") {
        let (before, after) = rest.split_at(k);
        let tail = &after[3..];
        let word_end = !tail.starts_with(|c: char| c.is_alphanumeric() || c == '_' || c == '\'');
        let after_eq = before.trim_end().ends_with('=');
        out.push_str(before);
        out.push_str(if word_end && after_eq {
            ANY_MARKER
        } else {
            "any"
        });
        rest = tail;
    }
    out.push_str(rest);
    out
}

/// `x arbitrary`, `x is arbitrary` and `x = arbitrary` (how `modes` words a continuum) as
/// `x = any`; text without the word `arbitrary` is returned unchanged.
pub(crate) fn arbitrary_as_any(input: &str) -> String {
    const WORD: &str = "arbitrary";
    if !input.contains(WORD) {
        return input.to_string();
    }
    let mut out = String::with_capacity(input.len() + 8);
    let mut rest = input;
    while let Some(k) = rest.find(WORD) {
        let (before, after) = rest.split_at(k);
        let tail = &after[WORD.len()..];
        let name_char = |c: char| c.is_alphanumeric() || c == '_' || c == '\'';
        let whole = !before.ends_with(name_char) && !tail.starts_with(name_char);
        let lead = before.trim_end();
        // `x is arbitrary`: the `is` goes with the word.
        let lead = match lead.strip_suffix("is") {
            Some(l) if l.ends_with(char::is_whitespace) => l.trim_end(),
            _ => lead,
        };
        if whole && lead.ends_with('=') {
            out.push_str(before);
            out.push_str("any");
        } else if whole && lead.ends_with(|c: char| !"(,;".contains(c)) {
            out.push_str(lead);
            out.push_str(" = any");
        } else {
            out.push_str(before);
            out.push_str(WORD);
        }
        rest = tail;
    }
    out.push_str(rest);
    out
}

/// Reads an equilibrium item that may leave coordinates arbitrary, `x = any, theta = 0`
/// (a continuum of equilibria along x): the point, with 0 for each arbitrary coordinate,
/// and which coordinates are arbitrary. `any` is a word only where it is not a parameter.
pub(crate) fn read_point_any(
    p: &mut Prepared,
    src: &str,
) -> Result<(Vec<Id>, Vec<bool>), CheckError> {
    let n = p.system.n();
    let mut free = vec![false; n];
    if p.system.parameters.iter().any(|q| q.name == "any") {
        return Ok((read_point_exact(p, src)?, free));
    }
    let mut items = Vec::new();
    for item in top_level_items(src) {
        if let Some((lhs, rhs)) = item.split_once('=')
            && rhs.trim() == "any"
        {
            let name = crate::expr::names::normalize(lhs.trim());
            if let Some(i) = p.system.coordinates.iter().position(|c| c.name == name) {
                free[i] = true;
                items.push(format!("{} = 0", lhs.trim()));
                continue;
            }
        }
        items.push(item.to_string());
    }
    if !free.iter().any(|&f| f) {
        return Ok((read_point_exact(p, src)?, free));
    }
    Ok((read_point_exact(p, &items.join(", "))?, free))
}

/// `src` split at its commas outside brackets.
pub(super) fn top_level_items(src: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let (mut depth, mut start) = (0i32, 0);
    for (i, ch) in src.char_indices() {
        match ch {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            ',' if depth == 0 => {
                out.push(&src[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    out.push(&src[start..]);
    out
}

/// Reads an equilibrium item in which every coordinate has a value.
fn read_point_exact(p: &mut Prepared, src: &str) -> Result<Vec<Id>, CheckError> {
    let reading =
        read(src, &p.context, &mut p.system.pool).map_err(|e| CheckError::UnreadablePoint {
            src: src.to_string(),
            error: Box::new(e),
        })?;
    let n = p.system.n();
    let mut point: Vec<Option<Id>> = vec![None; n];
    let assign = |lhs: Id, rhs: Id, point: &mut Vec<Option<Id>>| -> Result<(), CheckError> {
        match p.system.pool.node(lhs) {
            Node::Var(s, 0) => match p.system.coordinates.iter().position(|c| c.sym == *s) {
                Some(i) => {
                    point[i] = Some(rhs);
                    Ok(())
                }
                None => Err(CheckError::NotACoordinate {
                    src: src.to_string(),
                }),
            },
            _ => Err(CheckError::NotAnAssignment {
                src: src.to_string(),
            }),
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
                        return Err(CheckError::NotAssignments {
                            src: src.to_string(),
                        });
                    }
                }
            }
        }
        _ => {
            return Err(CheckError::NotAnEquilibrium {
                src: src.to_string(),
            });
        }
    }
    point
        .into_iter()
        .enumerate()
        .map(|(i, v)| {
            v.ok_or_else(|| CheckError::MissingCoordinate {
                src: src.to_string(),
                coordinate: p.system.coordinates[i].name.clone(),
            })
        })
        .collect()
}

/// Whether two coordinate values found numerically are the same (modulo 2π for periodic
/// coordinates), to the precision of a root search ([`tolerance::COORDINATE`]).
pub(crate) fn same_coordinate(periodic: bool, a: f64, b: f64) -> bool {
    same_coordinate_within(periodic, a, b, tolerance::COORDINATE)
}

/// Whether two coordinate values agree to the relative tolerance `tol` (modulo 2π for
/// periodic coordinates, where the difference is measured after wrapping).
pub(crate) fn same_coordinate_within(periodic: bool, a: f64, b: f64, tol: f64) -> bool {
    let d = if periodic { wrap_angle(a - b) } else { a - b };
    let d = if periodic && (d.abs() - std::f64::consts::PI).abs() < tolerance::ANGLE {
        std::f64::consts::PI.min(d.abs())
    } else {
        d
    };
    d.abs() <= tol * (1.0 + a.abs().max(b.abs()))
}

/// Reads a frequency item, allowing a label: `omega = sqrt(g/l)` or `sqrt(g/l)`.
pub(crate) fn read_frequency(p: &mut Prepared, src: &str) -> Result<Id, CheckError> {
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
pub(crate) fn equilibrium_of(p: &mut Prepared, part: &Part) -> Result<Vec<Id>, CheckError> {
    let n = p.system.n();
    let zero = p.system.pool.zero();
    let mut at = vec![zero; n];
    for (name, v) in &part.at {
        let i = p
            .system
            .coordinates
            .iter()
            .position(|c| c.name == crate::expr::names::normalize(name))
            .ok_or_else(|| CheckError::BadAt { name: name.clone() })?;
        at[i] = read_one(p, v)?;
    }
    Ok(at)
}

/// True accelerations at every point, computed once per prepared part (the equation
/// checks and the misconceptions about motion share them).
pub(crate) fn true_accelerations(p: &Prepared) -> Result<Vec<Option<Vec<f64>>>, CheckError> {
    if let Some(a) = p.accelerations.get() {
        return Ok(a.clone());
    }
    let a = compute_accelerations(p)?;
    Ok(p.accelerations.get_or_init(|| a).clone())
}

fn compute_accelerations(p: &Prepared) -> Result<Vec<Option<Vec<f64>>>, CheckError> {
    let sys = &p.system;
    if !sys.constraints.is_empty() {
        let mut s = sys.clone();
        let rows = s.constraint_rows();
        return Ok(p
            .points
            .points
            .iter()
            .map(|x| {
                s.multipliers_at(&p.derivation, &rows, x)
                    .ok()
                    .map(|(a, _)| a)
            })
            .collect());
    }
    let dynamics =
        Dynamics::new(sys, &p.derivation).map_err(|error| CheckError::Dynamics { error })?;
    let mut scratch = dynamics.scratch();
    Ok(p.points
        .points
        .iter()
        .map(|x| dynamics.accelerations(x, &mut scratch).ok())
        .collect())
}

/// The answer being checked, and its quotes once made.
#[derive(Clone, Debug, Default)]
pub struct Quotes {
    pub(super) source: String,
    pub(super) table: Option<FxHashMap<Id, String>>,
}

impl Quotes {
    /// Quotes for the answer `source` (made when first asked for).
    pub(crate) fn of(source: &str) -> Quotes {
        Quotes {
            source: source.to_string(),
            table: None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_where_the_reference_is_undefined_are_redrawn() {
        let text = r#"
    id = "half-line"
    title = "A reference defined for x >= 0 only"
    coordinates = [{ name = "x", range = [-2.0, 2.0] }]
    lagrangian = "1/2*m*x'^2"

    [parameters]
    m = { dimension = "M", range = [0.5, 2.0] }

    [[parts]]
    id = "root"
    kind = "expression"
    prompt = "p"
    answer = "m*sqrt(x)"
    hints = ["a", "b"]
    "#;
        let problem = crate::bank::load_str("half-line.toml", text).unwrap();
        let part = problem.part("root").unwrap();
        let p = prepare(&problem, part).unwrap();
        // The nominal points and, beyond them, the share drawn far outside the box.
        assert_eq!(
            p.points.points.len(),
            POINTS + POINTS / crate::check::points::WIDE_SHARE
        );
        assert!(
            p.points.points.iter().all(|x| x[1] >= 0.0),
            "a point with x < 0 was kept"
        );
        let mut checker = crate::check::Checker::new(&problem);
        let v = checker.check("root", "m*abs(x)^(1/2)").unwrap();
        assert_eq!(v.status, crate::check::Status::Correct);
    }
}

//! Follow-through: an answer that is wrong for the reference but exactly what follows from the
//! student's own earlier wrong answer stays incorrect, and gets the diagnosis
//! `follows-from-earlier`, which names where the real mistake is. Chains: their T or V → L;
//! their T, V or L → the momenta, the energy function, the equations of motion, the
//! equilibria and the frequencies; their equations of motion → the equilibria and (one
//! coordinate) the frequencies.
//!
//! Mechanism: a variant of the problem whose system is built from the earlier answer (the
//! student's L, or T − V with their T or V, or a system with the rest dynamics of their
//! equations of motion); the current answer is checked against that variant with the existing
//! checker (expressions and equations) or verified against it as the bank verifies a reference
//! (equilibria and frequencies, which the engine finds numerically).

use rustc_hash::FxHashMap;

use crate::bank::verify::verify;
use crate::check::{CheckError, Code, Diagnosis, Status, Verdict, check};
use crate::expr::{Id, read_equation, read_expr};
use crate::mechanics::System;
use crate::problem::{Part, PartKind, Problem, Quantity};

/// An earlier answer of the same student to part `part` (its id) of the same problem.
/// Serialisable, so a session's progress can keep the answers follow-through needs.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Earlier {
    /// The id of the part the answer was given to.
    pub(crate) part: String,
    /// The answer as typed.
    pub(crate) answer: String,
}

impl Earlier {
    /// An earlier answer `answer` to part `part`.
    pub fn new(part: impl Into<String>, answer: impl Into<String>) -> Self {
        Earlier {
            part: part.into(),
            answer: answer.into(),
        }
    }
}

/// The follow-through diagnosis for `input` to `part`, given the student's earlier answers
/// (oldest first; the latest answer to each part counts, the most recent part first).
///
/// `None` when `input` is correct or unreadable, when no earlier answer is both wrong and
/// readable and upstream of `part`, or when `input` does not follow from any of them.
pub fn follow_through(
    problem: &Problem,
    part: &Part,
    input: &str,
    earlier: &[Earlier],
) -> Option<Diagnosis> {
    let own = check(problem, part, input).ok()?;
    if own.status != Status::Incorrect {
        return None;
    }
    follows(problem, part, input, earlier)
}

/// The `follows-from-earlier` diagnosis for an answer already judged incorrect (by [`check`] or
/// a prepared check of the same part), given the student's earlier answers as for
/// [`follow_through`]. For a caller that has the verdicts already: `known` gives the verdict
/// it holds on an earlier answer (`None`: it is checked here), so nothing is checked twice.
/// `None` when the answer does not follow from any earlier wrong answer.
pub fn follows_from_earlier(
    problem: &Problem,
    part: &Part,
    input: &str,
    earlier: &[Earlier],
    known: &dyn Fn(&Earlier) -> Option<Verdict>,
) -> Option<Diagnosis> {
    follows_with(problem, part, input, earlier, known)
}

/// Checks `input` against `part` (as [`check`]) and, when the answer is incorrect but follows
/// from one of the student's earlier answers, adds the diagnosis [`follows_from_earlier`]
/// gives, as [`apply`] does.
pub fn check_with_history(
    problem: &Problem,
    part: &Part,
    input: &str,
    earlier: &[Earlier],
) -> Result<Verdict, CheckError> {
    let mut v = check(problem, part, input)?;
    if v.status == Status::Incorrect
        && let Some(d) = follows(problem, part, input, earlier)
    {
        apply(&mut v, d);
    }
    Ok(v)
}

/// Whether a follow-through diagnosis accepts the answer: it follows from an earlier
/// Lagrangian that was accepted though it is not T − V up to a constant (a total time
/// derivative added: `total-derivative`; any L with the right motion on a part that accepts
/// it: `equivalent-lagrangian`), so it is right for the student's own L.
pub fn accepts(d: &Diagnosis) -> bool {
    matches!(d.code, Code::TotalDerivative | Code::EquivalentLagrangian)
}

/// Adds a follow-through diagnosis to the incorrect verdict `v`: one that [`accepts`] makes
/// the answer correct (with it as the note); `follows-from-earlier` leaves it incorrect.
pub fn apply(v: &mut Verdict, d: Diagnosis) {
    if accepts(&d) {
        v.status = Status::Correct;
        v.score = 1.0;
        v.diagnoses = vec![d];
    } else {
        v.diagnoses.push(d);
        v.sort();
    }
}

/// The step of a derivation a part asks for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Stage {
    Kinetic,
    Potential,
    Lagrangian,
    /// The momentum conjugate to coordinate i.
    Momentum(usize),
    /// The energy function h.
    Energy,
    Motion,
    Equilibria,
    Frequencies,
}

impl Stage {
    /// The stage part `part` asks for, if follow-through knows it.
    fn of(part: &Part) -> Option<Stage> {
        match part.kind {
            PartKind::Lagrangian => Some(Stage::Lagrangian),
            PartKind::Equation | PartKind::Equations => Some(Stage::Motion),
            PartKind::Equilibria => Some(Stage::Equilibria),
            PartKind::Frequencies => Some(Stage::Frequencies),
            PartKind::Expression => match part.quantity {
                Quantity::Kinetic => Some(Stage::Kinetic),
                Quantity::Potential => Some(Stage::Potential),
                Quantity::Lagrangian => Some(Stage::Lagrangian),
                Quantity::Momentum(i) => Some(Stage::Momentum(i)),
                Quantity::EnergyFunction => Some(Stage::Energy),
                _ => None,
            },
            _ => None,
        }
    }

    /// Whether a mistake at `self` carries into an answer at `to`.
    fn feeds(self, to: Stage) -> bool {
        use Stage::*;
        match to {
            Lagrangian => matches!(self, Kinetic | Potential),
            Momentum(_) | Energy => matches!(self, Kinetic | Potential | Lagrangian),
            Motion => matches!(self, Kinetic | Potential | Lagrangian),
            Equilibria | Frequencies => matches!(self, Kinetic | Potential | Lagrangian | Motion),
            _ => false,
        }
    }

    /// What the student wrote at this stage, as in "your … follows".
    fn noun(self, part: &Part) -> &'static str {
        match self {
            Stage::Kinetic => "kinetic energy",
            Stage::Potential => "potential energy",
            Stage::Lagrangian => "Lagrangian",
            Stage::Momentum(_) => "momentum",
            Stage::Energy => "energy function",
            // A condition such as an equilibrium condition has no accelerations.
            Stage::Motion if !part.answers.iter().any(|a| a.contains("''")) => "equation",
            Stage::Motion if part.kind == PartKind::Equations => "equations of motion",
            Stage::Motion => "equation of motion",
            Stage::Equilibria => "equilibria",
            Stage::Frequencies => "frequencies",
        }
    }

    /// Where the mistake is, as in "the mistake is in …".
    fn place(self, part: &Part) -> String {
        match self {
            Stage::Kinetic => "T".into(),
            Stage::Potential => "V".into(),
            Stage::Lagrangian => "L".into(),
            _ => format!("your {}", self.noun(part)),
        }
    }
}

/// The diagnosis for an incorrect `input`, from the most recent earlier answer it follows from.
/// Only the latest answer to each part counts (a part answered again, or put right, no longer
/// carries its older answers), which also bounds the work by the number of parts.
fn follows(problem: &Problem, part: &Part, input: &str, earlier: &[Earlier]) -> Option<Diagnosis> {
    follows_with(problem, part, input, earlier, &|_| None)
}

/// [`follows`], with the verdicts on earlier answers the caller already has.
fn follows_with(
    problem: &Problem,
    part: &Part,
    input: &str,
    earlier: &[Earlier],
    known: &dyn Fn(&Earlier) -> Option<Verdict>,
) -> Option<Diagnosis> {
    let to = Stage::of(part)?;
    // A frequency labelled as another quantity (ω² for ω) is that mistake, not a follow-through.
    if crate::check::states_another_frequency(part, input) {
        return None;
    }
    let mut seen: Vec<&str> = vec![part.id.as_str()];
    for e in earlier.iter().rev() {
        // Only the problem's own parts are remembered, so `seen` stays as short as its parts.
        let Some(ep) = problem.part(&e.part) else {
            continue;
        };
        if seen.contains(&ep.id.as_str()) {
            continue;
        }
        seen.push(&ep.id);
        let Some(from) = Stage::of(ep) else { continue };
        if !from.feeds(to) || !ep.substitute.iter().all(|s| part.substitute.contains(s)) {
            continue;
        }
        let Some(before) = known(e).or_else(|| check(problem, ep, &e.answer).ok()) else {
            continue;
        };
        // An L accepted though it is not T − V (a total derivative added) has momenta and an
        // h of its own; its equations of motion, equilibria and frequencies are the right ones.
        let other_l = before.status == Status::Correct
            && from == Stage::Lagrangian
            && matches!(to, Stage::Momentum(_) | Stage::Energy)
            && before.diagnoses.first().is_some_and(accepts);
        if before.status != Status::Incorrect && !other_l {
            continue;
        }
        let answer = crate::check::unlabelled(problem, ep, &e.answer);
        let Some((system, dynamics)) = variant_system(problem, from, answer) else {
            continue;
        };
        if to == Stage::Frequencies && !dynamics {
            continue;
        }
        if holds_in(problem, system, part, to, input) {
            return Some(match before.diagnoses.first() {
                Some(note) if other_l => accepted(part, to, ep, note),
                _ => diagnosis(part, to, ep, from, &before),
            });
        }
    }
    None
}

/// The note on an answer that is right for the student's own accepted L (`note` is the note
/// that L got).
fn accepted(part: &Part, to: Stage, ep: &Part, note: &Diagnosis) -> Diagnosis {
    Diagnosis::new(
        note.code,
        format!(
            "your {} follows correctly from your Lagrangian (part `{}`), which was accepted: it differs from T − V by more than a constant, so its {} differs from the reference's too",
            to.noun(part),
            ep.id,
            to.noun(part)
        ),
    )
}

/// The sentence naming where the real mistake is.
fn diagnosis(part: &Part, to: Stage, ep: &Part, from: Stage, before: &Verdict) -> Diagnosis {
    let verb = match to {
        Stage::Equilibria | Stage::Frequencies => "follow",
        Stage::Motion if part.kind == PartKind::Equations => "follow",
        _ => "follows",
    };
    let head = format!(
        "your {} {verb} correctly from your {}; the mistake is in {} (part `{}`)",
        to.noun(part),
        from.noun(ep),
        from.place(ep),
        ep.id
    );
    let message = match before.diagnoses.first() {
        Some(d) => format!("{head}: {}", d.message),
        None => head,
    };
    Diagnosis::new(Code::FollowsFromEarlier, message)
}

/// The problem's system rebuilt on the student's answer `answer` at stage `from`, and whether
/// its small oscillations are the student's too (not only its equilibria).
fn variant_system(problem: &Problem, from: Stage, answer: &str) -> Option<(System, bool)> {
    let mut sys = problem.system.clone();
    let ctx = problem.context();
    match from {
        Stage::Kinetic => {
            let t = read_expr(answer, &ctx, &mut sys.pool).ok()?;
            let v = match (sys.potential, sys.kinetic) {
                (Some(v), _) => v,
                (None, Some(t0)) => sys.pool.sub(t0, sys.lagrangian),
                (None, None) => return None,
            };
            sys.lagrangian = sys.pool.sub(t, v);
            sys.kinetic = Some(t);
            sys.potential = Some(v);
        }
        Stage::Potential => {
            let v = read_expr(answer, &ctx, &mut sys.pool).ok()?;
            let t = match (sys.kinetic, sys.potential) {
                (Some(t), _) => t,
                (None, Some(v0)) => sys.pool.add(sys.lagrangian, v0),
                (None, None) => return None,
            };
            sys.lagrangian = sys.pool.sub(t, v);
            sys.kinetic = Some(t);
            sys.potential = Some(v);
        }
        Stage::Lagrangian => {
            sys.lagrangian = read_expr(answer, &ctx, &mut sys.pool).ok()?;
            sys.kinetic = None;
            sys.potential = None;
        }
        Stage::Motion => {
            let dynamics = resting_like(&mut sys, answer)?;
            return Some((sys, dynamics));
        }
        Stage::Momentum(_) | Stage::Energy | Stage::Equilibria | Stage::Frequencies => {
            return None;
        }
    }
    Some((sys, true))
}

/// Makes `sys` a system with the rest dynamics of the student's equations `answer`
/// (`;`-separated, one per coordinate) written A(q)·q̈ + r(q) = 0 at rest: L = Σ ½ q̇ᵢ² with
/// generalized forces Q, so q̈ = Q has the student's equilibria (where r = 0). Returns whether
/// its frequencies are the student's too: for one coordinate with an acceleration term
/// (Q = −r/a); not for an equation without accelerations or for several coordinates.
fn resting_like(sys: &mut System, answer: &str) -> Option<bool> {
    let ctx = sys.context();
    let pieces: Vec<&str> = answer.split(';').filter(|s| !s.trim().is_empty()).collect();
    let n = sys.n();
    if pieces.len() != n {
        return None;
    }
    let zero = sys.pool.zero();
    let syms: Vec<_> = sys.coordinates.iter().map(|c| c.sym).collect();
    let rest: FxHashMap<_, Id> = syms
        .iter()
        .flat_map(|&c| [((c, 1), zero), ((c, 2), zero)])
        .collect();
    let (mut r, mut a) = (Vec::with_capacity(n), Vec::with_capacity(n));
    for piece in pieces {
        let (lhs, rhs) = read_equation(piece, &ctx, &mut sys.pool).ok()?;
        let residual = sys.pool.sub(lhs, rhs);
        r.push(sys.pool.substitute(residual, &rest));
        let row: Vec<Id> = syms
            .iter()
            .map(|&c| {
                let d = sys.pool.diff(residual, c, 2);
                sys.pool.substitute(d, &rest)
            })
            .collect();
        a.push(row);
    }
    // One coordinate with an acceleration: Q = −r/a. Otherwise Q = −r, right for the
    // equilibria only: the engine's modes assume a symmetric stiffness, which −A⁻¹·r need
    // not have for several coordinates.
    let (forces, dynamics) = match (&a[..], &r[..]) {
        ([row], [r0]) if !sys.is_zero(row[0]) => {
            let q = sys.pool.div(*r0, row[0]);
            (vec![sys.pool.neg(q)], true)
        }
        _ => (r.iter().map(|&x| sys.pool.neg(x)).collect(), false),
    };
    let kinetic: Vec<String> = sys
        .coordinates
        .iter()
        .map(|c| format!("1/2*{}'^2", c.name))
        .collect();
    sys.lagrangian = read_expr(&kinetic.join(" + "), &ctx, &mut sys.pool).ok()?;
    sys.kinetic = None;
    sys.potential = None;
    sys.forces = forces;
    Some(dynamics)
}

/// Whether `input` is the right answer to `part` in the problem whose system is `system`.
fn holds_in(problem: &Problem, system: System, part: &Part, to: Stage, input: &str) -> bool {
    let mut variant = problem.clone();
    variant.system = system;
    variant.stated_lagrangian = None;
    match to {
        Stage::Lagrangian => {
            let mut vp = part.clone();
            vp.answers = vec![variant.system.pool.plain(variant.system.lagrangian)];
            correct_in(&variant, &vp, input)
        }
        Stage::Momentum(_) | Stage::Energy => {
            let Ok(d) = variant.system.derive() else {
                return false;
            };
            let derived = match to {
                Stage::Momentum(i) => match d.steps.get(i) {
                    Some(s) => s.momentum,
                    None => return false,
                },
                _ => variant.system.energy(&d).function,
            };
            let mut vp = part.clone();
            vp.answers = vec![variant.system.pool.plain(derived)];
            correct_in(&variant, &vp, input)
        }
        Stage::Motion => correct_in(&variant, part, input),
        Stage::Equilibria | Stage::Frequencies => verified_in(variant, part, input),
        Stage::Kinetic | Stage::Potential => false,
    }
}

/// Whether the checker accepts `input` to `part` of `variant`.
fn correct_in(variant: &Problem, part: &Part, input: &str) -> bool {
    matches!(check(variant, part, input), Ok(v) if v.status == Status::Correct)
}

/// Whether `input`, stated as the reference of a list part of `variant`, passes the bank's
/// verification: the items are exactly the equilibria (or frequencies) the engine finds.
fn verified_in(mut variant: Problem, part: &Part, input: &str) -> bool {
    let items = list_items(
        input,
        part.kind == PartKind::Equilibria && variant.system.n() > 1,
    );
    if items.is_empty() {
        return false;
    }
    let mut vp = part.clone();
    vp.answers = items;
    // Only the points are followed through: their stability (and a prompt asking for it)
    // is not the question here.
    vp.stability.clear();
    vp.require_stability = false;
    vp.prompt.clear();
    variant.parts = vec![vp];
    verify(&variant).iter().all(|f| f.part.is_none())
}

/// The items of a list answer: split at top-level `;` (and `,` unless `points_by_semicolon`),
/// outside brackets, without a pair of braces or brackets around the whole.
fn list_items(input: &str, points_by_semicolon: bool) -> Vec<String> {
    let t = input.trim();
    let t = match (t.chars().next(), t.chars().last()) {
        (Some('{'), Some('}')) | (Some('['), Some(']')) if t.len() >= 2 => &t[1..t.len() - 1],
        _ => t,
    };
    let mut out = Vec::new();
    let (mut depth, mut start) = (0i32, 0usize);
    for (i, c) in t.char_indices() {
        match c {
            '(' | '[' | '{' => depth += 1,
            ')' | ']' | '}' => depth -= 1,
            ';' if depth <= 0 => {
                out.push(t[start..i].trim().to_string());
                start = i + 1;
            }
            ',' if depth <= 0 && !points_by_semicolon => {
                out.push(t[start..i].trim().to_string());
                start = i + 1;
            }
            _ => {}
        }
    }
    out.push(t[start..].trim().to_string());
    out.retain(|s| !s.is_empty());
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pendulum() -> Problem {
        crate::bank::embedded::problem("simple-pendulum").unwrap()
    }

    #[test]
    fn list_items_split_at_top_level() {
        assert_eq!(list_items("0, pi", false), ["0", "pi"]);
        assert_eq!(
            list_items("{theta = 0; theta = pi}", false),
            ["theta = 0", "theta = pi"]
        );
        assert_eq!(
            list_items("x = 0, y = 1; x = 1, y = atan2(1, 2)", true),
            ["x = 0, y = 1", "x = 1, y = atan2(1, 2)"]
        );
        assert!(list_items("  ", false).is_empty());
    }

    #[test]
    fn earlier_answers_round_trip_through_json() {
        let e = Earlier::new("lagrangian", "1/2*m*l^2*theta'^2");
        let json = serde_json::to_string(&e).unwrap();
        assert_eq!(
            json,
            r#"{"part":"lagrangian","answer":"1/2*m*l^2*theta'^2"}"#
        );
        assert_eq!(serde_json::from_str::<Earlier>(&json).unwrap(), e);
    }

    #[test]
    fn stages_feed_downstream_only() {
        assert!(Stage::Lagrangian.feeds(Stage::Motion));
        assert!(Stage::Motion.feeds(Stage::Equilibria));
        assert!(!Stage::Motion.feeds(Stage::Lagrangian));
        assert!(!Stage::Lagrangian.feeds(Stage::Lagrangian));
    }

    #[test]
    fn wrong_l_then_its_eom() {
        let p = pendulum();
        let eom = p.part("eom").unwrap();
        let earlier = [Earlier::new(
            "lagrangian",
            "1/2*m*l^2*theta'^2 - m*g*l*cos(theta)",
        )];
        let d = follow_through(&p, eom, "m*l^2*theta'' - m*g*l*sin(theta) = 0", &earlier).unwrap();
        assert_eq!(d.code, Code::FollowsFromEarlier);
        assert!(d.message.contains("the mistake is in L"), "{}", d.message);
        // The right EOM, and an EOM from nowhere, get nothing.
        let right = "m*l^2*theta'' + m*g*l*sin(theta) = 0";
        assert!(follow_through(&p, eom, right, &earlier).is_none());
        assert!(follow_through(&p, eom, "theta'' = 0", &earlier).is_none());
    }

    #[test]
    fn earlier_correct_or_unreadable_answers_are_ignored() {
        let p = pendulum();
        let eom = p.part("eom").unwrap();
        let wrong = "m*l^2*theta'' - m*g*l*sin(theta) = 0";
        for l in ["1/2*m*l^2*theta'^2 + m*g*l*cos(theta)", "1/2*m*(("] {
            assert!(follow_through(&p, eom, wrong, &[Earlier::new("lagrangian", l)]).is_none());
        }
        assert!(follow_through(&p, eom, wrong, &[Earlier::new("no-such-part", "x")]).is_none());
    }
}

//! The factors of a term: which state variables it depends on, its factors, and the
//! diagnosis of a term right but for one wrong factor inside it (`wrong_factor`).

use super::*;

/// The state variables (coordinates at any order, and time) a term depends on.
pub(super) fn state_vars(p: &Prepared, e: Id) -> Vec<(Sym, u8)> {
    let time = p.system.pool.time();
    let coords = p.system.coordinate_syms();
    let mut v: Vec<(Sym, u8)> = p
        .system
        .pool
        .variables(e)
        .into_iter()
        .filter(|(s, _)| *s == time || coords.contains(s))
        .collect();
    v.sort();
    v.dedup();
    v
}

/// The non-numeric factors of a term.
fn factors(p: &Prepared, e: Id) -> Vec<Id> {
    match p.system.pool.node(e) {
        Node::Mul(f) => f
            .iter()
            .copied()
            .filter(|&x| !matches!(p.system.pool.node(x), Node::Num(_)))
            .collect(),
        Node::Num(_) => Vec::new(),
        _ => vec![e],
    }
}

/// Whether `e` depends on the state (a coordinate at any order, or time).
fn is_state(p: &Prepared, e: Id) -> bool {
    !state_vars(p, e).is_empty()
}

/// A wrong factor inside one term: said only when the student's term has every state variable
/// of the reference's (sin ↔ cos, l ↔ l², θ₁ + θ₂ for θ₁ − θ₂, a missing sin α, an extra
/// cos θ), so that it is one term with a wrong part, not a different term altogether (θ̇² for
/// sin θ, or ½mṙ² for ½m(ṙ² + ω²r²), where a whole term is missing). Under a common scaling (equations) the
/// parameters of a term are compared only through the numbers, so only its state factors are
/// named (and functions of them, like sin α). The flag says whether one factor was named.
pub(super) fn wrong_factor(
    p: &Prepared,
    s: Id,
    r: Id,
    yours: &str,
    how: Scaling,
) -> Option<(Diagnosis, bool)> {
    let (vs, vr) = (state_vars(p, s), state_vars(p, r));
    let within = |a: &[(Sym, u8)], b: &[(Sym, u8)]| a.iter().all(|x| b.contains(x));
    if vs.is_empty() != vr.is_empty() || !within(&vr, &vs) {
        return None;
    }
    let keep = |x: &Id| {
        how == Scaling::None || is_state(p, *x) || matches!(p.system.pool.node(*x), Node::Func(..))
    };
    let fs: Vec<Id> = factors(p, s).into_iter().filter(keep).collect();
    let fr: Vec<Id> = factors(p, r).into_iter().filter(keep).collect();
    let wrong: Vec<Id> = fs.iter().copied().filter(|x| !fr.contains(x)).collect();
    let lacking: Vec<Id> = fr.iter().copied().filter(|x| !fs.contains(x)).collect();
    let pool = &p.system.pool;
    // (1 − cos θ) where (cos θ − 1) belongs: the factor is right but for its sign.
    if let ([w], [l]) = (wrong.as_slice(), lacking.as_slice())
        && negatives(p, *w, *l)
    {
        return Some((
            Diagnosis::new(
                Code::SignError,
                format!("sign error: {yours} should have the opposite sign"),
            ),
            true,
        ));
    }
    let (message, named) = match (wrong.as_slice(), lacking.as_slice()) {
        ([w], _) => {
            // A power of a function (1/sin α, cos²θ) is judged by the function inside.
            let base = match pool.node(*w) {
                Node::Pow(b, _) => *b,
                _ => *w,
            };
            let why = if matches!(
                pool.node(base),
                Node::Func(crate::expr::Func::Sin | crate::expr::Func::Cos, _)
            ) {
                "check sin against cos, and the angle inside"
            } else if matches!(pool.node(base), Node::Func(..)) {
                "check the function and what is inside it"
            } else if is_state(p, *w) {
                "check its power and what is inside"
            } else {
                "check which masses and lengths this term involves, and their powers"
            };
            (
                format!(
                    "in {yours}, the factor {} is wrong: {why}",
                    quote::shown(p, *w)
                ),
                true,
            )
        }
        ([], [l]) => {
            let vars: Vec<String> = pool
                .variables(*l)
                .into_iter()
                .map(|(s, o)| pool.var_name(s, o, Style::Unicode))
                .collect();
            (
                format!("{yours} lacks a factor (one in {})", vars.join(", ")),
                true,
            )
        }
        ([], []) if how == Scaling::Common => (
            format!(
                "{yours} has a wrong factor among its parameters, compared with your other terms"
            ),
            true,
        ),
        _ => (format!("{yours} has a wrong factor"), false),
    };
    Some((Diagnosis::new(Code::WrongFactor, message), named))
}

/// Whether `a` is −`b` at every sample point where both are defined (and at one at least).
fn negatives(p: &Prepared, a: Id, b: Id) -> bool {
    let Ok(vals) = values(&p.system, &[a, b], &p.points) else {
        return false;
    };
    let defined: Vec<&Vec<f64>> = vals.iter().flatten().collect();
    !defined.is_empty()
        && defined
            .iter()
            .all(|v| close(v[0], -v[1], 0.0, p.tolerance) && v[0] != 0.0)
}

/// What a reference term contains, without its coefficient: the product of its factors that
/// depend on the state, e.g. `θ̇₂²·sin(θ₁ − θ₂)`. `None` for a term without any.
/// Whether `r` is a product of two different velocities (θ̇₁·θ̇₂·cos(θ₁ − θ₂)): the cross term
/// of a kinetic energy.
pub(super) fn cross_velocities(p: &Prepared, r: Id) -> bool {
    let coords = p.system.coordinate_syms();
    let velocities = p
        .system
        .pool
        .variables(r)
        .iter()
        .filter(|(s, o)| *o == 1 && coords.contains(s))
        .count();
    velocities >= 2
}

pub(super) fn content(p: &Prepared, r: Id) -> Option<String> {
    let time = p.system.pool.time();
    let coords = p.system.coordinate_syms();
    let state: Vec<String> = factors(p, r)
        .into_iter()
        .filter(|&f| {
            p.system
                .pool
                .variables(f)
                .iter()
                .any(|(s, _)| *s == time || coords.contains(s))
        })
        .map(|f| p.system.pool.unicode(f))
        .collect();
    (!state.is_empty()).then(|| state.join("·"))
}

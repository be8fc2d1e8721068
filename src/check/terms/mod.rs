//! Term-level diagnosis: the student's answer and the reference are split into terms, the
//! terms matched numerically at every sample point (for equations after the best common
//! scaling), and when exactly one term differs — missing, extra, with the wrong sign, off by a
//! constant factor, or with a wrong factor inside — the diagnosis names it in the student's own
//! terms (the term as they wrote it, on the side where they wrote it).
//!
//! All the work is arithmetic on the terms' values, evaluated once: the search over scalings
//! and matchings never builds or evaluates an expression, so it stays cheap.

use super::compare::{close, values};
use super::diagnose::{
    MAX_SEARCH_TERMS, bare_numbers_for, has_decimal, how_far_off, near_miss, nice_fraction,
    student_numbers,
};
use super::prepare::Prepared;
use super::quote;
use super::tolerance;
use super::verdict::{Code, Diagnosis};
use crate::expr::{Id, Node, Style, Sym};

mod factor;
use factor::{content, cross_velocities, state_vars, wrong_factor};

/// Most terms on either side for the all-pairs scaling search of an equation.
const MAX_SCALED_TERMS: usize = 16;

/// Terms of a sum with their sign in it: `shown` is the term as written on its side, `signed`
/// its contribution (the negative of `shown` for a term on the right of `=`). `named` is how
/// a message names each term as the student's: their own text where they typed the term
/// ([`quote`](super::quote)), the side it is on when both sides have terms, and for a piece of
/// a term that expanding split, the term it is a part of.
#[derive(Clone, Debug, Default)]
pub(super) struct Terms {
    shown: Vec<Id>,
    signed: Vec<Id>,
    named: Vec<Named>,
}

/// How a message names one of the student's terms.
#[derive(Clone, Debug, Default)]
struct Named {
    /// The term as the student typed it, or printed where they did not type it as one.
    text: String,
    /// `on the left` or `on the right` of `=`, when both sides have terms.
    side: Option<&'static str>,
    /// The student's term this is a part of, when expanding split one.
    within: Option<String>,
}

impl Named {
    /// The phrase naming the term in a message: "your term −(m₂ − m₁) g", "your term
    /// (m₂ − m₁) g on the right", "the part −½·m₂·ẋ² of your term ½ (m₁ − m₂) ẋ²".
    fn phrase(&self) -> String {
        let side = self.side.map(|s| format!(" {s}")).unwrap_or_default();
        match &self.within {
            None => format!("your term {}{side}", self.text),
            Some(whole) => format!("the part {} of your term {whole}{side}", self.text),
        }
    }
}

/// The top-level terms of `e` (a sum's terms, or `e` itself; none for 0).
fn top_terms(p: &Prepared, e: Id) -> Vec<Id> {
    if p.system.pool.is_zero(e) {
        return Vec::new();
    }
    match p.system.pool.node(e) {
        Node::Add(t) => t.to_vec(),
        _ => vec![e],
    }
}

impl Terms {
    /// The terms of an expression, as written.
    pub(super) fn of_expression(p: &mut Prepared, e: Id) -> Terms {
        quote::ensure(p);
        let t = top_terms(p, e);
        let named = t
            .iter()
            .map(|&x| Named {
                text: quote::shown(p, x),
                ..Named::default()
            })
            .collect();
        Terms {
            shown: t.clone(),
            signed: t,
            named,
        }
    }

    /// The terms of an equation `lhs = rhs`, each shown on its own side.
    pub(super) fn of_equation(p: &mut Prepared, lhs: Id, rhs: Id) -> Terms {
        let mut out = Terms::of_expression(p, lhs);
        let right = top_terms(p, rhs);
        // "On the left" only helps where there is a right to tell it from.
        if !out.shown.is_empty() && !right.is_empty() {
            for n in &mut out.named {
                n.side = Some("on the left");
            }
        }
        let side = (!out.shown.is_empty()).then_some("on the right");
        for t in right {
            out.shown.push(t);
            let n = p.system.pool.neg(t);
            out.signed.push(n);
            out.named.push(Named {
                text: quote::shown(p, t),
                side,
                within: None,
            });
        }
        out
    }

    /// Each term expanded into its own terms (`(m₁ + m₂)·g` gives two), keeping its side; a
    /// term that splits names its parts as parts of it.
    fn expanded(&self, p: &mut Prepared) -> Terms {
        let mut out = Terms::default();
        for ((&s, &g), named) in self.shown.iter().zip(&self.signed).zip(&self.named) {
            let flip = s != g;
            let x = p.system.pool.expand(s);
            let parts = top_terms(p, x);
            let split = parts.len() > 1;
            for t in parts {
                out.shown.push(t);
                out.signed.push(if flip { p.system.pool.neg(t) } else { t });
                out.named.push(if split {
                    Named {
                        text: quote::shown(p, t),
                        side: named.side,
                        within: Some(named.within.clone().unwrap_or_else(|| named.text.clone())),
                    }
                } else {
                    // The same term, rewritten: still the one the student wrote.
                    named.clone()
                });
            }
        }
        out
    }

    /// Number of terms.
    pub(super) fn len(&self) -> usize {
        self.shown.len()
    }

    /// How a message names term `i`.
    fn phrase(&self, i: usize) -> String {
        self.named.get(i).map_or_else(String::new, Named::phrase)
    }
}

/// How the student's terms may be scaled to the reference's.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Scaling {
    /// Not at all (expressions).
    None,
    /// By a common factor, which may vary from point to point (equations: m·l²·θ'' + … and
    /// θ'' + … are the same equation).
    Common,
}

/// The one difference found between the matched terms.
enum Difference {
    /// Reference term `j` has no counterpart.
    Missing(usize),
    /// Student term `i` has no counterpart.
    Extra(usize),
    /// Student term `i` differs from reference term `j` by the ratio at each point.
    Pair(usize, usize, Vec<f64>),
}

/// The values of the student's and the reference's terms at the points where all are defined.
struct Table {
    student: Vec<Vec<f64>>,
    reference: Vec<Vec<f64>>,
}

fn table(p: &Prepared, student: &Terms, reference: &Terms) -> Option<Table> {
    let ids: Vec<Id> = student
        .signed
        .iter()
        .chain(&reference.signed)
        .copied()
        .collect();
    let vals = values(&p.system, &ids, &p.points).ok()?;
    let rows: Vec<Vec<f64>> = vals
        .into_iter()
        .flatten()
        .filter(|r| r.iter().all(|x| x.is_finite()))
        .collect();
    // Verified at most points, never at one or two that happen to be defined.
    if rows.len() < 3 || rows.len() * 2 < p.points.points.len() {
        return None;
    }
    let n = student.len();
    let col = |i: usize| rows.iter().map(|r| r[i]).collect::<Vec<f64>>();
    Some(Table {
        student: (0..n).map(col).collect(),
        reference: (n..ids.len()).map(col).collect(),
    })
}

/// Whether `s = c·r` at every point.
fn proportional(s: &[f64], r: &[f64], c: &[f64]) -> bool {
    s.iter()
        .zip(r)
        .zip(c)
        .all(|((x, y), k)| close(*x, k * y, 0.0, tolerance::SAME))
}

/// Matches the terms under the scaling `c`; `Some` when exactly one term differs.
fn match_with(t: &Table, c: &[f64]) -> Option<Difference> {
    let mut used = vec![false; t.reference.len()];
    let mut unmatched = Vec::new();
    for (i, s) in t.student.iter().enumerate() {
        match (0..t.reference.len()).find(|&j| !used[j] && proportional(s, &t.reference[j], c)) {
            Some(j) => used[j] = true,
            None => unmatched.push(i),
        }
    }
    let left: Vec<usize> = (0..used.len()).filter(|&j| !used[j]).collect();
    match (unmatched.as_slice(), left.as_slice()) {
        ([], [j]) => Some(Difference::Missing(*j)),
        ([i], []) => Some(Difference::Extra(*i)),
        ([i], [j]) => {
            let ratio = t.student[*i]
                .iter()
                .zip(&t.reference[*j])
                .zip(c)
                .map(|((x, y), k)| x / (k * y))
                .collect();
            Some(Difference::Pair(*i, *j, ratio))
        }
        _ => None,
    }
}

/// The common scalings to try: 1 for expressions; for equations the ratio of a student term
/// to a reference term of the same shape (the same state variables) at each point. A ratio
/// of acceleration terms may depend on the parameters (θ'' + g/l·sin θ is m·l²·θ'' + … over
/// m·l²); any other ratio must be a plain number, or terms of one shape (ω²·r, 2·a·g·r) could
/// be "matched" through a scaling that means nothing.
fn scalings(
    p: &Prepared,
    student: &Terms,
    reference: &Terms,
    t: &Table,
    how: Scaling,
) -> Vec<Vec<f64>> {
    let k = t
        .student
        .first()
        .or(t.reference.first())
        .map_or(0, Vec::len);
    if how == Scaling::None {
        return vec![vec![1.0; k]];
    }
    if student.len() > MAX_SCALED_TERMS || reference.len() > MAX_SCALED_TERMS {
        return Vec::new();
    }
    let accel = |e: Id| p.system.pool.variables(e).iter().any(|v| v.1 == 2);
    let mut pairs: Vec<(bool, usize, usize)> = Vec::new();
    // (not both accelerations, student term, reference term), in the order tried.
    for i in 0..student.len() {
        for j in 0..reference.len() {
            let (si, rj) = (student.signed[i], reference.signed[j]);
            let both = accel(si) && accel(rj);
            // Acceleration terms pair by their accelerations (a mass matrix entry may depend
            // on the state: ψ'' and (1 + x²)·ψ''); other terms by all their state variables.
            let shape = |e: Id| -> Vec<(Sym, u8)> {
                let v = state_vars(p, e);
                if both {
                    v.into_iter().filter(|x| x.1 == 2).collect()
                } else {
                    v
                }
            };
            if shape(si) != shape(rj) {
                continue;
            }
            pairs.push((!both, i, j));
        }
    }
    // Acceleration pairs first, then a scaling of 1 (the student's equation as written), then
    // the other numbers: among equally true readings, the plainest.
    let mut found: Vec<(bool, bool, usize, Vec<f64>)> = pairs
        .into_iter()
        .enumerate()
        .filter_map(|(rank, (numeric_only, i, j))| {
            let c: Vec<f64> = t.student[i]
                .iter()
                .zip(&t.reference[j])
                .map(|(x, y)| x / y)
                .collect();
            let c0 = *c.first()?;
            let constant = c.iter().all(|x| close(*x, c0, 0.0, tolerance::NUMBER));
            let usable =
                c.iter().all(|x| x.is_finite() && *x != 0.0) && (!numeric_only || constant);
            let one = constant && (c0 - 1.0).abs() < tolerance::NUMBER;
            usable.then_some((numeric_only, !one, rank, c))
        })
        .collect();
    crate::sort::sort_by_key(&mut found, |&(numeric_only, not_one, rank, _)| {
        (numeric_only, not_one, rank)
    });
    found.into_iter().map(|(_, _, _, c)| c).collect()
}

/// The one term that differs between `student` and `reference`, as a diagnosis about
/// `which` ("your answer", "equation 2"), or `None` when not exactly one term differs at
/// every sample point. Tries the terms as written, then expanded.
pub(super) fn one_term(
    p: &mut Prepared,
    student: &Terms,
    reference: &Terms,
    how: Scaling,
    which: &str,
) -> Option<Diagnosis> {
    if student.len() > MAX_SEARCH_TERMS || reference.len() > MAX_SEARCH_TERMS {
        return None;
    }
    let given = one_term_as_given(p, student, reference, how, which);
    if let Some((d, true)) = &given
        && d.code != Code::WrongFactor
    {
        return Some(d.clone());
    }
    // A wrong factor in a term as written may be a sign or a factor in one of its terms once
    // expanded (½(m₁ − m₂)ẋ² for ½(m₁ + m₂)ẋ²), or a vaguer finding a plain missing term.
    let (se, re) = (student.expanded(p), reference.expanded(p));
    let expanded = if se.len() > MAX_SEARCH_TERMS
        || re.len() > MAX_SEARCH_TERMS
        || (se.shown == student.shown && re.shown == reference.shown)
    {
        None
    } else {
        one_term_as_given(p, &se, &re, how, which)
    };
    // A factor that is itself a sum (½m(ṙ² + ω²r²)) is better told term by term: the
    // expanded finding (a missing 4a²r²ṙ²) names what is wrong inside it.
    let split = se.len() > student.len();
    let plain = |c: Code| {
        matches!(
            c,
            Code::SignError | Code::ConstantFactor | Code::RoundedConstant
        ) || (split && matches!(c, Code::MissingTerm | Code::ExtraTerm))
    };
    match (given, expanded) {
        (Some((g, true)), Some((e, _))) if !plain(e.code) => Some(g),
        (_, Some((e, _))) => Some(e),
        (g, None) => g.map(|(d, _)| d),
    }
}

/// The one differing term of the terms as given, and whether the finding is specific (a
/// wrong factor named, not only "a wrong factor").
fn one_term_as_given(
    p: &mut Prepared,
    student: &Terms,
    reference: &Terms,
    how: Scaling,
    which: &str,
) -> Option<(Diagnosis, bool)> {
    let t = table(p, student, reference)?;
    for c in scalings(p, student, reference, &t, how) {
        let Some(d) = match_with(&t, &c) else {
            continue;
        };
        if let Some(found) = describe(p, (student, reference), d, how, which) {
            return Some(found);
        }
    }
    None
}

/// The sentence for a difference, or `None` when it would not be telling.
fn describe(
    p: &Prepared,
    (student, reference): (&Terms, &Terms),
    d: Difference,
    how: Scaling,
    which: &str,
) -> Option<(Diagnosis, bool)> {
    let found = match d {
        Difference::Missing(j) => {
            let what = content(p, reference.signed[j]);
            // "no term in ẍ" would be false when the student has one: then the coefficient
            // of that term is what is incomplete ((m₁ + m₂)·ẍ written m₁·ẍ).
            let shared = what.is_some() && student.signed.iter().any(|&t| content(p, t) == what);
            match what {
                Some(what) if shared => Diagnosis::new(
                    Code::WrongFactor,
                    format!(
                        "the coefficient of {which}'s term in {what} is incomplete: part of it is missing"
                    ),
                ),
                Some(what)
                    if which == "your answer"
                        && p.squares_velocities
                        && cross_velocities(p, reference.signed[j]) =>
                {
                    Diagnosis::new(
                        Code::MissingTerm,
                        format!(
                            "{which} has no cross term in {what}: velocities add as vectors, so the square of a sum of velocities has a cross term"
                        ),
                    )
                }
                Some(what) => {
                    Diagnosis::new(Code::MissingTerm, format!("{which} has no term in {what}"))
                }
                None => Diagnosis::new(
                    Code::MissingTerm,
                    format!(
                        "{which} lacks a term that does not depend on the coordinates or velocities"
                    ),
                ),
            }
        }
        Difference::Extra(i) => Diagnosis::new(
            Code::ExtraTerm,
            format!(
                "{which} has a term too many: {} should not be there",
                student.phrase(i)
            ),
        ),
        Difference::Pair(i, j, ratio) => {
            // In a system, say which equation ("sign error in equation 2: …").
            let place = if which.starts_with("equation") {
                format!(" in {which}")
            } else {
                String::new()
            };
            return pair(p, (student, reference), (i, j), &ratio, (how, &place));
        }
    };
    Some((found, true))
}

/// One student term against one reference term: a sign, a constant factor, rounding, or a
/// wrong factor inside.
fn pair(
    p: &Prepared,
    (student, reference): (&Terms, &Terms),
    (i, j): (usize, usize),
    ratio: &[f64],
    (how, place): (Scaling, &str),
) -> Option<(Diagnosis, bool)> {
    let yours = student.phrase(i);
    // 0/0 (both terms vanish at a point) says nothing about the ratio; x/0 is infinite and
    // never constant.
    let known: Vec<f64> = ratio.iter().copied().filter(|r| !r.is_nan()).collect();
    let f = known.first().copied()?;
    let constant = known.len() >= 2
        && known
            .iter()
            .all(|r| r.is_finite() && close(*r, f, 0.0, tolerance::NUMBER));
    if constant {
        // Yours is f times the right term: it should be 1/f times what you wrote.
        let want = 1.0 / f;
        if (f + 1.0).abs() < tolerance::NUMBER {
            return Some((
                Diagnosis::new(
                    Code::SignError,
                    format!("sign error{place}: {yours} should have the opposite sign"),
                ),
                true,
            ));
        }
        if (f - 1.0).abs() < tolerance::ROUNDED
            && has_decimal(p, student.signed[i])
            && student_numbers(p)
        {
            let what = format!("the coefficient of {yours}{place}");
            return Some((
                Diagnosis::new(
                    Code::RoundedConstant,
                    near_miss(&what, (f - 1.0).abs(), p.tolerance),
                ),
                true,
            ));
        }
        if (f - 1.0).abs() < tolerance::ROUNDED && has_decimal(p, student.signed[i]) {
            return Some((
                Diagnosis::new(
                    Code::RoundedConstant,
                    format!(
                        "the coefficient of {yours}{place} is off by {:.2}%: a decimal where an exact constant (sqrt(2), pi, 1/3) belongs",
                        (f - 1.0).abs() * 100.0
                    ),
                ),
                true,
            ));
        }
        // Bare numbers where the reference term has parameters: the ratio is no factor.
        if bare_numbers_for(p, student.signed[i], reference.signed[j]) {
            return Some((
                Diagnosis::new(
                    Code::NotEqual,
                    format!(
                        "the value of {yours}{place} is wrong: it is {}",
                        how_far_off(f)
                    ),
                ),
                true,
            ));
        }
        let text = nice_fraction(want)
            .map(|n| format!("it should be {n} times what you wrote"))
            .unwrap_or_else(|| {
                format!(
                    "it should be about {} times what you wrote",
                    super::compare::fmt_value(want)
                )
            });
        return Some((
            Diagnosis::new(
                Code::ConstantFactor,
                format!("{yours}{place} is off by a constant factor: {text}"),
            ),
            true,
        ));
    }
    let yours = format!("{yours}{place}");
    wrong_factor(p, student.signed[i], reference.signed[j], &yours, how)
}

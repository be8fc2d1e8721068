//! Keys for checking answers in bulk (a class's answers graded together): the canonical form of
//! an answer, so that answers read the same are checked once, and its fingerprint, so that
//! answers equal at the sample points — the same mathematics spelt differently — group
//! together in a summary of what a class got wrong.
//!
//! A fingerprint is the answer's values at the first few sample points, rounded to eight
//! significant digits. Equations are compared by what they say, not how they are scaled: a
//! system is fingerprinted by the accelerations it implies, a single equation by its residual
//! divided by the coefficient of its first acceleration (or, without accelerations, by its
//! value at the first point where it does not vanish). List items are sorted, so the order of
//! the items does not matter. Two equivalent answers share a fingerprint; two answers with one
//! fingerprint are equal at those points (which is what the checker means by equal).

use nalgebra::{DMatrix, DVector};

use super::compare::values;
use super::item_reading::read_stated_items;
use super::points::PointSet;
use super::prepare::Prepared;
use crate::expr::lower::lower_statement;
use crate::expr::parser::parse;
use crate::expr::{Id, Reading, Style, read};
use crate::problem::{Part, PartKind};

/// How many sample points a fingerprint uses.
const POINTS: usize = 6;

/// Significant digits kept of each value.
const DIGITS: usize = 8;

/// Values smaller than this are taken as zero (round-off of an expression that vanishes).
const ZERO: f64 = 1e-10;

/// The canonical form of `input` read for `part` (plain style); list items sorted. `None` when
/// the input cannot be read.
pub(crate) fn canonical(part: &Part, p: &mut Prepared, input: &str) -> Option<String> {
    let input = unnamed(part, p, input);
    if is_list(part) {
        let (items, said) = read_said(part, p, input)?;
        let mut shown: Vec<String> = items
            .iter()
            .zip(&said)
            .map(|(it, s)| {
                let value = it
                    .iter()
                    .map(|&x| p.system.pool.display(x, Style::Plain))
                    .collect::<Vec<_>>()
                    .join(", ");
                format!("{s}{value}")
            })
            .collect();
        shown.sort();
        return Some(format!("[{}]", shown.join("; ")));
    }
    let parsed = parse(input, &p.context).ok()?;
    let r = lower_statement(&mut p.system.pool, &parsed.statement);
    // Diagnoses quote the student's terms as they built them (`−(m₂ − m₁) g`, not
    // `(m₁ − m₂)·g`): answers read the same but built otherwise get verdicts worded otherwise,
    // so the way they were built is part of the form (spacing and spelling are not).
    let typed = super::quote::statement_text(input, &parsed.statement);
    Some(format!("{} | as built: {typed}", show(p, &r)))
}

fn show(p: &Prepared, r: &Reading) -> String {
    match r {
        Reading::Expr(e, _) => p.system.pool.display(*e, Style::Plain),
        Reading::Equation { lhs, rhs, .. } => {
            p.system.pool.display_equation(*lhs, *rhs, Style::Plain)
        }
        Reading::List(items, _) => {
            let inner: Vec<String> = items.iter().map(|i| show(p, i)).collect();
            format!("({})", inner.join(", "))
        }
        Reading::System(items, _) => {
            let inner: Vec<String> = items.iter().map(|i| show(p, i)).collect();
            format!("{{{}}}", inner.join("; "))
        }
    }
}

/// The answer without a name the checker reads as the quantity's (`T = …` for a part asking
/// for T): `T = ½ m v²` and `½ m v²` are one answer. A wrong name is kept, so the answer
/// stays apart from the bare value (its verdict differs).
fn unnamed<'i>(part: &Part, p: &mut Prepared, input: &'i str) -> &'i str {
    match super::named::label(part, p, input) {
        Some(l) if super::named::fits_part(part, &l) => &input[l.offset..],
        _ => input,
    }
}

/// A list's items, each with a mark of the quantity its label states when that is not what
/// the part asks for (`ω² = √(g/l)` is not `√(g/l)`: its verdict differs); empty otherwise.
fn read_said(part: &Part, p: &mut Prepared, input: &str) -> Option<(Vec<Vec<Id>>, Vec<String>)> {
    let read = read_stated_items(part, p, input).ok()?;
    let said = read
        .labels
        .iter()
        .map(|l| match l {
            Some(l) if !super::freq_label::fits(part, Some(l.said)) => format!("{:?}:", l.said),
            _ => String::new(),
        })
        .collect();
    Some((read.items, said))
}

fn is_list(part: &Part) -> bool {
    matches!(
        part.kind,
        PartKind::Equilibria | PartKind::Frequencies | PartKind::Values
    )
}

/// The fingerprint of `input` for `part`; `None` when it cannot be read or evaluated.
pub(crate) fn fingerprint(part: &Part, p: &mut Prepared, input: &str) -> Option<String> {
    let input = unnamed(part, p, input);
    let pts = PointSet {
        points: p.points.points.iter().take(POINTS).cloned().collect(),
    };
    if is_list(part) {
        let (items, said) = read_said(part, p, input)?;
        let mut keys: Vec<String> = Vec::with_capacity(items.len());
        for (it, s) in items.iter().zip(&said) {
            let vals = values(&p.system, it, &pts).ok()?;
            let key = vals
                .iter()
                .map(|v| v.as_deref().map_or("u".to_string(), quantise_all))
                .collect::<Vec<_>>()
                .join(" ");
            keys.push(format!("{s}{key}"));
        }
        keys.sort();
        return Some(format!("[{}]", keys.join("; ")));
    }
    let r = read(input, &p.context, &mut p.system.pool).ok()?;
    match part.kind {
        PartKind::Equation | PartKind::Equations => {
            let res = residuals(p, r)?;
            Some(format!("eq:{}", equations_key(p, &res, &pts)?))
        }
        _ => match r {
            Reading::Expr(e, _) => {
                let vals = values(&p.system, &[e], &pts).ok()?;
                Some(
                    vals.iter()
                        .map(|v| v.as_deref().map_or("u".to_string(), quantise_all))
                        .collect::<Vec<_>>()
                        .join(" "),
                )
            }
            // Not an expression (an equation for an expression part…): the canonical form
            // is as far as sameness goes.
            other => Some(format!("text:{}", show(p, &other))),
        },
    }
}

/// The residuals `lhs − rhs` of the equations read (a bare expression is `expression = 0`).
fn residuals(p: &mut Prepared, r: Reading) -> Option<Vec<Id>> {
    let mut flat = Vec::new();
    match r {
        Reading::System(items, _) | Reading::List(items, _) => flat.extend(items),
        other => flat.push(other),
    }
    flat.into_iter()
        .map(|it| match it {
            Reading::Expr(e, _) => Some(e),
            Reading::Equation { lhs, rhs, .. } => Some(p.system.pool.sub(lhs, rhs)),
            _ => None,
        })
        .collect()
}

/// One equation at one point: the coefficients of the accelerations, and the rest.
type Row = (Vec<f64>, f64);

/// The key of a set of equations: the implied accelerations when they determine them, or
/// else each equation normalised on its own (sorted).
fn equations_key(p: &mut Prepared, res: &[Id], pts: &PointSet) -> Option<String> {
    let n = p.system.n();
    let coords = p.system.coordinate_syms();
    // Per equation: the coefficients of every acceleration, then the residual.
    let mut roots = Vec::with_capacity(res.len() * (n + 1));
    for &r in res {
        for &c in &coords {
            roots.push(p.system.pool.diff(r, c, 2));
        }
        roots.push(r);
    }
    let vals = values(&p.system, &roots, pts).ok()?;
    let at = p.system.state_layout();
    // Equation `i` at one point as its affine form: (coefficients of q'', the rest).
    let rows = |v: &[f64], x: &[f64]| -> Vec<Row> {
        (0..res.len())
            .map(|i| {
                let a = v[i * (n + 1)..i * (n + 1) + n].to_vec();
                let b = v[i * (n + 1) + n] - (0..n).map(|j| a[j] * x[at.qddot(j)]).sum::<f64>();
                (a, b)
            })
            .collect()
    };
    let affine: Vec<Option<Vec<Row>>> = vals
        .iter()
        .zip(&pts.points)
        .map(|(v, x)| v.as_deref().map(|v| rows(v, x)))
        .collect();
    if res.len() == n && n > 0 {
        let solved: Option<Vec<String>> = affine
            .iter()
            .map(|a| implied_accelerations(a.as_deref()?))
            .collect();
        if let Some(s) = solved {
            return Some(format!("acc:{}", s.join(" ")));
        }
    }
    let mut keys: Vec<String> = (0..res.len())
        .map(|i| normalised(&affine, i))
        .collect::<Option<_>>()?;
    keys.sort();
    Some(format!("each:{}", keys.join("; ")))
}

/// The accelerations a square system implies at one point (quantised), `None` when it does
/// not determine them.
fn implied_accelerations(rows: &[Row]) -> Option<String> {
    let n = rows.len();
    let m = DMatrix::from_fn(n, n, |i, j| rows[i].0[j]);
    let rhs = DVector::from_fn(n, |i, _| -rows[i].1);
    let scale = m.amax().max(f64::MIN_POSITIVE);
    let lu = m.lu();
    if lu.determinant().abs() <= 1e-12 * scale.powi(n as i32) {
        return None;
    }
    Some(quantise_all(lu.solve(&rhs)?.as_slice()))
}

/// Equation `i` at every point divided by a normaliser that scales with it: the coefficient of
/// the first acceleration nonzero at the first point, or (no accelerations) the residual's own
/// value at the first point where it is nonzero. `c·E = 0` and `E = 0` share the key.
fn normalised(affine: &[Option<Vec<Row>>], i: usize) -> Option<String> {
    let first = affine.iter().flatten().next()?;
    let pick = first[i].0.iter().position(|a| a.abs() > ZERO);
    // The value of the residual at a point, from its affine form (b holds the rest).
    let residual_lead = affine
        .iter()
        .flatten()
        .map(|rows| rows[i].1)
        .find(|r| r.abs() > ZERO);
    let parts: Vec<String> = affine
        .iter()
        .map(|rows| {
            let Some(rows) = rows else {
                return "u".to_string();
            };
            let (a, b) = &rows[i];
            let d = match pick {
                Some(j) => a[j],
                None => residual_lead.unwrap_or(1.0),
            };
            if d.abs() > ZERO {
                // Every coefficient and the acceleration-free rest, normalised.
                let mut all: Vec<f64> = a.iter().map(|c| c / d).collect();
                all.push(b / d);
                quantise_all(&all)
            } else {
                "u".to_string()
            }
        })
        .collect();
    Some(parts.join(" "))
}

fn quantise_all(vs: &[f64]) -> String {
    vs.iter()
        .map(|&v| quantise(v))
        .collect::<Vec<_>>()
        .join(",")
}

/// `v` to [`DIGITS`] significant digits; round-off around zero is zero.
fn quantise(v: f64) -> String {
    if !v.is_finite() {
        return "nan".into();
    }
    if v.abs() < ZERO {
        return "0".into();
    }
    format!("{:.*e}", DIGITS - 1, v)
}

#[cfg(test)]
mod tests {
    use crate::check::Checker;

    /// The fingerprints of `answers` to `part` of the embedded problem `problem`.
    fn prints(problem: &str, part: &str, answers: &[&str]) -> Vec<Option<String>> {
        let pr = crate::bank::embedded::problem(problem).expect("problem in the bank");
        let mut c = Checker::new(&pr);
        answers
            .iter()
            .map(|a| c.fingerprint(part, a).expect("part exists"))
            .collect()
    }

    fn assert_groups(problem: &str, part: &str, same: &[&str], other: &[&str]) {
        let s = prints(problem, part, same);
        assert!(s[0].is_some(), "{:?} has a fingerprint", same[0]);
        for (a, f) in same.iter().zip(&s) {
            assert_eq!(f, &s[0], "{a:?} groups with {:?}", same[0]);
        }
        for (a, f) in other.iter().zip(prints(problem, part, other)) {
            assert_ne!(f, s[0], "{a:?} must not group with {:?}", same[0]);
        }
    }

    #[test]
    fn equivalent_spellings_share_a_fingerprint() {
        assert_groups(
            "simple-pendulum",
            "eom",
            &[
                "m*l^2*theta'' - m*g*l*sin(theta) = 0",
                "m l^2 θ'' = m g l sin(θ)",
                "theta'' - g/l*sin(theta)",
                "-2*l*theta'' + 2*g*sin(theta) = 0",
            ],
            &[
                "m*l^2*theta'' + m*g*l*sin(theta) = 0",
                "theta'' - g*l*sin(theta) = 0",
                "theta'' = 0",
            ],
        );
        assert_groups(
            "simple-pendulum",
            "potential",
            &["m*g*l*cos(theta)", "m g l cos(θ)", "l*cos(theta)*g*m"],
            &["-m*g*l*cos(theta)", "m*g*l*sin(theta)"],
        );
        assert_groups(
            "double-pendulum",
            "frequencies",
            &[
                "sqrt(g/l), sqrt(3*g/l)",
                "omega2 = sqrt(3 g/l), omega1 = sqrt(g/l)",
            ],
            &["sqrt(g/l)", "g/l, 3*g/l"],
        );
        assert_groups(
            "simple-pendulum",
            "equilibria",
            &["0, pi", "pi, 0", "theta = pi, theta = 0"],
            &["0", "0, 2*pi"],
        );
    }

    #[test]
    fn a_system_is_fingerprinted_by_what_it_implies() {
        const A: &str = "(m1 + m2)*l1*theta1'' + m2*l2*theta2''*cos(theta1 - theta2) \
            + m2*l2*theta2'^2*sin(theta1 - theta2) + (m1 + m2)*g*sin(theta1) = 0";
        const B: &str = "l2*theta2'' + l1*theta1''*cos(theta1 - theta2) \
            - l1*theta1'^2*sin(theta1 - theta2) + g*sin(theta2) = 0";
        const WRONG_B: &str = "l2*theta2'' + l1*theta1''*cos(theta1 - theta2) \
            + l1*theta1'^2*sin(theta1 - theta2) + g*sin(theta2) = 0";
        // In another order, one equation scaled, or replaced by a combination: the same
        // accelerations.
        let combined = format!("{B}; 2*({})", A.replace("= 0", ""));
        let summed = format!(
            "{A}; ({}) + m2*({})",
            A.replace("= 0", ""),
            B.replace("= 0", "")
        );
        assert_groups(
            "double-pendulum",
            "eom",
            &[&format!("{A}; {B}"), &combined, &summed],
            &[&format!("{A}; {WRONG_B}"), A],
        );
    }

    #[test]
    fn a_lone_equation_of_a_system_keeps_every_coefficient() {
        // Same acceleration-free part relative to θ₁'', different θ₂'' coefficient.
        assert_groups(
            "double-pendulum",
            "eom",
            &[
                "theta1'' + theta2'' + g/l1*sin(theta1) = 0",
                "2*theta1'' + 2*theta2'' + 2*g/l1*sin(theta1) = 0",
            ],
            &["theta1'' + 2*theta2'' + g/l1*sin(theta1) = 0"],
        );
    }

    #[test]
    fn canonical_forms_ignore_spelling_and_item_order() {
        let pr = crate::bank::embedded::problem("simple-pendulum").expect("problem");
        let mut c = Checker::new(&pr);
        let a = c
            .canonical("eom", "m*l^2*theta''+m*g*l*sin(theta)=0")
            .unwrap();
        let b = c.canonical("eom", "m l² θ'' + m g l sin(θ) = 0").unwrap();
        assert!(a.is_some());
        assert_eq!(a, b);
        let a = c.canonical("equilibria", "0, pi").unwrap();
        let b = c.canonical("equilibria", "π, 0").unwrap();
        assert_eq!(a, b);
        assert_eq!(c.canonical("eom", "m*(").unwrap(), None);
        // A name the part asks for is not part of the answer; a wrong name is.
        let bare = c.canonical("kinetic", "1/2*m*l^2*theta'^2").unwrap();
        assert_eq!(c.canonical("kinetic", "T = 1/2 m l² θ̇²").unwrap(), bare);
        assert_ne!(c.canonical("kinetic", "V = 1/2 m l² θ̇²").unwrap(), bare);
    }

    #[test]
    fn problems_are_shared_and_checkers_move_between_threads() {
        fn send<T: Send>() {}
        fn sync<T: Sync>() {}
        sync::<crate::problem::Problem>();
        send::<Checker<'static>>();
    }
}

//! A sign error in an equilibrium: a point whose coordinates are each right or the negative of
//! the right one (`x = −m g sin α/k` for `x = m g sin α/k`), or right but for one coordinate
//! with one term of the wrong sign (`r = l₀ − m g/k` for `r = l₀ + m g/k`). Told as a
//! frequency's sign error is, in the student's own terms, instead of a bare `wrong-item`.

use super::super::compare::close;
use super::super::prepare::{Prepared, same_coordinate_within};
use super::super::quote;
use super::super::terms::{Scaling, Terms, one_term};
use super::super::verdict::{Code, Diagnosis};
use super::Lists;
use crate::problem::Part;

/// How one coordinate of a student point relates to the reference point's.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Coordinate {
    /// Equal at every point.
    Same,
    /// The negative at every point (and not zero everywhere).
    Negated,
    /// Anything else.
    Other,
}

/// The sign error that explains student point `i` against one of the `free` reference points:
/// the index in `free` of that point and the diagnosis.
pub(super) fn sign_error(
    part: &Part,
    p: &mut Prepared,
    lists: &Lists,
    i: usize,
    free: &[usize],
    label: &str,
) -> Option<(usize, Diagnosis)> {
    let ids = lists.student_ids.get(i)?.clone();
    let shown: Vec<String> = (p.system.coordinates.iter())
        .map(|q| crate::expr::names::unicode_name(&q.name))
        .collect();
    let names = |c: usize| shown.get(c).cloned().unwrap_or_else(|| "q".to_string());
    for (k, &j) in free.iter().enumerate() {
        let kinds = coordinates(part, p, &lists.student[i], &lists.reference[j], ids.len());
        if kinds.iter().all(|&c| c != Coordinate::Other) && kinds.contains(&Coordinate::Negated) {
            quote::ensure(p);
            let which: Vec<String> = (0..kinds.len())
                .filter(|&c| kinds[c] == Coordinate::Negated)
                .map(|c| format!("your {} = {}", names(c), quote::shown(p, ids[c])))
                .collect();
            let message = format!(
                "{label}: sign error: {} should have the opposite sign",
                which.join(" and ")
            );
            return Some((k, Diagnosis::new(Code::SignError, message)));
        }
        // One coordinate with one term of the wrong sign, the others right.
        let others: Vec<usize> = (0..kinds.len())
            .filter(|&c| kinds[c] != Coordinate::Same)
            .collect();
        let [c] = others[..] else { continue };
        let r = *lists.reference_ids.get(j)?.get(c)?;
        let st = Terms::of_expression(p, ids[c]);
        let rt = Terms::of_expression(p, r);
        let name = names(c);
        if let Some(d) =
            one_term(p, &st, &rt, Scaling::None, &name).filter(|d| d.code == Code::SignError)
        {
            let message = format!("{label}, in {name}: {}", d.message);
            return Some((k, Diagnosis::new(Code::SignError, message)));
        }
    }
    None
}

/// How each of the `n` coordinates of a student point relates to the reference point's,
/// over the sample points where both are defined (angles modulo 2π).
fn coordinates(
    part: &Part,
    p: &Prepared,
    s: &[Option<Vec<f64>>],
    r: &[Option<Vec<f64>>],
    n: usize,
) -> Vec<Coordinate> {
    (0..n)
        .map(|c| {
            let periodic = p.system.coordinates.get(c).is_some_and(|q| q.periodic);
            let pairs: Vec<(f64, f64)> = s
                .iter()
                .zip(r)
                .filter_map(|(x, y)| Some((*x.as_ref()?.get(c)?, *y.as_ref()?.get(c)?)))
                .collect();
            let same = |u: f64, w: f64| {
                if periodic {
                    same_coordinate_within(true, u, w, part.tolerance)
                } else {
                    close(u, w, 0.0, part.tolerance)
                }
            };
            if pairs.is_empty() {
                Coordinate::Other
            } else if pairs.iter().all(|&(u, w)| same(u, w)) {
                Coordinate::Same
            } else if pairs.iter().all(|&(u, w)| same(u, -w)) {
                Coordinate::Negated
            } else {
                Coordinate::Other
            }
        })
        .collect()
}

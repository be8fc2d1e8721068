//! What a frequencies list gets wrong about its modes: a zero mode (a free motion, ω = 0)
//! left out where the part lists them, or given where the part omits them
//! (`omit_zero_modes`); and, for a part asking the growth rates at an unstable equilibrium
//! (`growth`), a frequency of an oscillating mode given for a rate, or a rate worded as a
//! frequency.

use super::compare::values;
use super::items::Lists;
use super::prepare::{Prepared, equilibrium_of};
use super::verdict::{Code, Diagnosis, Verdict};
use crate::problem::{Part, PartKind};

/// Whether a list item is 0 at every point where it is defined (and defined somewhere).
fn is_zero(item: &[Option<Vec<f64>>]) -> bool {
    let mut any = false;
    for v in item.iter().flatten() {
        if v.first().is_some_and(|x| *x != 0.0) {
            return false;
        }
        any = true;
    }
    any
}

/// An unmatched student item that is 0: a zero mode where the part omits them, or where it
/// asks for growth rates. `None` for any other item.
pub(super) fn zero_item(part: &Part, lists: &Lists, i: usize, label: &str) -> Option<Diagnosis> {
    if part.kind != PartKind::Frequencies || !is_zero(&lists.student[i]) {
        return None;
    }
    if part.growth {
        return Some(Diagnosis::new(
            Code::ExtraItem,
            format!(
                "{label} is not a growth rate: a free motion (ω = 0) neither grows nor oscillates; list only the rates λ of the modes that grow"
            ),
        ));
    }
    part.omit_zero_modes.then(|| {
        Diagnosis::new(
            Code::ExtraItem,
            format!(
                "{label} is the zero mode of a free motion: this part asks only for the nonzero frequencies, so leave it out"
            ),
        )
    })
}

/// Reference zero modes the student left out (taken out of `free`): said as zero modes, so
/// that a student who gave the physical frequency alone learns what the missing one is.
pub(super) fn missing_zero_modes(
    part: &Part,
    lists: &Lists,
    free: &mut Vec<usize>,
) -> Option<Diagnosis> {
    if part.kind != PartKind::Frequencies || part.growth {
        return None;
    }
    let zeros: Vec<usize> = free
        .iter()
        .copied()
        .filter(|&j| is_zero(&lists.reference[j]))
        .collect();
    if zeros.is_empty() {
        return None;
    }
    free.retain(|j| !zeros.contains(j));
    let n = zeros.len();
    Some(Diagnosis::new(
        Code::MissingItem,
        if n == 1 {
            "the missing one is the zero mode: the system has a free motion (nothing pulls it back, so ω = 0), and this part lists 0 for it".to_string()
        } else {
            format!(
                "{n} zero modes are missing: the system has {n} free motions (ω = 0), and this part lists 0 once for each"
            )
        },
    ))
}

/// For a growth-rates part: an unmatched item that is the angular frequency of a mode that
/// oscillates at the equilibrium (at every sample point).
pub(super) fn oscillating_item(
    part: &Part,
    p: &mut Prepared,
    lists: &Lists,
    i: usize,
    label: &str,
) -> Option<Diagnosis> {
    if part.kind != PartKind::Frequencies || !part.growth {
        return None;
    }
    let at = equilibrium_of(p, part).ok()?;
    let at_vals = values(&p.system, &at, &p.points).ok()?;
    let mut checked = 0;
    for (k, (q0, item)) in at_vals.iter().zip(&lists.student[i]).enumerate() {
        let (Some(q0), Some(item)) = (q0, item) else {
            continue;
        };
        let params = p.points.params(&p.system, k).to_vec();
        let modes = p.system.modes_at(&p.derivation, &params, q0).ok()?;
        let scale = modes.frequencies.iter().fold(0.0f64, |a, w| a.max(w.abs()));
        let hit = modes.frequencies.iter().any(|w| {
            *w != 0.0 && super::compare::close(item[0], *w, scale, part.tolerance.max(1e-7))
        });
        if !hit {
            return None;
        }
        checked += 1;
    }
    (checked > 0).then(|| {
        Diagnosis::new(
            Code::WrongItem,
            format!(
                "{label} is the angular frequency of a mode that oscillates about this equilibrium; this part asks for the growth rates λ (q ~ e^(λt)) of the modes that grow"
            ),
        )
    })
}

/// A growth-rates part's findings speak of rates, not frequencies.
pub(super) fn growth_wording(part: &Part, v: &mut Verdict) {
    if !part.growth {
        return;
    }
    for d in &mut v.diagnoses {
        d.message = d
            .message
            .replace("the square of a frequency", "the square of a growth rate")
            .replace("the frequency itself", "the rate itself")
            .replace("is a frequency, but", "is a growth rate, but")
            .replace("one frequency is missing", "one growth rate is missing")
            .replace("frequency values", "growth rates");
    }
}

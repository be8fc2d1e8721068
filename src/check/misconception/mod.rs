//! The mistakes the physics-education literature documents (issue 12): a wrong potential
//! geometry, a lost product- or chain-rule term, a conserved momentum substituted too early,
//! h taken as T + V, the wrong inertia in a frequency, roots lost by dividing, the wrong
//! expansion point and another sign convention.
//!
//! Sound by construction: each detector *generates* the wrong answer that exactly that mistake
//! produces, from the problem's own physics, and fires only when the student's answer equals it
//! at every sample point with the checker's tolerance. Where a problem lacks what a generator
//! needs (bodies, a gravity parameter, a cyclic coordinate), the detector stays silent.
//!
//! The hooks ([`expression`], [`equations`], [`condition`], [`list`]) run after the checker's own diagnosis of
//! a wrong answer; a literature diagnosis found replaces the generic `not-equal`.

mod condition;
mod energies;
mod frequencies;
mod motion;
mod numeric;
mod roots;

use super::prepare::Prepared;
use super::verdict::{Code, Diagnosis, Status, Verdict};
use crate::expr::Id;
use crate::problem::{Part, Problem};

/// Adds `found` to a wrong verdict, dropping the generic `not-equal` it makes redundant.
fn report(v: &mut Verdict, found: Option<Diagnosis>) {
    let Some(d) = found else { return };
    if v.status == Status::Correct {
        return;
    }
    if d.code == Code::Convention {
        // The answer is exactly the reference in another convention: the term-level guesses
        // (x and y swapped, a wrong factor) would misname it.
        v.diagnoses.clear();
    }
    v.diagnoses.retain(|x| x.code != Code::NotEqual);
    v.diagnoses.push(d);
}

/// Largest answer (in expression nodes) the detectors look at: students' answers have tens of
/// nodes; past this the story is not one documented slip, and the work stays bounded.
const MAX_ANSWER_NODES: usize = 2_000;

/// Whether the answer `ids` is small enough to search.
fn small(p: &Prepared, ids: &[Id]) -> bool {
    ids.iter()
        .map(|&i| p.system.pool.tree_size(i))
        .sum::<usize>()
        <= MAX_ANSWER_NODES
}

/// Hook for a wrong expression answer `s` (T, V, L, h, a momentum).
pub(crate) fn expression(part: &Part, p: &mut Prepared, s: Id, reference: Id, v: &mut Verdict) {
    if v.status == Status::Correct || !small(p, &[s]) {
        return;
    }
    let found = energies::diagnose(part, p, s, reference);
    report(v, found);
}

/// Hook for wrong equations of motion (`res` are the student's residuals).
pub(crate) fn equations(part: &Part, p: &mut Prepared, res: &[Id], v: &mut Verdict) {
    if v.status == Status::Correct || !small(p, res) {
        return;
    }
    let found = motion::diagnose(part, p, res);
    report(v, found);
}

/// Hook for a wrong condition without accelerations (an equation part such as an equilibrium
/// condition; `res` are the student's residuals).
pub(crate) fn condition(p: &mut Prepared, res: &[Id], v: &mut Verdict) {
    if v.status == Status::Correct || !small(p, res) {
        return;
    }
    let found = condition::lost_root(p, res);
    report(v, found);
}

/// Hook for a wrong list (frequencies, equilibria); `items` are the student's.
pub(crate) fn list(
    problem: &Problem,
    part: &Part,
    p: &mut Prepared,
    items: &[Vec<Id>],
    v: &mut Verdict,
) {
    let all: Vec<Id> = items.iter().flatten().copied().collect();
    if v.status == Status::Correct || !small(p, &all) {
        return;
    }
    let found = frequencies::diagnose(problem, part, p, items);
    report(v, found);
}

//! Verification of frequencies parts: for every parameter sample, the stated frequencies (or
//! their squares) against the eigen-solver's at the part's equilibrium.

use super::FindingCode;
use super::verify_failed::{Check, Failed, check_dimension};
use crate::check::compare::{close, parameter_text, values};
use crate::check::points::PointSet;
use crate::check::prepare::{Prepared, equilibrium_of, read_frequency};
use crate::check::tolerance;
use crate::expr::{Dimension, Id};
use crate::mechanics::modes::Modes;
use crate::mechanics::sample::seed_from;
use crate::problem::{Part, Problem};

/// Parameter samples for frequencies.
const FREQUENCY_SAMPLES: usize = 20;

pub(super) fn verify_frequencies(problem: &Problem, part: &Part, p: &mut Prepared) -> Check {
    let stated: Vec<Id> = part
        .answers
        .iter()
        .map(|a| read_frequency(p, a))
        .collect::<Result<_, _>>()?;
    let per_time = if part.squared {
        Dimension::new(0, 0, -2)
    } else {
        Dimension::new(0, 0, -1)
    };
    // A numeric part's numbers are dimensionless; their units were checked when the file was
    // read.
    for &s in stated.iter().filter(|_| part.units.is_none()) {
        check_dimension(problem, p, s, Some(per_time))?;
    }
    let at = equilibrium_of(p, part)?;
    let samples = PointSet::draw(
        &p.system,
        &p.assumptions,
        seed_from(&[&problem.id, &part.id, "frequencies"]),
        FREQUENCY_SAMPLES,
    )
    .map_err(|e| Failed::new(FindingCode::Sampling, e.to_string()))?;
    let mut roots = stated.clone();
    roots.extend(at.iter().copied());
    let vals = values(&p.system, &roots, &samples)
        .map_err(|e| Failed::new(FindingCode::Sampling, e.to_string()))?;
    for (k, v) in vals.iter().enumerate() {
        let Some(v) = v else { continue };
        let params = samples.params(&p.system, k).to_vec();
        let q0 = &v[stated.len()..];
        p.system
            .check_equilibrium(&p.derivation, &params, q0)
            .map_err(|e| Failed::new(FindingCode::NotAnEquilibrium, e.to_string()))?;
        let modes = p
            .system
            .modes_at(&p.derivation, &params, q0)
            .map_err(|e| Failed::new(FindingCode::Unusable, e.to_string()))?;
        let mut want = wanted(part, &modes);
        let mut got: Vec<f64> = v[..stated.len()].to_vec();
        crate::sort::sort_by(&mut want, f64::total_cmp);
        crate::sort::sort_by(&mut got, f64::total_cmp);
        let scale = want.iter().fold(0.0f64, |a, x| a.max(x.abs()));
        if want.len() != got.len()
            || !want
                .iter()
                .zip(&got)
                .all(|(a, b)| close(*a, *b, scale, part.tolerance.max(tolerance::EIGEN)))
        {
            let pstr = parameter_text(&p.system, &params);
            return Err(Failed::new(
                FindingCode::WrongFrequency,
                format!(
                    "for {pstr} the stated {} are {got:.6?}, the eigen-solver gives {want:.6?}{}",
                    if part.growth {
                        "growth rates"
                    } else {
                        "frequencies"
                    },
                    why_differ(part, &modes, &got)
                ),
            ));
        }
    }
    Ok(())
}

/// What the part lists from the engine's modes: the frequencies (without the zero modes
/// where the part omits them) or the growth rates, or their squares.
fn wanted(part: &Part, modes: &Modes) -> Vec<f64> {
    let base: Vec<f64> = if part.growth {
        modes.growth_rates.clone()
    } else if part.omit_zero_modes {
        modes
            .frequencies
            .iter()
            .copied()
            .filter(|w| *w != 0.0)
            .collect()
    } else {
        modes.frequencies.clone()
    };
    if part.squared {
        base.iter().map(|w| w * w).collect()
    } else {
        base
    }
}

/// What the engine's list holds beside the undamped frequencies, when the stated list may
/// have left it out: ω = 0 for free motions, damped or growing modes.
fn why_differ(part: &Part, modes: &Modes, got: &[f64]) -> String {
    let zeros = modes.frequencies.iter().filter(|w| **w == 0.0).count();
    let stated_zeros = got.iter().filter(|w| **w == 0.0).count();
    let mut notes = Vec::new();
    if part.growth {
        if modes.growth_rates.is_empty() {
            notes.push(
                "nothing grows there: the equilibrium is not unstable, so it has no growth rates"
                    .to_string(),
            );
        }
        if stated_zeros > 0 {
            notes.push("a free motion (ω = 0) is not a growth rate".to_string());
        }
    } else if part.omit_zero_modes {
        if stated_zeros > 0 {
            notes.push(
                "the part omits the zero modes (`omit_zero_modes`): do not list 0".to_string(),
            );
        }
    } else if zeros != stated_zeros {
        notes.push(format!(
            "the system has {zeros} free motion(s) (ω = 0): list 0 once for each"
        ));
    }
    if !modes.damped.is_empty() || !modes.decay_rates.is_empty() {
        notes.push("damped modes are not undamped frequencies".to_string());
    }
    if !modes.growth_rates.is_empty() && !part.growth {
        notes.push(format!(
            "{} mode(s) grow instead of oscillating",
            modes.growth_rates.len()
        ));
    }
    if notes.is_empty() {
        String::new()
    } else {
        format!(" ({})", notes.join("; "))
    }
}

//! The `steady` option of [`modes()`](super::modes()): reduces the system by the cyclic
//! coordinates whose momenta are fixed (the Routhian), so that the equilibria found are the
//! steady motions and the modes the small oscillations about them.

use serde::Serialize;

use rustc_hash::FxHashMap;

use super::Formula;
use crate::expr::{Id, Sym};
use crate::mechanics::System;
use crate::mechanics::steady::SteadyError;

/// What a steady-motion analysis adds to the modes report.
#[derive(Clone, Debug, Serialize)]
pub struct SteadyNote {
    /// The fixed momenta, `p_phi = value`, as given.
    pub(crate) momenta: Vec<(String, String)>,
    /// The Routhian R = L − Σ p φ', the Lagrangian of the coordinates that stay put.
    pub(crate) routhian: Formula,
    /// Each cyclic velocity at the fixed momenta, `phi'` and its expression.
    pub(crate) rates: Vec<(String, Formula)>,
    /// The same expressions, in the reduced system's pool.
    #[serde(skip)]
    rate_ids: Vec<Id>,
}

/// The coordinates named by `p_<coordinate>` keys, each once.
fn cyclic_names(momenta: &[(String, String)]) -> Result<Vec<String>, SteadyError> {
    let mut names: Vec<String> = Vec::with_capacity(momenta.len());
    for (k, _) in momenta {
        let k = k.trim();
        let name = k
            .strip_prefix("p_")
            .ok_or_else(|| SteadyError::NotMomentum { key: k.to_string() })?;
        if names.iter().any(|n| n == name) {
            return Err(SteadyError::GivenTwice { key: k.to_string() });
        }
        names.push(name.to_string());
    }
    Ok(names)
}

/// The Routhian system for the fixed `momenta` (none: the system itself, no note).
pub(super) fn reduce(
    sys: System,
    momenta: &[(String, String)],
) -> Result<(System, Option<SteadyNote>), SteadyError> {
    if momenta.is_empty() {
        return Ok((sys, None));
    }
    let names = cyclic_names(momenta)?;
    let mut full = sys;
    let d = full.derive()?;
    let reduced = full.routhian(&d, &names)?;
    let pool = &reduced.system.pool;
    let note = SteadyNote {
        momenta: momenta.to_vec(),
        routhian: Formula::new(pool, reduced.system.lagrangian),
        rates: reduced
            .cyclic
            .iter()
            .zip(&reduced.rates)
            .map(|(n, &r)| (format!("{n}'"), Formula::new(pool, r)))
            .collect(),
        rate_ids: reduced.rates.clone(),
    };
    Ok((reduced.system, Some(note)))
}

impl SteadyNote {
    /// The heading lines: what is fixed, the Routhian and the cyclic velocities.
    pub(super) fn write_text(
        &self,
        style: crate::expr::Style,
        paint: &dyn super::Paint,
        o: &mut String,
    ) -> std::fmt::Result {
        use std::fmt::Write as _;
        let fixed: Vec<String> = self
            .momenta
            .iter()
            .map(|(k, v)| format!("{} = {}", k.trim(), v.trim()))
            .collect();
        writeln!(
            o,
            "{} {} fixed; equilibria of the Routhian R = {} are the steady motions",
            paint.heading("steady motions:"),
            fixed.join(", "),
            self.routhian.get(style)
        )?;
        for (name, rate) in &self.rates {
            writeln!(o, "  {name} = {}", rate.get(style))?;
        }
        Ok(())
    }
}

/// The cyclic velocities in the steady motion at each point `q` (coordinates of the reduced
/// system), with the parameter `values` substituted; a rate that cannot be evaluated there
/// is left out.
pub(super) fn rates_at(
    note: &SteadyNote,
    sys: &mut System,
    values: &FxHashMap<(Sym, u8), Id>,
    points: &[Vec<f64>],
) -> Vec<Vec<(String, f64)>> {
    let ids: Vec<Id> = note
        .rate_ids
        .iter()
        .map(|&r| sys.pool.substitute(r, values))
        .collect();
    let Ok(program) = sys.compile(&ids) else {
        return vec![Vec::new(); points.len()];
    };
    let layout = sys.state_layout();
    let params = vec![0.0; sys.parameters.len()];
    points
        .iter()
        .map(|q| match program.eval(&layout.at_rest(q, &params)) {
            Ok(v) => note
                .rates
                .iter()
                .map(|(n, _)| n.clone())
                .zip(v)
                .filter(|(_, x)| x.is_finite())
                .collect(),
            Err(_) => Vec::new(),
        })
        .collect()
}

//! A problem's simulation defaults: the parameters' `value`s and the `[simulation]` table
//! (initial state, end time), checked against the system so that `lagrange simulate PROBLEM`
//! never starts from a name that is not there or a number that cannot be used.

use crate::mechanics::System;
use crate::problem::SimulationDefaults;

use super::FindingCode;
use super::build_reader::Builder;
use super::finding::{Finding, line_of};
use super::schema::ProblemFile;

impl Builder<'_> {
    /// The defaults, or a finding at the `[simulation]` table (or the id line for a value).
    pub(super) fn simulation(
        &self,
        pf: &ProblemFile,
        sys: &System,
    ) -> Result<SimulationDefaults, Finding> {
        let mut params = Vec::new();
        for p in &sys.parameters {
            let spec = pf
                .parameters
                .iter()
                .find(|(name, _)| crate::expr::names::normalize(name) == p.name);
            if let Some(v) = spec.and_then(|(_, s)| s.value) {
                if !v.is_finite() {
                    let message =
                        format!("parameter `{}`: value {v} is not a finite number", p.name);
                    return Err(self.fail(self.id_line, FindingCode::BadSimulation, message));
                }
                params.push((p.name.clone(), v));
            }
        }
        let Some(spec) = &pf.simulation else {
            return Ok(SimulationDefaults {
                params,
                ..SimulationDefaults::default()
            });
        };
        let line = line_of(self.text, spec.span().start);
        let fail = |message: String| self.fail(line, FindingCode::BadSimulation, message);
        let spec = spec.get_ref();
        let mut init = Vec::new();
        for (name, &v) in &spec.init {
            let normal = crate::expr::names::normalize(name);
            let base = normal.trim_end_matches('\'');
            let order = normal.len() - base.len();
            if order > 1 || !sys.coordinates.iter().any(|c| c.name == base) {
                let known = (sys.coordinates.iter())
                    .map(|c| format!("{0}, {0}'", c.name))
                    .collect::<Vec<_>>()
                    .join(", ");
                return Err(fail(format!(
                    "simulation.init: `{name}` is not a coordinate or velocity (they are {known})"
                )));
            }
            if !v.is_finite() {
                return Err(fail(format!(
                    "simulation.init: `{name}` = {v} is not finite"
                )));
            }
            init.push((normal, v));
        }
        if let Some(t) = spec.t_end
            && !(t.is_finite() && t > 0.0)
        {
            return Err(fail(format!("simulation.t_end must be positive, not {t}")));
        }
        Ok(SimulationDefaults {
            params,
            init,
            t_end: spec.t_end,
        })
    }
}

//! The phase-portrait family of a one-degree-of-freedom system (`simulate --portrait N`): the
//! setup shared with a single run (options, parameters, the compiled equations), then
//! [`crate::simulate::portrait`].

use super::simulation::{SimulationError, SimulationOptions, check_options, motion_parameters};
use crate::mechanics::System;
use crate::simulate::Rhs;
use crate::simulate::portrait::{Coordinate1, FamilySpec, Portrait, PortraitError};

/// The phase-portrait family of `sys` (one degree of freedom, conserved h) at `count`
/// energies with `opts`' parameters, tolerances, end time and samples: see
/// [`crate::simulate::portrait`] for the choices (start at V's minimum, energies up to 1.8 ×
/// the highest barrier with the separatrix, one period per curve).
pub fn portrait_family(
    sys: &mut System,
    opts: &SimulationOptions,
    count: usize,
) -> Result<Portrait, SimulationError> {
    check_options(opts)?;
    let params = motion_parameters(sys, &opts.params);
    let mut rhs = Rhs::new(sys, &params)?;
    let c = sys
        .coordinates
        .first()
        .ok_or(PortraitError::Dimension { n: 0 })?;
    let coordinate = Coordinate1 {
        name: c.name.clone(),
        range: c.range,
        periodic: c.periodic,
    };
    let spec = FamilySpec {
        count,
        t_end: opts.t_end,
        rtol: opts.rtol,
        atol: opts.atol,
        samples: opts.samples,
    };
    Ok(crate::simulate::portrait::portrait(
        &mut rhs,
        &coordinate,
        &spec,
    )?)
}

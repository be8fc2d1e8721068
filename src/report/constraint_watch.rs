//! Constraints along a simulated motion. The integrator keeps only their second time
//! derivative zero (A q'' = −r), so a motion started off a constraint stays off it: the start
//! is checked first. Along the way the holonomic constraints' residual |f(q, t)| is watched
//! on the output grid, as a check on the numerics beside the energy.

use crate::expr::Program;
use crate::mechanics::constraints::ConstraintLevel;
use crate::mechanics::{ConstraintKind, Layout, System};

use crate::mechanics::MechError;

/// A start off a constraint: its number (from 1), text, level and residual.
pub(super) struct Off {
    pub(crate) index: usize,
    pub(crate) text: String,
    pub(crate) level: &'static str,
    pub(crate) residual: f64,
}

/// The holonomic constraints compiled at fixed parameter values.
pub(super) struct ConstraintWatch {
    program: Program,
    count: usize,
    layout: Layout,
    point: Vec<f64>,
    scratch: Vec<f64>,
}

/// The sample point of the standard layout at `(t, y)` with the parameters at `values`.
fn point(layout: Layout, values: &[f64], t: f64, y: &[f64]) -> Vec<f64> {
    let mut x = vec![0.0; layout.params_start()];
    x.extend_from_slice(values);
    layout.load_phase(t, y, &mut x);
    x
}

/// The constraint an initial state is off (positions first, then velocities), if any.
pub(super) fn off_constraint(
    sys: &mut System,
    values: &[f64],
    y0: &[f64],
) -> Result<Option<Off>, MechError> {
    if sys.constraints.is_empty() {
        return Ok(None);
    }
    let x = point(sys.state_layout(), values, 0.0, y0);
    Ok(sys.constraint_violation(&x)?.map(|v| Off {
        index: v.index + 1,
        text: sys.pool.plain(sys.constraints[v.index].expr),
        level: match v.level {
            ConstraintLevel::Position => "positions",
            ConstraintLevel::Velocity => "velocities",
        },
        residual: v.residual,
    }))
}

impl ConstraintWatch {
    /// `None` when the system has no holonomic constraint to watch.
    pub(super) fn new(sys: &System, values: &[f64]) -> Result<Option<ConstraintWatch>, MechError> {
        let roots: Vec<_> = (sys.constraints.iter())
            .filter(|c| c.kind == ConstraintKind::Holonomic)
            .map(|c| c.expr)
            .collect();
        if roots.is_empty() {
            return Ok(None);
        }
        let program = sys.compile(&roots)?;
        let layout = sys.state_layout();
        let point = point(layout, values, 0.0, &vec![0.0; 2 * sys.n()]);
        Ok(Some(ConstraintWatch {
            scratch: program.scratch(),
            program,
            count: roots.len(),
            layout,
            point,
        }))
    }

    /// The largest |f(q, t)| over the holonomic constraints at `(t, y)`; infinite where a
    /// constraint cannot be evaluated.
    pub(super) fn residual(&mut self, t: f64, y: &[f64]) -> f64 {
        self.layout.load_phase(t, y, &mut self.point);
        if self.program.run(&self.point, &mut self.scratch).is_err() {
            return f64::INFINITY;
        }
        (0..self.count)
            .map(|k| self.program.output(k, &self.scratch).abs())
            .fold(0.0, f64::max)
    }
}

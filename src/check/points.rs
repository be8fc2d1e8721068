//! Sample points for a system: random states (t, q, q', q'') and parameter values drawn in
//! their ranges, redrawn until every assumption holds (`2*g*a > omega^2`).

use super::error::CheckError;
use crate::expr::{Id, Program};
use crate::mechanics::System;
use crate::mechanics::sample::Sampler;
use crate::problem::Assumption;

/// Points in a system's standard layout, every one satisfying the assumptions.
#[derive(Clone, Debug)]
pub struct PointSet {
    pub points: Vec<Vec<f64>>,
}

/// How many draws may be rejected before the assumptions are declared unsatisfiable.
const MAX_DRAWS: usize = 10_000;

impl PointSet {
    /// `count` points from `seed`. Fails when the assumptions reject (nearly) every draw.
    pub fn draw(
        sys: &System,
        assumptions: &[Assumption],
        seed: u64,
        count: usize,
    ) -> Result<PointSet, CheckError> {
        Self::draw_defined(sys, assumptions, &[], seed, count)
    }

    /// Like [`draw`](Self::draw), but a point where any of `defined` is undefined (the
    /// reference answer, say) is redrawn.
    pub fn draw_defined(
        sys: &System,
        assumptions: &[Assumption],
        defined: &[Id],
        seed: u64,
        count: usize,
    ) -> Result<PointSet, CheckError> {
        let must: Option<Program> = if defined.is_empty() {
            None
        } else {
            Some(
                sys.compile(defined)
                    .map_err(|error| CheckError::Compile { error })?,
            )
        };
        let roots: Vec<Id> = assumptions.iter().flat_map(|a| [a.lhs, a.rhs]).collect();
        let prog: Option<Program> = if roots.is_empty() {
            None
        } else {
            Some(
                sys.compile(&roots)
                    .map_err(|error| CheckError::Compile { error })?,
            )
        };
        let mut sampler = Sampler::new(seed);
        let mut points = Vec::with_capacity(count);
        let mut draws = 0;
        while points.len() < count {
            draws += 1;
            if draws > MAX_DRAWS {
                return Err(CheckError::Unsatisfiable {
                    assumptions: assumptions
                        .iter()
                        .map(|a| a.text.as_str())
                        .collect::<Vec<_>>()
                        .join(", "),
                });
            }
            let x = sys.sample_point(&mut sampler);
            if let Some(p) = &prog {
                let Ok(v) = p.eval(&x) else { continue };
                let ok = assumptions.iter().enumerate().all(|(i, a)| {
                    if a.greater {
                        v[2 * i] > v[2 * i + 1]
                    } else {
                        v[2 * i] < v[2 * i + 1]
                    }
                });
                if !ok {
                    continue;
                }
            }
            if let Some(m) = &must
                && m.eval(&x).is_err()
            {
                continue;
            }
            points.push(x);
        }
        Ok(PointSet { points })
    }

    /// The parameter values of point `k` (the tail of the layout).
    pub fn params<'a>(&'a self, sys: &System, k: usize) -> &'a [f64] {
        let start = sys.state_layout().params_start();
        &self.points[k][start..]
    }
}

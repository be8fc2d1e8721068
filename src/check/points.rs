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
    pub(crate) points: Vec<Vec<f64>>,
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
    /// reference answer, say) is redrawn; and a further [`WIDE_SHARE`] of points is drawn far
    /// outside the nominal ranges ([`wide_point`]), since an answer must hold for every angle
    /// and every parameter value the assumptions allow, not only inside the sampled box.
    pub fn draw_defined(
        sys: &System,
        assumptions: &[Assumption],
        defined: &[Id],
        seed: u64,
        count: usize,
    ) -> Result<PointSet, CheckError> {
        let filter = Filter::new(sys, assumptions, defined)?;
        let mut sampler = Sampler::new(seed);
        let mut points = Vec::with_capacity(count + count / WIDE_SHARE);
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
            if filter.accepts(&x) {
                points.push(x);
            }
        }
        if defined.is_empty() {
            return Ok(PointSet { points });
        }
        // A separate stream, so the nominal points are the ones every earlier version drew.
        let mut wide = Sampler::new(seed ^ WIDE_SEED);
        let want = points.len() + count / WIDE_SHARE;
        for _ in 0..MAX_DRAWS {
            if points.len() >= want {
                break;
            }
            let x = wide_point(sys, &mut wide, points.len() % 2 == 0);
            if filter.accepts(&x) {
                points.push(x);
            }
        }
        Ok(PointSet { points })
    }

    /// The parameter values of point `k` (the tail of the layout).
    pub fn params<'a>(&'a self, sys: &System, k: usize) -> &'a [f64] {
        let start = sys.state_layout().params_start();
        &self.points[k][start..]
    }
}

/// One point in [`WIDE_SHARE`] is drawn far outside the nominal ranges.
pub(crate) const WIDE_SHARE: usize = 3;

/// Mixed into the seed of the wide points' stream.
const WIDE_SEED: u64 = 0x9e37_79b9_7f4a_7c15;

/// How far beyond its nominal range a wide point may take a non-periodic coordinate (in
/// half-widths of the range) or a parameter (as a factor either way).
const WIDEN: f64 = 10.0;

/// The parameters of a free wide point range over [1/FREE_SCALE, FREE_SCALE].
const FREE_SCALE: f64 = 100.0;

/// A point far outside the nominal box: angles anywhere in [−4π, 4π], other coordinates up to
/// [`WIDEN`] half-widths from the middle of their range. Parameters are log-uniform from
/// 1/[`WIDEN`] of their least to [`WIDEN`] times their greatest value, or, for a `free` point,
/// over [1/[`FREE_SCALE`], [`FREE_SCALE`]] whatever their range. A right answer is an identity
/// in the parameters (under the assumptions), so it holds there too; and a term that is
/// negligible at the problem's scale (m·g next to k·x for an electron on a spring, 1e-30 of
/// it) becomes comparable to the others there, so getting it wrong is seen. Velocities,
/// accelerations and time are drawn as usual.
pub(crate) fn wide_point(sys: &System, s: &mut Sampler, free: bool) -> Vec<f64> {
    let layout = sys.state_layout();
    let mut x = sys.sample_point(s);
    for (i, c) in sys.coordinates.iter().enumerate() {
        x[layout.q(i)] = if c.periodic {
            s.uniform(-4.0 * std::f64::consts::PI, 4.0 * std::f64::consts::PI)
        } else {
            let (lo, hi) = c.range;
            let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            s.uniform(mid - WIDEN * half, mid + WIDEN * half)
        };
    }
    for (j, p) in sys.parameters.iter().enumerate() {
        let (lo, hi) = p.range;
        // A parameter pinned to one value (a student's variant: `Problem::pinned`) keeps it:
        // the student's numbers are those of that value alone.
        if lo > 0.0 && hi > lo {
            let (lo, hi) = if free {
                (1.0 / FREE_SCALE, FREE_SCALE)
            } else {
                (lo / WIDEN, hi * WIDEN)
            };
            x[layout.param(j)] = s.uniform(lo.ln(), hi.ln()).exp();
        }
    }
    x
}

/// The tests a drawn point must pass: every assumption holds, and every expression that must
/// be defined is.
pub(crate) struct Filter {
    assumptions: Vec<bool>,
    assumed: Option<Program>,
    must: Option<Program>,
    /// The domain's ends: the slot of the value, whether the end is a lower one, and the
    /// end — a number, or output k of `ends` (the ends that depend on parameters).
    domain: Vec<(usize, bool, End)>,
    ends: Option<Program>,
}

/// One end of a domain: most are numbers (r > 0), checked without running a program.
#[derive(Clone, Copy, Debug)]
enum End {
    Number(f64),
    Output(usize),
}

impl Filter {
    /// The tests for `assumptions` and for `defined` being defined.
    pub(crate) fn new(
        sys: &System,
        assumptions: &[Assumption],
        defined: &[Id],
    ) -> Result<Filter, CheckError> {
        let compile = |ids: &[Id]| -> Result<Option<Program>, CheckError> {
            if ids.is_empty() {
                return Ok(None);
            }
            sys.compile(ids)
                .map(Some)
                .map_err(|error| CheckError::Compile { error })
        };
        let roots: Vec<Id> = assumptions.iter().flat_map(|a| [a.lhs, a.rhs]).collect();
        let mut end_ids: Vec<Id> = Vec::new();
        let mut domain = Vec::new();
        for (slot, e, lower) in sys.domain_ends() {
            let end = match sys.pool.number_value(e) {
                Some(v) => End::Number(v),
                None => {
                    end_ids.push(e);
                    End::Output(end_ids.len() - 1)
                }
            };
            domain.push((slot, lower, end));
        }
        Ok(Filter {
            assumptions: assumptions.iter().map(|a| a.greater).collect(),
            assumed: compile(&roots)?,
            must: compile(defined)?,
            domain,
            ends: compile(&end_ids)?,
        })
    }

    /// Whether point `x` passes.
    pub(crate) fn accepts(&self, x: &[f64]) -> bool {
        if !self.domain.is_empty() {
            let values = match &self.ends {
                Some(p) => match p.eval(x) {
                    Ok(v) => v,
                    Err(_) => return false,
                },
                None => Vec::new(),
            };
            let inside = self.domain.iter().all(|&(slot, lower, end)| {
                let end = match end {
                    End::Number(v) => v,
                    End::Output(k) => values[k],
                };
                if lower { x[slot] > end } else { x[slot] < end }
            });
            if !inside {
                return false;
            }
        }
        if let Some(p) = &self.assumed {
            let Ok(v) = p.eval(x) else { return false };
            let ok = self.assumptions.iter().enumerate().all(|(i, &greater)| {
                if greater {
                    v[2 * i] > v[2 * i + 1]
                } else {
                    v[2 * i] < v[2 * i + 1]
                }
            });
            if !ok {
                return false;
            }
        }
        self.must.as_ref().is_none_or(|m| m.eval(x).is_ok())
    }
}

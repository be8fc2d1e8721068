//! det C at a point: the answer's acceleration coefficients A over the mass matrix M (or, for
//! one equation of several coordinates, its projection on the reference equation), compiled
//! once and evaluated into reused buffers.

use crate::check::prepare::Prepared;
use crate::expr::{Id, Program};

/// What det C is at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Det {
    /// The reference does not determine the accelerations here either (M singular or
    /// undefined): nothing to judge.
    Skip,
    /// The answer is undefined where the reference is defined.
    Undefined,
    Value(f64),
}

/// det C at any point: the answer's acceleration coefficients A and the mass matrix M, each
/// compiled once and evaluated into reused buffers (this runs a few hundred times a check).
pub(super) struct DetC {
    a: Program,
    m: Option<Program>,
    n: usize,
    /// One equation of a system with several coordinates: `m` holds the reference
    /// equation's acceleration row r, and the factor is a·r / r·r (the answer must be the
    /// reference times a factor that vanishes nowhere).
    projection: bool,
    scratch: std::cell::RefCell<(Vec<f64>, Vec<f64>)>,
}

impl DetC {
    pub(super) fn new(p: &mut Prepared, res: &[Id]) -> Option<DetC> {
        let coords = p.system.coordinate_syms();
        let n = coords.len();
        let mut roots: Vec<Id> = Vec::new();
        for &r in res {
            for &c in &coords {
                roots.push(p.system.pool.diff(r, c, 2));
            }
        }
        let a = p.system.compile(&roots).ok()?;
        // Divide by det M (without constraints); with constraints A alone is judged.
        let m = if p.system.constraints.is_empty() {
            let entries: Vec<Id> = p.derivation.mass.iter().flatten().copied().collect();
            Some(p.system.compile(&entries).ok()?)
        } else {
            None
        };
        let scratch = (
            a.scratch(),
            m.as_ref().map_or_else(Vec::new, Program::scratch),
        );
        Some(DetC {
            a,
            m,
            n,
            projection: false,
            scratch: std::cell::RefCell::new(scratch),
        })
    }

    /// For one equation `r` of a system with several coordinates, against the reference
    /// equation `reference`.
    pub(super) fn projection(p: &mut Prepared, r: Id, reference: Id) -> Option<DetC> {
        let coords = p.system.coordinate_syms();
        let row = |p: &mut Prepared, e: Id| -> Vec<Id> {
            coords
                .iter()
                .map(|&c| p.system.pool.diff(e, c, 2))
                .collect()
        };
        let (ra, rr) = (row(p, r), row(p, reference));
        let a = p.system.compile(&ra).ok()?;
        let m = p.system.compile(&rr).ok()?;
        let scratch = (a.scratch(), m.scratch());
        Some(DetC {
            a,
            m: Some(m),
            n: coords.len(),
            projection: true,
            scratch: std::cell::RefCell::new(scratch),
        })
    }

    /// a·r / r·r at `x` (projection mode).
    fn ratio_at(&self, x: &[f64], m: &Program, sa: &mut [f64], sm: &mut [f64]) -> Det {
        if m.run(x, sm).is_err() {
            return Det::Skip;
        }
        let rr: f64 = (0..self.n).map(|j| m.output(j, sm).powi(2)).sum();
        if !rr.is_finite() || rr == 0.0 {
            return Det::Skip;
        }
        if self.a.run(x, sa).is_err() {
            return Det::Undefined;
        }
        let ar: f64 = (0..self.n)
            .map(|j| self.a.output(j, sa) * m.output(j, sm))
            .sum();
        let d = ar / rr;
        if d.is_finite() {
            Det::Value(d)
        } else {
            Det::Undefined
        }
    }

    pub(super) fn at(&self, x: &[f64]) -> Det {
        let n = self.n;
        let mut guard = self.scratch.borrow_mut();
        let (sa, sm) = &mut *guard;
        if let (true, Some(m)) = (self.projection, &self.m) {
            return self.ratio_at(x, m, sa, sm);
        }
        // The reference first: where M is undefined or singular it does not determine the
        // accelerations either, and there is nothing to judge.
        let det_m = match &self.m {
            Some(m) => {
                if m.run(x, sm).is_err() {
                    return Det::Skip;
                }
                det(n, |i, j| m.output(i * n + j, sm))
            }
            None => 1.0,
        };
        if !det_m.is_finite() || det_m == 0.0 {
            return Det::Skip;
        }
        if self.a.run(x, sa).is_err() {
            return Det::Undefined;
        }
        let d = det(n, |i, j| self.a.output(i * n + j, sa)) / det_m;
        if d.is_finite() {
            Det::Value(d)
        } else {
            Det::Undefined
        }
    }
}

/// The determinant of the n×n matrix with entries `e(i, j)`: by formula up to 3×3 (no
/// allocation), by LU beyond.
fn det(n: usize, e: impl Fn(usize, usize) -> f64) -> f64 {
    match n {
        1 => e(0, 0),
        2 => e(0, 0) * e(1, 1) - e(0, 1) * e(1, 0),
        3 => {
            e(0, 0) * (e(1, 1) * e(2, 2) - e(1, 2) * e(2, 1))
                - e(0, 1) * (e(1, 0) * e(2, 2) - e(1, 2) * e(2, 0))
                + e(0, 2) * (e(1, 0) * e(2, 1) - e(1, 1) * e(2, 0))
        }
        _ => nalgebra::DMatrix::from_fn(n, n, e).determinant(),
    }
}

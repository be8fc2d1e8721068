//! det C at a point, and what the physics is there: the answer's acceleration coefficients A
//! over the mass matrix M (or, for one equation of several coordinates, its projection on the
//! reference equation), compiled once and evaluated into reused buffers.
//!
//! The yardstick is the physics' own. Where M is not finite, or the true equations are not
//! (the force k/r² at r = 0), nothing is judged. Where M is singular (r = 0 in polar
//! coordinates, sin θ = 0 for a spherical pendulum's φ) the answer is judged direction by
//! direction: its A must keep at least M's rank. Elsewhere det C = det A / det M must not
//! vanish, and A must be finite.

use std::cell::RefCell;

use crate::check::prepare::Prepared;
use crate::expr::{Id, Program};

/// A singular value below this fraction of the matrix's typical size is zero.
const RANK_ZERO: f64 = 1e-8;
/// A value of M or of the true equations beyond this many times its typical size is a
/// singularity of the physics (the force k/r² as r → 0), not a place to judge the answer.
const BLOW_UP: f64 = 1e8;
/// How many sample states give the typical sizes at a point's parameter values.
const TYPICAL_STATES: usize = 5;

/// What det C is at one point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum Det {
    /// Outside what is judged: M or the true equations are not finite (or blow up) here.
    Skip,
    /// The answer is not finite where the physics determines every acceleration.
    Undefined,
    /// det C, where M is regular.
    Value(f64),
    /// M is singular here; `deficient` when the answer's A has a lower rank than M (it stops
    /// determining an acceleration the physics still determines).
    Singular { deficient: bool },
}

/// Typical sizes at one set of parameter values: of M (or the reference row), of A and of
/// the true equations (det C's is [`DetC::typical_det`]).
#[derive(Clone, Copy, Debug)]
pub(super) struct Typical {
    m: f64,
    a: f64,
    equations: f64,
}

/// det C at any point: the answer's acceleration coefficients A, the mass matrix M and the
/// true equations, each compiled once and evaluated into reused buffers (this runs a few
/// hundred times a check).
pub(super) struct DetC<'p> {
    a: Program,
    m: Option<Program>,
    /// The true equations (all of them, or the one reference equation in projection mode),
    /// compiled from the prepared system when the careful test first needs them.
    prepared: &'p Prepared,
    equation_ids: Vec<Id>,
    equations: std::cell::OnceCell<Option<Program>>,
    n: usize,
    /// One equation of a system with several coordinates: `m` holds the reference
    /// equation's acceleration row r, and the factor is a·r / r·r (the answer must be the
    /// reference times a factor that vanishes nowhere).
    projection: bool,
    /// Where the parameters start in a point, and the sample states typical sizes use.
    params_start: usize,
    states: Vec<Vec<f64>>,
    scratch: RefCell<Scratch>,
    /// Typical sizes by parameter values (a line scan in a parameter needs a few dozen).
    typical: RefCell<Vec<(Vec<f64>, Typical)>>,
    /// det C's typical size by parameter values, computed on the fast path alone: the only
    /// size a zero test needs, so a small but regular value is settled without the rest.
    typical_det: RefCell<Vec<(Vec<f64>, f64)>>,
}

struct Scratch {
    a: Vec<f64>,
    m: Vec<f64>,
    e: Vec<f64>,
}

impl Scratch {
    /// det A / det M (or a·r / r·r) from the programs' outputs in place, without copying
    /// them out (this is the hot path of the search).
    fn det_c(&self, c: &DetC<'_>) -> Option<f64> {
        let n = c.n;
        let a = |k: usize| c.a.output(k, &self.a);
        let m = |k: usize| match &c.m {
            Some(m) => m.output(k, &self.m),
            None => f64::from(u8::from(k / n == k % n)),
        };
        let d = if c.projection {
            let rr: f64 = (0..n).map(|k| m(k) * m(k)).sum();
            let ar: f64 = (0..n).map(|k| a(k) * m(k)).sum();
            ar / rr
        } else {
            det(n, |i, j| a(i * n + j)) / det(n, |i, j| m(i * n + j))
        };
        d.is_finite().then_some(d)
    }
}

/// One evaluation: M (or r) and A as matrices, or why they are not there.
enum Raw {
    Skip,
    /// M and the equations are finite; A is not.
    AnswerUndefined {
        m: Vec<f64>,
    },
    Both {
        m: Vec<f64>,
        a: Vec<f64>,
        equations: f64,
    },
}

impl<'p> DetC<'p> {
    pub(super) fn new(p: &'p mut Prepared, res: &[Id]) -> Option<DetC<'p>> {
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
        let equations = p.derivation.equations();
        let p: &'p Prepared = p;
        Some(Self::assemble(p, a, m, equations, n, false))
    }

    /// For one equation `r` of a system with several coordinates, against the reference
    /// equation `reference`.
    pub(super) fn projection(p: &'p mut Prepared, r: Id, reference: Id) -> Option<DetC<'p>> {
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
        let p: &'p Prepared = p;
        Some(Self::assemble(
            p,
            a,
            Some(m),
            vec![reference],
            coords.len(),
            true,
        ))
    }

    fn assemble(
        p: &'p Prepared,
        a: Program,
        m: Option<Program>,
        equation_ids: Vec<Id>,
        n: usize,
        projection: bool,
    ) -> DetC<'p> {
        let scratch = Scratch {
            a: a.scratch(),
            m: m.as_ref().map_or_else(Vec::new, Program::scratch),
            e: Vec::new(),
        };
        DetC {
            a,
            m,
            prepared: p,
            equation_ids,
            equations: std::cell::OnceCell::new(),
            n,
            projection,
            params_start: p.system.state_layout().params_start(),
            states: p
                .points
                .points
                .iter()
                .take(TYPICAL_STATES)
                .cloned()
                .collect(),
            scratch: RefCell::new(scratch),
            typical: RefCell::new(Vec::new()),
            typical_det: RefCell::new(Vec::new()),
        }
    }

    /// The prepared part this search reads.
    pub(super) fn prepared(&self) -> &'p Prepared {
        self.prepared
    }

    /// M (or the reference row) and A at `x`, with the size of the true equations when
    /// `sized` (only the careful test needs it; the equations cost more than M and A).
    fn raw(&self, x: &[f64], sized: bool) -> Raw {
        let mut guard = self.scratch.borrow_mut();
        let s = &mut *guard;
        let rows = if self.projection { 1 } else { self.n };
        let mut equations = 0.0;
        if sized {
            let Some(program) = self
                .equations
                .get_or_init(|| self.prepared.system.compile(&self.equation_ids).ok())
            else {
                return Raw::Skip;
            };
            if s.e.len() < program.len() {
                s.e = program.scratch();
            }
            if program.run(x, &mut s.e).is_err() {
                return Raw::Skip;
            }
            equations = (0..rows)
                .map(|i| program.output(i, &s.e).abs())
                .fold(0.0, f64::max);
        }
        let m = match &self.m {
            Some(m) => {
                if m.run(x, &mut s.m).is_err() {
                    return Raw::Skip;
                }
                (0..rows * self.n).map(|k| m.output(k, &s.m)).collect()
            }
            // With constraints A alone is judged: M counts as the identity.
            None => identity(self.n),
        };
        if self.a.run(x, &mut s.a).is_err() {
            return Raw::AnswerUndefined { m };
        }
        let a = (0..rows * self.n).map(|k| self.a.output(k, &s.a)).collect();
        Raw::Both { m, a, equations }
    }

    /// Typical sizes at `x`'s parameter values: medians over a few sample states given those
    /// values. Medians, so that one state near a pole cannot set the scale.
    pub(super) fn typical(&self, x: &[f64]) -> Option<Typical> {
        let params = &x[self.params_start..];
        if let Some((_, t)) = self.typical.borrow().iter().find(|(p, _)| p == params) {
            return Some(*t);
        }
        let (mut ms, mut as_, mut es) = (vec![], vec![], vec![]);
        for state in &self.states {
            let mut y = state.clone();
            y[self.params_start..].copy_from_slice(params);
            if let Raw::Both { m, a, equations } = self.raw(&y, true) {
                ms.push(norm(&m));
                as_.push(norm(&a));
                es.push(equations);
            }
        }
        let t = Typical {
            m: median(ms)?,
            a: median(as_).unwrap_or(0.0),
            equations: median(es).unwrap_or(0.0),
        };
        let mut cache = self.typical.borrow_mut();
        if cache.len() < 256 {
            cache.push((params.to_vec(), t));
        }
        Some(t)
    }

    /// det A / det M, or a·r / r·r in projection mode (None when not finite).
    fn det_c(&self, m: &[f64], a: &[f64]) -> Option<f64> {
        let d = if self.projection {
            let rr: f64 = m.iter().map(|v| v * v).sum();
            let ar: f64 = a.iter().zip(m).map(|(x, y)| x * y).sum();
            ar / rr
        } else {
            det(self.n, |i, j| a[i * self.n + j]) / det(self.n, |i, j| m[i * self.n + j])
        };
        d.is_finite().then_some(d)
    }

    /// det C at `x`, cheaply: a value where M is regular and det C is finite and not 0; the
    /// [`careful`](Self::careful) verdict otherwise. A small value may still be a
    /// singularity of the physics: ask [`careful`](Self::careful) before calling it a zero.
    pub(super) fn at(&self, x: &[f64]) -> Det {
        {
            let mut guard = self.scratch.borrow_mut();
            let s = &mut *guard;
            if let Some(m) = &self.m
                && m.run(x, &mut s.m).is_err()
            {
                return Det::Skip;
            }
            if self.a.run(x, &mut s.a).is_ok()
                && let Some(d) = s.det_c(self)
                && d != 0.0
            {
                return Det::Value(d);
            }
        }
        self.careful(x)
    }

    /// det C at `x` against the typical sizes at its parameter values: [`Det::Skip`] where M
    /// or the true equations blow up, [`Det::Singular`] where M loses rank.
    pub(super) fn careful(&self, x: &[f64]) -> Det {
        let Some(typical) = self.typical(x) else {
            return Det::Skip;
        };
        let (m, a, equations) = match self.raw(x, true) {
            Raw::Skip => return Det::Skip,
            Raw::AnswerUndefined { m } => {
                // Undefined where the physics determines every acceleration is a fault of
                // the answer; where it does not, the answer is not judged (per direction,
                // "wherever the answer is finite").
                if !blows_up(norm(&m), typical.m) && self.rank(&m, typical.m) == self.rows() {
                    return Det::Undefined;
                }
                return Det::Skip;
            }
            Raw::Both { m, a, equations } => (m, a, equations),
        };
        if blows_up(norm(&m), typical.m) || blows_up(equations, typical.equations) {
            return Det::Skip;
        }
        let rank_m = self.rank(&m, typical.m);
        if rank_m < self.rows() {
            let rank_a = self.rank(&a, typical.a);
            return Det::Singular {
                deficient: rank_a < rank_m,
            };
        }
        match self.det_c(&m, &a) {
            Some(d) => Det::Value(d),
            // det A overflowed while A is finite: far from zero, nothing to report.
            None => Det::Skip,
        }
    }

    /// Whether `d` is zero: exactly, or against det C's typical size at the parameter values
    /// of `reference` (the point a search started from: a factor of the parameters alone,
    /// cos α, is as small at every state with α near π/2).
    pub(super) fn is_zero(&self, reference: &[f64], d: f64) -> bool {
        d == 0.0 || d.abs() <= crate::check::tolerance::SAME * self.typical_det(reference)
    }

    /// The median |det C| over a few sample states given `x`'s parameter values, on the
    /// fast path (no allocation, no true equations).
    pub(super) fn typical_det(&self, x: &[f64]) -> f64 {
        let params = &x[self.params_start..];
        if let Some((_, t)) = self.typical_det.borrow().iter().find(|(p, _)| p == params) {
            return *t;
        }
        let mut y = vec![0.0; x.len()];
        let mut dets = Vec::with_capacity(self.states.len());
        for state in &self.states {
            y.copy_from_slice(state);
            y[self.params_start..].copy_from_slice(params);
            let mut guard = self.scratch.borrow_mut();
            let s = &mut *guard;
            let m_ok = self.m.as_ref().is_none_or(|m| m.run(&y, &mut s.m).is_ok());
            if m_ok
                && self.a.run(&y, &mut s.a).is_ok()
                && let Some(d) = s.det_c(self)
            {
                dets.push(d.abs());
            }
        }
        let t = median(dets).unwrap_or(0.0);
        let mut cache = self.typical_det.borrow_mut();
        if cache.len() < 256 {
            cache.push((params.to_vec(), t));
        }
        t
    }

    /// The rows of the matrices compared: n, or 1 in projection mode.
    fn rows(&self) -> usize {
        if self.projection { 1 } else { self.n }
    }

    /// The numerical rank of a `rows × n` matrix, singular values below [`RANK_ZERO`] of
    /// `scale` counting as zero.
    fn rank(&self, entries: &[f64], scale: f64) -> usize {
        let rows = self.rows();
        let zero = RANK_ZERO * scale;
        if rows == 1 {
            return usize::from(norm(entries) > zero);
        }
        let mat = nalgebra::DMatrix::from_row_slice(rows, self.n, entries);
        mat.singular_values().iter().filter(|&&s| s > zero).count()
    }
}

fn identity(n: usize) -> Vec<f64> {
    (0..n * n)
        .map(|k| if k / n == k % n { 1.0 } else { 0.0 })
        .collect()
}

/// Whether `v` is beyond [`BLOW_UP`] times its typical size `t` (a typical size of 0, as of
/// equations that vanish at every sampled state, sets no scale).
fn blows_up(v: f64, t: f64) -> bool {
    t > 0.0 && v > BLOW_UP * t
}

/// The Frobenius norm.
fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// The median of the finite values (None when there is none or it is not positive).
pub(super) fn median(v: Vec<f64>) -> Option<f64> {
    let mut v: Vec<f64> = v.into_iter().filter(|x| x.is_finite()).collect();
    if v.is_empty() {
        return None;
    }
    crate::sort::sort_by(&mut v, f64::total_cmp);
    let m = v[v.len() / 2];
    (m > 0.0).then_some(m)
}

/// The determinant of the n×n matrix with entries `e(i, j)`: by formula up to 3×3 (no
/// allocation), by LU beyond.
pub(super) fn det(n: usize, e: impl Fn(usize, usize) -> f64) -> f64 {
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

//! Accelerations at a numeric state: M q'' = f solved with nalgebra (Cholesky, falling back
//! to LU for an indefinite M), from one compiled program holding M and f.

use nalgebra::{DMatrix, DVector};

use super::constraints::ConstraintRows;
use super::derive::Derivation;
use super::error::MechError;
use super::system::System;
use crate::expr::Program;

/// M and f compiled together; evaluates accelerations without re-reading expressions.
#[derive(Clone, Debug)]
pub struct Dynamics {
    program: Program,
    n: usize,
    /// Constraint rows compiled after M and f (A, m × n, then r), none when unconstrained.
    constraints: usize,
    names: Vec<String>,
}

impl Dynamics {
    /// Compiles M and f of `d` over the system's standard layout.
    pub fn new(sys: &System, d: &Derivation) -> Result<Dynamics, MechError> {
        Dynamics::compiled(sys, d, &ConstraintRows::default())
    }

    /// Compiles M and f of `d` and the constraint rows (A, r) of the system's constraints:
    /// the augmented equations M q'' − Aᵀλ = f, A q'' = −r.
    pub fn constrained(sys: &mut System, d: &Derivation) -> Result<Dynamics, MechError> {
        let rows = sys.constraint_rows();
        Dynamics::compiled(sys, d, &rows)
    }

    /// M, f, then A and r (none for empty rows) in one program.
    fn compiled(
        sys: &System,
        d: &Derivation,
        rows: &ConstraintRows,
    ) -> Result<Dynamics, MechError> {
        let mut roots: Vec<_> = d.mass.iter().flatten().copied().collect();
        roots.extend(d.forcing.iter().copied());
        roots.extend(rows.a.iter().flatten().copied());
        roots.extend(rows.r.iter().copied());
        Ok(Dynamics {
            program: sys.compile(&roots)?,
            n: sys.n(),
            constraints: rows.r.len(),
            names: sys.coordinates.iter().map(|c| c.name.clone()).collect(),
        })
    }

    /// Number of constraint rows compiled with M and f.
    pub fn constraints(&self) -> usize {
        self.constraints
    }

    /// A (row-major, m·n) and r (m) after a successful
    /// [`mass_and_forcing_into`](Self::mass_and_forcing_into) with the same scratch.
    pub fn constraint_rows_from(&self, scratch: &[f64], a: &mut [f64], r: &mut [f64]) {
        let (n, m) = (self.n, self.constraints);
        let base = n * n + n;
        for (k, v) in a.iter_mut().enumerate().take(m * n) {
            *v = self.program.output(base + k, scratch);
        }
        for (k, v) in r.iter_mut().enumerate().take(m) {
            *v = self.program.output(base + m * n + k, scratch);
        }
    }

    /// M and f at `point` (the standard layout; accelerations in it are ignored).
    pub(crate) fn mass_and_forcing(
        &self,
        point: &[f64],
        scratch: &mut [f64],
    ) -> Result<(DMatrix<f64>, DVector<f64>), MechError> {
        let n = self.n;
        self.program
            .run(point, scratch)
            .map_err(|_| MechError::Undefined {
                what: "the mass matrix or forcing".into(),
            })?;
        let m = DMatrix::from_fn(n, n, |r, c| self.program.output(r * n + c, scratch));
        let f = DVector::from_fn(n, |r, _| self.program.output(n * n + r, scratch));
        Ok((m, f))
    }

    /// The same dynamics with the inputs at `fixed` (index in the standard layout, value)
    /// folded in as constants: a simulation fixes the parameters once.
    pub fn specialize(&self, fixed: &[(usize, f64)]) -> Dynamics {
        Dynamics {
            program: self.program.specialize(fixed),
            n: self.n,
            constraints: self.constraints,
            names: self.names.clone(),
        }
    }

    /// Number of coordinates.
    pub fn n(&self) -> usize {
        self.n
    }

    /// M (row-major, n·n) and f (n) at `point` into the caller's buffers, without
    /// allocating: the hot path of an ODE right-hand side. `Err` when the program is
    /// undefined there.
    pub fn mass_and_forcing_into(
        &self,
        point: &[f64],
        scratch: &mut [f64],
        m: &mut [f64],
        f: &mut [f64],
    ) -> Result<(), crate::expr::Undefined> {
        let n = self.n;
        self.program.run(point, scratch)?;
        for (k, v) in m.iter_mut().enumerate().take(n * n) {
            *v = self.program.output(k, scratch);
        }
        for (r, v) in f.iter_mut().enumerate().take(n) {
            *v = self.program.output(n * n + r, scratch);
        }
        Ok(())
    }

    /// M (row-major, n·n slots) and f (n slots) at `K` sample points at once (lanes, see
    /// [`Program::run_lanes`]) into the caller's buffers; no allocation. Returns the mask of
    /// the lanes where the program is undefined (their M and f are meaningless).
    pub fn mass_and_forcing_lanes<const K: usize>(
        &self,
        points: &[[f64; K]],
        scratch: &mut [[f64; K]],
        m: &mut [[f64; K]],
        f: &mut [[f64; K]],
    ) -> u64 {
        let n = self.n;
        let bad = self.program.run_lanes(points, scratch);
        for (k, v) in m.iter_mut().enumerate().take(n * n) {
            *v = self.program.output_lanes(k, scratch);
        }
        for (r, v) in f.iter_mut().enumerate().take(n) {
            *v = self.program.output_lanes(n * n + r, scratch);
        }
        bad
    }

    /// A lane scratch buffer for [`mass_and_forcing_lanes`](Self::mass_and_forcing_lanes).
    pub fn scratch_lanes<const K: usize>(&self) -> Vec<[f64; K]> {
        self.program.scratch_lanes()
    }

    /// A scratch buffer for [`accelerations`](Self::accelerations).
    pub fn scratch(&self) -> Vec<f64> {
        self.program.scratch()
    }

    /// q'' at `point`.
    pub fn accelerations(&self, point: &[f64], scratch: &mut [f64]) -> Result<Vec<f64>, MechError> {
        let (m, f) = self.mass_and_forcing(point, scratch)?;
        solve(&m, &f, &self.names).map(|v| v.iter().copied().collect())
    }
}

/// Solves M x = f: Cholesky when M is positive definite, LU otherwise; an M singular by the
/// one rule (`mechanics::singular`) is an error naming the coordinate whose row vanishes (or all of them).
pub(crate) fn solve(
    m: &DMatrix<f64>,
    f: &DVector<f64>,
    names: &[String],
) -> Result<DVector<f64>, MechError> {
    if !super::singular::is_singular(m) {
        let x = match m.clone().cholesky() {
            Some(ch) => Some(ch.solve(f)),
            None => m.clone().lu().solve(f),
        };
        if let Some(x) = x.filter(|x| x.iter().all(|v| v.is_finite())) {
            return Ok(x);
        }
    }
    let scale = m.amax();
    for (i, name) in names.iter().enumerate() {
        // Relative to the largest entry; an all-zero M has every row zero.
        if m.row(i).amax() <= 1e-14 * scale {
            return Err(MechError::NoKineticTerm { name: name.clone() });
        }
    }
    Err(MechError::SingularMass {
        names: names
            .iter()
            .map(|n| format!("{n}'"))
            .collect::<Vec<_>>()
            .join(", "),
    })
}

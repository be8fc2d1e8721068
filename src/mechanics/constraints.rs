//! Constraints with Lagrange multipliers. A holonomic constraint f(q, t) = 0 is used through
//! its time derivative c = df/dt; a nonholonomic one is already a velocity form c = 0. With
//! A = ∂c/∂q' and r = dc/dt at q'' = 0, the augmented equations
//!     M q'' − Aᵀλ = f,   A q'' = −r
//! give the accelerations and the multipliers (the constraint forces).

use nalgebra::{DMatrix, DVector};
use rustc_hash::FxHashMap;

use super::derive::Derivation;
use super::error::MechError;
use super::linalg::cramer;
use super::system::{ConstraintKind, System};
use crate::expr::{Factored, Id};

/// The constraint rows: A (m×n) and r (m).
#[derive(Clone, Debug)]
pub struct ConstraintRows {
    pub a: Vec<Vec<Id>>,
    pub r: Vec<Id>,
}

impl System {
    /// A and r for the system's constraints.
    pub fn constraint_rows(&mut self) -> ConstraintRows {
        let coords = self.coordinate_syms();
        let zero = self.pool.zero();
        let no_acc: FxHashMap<_, _> = coords.iter().map(|&c| ((c, 2), zero)).collect();
        let mut a = Vec::new();
        let mut r = Vec::new();
        for c in self.constraints.clone() {
            let vel = match c.kind {
                ConstraintKind::Holonomic => self.pool.dt(c.expr, &coords),
                ConstraintKind::Nonholonomic => c.expr,
            };
            let row: Vec<Id> = coords
                .iter()
                .map(|&q| {
                    let d = self.pool.diff(vel, q, 1);
                    self.simplify(d)
                })
                .collect();
            let acc = self.pool.dt(vel, &coords);
            let rest = self.pool.substitute(acc, &no_acc);
            a.push(row);
            r.push(self.simplify(rest));
        }
        ConstraintRows { a, r }
    }

    /// The augmented equations Eᵢ − Σⱼ λⱼ Aⱼᵢ (meaning = 0), with multipliers named
    /// lambda1, lambda2, ….
    pub fn augmented_equations(&mut self, d: &Derivation, rows: &ConstraintRows) -> Vec<Id> {
        let lambdas: Vec<Id> = (1..=rows.a.len())
            .map(|j| self.pool.sym(&format!("lambda{j}")))
            .collect();
        (0..self.n())
            .map(|i| {
                let mut terms = vec![d.steps[i].equation];
                for (j, row) in rows.a.iter().enumerate() {
                    let t = self.pool.mul(lambdas[j], row[i]);
                    terms.push(self.pool.neg(t));
                }
                let s = self.pool.sum(terms);
                self.simplify(s)
            })
            .collect()
    }

    /// Accelerations and multipliers at a state (standard layout).
    pub fn multipliers_at(
        &self,
        d: &Derivation,
        rows: &ConstraintRows,
        point: &[f64],
    ) -> Result<(Vec<f64>, Vec<f64>), MechError> {
        let n = self.n();
        let m = rows.a.len();
        let mut roots: Vec<Id> = d.mass.iter().flatten().copied().collect();
        roots.extend(d.forcing.iter().copied());
        roots.extend(rows.a.iter().flatten().copied());
        roots.extend(rows.r.iter().copied());
        let prog = self.compile(&roots)?;
        let mut scratch = prog.scratch();
        prog.run(point, &mut scratch)
            .map_err(|_| MechError::Undefined {
                what: "the constrained equations".into(),
            })?;
        let out = |k: usize| prog.output(k, &scratch);
        let size = n + m;
        let mut s = DMatrix::<f64>::zeros(size, size);
        let mut rhs = DVector::<f64>::zeros(size);
        for i in 0..n {
            for j in 0..n {
                s[(i, j)] = out(i * n + j);
            }
            rhs[i] = out(n * n + i);
        }
        for j in 0..m {
            for i in 0..n {
                let aji = out(n * n + n + j * n + i);
                s[(i, n + j)] = -aji;
                s[(n + j, i)] = aji;
            }
            rhs[n + j] = -out(n * n + n + m * n + j);
        }
        let x = s.lu().solve(&rhs).ok_or(MechError::DependentConstraints)?;
        Ok((
            x.iter().take(n).copied().collect(),
            x.iter().skip(n).copied().collect(),
        ))
    }

    /// num/den built from their factored forms (so the quotient keeps the common factors
    /// together: 2·m₁·m₂·g/(m₁ + m₂)) without putting a factored form into the pool.
    fn factored_quotient(&mut self, num: Id, den: Id) -> Id {
        let mut parts = self.pool.factored(num).into_parts();
        // 1/(a·b·…) is built as the pool builds the reciprocal of a product node.
        let inverse = match self.pool.factored(den) {
            Factored::Plain(d) => self.pool.recip(d),
            Factored::Product(ds) => {
                let inv: Vec<Id> = ds.into_iter().map(|d| self.pool.recip(d)).collect();
                self.pool.product(inv)
            }
        };
        parts.push(inverse);
        self.pool.product(parts)
    }

    /// The multipliers in closed form (Cramer's rule on the augmented system), for systems
    /// with at most four unknowns.
    // Assembling a block matrix writes row i and column i together; an index reads best.
    #[allow(clippy::needless_range_loop)]
    pub fn multipliers_symbolic(
        &mut self,
        d: &Derivation,
        rows: &ConstraintRows,
    ) -> Option<Vec<Id>> {
        let n = self.n();
        let m = rows.a.len();
        if n + m > 4 || m == 0 {
            return None;
        }
        let zero = self.pool.zero();
        let mut s = vec![vec![zero; n + m]; n + m];
        let mut rhs = vec![zero; n + m];
        for i in 0..n {
            s[i][..n].copy_from_slice(&d.mass[i]);
            rhs[i] = d.forcing[i];
        }
        for j in 0..m {
            for i in 0..n {
                s[i][n + j] = self.pool.neg(rows.a[j][i]);
                s[n + j][i] = rows.a[j][i];
            }
            rhs[n + j] = self.pool.neg(rows.r[j]);
        }
        let sol = cramer(&mut self.pool, &s, &rhs)?;
        Some(
            sol[n..]
                .iter()
                .map(|&(num, den)| {
                    let num = self.simplify(num);
                    let den = self.simplify(den);
                    self.factored_quotient(num, den)
                })
                .collect(),
        )
    }
}

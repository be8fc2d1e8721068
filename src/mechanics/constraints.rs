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
#[derive(Clone, Debug, Default)]
pub struct ConstraintRows {
    pub(crate) a: Vec<Vec<Id>>,
    pub(crate) r: Vec<Id>,
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

/// Starts of the search for a real state on a constraint.
const REALITY_STARTS: usize = 16;
/// Damped Gauss–Newton steps from each start.
const REALITY_STEPS: usize = 200;

/// The level at which a state violates a constraint.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConstraintLevel {
    /// f(q, t) ≠ 0.
    Position,
    /// df/dt ≠ 0 (or the velocity form of a rolling condition ≠ 0).
    Velocity,
}

/// A constraint a state violates: its index (from 0), the level, and the residual there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Violation {
    pub(crate) index: usize,
    pub(crate) level: ConstraintLevel,
    pub(crate) residual: f64,
}

impl System {
    /// The first constraint the sample point `point` violates — positions first, then
    /// velocities — judged relative to the size of the constraint's own terms (a residual
    /// of rounding size is no violation, whatever the scale).
    pub fn constraint_violation(&mut self, point: &[f64]) -> Result<Option<Violation>, MechError> {
        let coords = self.coordinate_syms();
        let mut roots = Vec::new();
        let mut levels = Vec::new();
        for (k, c) in self.constraints.clone().iter().enumerate() {
            if c.kind == ConstraintKind::Holonomic {
                roots.push(c.expr);
                levels.push((k, ConstraintLevel::Position));
                let v = self.pool.dt(c.expr, &coords);
                roots.push(v);
            } else {
                roots.push(c.expr);
            }
            levels.push((k, ConstraintLevel::Velocity));
        }
        let sizes = self.magnitudes(&roots)?;
        let values = sizes.eval(point).ok_or(MechError::Undefined {
            what: "a constraint".into(),
        })?;
        let mut found: Vec<Violation> = levels
            .iter()
            .zip(values)
            .filter(|(_, s)| !s.negligible())
            .map(|(&(index, level), s)| Violation {
                index,
                level,
                residual: s.value,
            })
            .collect();
        crate::sort::sort_by_key(&mut found, |v| {
            (v.level == ConstraintLevel::Velocity, v.index)
        });
        Ok(found.first().copied())
    }

    /// A holonomic constraint (of the coordinates alone: no parameter, no t) that no real
    /// state satisfies, with the least |f| found: a damped Newton search from
    /// several sampled starts ends, from every start, at a minimum of |f| that is not zero
    /// (`x² = −1`). `None` when some start reaches the constraint, or the search cannot tell
    /// (a start runs off or stops where f is not stationary: `1/x = 0`).
    pub fn unsatisfiable_constraint(&mut self) -> Result<Option<(usize, f64)>, MechError> {
        for (k, c) in self.constraints.clone().iter().enumerate() {
            let vars = self.pool.variables(c.expr);
            let only_coordinates = !vars.is_empty()
                && vars
                    .iter()
                    .all(|(s, _)| self.coordinates.iter().any(|q| q.sym == *s));
            if c.kind != ConstraintKind::Holonomic || !only_coordinates {
                continue;
            }
            if let Some(least) = self.least_residual(c.expr)? {
                return Ok(Some((k, least)));
            }
        }
        Ok(None)
    }

    /// The least |f| over the ends of the searches when every one stalls at a nonzero
    /// stationary point of f²; `None` otherwise.
    fn least_residual(&mut self, f: Id) -> Result<Option<f64>, MechError> {
        let n = self.n();
        let coords = self.coordinate_syms();
        let mut roots = vec![f];
        for &q in &coords {
            roots.push(self.pool.diff(f, q, 0));
        }
        let prog = self.compile(&roots)?;
        let sizes = self.magnitudes(&[f])?;
        let layout = self.state_layout();
        let mut scratch = prog.scratch();
        let mut sampler = super::sample::Sampler::new(0x5eed_0c0c);
        let mut least = f64::INFINITY;
        for _ in 0..REALITY_STARTS {
            let mut x = self.sample_point(&mut sampler);
            let mut value = f64::NAN;
            let mut gradient = f64::NAN;
            for _ in 0..REALITY_STEPS {
                let Some(s) = sizes.eval(&x) else {
                    return Ok(None);
                };
                if s[0].negligible() {
                    return Ok(None);
                }
                if prog.run(&x, &mut scratch).is_err() {
                    return Ok(None);
                }
                value = prog.output(0, &scratch);
                let g: Vec<f64> = (0..n).map(|i| prog.output(1 + i, &scratch)).collect();
                let g2: f64 = g.iter().map(|v| v * v).sum();
                gradient = g2.sqrt();
                if g2 == 0.0 {
                    break;
                }
                // Minimum-norm Newton step, halved until |f| decreases (so the search
                // settles in a minimum of |f| instead of jumping about).
                let mut t = 1.0;
                let mut moved = false;
                for _ in 0..60 {
                    let mut y = x.clone();
                    for i in 0..n {
                        y[layout.q(i)] -= t * value * g[i] / g2;
                    }
                    if prog.run(&y, &mut scratch).is_ok()
                        && prog.output(0, &scratch).abs() < value.abs()
                    {
                        x = y;
                        moved = true;
                        break;
                    }
                    t *= 0.5;
                }
                if !moved {
                    break;
                }
            }
            let scale = 1.0 + (0..n).map(|i| x[layout.q(i)].abs()).fold(0.0, f64::max);
            // Not at a stationary point of f²: the search stopped for another reason.
            // (NaN compares false: an undefined end is not stationary either.)
            let stationary = gradient * scale <= 1e-6 * value.abs();
            if !stationary {
                return Ok(None);
            }
            least = least.min(value.abs());
        }
        Ok(Some(least))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn circle() -> System {
        let mut sys = System::from_lagrangian("1/2*(x'^2 + y'^2) - 9.81*y", &["x", "y"]).unwrap();
        sys.add_constraint("x^2 + y^2 = 4").unwrap();
        sys
    }

    /// A point at rest at (x, y) with velocity (vx, vy).
    fn state(sys: &System, q: [f64; 2], v: [f64; 2]) -> Vec<f64> {
        let layout = sys.state_layout();
        let mut x = layout.at_rest(&q, &[]);
        x[layout.qdot(0)] = v[0];
        x[layout.qdot(1)] = v[1];
        x
    }

    #[test]
    fn violations_are_found_at_each_level() {
        let mut sys = circle();
        let on = state(&sys, [1.2, -1.6], [1.6, 1.2]);
        assert_eq!(sys.constraint_violation(&on).unwrap(), None);
        let off = state(&sys, [1.2, -1.5], [0.0, 0.0]);
        let v = sys.constraint_violation(&off).unwrap().unwrap();
        assert_eq!((v.index, v.level), (0, ConstraintLevel::Position));
        assert!((v.residual + 0.31).abs() < 1e-12, "{v:?}");
        let across = state(&sys, [1.2, -1.6], [1.0, 0.0]);
        let v = sys.constraint_violation(&across).unwrap().unwrap();
        assert_eq!(v.level, ConstraintLevel::Velocity);
        assert!((v.residual - 2.4).abs() < 1e-12, "{v:?}");
    }

    #[test]
    fn a_constraint_with_no_real_state_is_found_and_others_are_not() {
        let mut sys = circle();
        assert_eq!(sys.unsatisfiable_constraint().unwrap(), None);
        let mut none = System::from_lagrangian("1/2*(x'^2 + y'^2)", &["x", "y"]).unwrap();
        none.add_constraint("x^2 + (y - 1)^2 = -2").unwrap();
        let (k, least) = none.unsatisfiable_constraint().unwrap().unwrap();
        assert_eq!(k, 0);
        assert!((least - 2.0).abs() < 1e-6, "{least}");
        // x³ − 3x + 5 has a local minimum 3 at x = 1 but a real root near −2.28.
        let mut cubic = System::from_lagrangian("1/2*(x'^2 + y'^2)", &["x", "y"]).unwrap();
        cubic.add_constraint("x^3 - 3*x + 5 = 0").unwrap();
        assert_eq!(cubic.unsatisfiable_constraint().unwrap(), None);
    }
}

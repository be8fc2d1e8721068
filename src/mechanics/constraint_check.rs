//! Validation of a system's constraints before they are used: a constraint with no
//! coordinate (`1 = 0`, `0 = 0`), more constraints than coordinates, a constraint whose row
//! is a combination of the earlier ones (repeated, or contradicting them: `x = 0` with
//! `x = 1`), and parameters named like the multipliers (`lambda1`).

use nalgebra::DMatrix;

use super::error::MechError;
use super::sample::Sampler;
use super::system::{ConstraintKind, System};
use crate::expr::Id;

/// Sample points at which the rank of the constraint rows is taken.
const RANK_SAMPLES: usize = 8;
/// Starts for finding a point on the earlier constraints.
const PROJECTION_STARTS: usize = 6;
/// Gauss–Newton steps from each start.
const PROJECTION_STEPS: usize = 60;
/// A coordinate past this size means the projection diverges: no state was found.
const MAX_PROJECTED: f64 = 1e12;

impl System {
    /// Checks the constraints; `rows` are their velocity rows A (m×n), as
    /// [`constraint_rows`](Self::constraint_rows) gives them.
    pub(crate) fn validate_constraints(&mut self, rows: &[Vec<Id>]) -> Result<(), MechError> {
        let m = self.constraints.len();
        if m == 0 {
            return Ok(());
        }
        self.check_multiplier_names(m)?;
        for (k, c) in self.constraints.iter().enumerate() {
            let moves = self
                .pool
                .variables(c.expr)
                .iter()
                .any(|(s, _)| self.coordinates.iter().any(|q| q.sym == *s));
            if moves {
                continue;
            }
            let text = self.pool.plain(c.expr);
            return Err(if self.is_zero(c.expr) {
                MechError::EmptyConstraint { index: k + 1, text }
            } else {
                MechError::ConstraintNeverHolds { index: k + 1, text }
            });
        }
        if m > self.n() {
            return Err(MechError::TooManyConstraints {
                constraints: m,
                coordinates: self.n(),
            });
        }
        let Some(k) = self.first_dependent_row(rows)? else {
            return Ok(());
        };
        Err(MechError::DependentConstraint {
            index: k + 1,
            text: self.pool.plain(self.constraints[k].expr),
            contradicts: self.contradicts_earlier(k)?,
        })
    }

    /// `lambda1` … `lambdaM` name the multipliers: no coordinate or parameter may.
    pub(crate) fn check_multiplier_names(&self, m: usize) -> Result<(), MechError> {
        let names = self
            .coordinates
            .iter()
            .map(|c| c.name.as_str())
            .chain(self.parameters.iter().map(|p| p.name.as_str()));
        for name in names {
            let taken = (1..=m).any(|j| name == format!("lambda{j}") || name == format!("λ{j}"));
            if taken {
                return Err(MechError::MultiplierName {
                    name: name.to_string(),
                });
            }
        }
        Ok(())
    }

    /// The first constraint whose row is, at every sampled state, a combination of the rows
    /// before it (the rank is the largest found over the samples, so a state where the rows
    /// happen to align does not count).
    fn first_dependent_row(&self, rows: &[Vec<Id>]) -> Result<Option<usize>, MechError> {
        let n = self.n();
        let entries: Vec<Id> = rows.iter().flatten().copied().collect();
        let prog = self.compile(&entries)?;
        let mut scratch = prog.scratch();
        let mut sampler = Sampler::new(0x5eed_0c0a);
        // best[k]: the largest rank of rows 0..=k seen.
        let mut best = vec![0usize; rows.len()];
        for _ in 0..RANK_SAMPLES {
            let x = self.sample_point(&mut sampler);
            if prog.run(&x, &mut scratch).is_err() {
                continue;
            }
            for (k, b) in best.iter_mut().enumerate() {
                let a = DMatrix::from_fn(k + 1, n, |r, c| prog.output(r * n + c, &scratch));
                *b = (*b).max(rank(&a));
            }
        }
        if best.iter().all(|&r| r == 0) {
            // Nowhere evaluable: leave it to the analysis, which names what is undefined.
            return Ok(None);
        }
        Ok((0..rows.len()).find(|&k| best[k] < k + 1))
    }

    /// Whether constraint `k` (dependent on the earlier ones) fails on states that satisfy
    /// the earlier holonomic ones: its row lies in their span, so it is constant along them,
    /// and a nonzero constant there is a contradiction, zero a repetition — judged at the
    /// states found from several starts. `None` when it cannot be told: a velocity constraint
    /// (rows alone cannot tell), no state on the earlier constraints was found (`1/x = 0`
    /// has none), or it holds at some and not at others (`x² = 1` with `x = 1`).
    fn contradicts_earlier(&mut self, k: usize) -> Result<Option<bool>, MechError> {
        let holonomic = |c: &super::system::Constraint| c.kind == ConstraintKind::Holonomic;
        if !holonomic(&self.constraints[k]) || !self.constraints[..k].iter().all(holonomic) {
            return Ok(None);
        }
        let exprs: Vec<Id> = self.constraints[..=k].iter().map(|c| c.expr).collect();
        let n = self.n();
        let coords = self.coordinate_syms();
        let mut roots = exprs.clone();
        for &e in &exprs[..k] {
            for &q in &coords {
                roots.push(self.pool.diff(e, q, 0));
            }
        }
        let prog = self.compile(&roots)?;
        // The constraints' values with the sizes of their terms: "zero" is zero up to
        // rounding relative to those, whatever the scale (a circle of radius 1000 or 0.001).
        let sizes = self.magnitudes(&exprs)?;
        let mut scratch = prog.scratch();
        let layout = self.state_layout();
        let mut sampler = Sampler::new(0x5eed_0c0b);
        // Whether constraint k holds, at each state found on the earlier ones: they may have
        // several components (x² = 1 with x = 1), so one state does not decide.
        let mut holds = Vec::new();
        for _ in 0..PROJECTION_STARTS {
            let mut x = self.sample_point(&mut sampler);
            // Gauss–Newton onto the earlier constraints (minimum-norm steps).
            for _ in 0..PROJECTION_STEPS {
                let Some(v) = sizes.eval(&x) else { break };
                if v[..k].iter().all(|g| g.negligible()) {
                    holds.push(v[k].negligible());
                    break;
                }
                // Running off to infinity (1/x = 0 has no state) finds nothing.
                if (0..n).any(|i| x[layout.q(i)].abs() > MAX_PROJECTED)
                    || prog.run(&x, &mut scratch).is_err()
                {
                    break;
                }
                let g = nalgebra::DVector::from_fn(k, |r, _| prog.output(r, &scratch));
                let j = DMatrix::from_fn(k, n, |r, c| prog.output(k + 1 + r * n + c, &scratch));
                let Ok(step) = j.svd(true, true).solve(&g, 1e-12) else {
                    break;
                };
                for i in 0..n {
                    x[layout.q(i)] -= step[i];
                }
            }
        }
        Ok(
            match (holds.iter().any(|&h| h), holds.iter().any(|&h| !h)) {
                (true, false) => Some(false),
                (false, true) => Some(true),
                _ => None,
            },
        )
    }
}

/// The numerical rank of `a`, relative to its largest singular value.
fn rank(a: &DMatrix<f64>) -> usize {
    let sv = a.singular_values();
    let hi = sv.iter().fold(0.0f64, |m, &x| m.max(x));
    if hi == 0.0 {
        return 0;
    }
    sv.iter().filter(|&&x| x > 1e-9 * hi).count()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn derive_with(l: &str, coords: &[&str], constraints: &[&str]) -> Result<(), MechError> {
        let mut sys = System::from_lagrangian(l, coords)?;
        for c in constraints {
            sys.add_constraint(c)?;
        }
        sys.derive().map(|_| ())
    }

    const FREE: &str = "1/2*m*(x'^2 + y'^2)";

    #[test]
    fn a_constraint_without_coordinates_never_holds() {
        let e = derive_with(FREE, &["x", "y"], &["1 = 0"]).unwrap_err();
        assert_eq!(e.code(), "constraint-never-holds", "{e}");
        let e = derive_with(FREE, &["x", "y"], &["x = x"]).unwrap_err();
        assert_eq!(e.code(), "empty-constraint", "{e}");
    }

    #[test]
    fn contradicting_constraints_are_named() {
        let e = derive_with(FREE, &["x", "y"], &["x = 0", "x = 1"]).unwrap_err();
        assert_eq!(e.code(), "contradictory-constraints", "{e}");
        assert!(e.to_string().contains("constraint 2"), "{e}");
    }

    #[test]
    fn concentric_circles_contradict_and_a_rescaled_circle_repeats() {
        let e = derive_with(FREE, &["x", "y"], &["x^2 + y^2 = 1", "x^2 + y^2 = 4"]).unwrap_err();
        assert_eq!(e.code(), "contradictory-constraints", "{e}");
        let e =
            derive_with(FREE, &["x", "y"], &["x^2 + y^2 = 1", "2*x^2 + 2*y^2 = 2"]).unwrap_err();
        assert_eq!(e.code(), "redundant-constraint", "{e}");
        // Independent except at special points: accepted.
        derive_with(FREE, &["x", "y"], &["x = 0", "x^2 + y^2 = 1"]).unwrap();
    }

    #[test]
    fn repeated_constraints_are_named() {
        let e = derive_with(FREE, &["x", "y"], &["x = y", "2*x = 2*y"]).unwrap_err();
        assert_eq!(e.code(), "redundant-constraint", "{e}");
        // No state satisfies 1/x = 0: whether x = 1 repeats or contradicts it is not claimed.
        let e = derive_with(FREE, &["x", "y"], &["1/x = 0", "x = 1"]).unwrap_err();
        assert_eq!(e.code(), "dependent-constraint", "{e}");
        // x = 1 picks one of the two solutions of x² = 1: neither repeated nor contradicted.
        let e = derive_with(FREE, &["x", "y"], &["x^2 = 1", "x = 1"]).unwrap_err();
        assert_eq!(e.code(), "dependent-constraint", "{e}");
    }

    #[test]
    fn more_constraints_than_coordinates() {
        let e = derive_with(FREE, &["x", "y"], &["x = 0", "y = 0", "x + y = 0"]).unwrap_err();
        assert_eq!(e.code(), "too-many-constraints", "{e}");
    }

    #[test]
    fn a_parameter_named_like_a_multiplier_is_refused() {
        let e = derive_with(
            "1/2*m*(x'^2 + y'^2) - lambda1*y",
            &["x", "y"],
            &["x^2 + y^2 = l^2"],
        )
        .unwrap_err();
        assert_eq!(e.code(), "multiplier-name", "{e}");
    }

    #[test]
    fn independent_constraints_pass() {
        derive_with(
            "1/2*m*(x'^2 + y'^2 + z'^2)",
            &["x", "y", "z"],
            &["x^2 + y^2 + z^2 = l^2", "z = 0"],
        )
        .unwrap();
    }

    #[test]
    fn a_force_with_an_acceleration_is_refused() {
        let mut sys = System::from_lagrangian(FREE, &["x", "y"]).unwrap();
        let e = sys.set_forces("F - m*x''").unwrap_err();
        assert_eq!(e.code(), "force-with-acceleration", "{e}");
    }
}

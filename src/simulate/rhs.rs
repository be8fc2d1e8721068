//! The right-hand side y' = F(t, y) of a system, y = (q, q'): M and f compiled once with the
//! parameter values fixed; each call loads the state into the sample point and solves
//! M q'' = f by Gaussian elimination with partial pivoting in reused buffers, singular by
//! the one rule the checker uses (`mechanics::singular`).
//! With constraints, the augmented equations M q'' − Aᵀλ = f, A q'' = −r are solved instead
//! (index reduced to the acceleration level; the report watches the constraints' drift).

use super::{Ode, SimError};
use crate::expr::Program;
use crate::mechanics::accel::Dynamics;
use crate::mechanics::singular::solve_in_place;
use crate::mechanics::{Layout, System};

/// The compiled equations of motion of one system at fixed parameter values.
#[derive(Clone, Debug)]
pub struct Rhs {
    dynamics: Dynamics,
    layout: Layout,
    names: Vec<String>,
    /// The sample point: t, q, q', q'' and the parameters (fixed).
    point: Vec<f64>,
    scratch: Vec<f64>,
    m: Vec<f64>,
    f: Vec<f64>,
    /// Constraint rows A (m × n) and r, and the augmented (n + m)² matrix and right side.
    a: Vec<f64>,
    r: Vec<f64>,
    aug: Vec<f64>,
    aug_rhs: Vec<f64>,
    energy: Program,
    energy_scratch: Vec<f64>,
    /// Whether h is conserved (no explicit t, no force doing work), from the derivation.
    energy_conserved: bool,
}

impl Rhs {
    /// Derives `sys`, compiles M, f (and the constraint rows, if any) and the energy function
    /// h, with every parameter given a value in `params` (by name).
    pub fn new<S: AsRef<str>>(sys: &mut System, params: &[(S, f64)]) -> Result<Rhs, SimError> {
        // Derived first: a coordinate missing from L (a typo in --coords) is the error to
        // report, not the "parameter" the misspelt coordinate became.
        let d = sys.derive()?;
        let values = parameter_values(sys, params)?;
        let layout = sys.state_layout();
        // The parameters never change along a motion: fold them in once.
        let fixed: Vec<(usize, f64)> = (values.iter().enumerate())
            .map(|(j, &v)| (layout.param(j), v))
            .collect();
        // Without constraints the rows are empty: M q'' = f alone.
        let dynamics = Dynamics::constrained(sys, &d)?.specialize(&fixed);
        let c = dynamics.constraints();
        let energy_analysis = sys.energy(&d);
        let energy = sys.compile(&[energy_analysis.function])?.specialize(&fixed);
        let n = sys.n();
        let mut point = vec![0.0; layout.params_start()];
        point.extend_from_slice(&values);
        Ok(Rhs {
            energy_scratch: energy.scratch(),
            energy,
            scratch: dynamics.scratch(),
            dynamics,
            layout,
            names: sys.coordinates.iter().map(|c| c.name.clone()).collect(),
            point,
            m: vec![0.0; n * n],
            f: vec![0.0; n],
            a: vec![0.0; c * n],
            r: vec![0.0; c],
            aug: vec![0.0; (n + c) * (n + c)],
            aug_rhs: vec![0.0; n + c],
            energy_conserved: energy_analysis.conserved,
        })
    }

    /// Whether the energy function is expected to stay constant along the motion.
    pub fn energy_conserved(&self) -> bool {
        self.energy_conserved
    }

    /// The coordinate names, in the order of q in y.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Where q and q' sit in y.
    pub fn layout(&self) -> Layout {
        self.layout
    }

    /// The compiled M and f (for evaluators over many states, e.g. [`flip_times`](super::flip_times)).
    pub fn dynamics(&self) -> &Dynamics {
        &self.dynamics
    }

    /// The sample point with the parameters loaded (t, q, q', q'' as last evaluated).
    pub fn sample_point(&self) -> &[f64] {
        &self.point
    }

    /// The energy function h = Σ qᵢ' ∂L/∂qᵢ' − L at (t, y).
    pub fn energy(&mut self, t: f64, y: &[f64]) -> Result<f64, SimError> {
        self.layout.load_phase(t, y, &mut self.point);
        self.energy
            .run(&self.point, &mut self.energy_scratch)
            .map_err(|_| SimError::Diverges { t })?;
        Ok(self.energy.output(0, &self.energy_scratch))
    }
}

impl Ode for Rhs {
    fn dim(&self) -> usize {
        self.layout.phase_len()
    }

    fn eval(&mut self, t: f64, y: &[f64], dy: &mut [f64]) -> Result<(), SimError> {
        let n = self.layout.coordinates();
        if !y.iter().all(|v| v.is_finite()) {
            return Err(SimError::Diverges { t });
        }
        self.layout.load_phase(t, y, &mut self.point);
        self.dynamics
            .mass_and_forcing_into(&self.point, &mut self.scratch, &mut self.m, &mut self.f)
            .map_err(|_| SimError::Diverges { t })?;
        if self.dynamics.constraints() > 0 {
            self.solve_constrained(t, y)?;
        } else {
            solve_in_place(n, &mut self.m, &mut self.f)
                .ok_or_else(|| SimError::Singular { t, y: y.to_vec() })?;
        }
        for i in 0..n {
            dy[self.layout.phase_q(i)] = y[self.layout.phase_qdot(i)];
            dy[self.layout.phase_qdot(i)] = self.f[i];
        }
        Ok(())
    }
}

impl Rhs {
    /// q'' into `f` from [M −Aᵀ; A 0] [q''; λ] = [f; −r] (M and f already evaluated).
    fn solve_constrained(&mut self, t: f64, y: &[f64]) -> Result<(), SimError> {
        let n = self.layout.coordinates();
        let c = self.dynamics.constraints();
        let w = n + c;
        self.dynamics
            .constraint_rows_from(&self.scratch, &mut self.a, &mut self.r);
        self.aug.fill(0.0);
        for i in 0..n {
            self.aug[i * w..i * w + n].copy_from_slice(&self.m[i * n..i * n + n]);
            self.aug_rhs[i] = self.f[i];
        }
        for k in 0..c {
            for j in 0..n {
                let v = self.a[k * n + j];
                self.aug[(n + k) * w + j] = v;
                self.aug[j * w + n + k] = -v;
            }
            self.aug_rhs[n + k] = -self.r[k];
        }
        solve_in_place(w, &mut self.aug, &mut self.aug_rhs)
            .ok_or_else(|| SimError::Singular { t, y: y.to_vec() })?;
        self.f.copy_from_slice(&self.aug_rhs[..n]);
        Ok(())
    }
}

/// The parameter values in the system's order, every one given exactly once (by name).
pub fn parameter_values<S: AsRef<str>>(
    sys: &System,
    params: &[(S, f64)],
) -> Result<Vec<f64>, SimError> {
    let known = || {
        sys.parameters
            .iter()
            .map(|p| p.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    };
    if let Some((name, _)) = params
        .iter()
        .find(|(name, _)| !sys.parameters.iter().any(|p| p.name == name.as_ref()))
    {
        return Err(SimError::UnknownParameter {
            name: name.as_ref().to_string(),
            known: known(),
        });
    }
    let missing: Vec<String> = (sys.parameters.iter())
        .filter(|p| !params.iter().any(|(name, _)| name.as_ref() == p.name))
        .map(|p| p.name.clone())
        .collect();
    if !missing.is_empty() {
        return Err(SimError::MissingParameters { names: missing });
    }
    Ok((sys.parameters.iter())
        .map(|p| {
            params
                .iter()
                .find(|(name, _)| name.as_ref() == p.name)
                .map_or(0.0, |x| x.1)
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parameters_are_checked_by_name() {
        let mut sys = System::from_lagrangian("m*x'^2/2 - k*x^2/2", &["x"]).unwrap();
        let e = Rhs::new(&mut sys, &[("m", 1.0)]).unwrap_err();
        assert_eq!(
            e,
            SimError::MissingParameters {
                names: vec!["k".into()]
            }
        );
        let e = Rhs::new(&mut sys, &[("m", 1.0), ("k", 1.0), ("c", 2.0)]).unwrap_err();
        assert!(matches!(e, SimError::UnknownParameter { .. }));
        let mut rhs = Rhs::new(&mut sys, &[("m", 2.0), ("k", 8.0)]).unwrap();
        let mut dy = [0.0; 2];
        rhs.eval(0.0, &[1.0, 3.0], &mut dy).unwrap();
        assert_eq!(dy, [3.0, -4.0]);
        assert!((rhs.energy(0.0, &[1.0, 3.0]).unwrap() - 13.0).abs() < 1e-12);
    }

    #[test]
    fn a_constrained_atwood_machine_accelerates_at_the_textbook_rate() {
        // y1 + y2 = c (string), y measured downwards: y1'' = (m1 − m2) g / (m1 + m2).
        let l = "(m1*y1'^2 + m2*y2'^2)/2 + m1*g*y1 + m2*g*y2";
        let mut sys = System::from_lagrangian(l, &["y1", "y2"]).unwrap();
        sys.add_constraint("y1 + y2 - c").unwrap();
        let p = [("m1", 3.0), ("m2", 1.0), ("g", 9.8), ("c", 2.0)];
        let mut rhs = Rhs::new(&mut sys, &p).unwrap();
        let mut dy = [0.0; 4];
        rhs.eval(0.0, &[0.5, 1.5, 0.2, -0.2], &mut dy).unwrap();
        let want = (3.0 - 1.0) * 9.8 / 4.0;
        assert!(
            (dy[2] - want).abs() < 1e-12 && (dy[3] + want).abs() < 1e-12,
            "{dy:?}"
        );
        assert_eq!((dy[0], dy[1]), (0.2, -0.2));
    }
}

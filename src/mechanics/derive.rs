//! The Euler–Lagrange equations, coordinate by coordinate, keeping every step a tutor shows:
//! pᵢ = ∂L/∂qᵢ', d/dt pᵢ, ∂L/∂qᵢ, and Eᵢ = d/dt pᵢ − ∂L/∂qᵢ − Qᵢ = 0. Also the mass matrix
//! M = ∂²L/∂q'∂q' and the forcing f with M q'' = f.

use rustc_hash::FxHashMap;

use super::error::MechError;
use super::system::System;
use crate::expr::Id;

/// The steps for one coordinate.
#[derive(Clone, Debug)]
pub struct CoordinateSteps {
    /// pᵢ = ∂L/∂qᵢ'.
    pub momentum: Id,
    /// d/dt pᵢ.
    pub(crate) momentum_dt: Id,
    /// ∂L/∂qᵢ.
    pub force: Id,
    /// Qᵢ (0 when there is none).
    pub(crate) generalized_force: Id,
    /// Eᵢ, meaning Eᵢ = 0.
    pub equation: Id,
}

/// A derivation: the steps, the mass matrix and the forcing.
#[derive(Clone, Debug)]
pub struct Derivation {
    pub steps: Vec<CoordinateSteps>,
    /// M, row-major n×n.
    pub mass: Vec<Vec<Id>>,
    /// f, with M q'' = f.
    pub forcing: Vec<Id>,
}

impl Derivation {
    /// The equations Eᵢ.
    pub fn equations(&self) -> Vec<Id> {
        self.steps.iter().map(|s| s.equation).collect()
    }
}

impl System {
    /// Derives the equations of motion. Fails when L contains an acceleration, a coordinate
    /// has no kinetic term or the mass matrix is singular everywhere.
    pub fn derive(&mut self) -> Result<Derivation, MechError> {
        self.check_first_order()?;
        let coords = self.coordinate_syms();
        let l = self.lagrangian;
        let mut steps = Vec::with_capacity(self.n());
        for (i, c) in self.coordinates.clone().iter().enumerate() {
            // Each step is built from the simplified previous one, so the simplifier's memo
            // tables carry over and nothing is expanded twice.
            let p = self.pool.try_diff(l, c.sym, 1)?;
            let p = self.simplify(p);
            let dp = self.pool.try_dt(p, &coords)?;
            let dp = self.simplify(dp);
            let dl = self.pool.try_diff(l, c.sym, 0)?;
            let dl = self.simplify(dl);
            let q = self.forces[i];
            let e1 = self.pool.sub(dp, dl);
            let e = self.pool.sub(e1, q);
            steps.push(CoordinateSteps {
                momentum: p,
                momentum_dt: dp,
                force: dl,
                generalized_force: q,
                equation: self.simplify(e),
            });
        }
        // M and f come from already simplified (expanded) expressions: differentiating by a
        // velocity or setting q'' = 0 cannot create products of sums or new trig pairs, so
        // collecting the constants is all the tidying they need.
        let positive = self.parameter_syms();
        let mut mass = Vec::with_capacity(self.n());
        for s in &steps {
            let row: Vec<Id> = coords
                .iter()
                .map(|&c| {
                    let d = self.pool.diff(s.momentum, c, 1);
                    self.pool.collect(d, &positive)
                })
                .collect();
            mass.push(row);
        }
        let zero = self.pool.zero();
        let no_acceleration: FxHashMap<_, _> = coords.iter().map(|&c| ((c, 2), zero)).collect();
        let forcing: Vec<Id> = steps
            .iter()
            .map(|s| {
                let e0 = self.pool.substitute(s.equation, &no_acceleration);
                let f = self.pool.neg(e0);
                self.pool.collect(f, &positive)
            })
            .collect();
        let d = Derivation {
            steps,
            mass,
            forcing,
        };
        self.check_mass_matrix(&d)?;
        if !self.constraints.is_empty() {
            let rows = self.constraint_rows();
            self.validate_constraints(&rows.a)?;
        }
        Ok(d)
    }

    /// Refuses a Lagrangian with an acceleration (or a higher derivative) of a coordinate: the
    /// derivation below treats L as a function of q, q' and t, and would drop such terms
    /// (`½ẋ² − ½x² + x ẍ` would give ẍ = −x, where its own higher-order equations give ẍ = x).
    pub fn check_first_order(&self) -> Result<(), MechError> {
        let coords = self.coordinate_syms();
        let vars = self.pool.variables(self.lagrangian);
        match vars.iter().find(|(s, o)| *o >= 2 && coords.contains(s)) {
            Some(&(s, o)) => Err(MechError::AccelerationInLagrangian {
                acceleration: format!("{}{}", self.pool.name(s), "'".repeat(o.into())),
            }),
            None => Ok(()),
        }
    }

    /// A zero row of M names the coordinate without a kinetic term; otherwise M must be
    /// invertible at some sampled point.
    fn check_mass_matrix(&self, d: &Derivation) -> Result<(), MechError> {
        for (i, row) in d.mass.iter().enumerate() {
            if row.iter().all(|&m| self.is_zero(m)) {
                return Err(MechError::NoKineticTerm {
                    name: self.coordinates[i].name.clone(),
                });
            }
        }
        let n = self.n();
        let entries: Vec<Id> = d.mass.iter().flatten().copied().collect();
        let prog = self.compile(&entries)?;
        let mut sampler = super::sample::Sampler::new(0x5eed_0002);
        let mut scratch = prog.scratch();
        // The first point where M is undefined, while it is undefined at every point.
        let mut nowhere = None;
        for k in 0..24 {
            let x = self.sample_point(&mut sampler);
            if prog.run(&x, &mut scratch).is_err() {
                if k == 0 {
                    nowhere = Some(x);
                }
                continue;
            }
            nowhere = None;
            let m = nalgebra::DMatrix::from_fn(n, n, |r, c| prog.output(r * n + c, &scratch));
            // The simulator and the checker apply the same rule (`mechanics::singular`).
            if !super::singular::is_singular(&m) {
                return Ok(());
            }
        }
        if let Some(x) = nowhere {
            return Err(self.undefined_at(&self.magnitudes(&entries)?, &x, "the mass matrix"));
        }
        Err(MechError::SingularMass {
            names: self
                .coordinates
                .iter()
                .map(|c| format!("{}'", c.name))
                .collect::<Vec<_>>()
                .join(", "),
        })
    }
}

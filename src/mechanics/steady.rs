//! Relative equilibria (steady motions): a cyclic coordinate φ moving uniformly while the
//! others stay put — circular orbits, the conical pendulum, a mass on a table through a hole,
//! steady precession. Through the Routhian R = L − Σ p_φ φ' with φ' eliminated at fixed
//! momenta p_φ: R is a Lagrangian for the other coordinates (p_φ a parameter), its equilibria
//! are the steady motions and its modes the small oscillations about them (with −R at rest
//! the effective potential; velocity-linear terms of R are gyroscopic). The momenta become
//! parameters of the reduced system and so, like every parameter, are taken as positive by
//! its simplifier: closed forms hold for p_φ > 0 (choose the sense of φ so).

use rustc_hash::FxHashMap;

use super::derive::Derivation;
use super::error::MechError;
use super::linalg::cramer;
use super::system::System;
use crate::expr::Id;

/// Why a system cannot be reduced by the coordinates asked for.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SteadyError {
    /// The system could not be analysed.
    #[error(transparent)]
    Mech(#[from] MechError),
    /// The coordinate is not cyclic, so its momentum is not conserved.
    #[error(
        "{name} is not cyclic: {reason}, so p_{name} is not conserved and there is no steady motion in it"
    )]
    NotCyclic {
        /// The coordinate.
        name: String,
        /// What makes it non-cyclic.
        reason: String,
    },
    /// A fixed momentum is named `p_<coordinate>`.
    #[error("`{key}` does not name a momentum")]
    NotMomentum {
        /// The name given.
        key: String,
    },
    /// The same momentum was fixed twice.
    #[error("{key} is given twice")]
    GivenTwice {
        /// The momentum.
        key: String,
    },
    /// Every coordinate was named: nothing is left to be at rest.
    #[error(
        "every coordinate is cyclic here: a steady motion needs at least one coordinate that stays put"
    )]
    NothingLeft,
    /// The cyclic velocities cannot be solved for from their momenta.
    #[error(
        "the momenta of {names} do not determine their velocities (their block of the mass matrix is singular)"
    )]
    SingularBlock {
        /// The coordinates.
        names: String,
    },
}

impl SteadyError {
    /// A stable kebab-case code.
    pub fn code(&self) -> &'static str {
        match self {
            SteadyError::Mech(e) => e.code(),
            SteadyError::NotCyclic { .. } => "not-cyclic",
            SteadyError::NotMomentum { .. } => "not-a-momentum",
            SteadyError::GivenTwice { .. } => "momentum-given-twice",
            SteadyError::NothingLeft => "nothing-left",
            SteadyError::SingularBlock { .. } => "singular-cyclic-block",
        }
    }

    /// What to do about it.
    pub fn help(&self) -> String {
        match self {
            SteadyError::Mech(e) => e.help(),
            SteadyError::NotCyclic { .. } => {
                "name only coordinates that L does not contain (and that no force, constraint or time dependence touches)".into()
            }
            SteadyError::NotMomentum { key } => {
                format!("write p_{key}: p_ and the cyclic coordinate")
            }
            SteadyError::GivenTwice { key } => format!("give {key} once"),
            SteadyError::NothingLeft => "leave at least one coordinate out".into(),
            SteadyError::SingularBlock { .. } => "choose independent cyclic coordinates".into(),
        }
    }
}

/// A system reduced by cyclic coordinates at fixed momenta.
#[derive(Clone, Debug)]
pub struct Reduced {
    /// The Routhian system: the other coordinates, with L = R; the momenta are parameters
    /// named `p_<coordinate>`.
    pub(crate) system: System,
    /// The cyclic coordinates' names, in the order asked.
    pub(crate) cyclic: Vec<String>,
    /// The momenta's parameter names, `p_<coordinate>`.
    pub momenta: Vec<String>,
    /// Each cyclic velocity in terms of the reduced system (its coordinates, velocities and
    /// parameters, momenta included), in `system`'s pool.
    pub(crate) rates: Vec<Id>,
}

impl System {
    /// The Routhian reduction by the coordinates `names`, which must be cyclic: L free of
    /// them, no generalized force on them, no constraint, no explicit time.
    pub fn routhian(&mut self, d: &Derivation, names: &[String]) -> Result<Reduced, SteadyError> {
        let idx = self.cyclic_indices(d, names)?;
        if idx.len() >= self.n() {
            return Err(SteadyError::NothingLeft);
        }
        let mut pool = self.pool.clone();
        let momenta: Vec<String> = idx
            .iter()
            .map(|&i| format!("p_{}", self.coordinates[i].name))
            .collect();
        let p_ids: Vec<Id> = momenta
            .iter()
            .map(|m| {
                let s = pool.symbol(m);
                pool.var(s, 0)
            })
            .collect();
        let rates = self.cyclic_rates(&mut pool, d, &idx, &p_ids, names)?;
        let map: FxHashMap<_, _> = idx
            .iter()
            .zip(&rates)
            .map(|(&i, &r)| ((self.coordinates[i].sym, 1), r))
            .collect();
        // R = L − Σ p v, with v eliminated.
        let mut terms = vec![pool.substitute(self.lagrangian, &map)];
        for (&p, &v) in p_ids.iter().zip(&rates) {
            let pv = pool.mul(p, v);
            terms.push(pool.neg(pv));
        }
        let r = pool.sum(terms);
        let r = pool.simplify(r, &self.parameter_syms());
        let keep: Vec<usize> = (0..self.n()).filter(|i| !idx.contains(i)).collect();
        let coords = keep.iter().map(|&i| self.coordinates[i].clone()).collect();
        let mut system = System::from_parts(pool, coords, r);
        let forces: Vec<Id> = keep
            .iter()
            .map(|&i| system.pool.substitute(self.forces[i], &map))
            .collect();
        system.forces = forces;
        system.collect_parameters();
        for p in &mut system.parameters {
            if let Some(orig) = self.parameters.iter().find(|o| o.sym == p.sym) {
                p.dimension = orig.dimension;
                p.range = orig.range;
            }
        }
        Ok(Reduced {
            system,
            cyclic: idx
                .iter()
                .map(|&i| self.coordinates[i].name.clone())
                .collect(),
            momenta,
            rates,
        })
    }

    /// The cyclic velocities at fixed momenta: p = A v + p|ᵥ₌₀ with A the cyclic block of M,
    /// so v = A⁻¹ (p − p|ᵥ₌₀), simplified (in `pool`, a copy of the system's).
    fn cyclic_rates(
        &self,
        pool: &mut crate::expr::Pool,
        d: &Derivation,
        idx: &[usize],
        p_ids: &[Id],
        names: &[String],
    ) -> Result<Vec<Id>, SteadyError> {
        let zero = pool.zero();
        let still: FxHashMap<_, _> = idx
            .iter()
            .map(|&i| ((self.coordinates[i].sym, 1), zero))
            .collect();
        let a: Vec<Vec<Id>> = idx
            .iter()
            .map(|&i| idx.iter().map(|&j| d.mass[i][j]).collect())
            .collect();
        let b: Vec<Id> = idx
            .iter()
            .zip(p_ids)
            .map(|(&i, &p)| {
                let p0 = pool.substitute(d.steps[i].momentum, &still);
                pool.sub(p, p0)
            })
            .collect();
        let solved = cramer(pool, &a, &b).ok_or_else(|| SteadyError::SingularBlock {
            names: names.join(", "),
        })?;
        let positive = self.parameter_syms();
        let rates = solved
            .into_iter()
            .map(|(num, den)| {
                let r = pool.div(num, den);
                pool.simplify(r, &positive)
            })
            .collect();
        Ok(rates)
    }

    /// The indices of `names`, each checked to be a cyclic coordinate.
    fn cyclic_indices(
        &mut self,
        d: &Derivation,
        names: &[String],
    ) -> Result<Vec<usize>, SteadyError> {
        let time = self.pool.time();
        let dldt = self.pool.diff(self.lagrangian, time, 0);
        let mut idx = Vec::with_capacity(names.len());
        for name in names {
            let norm = crate::expr::names::normalize(name.trim());
            let i = self
                .coordinates
                .iter()
                .position(|c| c.name == norm)
                .ok_or_else(|| MechError::UnknownCoordinate { name: name.clone() })?;
            let not = |reason: &str| SteadyError::NotCyclic {
                name: norm.clone(),
                reason: reason.into(),
            };
            if !self.is_zero(d.steps[i].force) {
                return Err(not("L depends on it"));
            }
            if !self.is_zero(self.forces[i]) {
                return Err(not("a generalized force acts on it"));
            }
            if !self.constraints.is_empty() {
                return Err(not("the system has constraints, which may involve it"));
            }
            if !self.is_zero(dldt) {
                return Err(not("L depends on time explicitly"));
            }
            if !idx.contains(&i) {
                idx.push(i);
            }
        }
        Ok(idx)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::expr::read_expr;

    #[test]
    fn central_force_routhian_is_the_effective_potential_lagrangian() {
        let mut sys =
            System::from_lagrangian("1/2*m*(r'^2 + r^2*phi'^2) + k/r", &["r", "phi"]).unwrap();
        let d = sys.derive().unwrap();
        let mut red = sys.routhian(&d, &["phi".into()]).unwrap();
        assert_eq!(red.momenta, vec!["p_phi".to_string()]);
        assert_eq!(red.system.n(), 1);
        let ctx = red.system.open_context();
        let want = read_expr(
            "1/2*m*r'^2 + k/r - p_phi^2/(2*m*r^2)",
            &ctx,
            &mut red.system.pool,
        )
        .unwrap();
        let diff = red.system.pool.sub(red.system.lagrangian, want);
        assert!(red.system.is_zero(diff));
        let rate = read_expr("p_phi/(m*r^2)", &ctx, &mut red.system.pool).unwrap();
        let diff = red.system.pool.sub(red.rates[0], rate);
        assert!(red.system.is_zero(diff));
    }

    #[test]
    fn refusals_name_their_reason() {
        let mut sys = System::from_lagrangian("1/2*m*x'^2 - k*x^2", &["x"]).unwrap();
        let d = sys.derive().unwrap();
        let e = sys.routhian(&d, &["x".into()]).unwrap_err();
        assert_eq!(e.code(), "not-cyclic");
        let mut free = System::from_lagrangian("1/2*m*x'^2", &["x"]).unwrap();
        let d = free.derive().unwrap();
        let e = free.routhian(&d, &["x".into()]).unwrap_err();
        assert_eq!(e, SteadyError::NothingLeft);
        let mut timed =
            System::from_lagrangian("1/2*m*(x'^2 + y'^2) - k*y^2*cos(t)", &["x", "y"]).unwrap();
        let d = timed.derive().unwrap();
        let e = timed.routhian(&d, &["x".into()]).unwrap_err();
        assert!(e.to_string().contains("time"), "{e}");
    }
}

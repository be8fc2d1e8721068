//! Forces given as a vector at a point: F applied at r(q, t) does virtual work F·δr, so its
//! generalized force is Qᵢ = F·∂r/∂qᵢ (added to the system's `forces`).

use super::error::MechError;
use super::rigid::{RigidError, rate_in};
use crate::expr::{Id, Pool, Sym};

/// A force `vector` applied at the point `at` (both 2 or 3 components, in the same frame).
#[derive(Clone, Debug)]
pub struct PointForce {
    pub(crate) at: Vec<Id>,
    pub(crate) vector: Vec<Id>,
}

impl PointForce {
    /// A point force, checked: matching dimensions of 2 or 3, a point free of velocities, a
    /// force free of accelerations.
    pub fn new(pool: &Pool, at: Vec<Id>, vector: Vec<Id>) -> Result<PointForce, RigidError> {
        if !(2..=3).contains(&at.len()) {
            return Err(RigidError::Components {
                what: "the point of application",
                given: at.len(),
            });
        }
        if vector.len() != at.len() {
            return Err(RigidError::ForceDimension {
                vector: vector.len(),
                at: at.len(),
            });
        }
        for &x in &at {
            if let Some(v) = rate_in(pool, x, 1) {
                return Err(RigidError::VelocityInPosition {
                    what: "the point of application",
                    velocity: v,
                });
            }
        }
        for &f in &vector {
            if let Some(a) = rate_in(pool, f, 2) {
                return Err(RigidError::ForceWithAcceleration { acceleration: a });
            }
        }
        Ok(PointForce { at, vector })
    }

    /// Qᵢ = F·∂r/∂qᵢ, one per coordinate.
    pub fn generalized(&self, pool: &mut Pool, coords: &[Sym]) -> Vec<Id> {
        coords
            .iter()
            .map(|&q| {
                let terms: Vec<Id> = self
                    .at
                    .iter()
                    .zip(&self.vector)
                    .map(|(&x, &f)| {
                        let dx = pool.diff(x, q, 0);
                        pool.mul(f, dx)
                    })
                    .collect();
                pool.sum(terms)
            })
            .collect()
    }
}

impl super::System {
    /// Adds a force `vector` applied at the point `at` (expressions in this system's
    /// symbols) to the generalized forces: Qᵢ += F·∂r/∂qᵢ.
    pub fn add_point_force(&mut self, at: &[&str], vector: &[&str]) -> Result<(), MechError> {
        let ctx = self.open_context();
        let read = |sys: &mut super::System, texts: &[&str], what: &str| {
            texts
                .iter()
                .map(|t| sys.read(t, what, &ctx))
                .collect::<Result<Vec<Id>, MechError>>()
        };
        let at = read(self, at, "the point of application")?;
        let vector = read(self, vector, "the force vector")?;
        let force = PointForce::new(&self.pool, at, vector)?;
        self.apply_point_force(&force);
        self.collect_parameters();
        Ok(())
    }

    /// Adds an already-built point force to the generalized forces.
    pub fn apply_point_force(&mut self, force: &PointForce) {
        let coords = self.coordinate_syms();
        let q = force.generalized(&mut self.pool, &coords);
        let none: Vec<Sym> = Vec::new();
        for (slot, qi) in self.forces.iter_mut().zip(q) {
            let sum = self.pool.add(*slot, qi);
            *slot = self.pool.simplify(sum, &none);
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::mechanics::System;

    #[test]
    fn a_force_on_a_bead_on_a_helix_projects_on_its_tangent() {
        // r = (R cos s, R sin s, c s), F = (0, 0, −m g): Q_s = F·∂r/∂s = −m g c.
        let mut s = System::from_lagrangian("1/2*m*(R^2 + c^2)*s'^2", &["s"]).unwrap();
        s.add_point_force(&["R*cos(s)", "R*sin(s)", "c*s"], &["0", "0", "-m*g"])
            .unwrap();
        let ctx = s.open_context();
        let want = s.read("-m*g*c", "test", &ctx).unwrap();
        let d = s.pool.sub(s.forces[0], want);
        assert!(s.is_zero(d));
    }

    #[test]
    fn ill_posed_point_forces_are_refused() {
        let mut s = System::from_lagrangian("1/2*x'^2", &["x"]).unwrap();
        let e = s.add_point_force(&["x", "0"], &["1"]).unwrap_err();
        assert_eq!(e.code(), "force-dimension");
        let e = s.add_point_force(&["x'", "0"], &["1", "0"]).unwrap_err();
        assert_eq!(e.code(), "velocity-in-position");
        let e = s.add_point_force(&["x", "0"], &["x''", "0"]).unwrap_err();
        assert_eq!(e.code(), "force-with-acceleration");
        let e = s.add_point_force(&["x"], &["1"]).unwrap_err();
        assert_eq!(e.code(), "bad-components");
    }
}

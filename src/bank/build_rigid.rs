//! Reading rigid bodies (`kind = "rigid"` in `[[bodies]]`) and forces given as vectors at a
//! point (`[[point_forces]]`) from a problem file; the mechanics is in
//! `mechanics/rigid.rs`.

use crate::expr::Pool;
use crate::mechanics::System;
use crate::mechanics::bodies::Body;
use crate::mechanics::point_force::PointForce;
use crate::mechanics::rigid::RigidSpec;

use super::FindingCode;
use super::build_reader::Reader;
use super::finding::{Finding, line_of};
use super::schema::{BodySpec, ProblemFile};

impl Reader<'_> {
    /// A rigid body: the file's fields read into a [`RigidSpec`], checked by the library
    /// (the command line's `--rigid` goes through the same checker).
    pub(super) fn rigid(
        &self,
        b: &BodySpec,
        line: usize,
        pool: &mut Pool,
    ) -> Result<Body, Finding> {
        let one = |pool: &mut Pool, v: &Option<String>, what| {
            v.as_ref()
                .map(|x| self.read(pool, x, line, what))
                .transpose()
        };
        let all = |pool: &mut Pool, v: &Option<Vec<String>>, what| {
            v.as_ref()
                .map(|x| self.read_all(pool, x, line, what))
                .transpose()
        };
        let tensor = match &b.tensor {
            Some(rows) => Some(
                rows.iter()
                    .map(|r| self.read_all(pool, r, line, "tensor"))
                    .collect::<Result<Vec<_>, _>>()?,
            ),
            None => None,
        };
        let spec = RigidSpec {
            mass: one(pool, &b.mass, "mass")?,
            position: all(pool, &b.position, "centre of mass")?,
            inertia: one(pool, &b.inertia, "inertia")?,
            moments: all(pool, &b.moments, "moments")?,
            tensor,
            angle: one(pool, &b.angle, "angle")?,
            omega_body: all(pool, &b.omega_body, "omega_body")?,
            euler: all(pool, &b.euler, "euler")?,
        };
        let r = spec.build(pool).map_err(|e| {
            self.b
                .fail(line, FindingCode::BadBody, format!("{e} ({})", e.help()))
        })?;
        Ok(Body::Rigid(Box::new(r)))
    }

    /// The `[[point_forces]]`, added to the system's generalized forces.
    pub(super) fn point_forces(
        &self,
        pf: &ProblemFile,
        system: &mut System,
    ) -> Result<(), Finding> {
        for spec in &pf.point_forces {
            let line = line_of(self.b.text, spec.span().start);
            let f = spec.get_ref();
            let at = self.read_all(&mut system.pool, &f.at, line, "point of application")?;
            let vector = self.read_all(&mut system.pool, &f.vector, line, "force vector")?;
            let force = PointForce::new(&system.pool, at, vector).map_err(|e| {
                self.b
                    .fail(line, FindingCode::BadForce, format!("{e} ({})", e.help()))
            })?;
            system.apply_point_force(&force);
        }
        Ok(())
    }
}

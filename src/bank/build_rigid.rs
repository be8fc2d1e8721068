//! Reading rigid bodies (`kind = "rigid"` in `[[bodies]]`) and forces given as vectors at a
//! point (`[[point_forces]]`) from a problem file; the mechanics is in
//! `mechanics/rigid.rs`.

use crate::expr::{Id, Pool};
use crate::mechanics::System;
use crate::mechanics::bodies::Body;
use crate::mechanics::point_force::PointForce;
use crate::mechanics::rigid::{Inertia, Orientation, Rigid};

use super::build_reader::Reader;
use super::finding::{Finding, line_of};
use super::schema::{BodySpec, ProblemFile};

impl Reader<'_> {
    /// A rigid body: mass, centre of mass, inertia (`inertia`, `moments` or `tensor`) and
    /// exactly one of `angle`, `omega_body`, `euler`.
    pub(super) fn rigid(
        &self,
        b: &BodySpec,
        line: usize,
        pool: &mut Pool,
    ) -> Result<Body, Finding> {
        let bad = |m: String| self.b.fail(line, "bad-body", m);
        let (Some(m), Some(pos)) = (&b.mass, &b.position) else {
            return Err(bad(
                "a rigid body needs `mass` and `position` (its centre of mass)".into(),
            ));
        };
        let mass = self.read(pool, m, line, "mass")?;
        let position = self.read_all(pool, pos, line, "centre of mass")?;
        let inertia = self.inertia(b, line, pool)?;
        let given = [b.angle.is_some(), b.omega_body.is_some(), b.euler.is_some()];
        if given.iter().filter(|&&g| g).count() != 1 {
            return Err(bad(
                "a rigid body needs exactly one of `angle` (planar), `omega_body` or `euler`"
                    .into(),
            ));
        }
        let orientation = if let Some(a) = &b.angle {
            Orientation::Planar(self.read(pool, a, line, "angle")?)
        } else if let Some(w) = &b.omega_body {
            Orientation::BodyRates(self.three(pool, w, line, "omega_body")?)
        } else if let Some(e) = &b.euler {
            Orientation::Euler(self.three(pool, e, line, "euler")?)
        } else {
            return Err(bad("a rigid body needs an orientation".into()));
        };
        let r = Rigid::new(pool, mass, position, inertia, orientation)
            .map_err(|e| bad(format!("{e} ({})", e.help())))?;
        Ok(Body::Rigid(Box::new(r)))
    }

    /// Exactly one of `inertia` (one moment), `moments` (principal) or `tensor` (3×3).
    fn inertia(&self, b: &BodySpec, line: usize, pool: &mut Pool) -> Result<Inertia, Finding> {
        let bad = |m: String| self.b.fail(line, "bad-body", m);
        match (&b.inertia, &b.moments, &b.tensor) {
            (Some(i), None, None) => Ok(Inertia::Principal(vec![
                self.read(pool, i, line, "inertia")?,
            ])),
            (None, Some(m), None) => {
                Ok(Inertia::Principal(self.read_all(pool, m, line, "moments")?))
            }
            (None, None, Some(rows)) => {
                if rows.len() != 3 || rows.iter().any(|r| r.len() != 3) {
                    return Err(bad("`tensor` has 3 rows of 3 entries".into()));
                }
                let mut t = [[pool.zero(); 3]; 3];
                for (r, row) in rows.iter().enumerate() {
                    t[r] = self.three(pool, row, line, "tensor")?;
                }
                Ok(Inertia::Tensor(t))
            }
            _ => Err(bad(
                "a rigid body needs exactly one of `inertia` (planar), `moments` or `tensor`"
                    .into(),
            )),
        }
    }

    /// Three expressions (a list of another length is a finding naming `what`).
    fn three(
        &self,
        pool: &mut Pool,
        srcs: &[String],
        line: usize,
        what: &str,
    ) -> Result<[Id; 3], Finding> {
        let v = self.read_all(pool, srcs, line, what)?;
        <[Id; 3]>::try_from(v).map_err(|v| {
            self.b.fail(
                line,
                "bad-body",
                format!("`{what}` has {} entries (3 are needed)", v.len()),
            )
        })
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
                    .fail(line, "bad-force", format!("{e} ({})", e.help()))
            })?;
            system.apply_point_force(&force);
        }
        Ok(())
    }
}

//! What building one problem file shares ([`Builder`]: the file, its text, the problem id and
//! a finding at a line) and the reading of expressions, bodies and potentials in the declared
//! symbols' context ([`Reader`]).

use crate::expr::{Context, Id, Pool, read_expr};
use crate::mechanics::bodies::{Anchor, Body, Potential};

use super::FindingCode;
use super::finding::{Finding, line_of};
use super::schema::{AnchorSpec, BodySpec, PotentialSpec, ProblemFile};

/// What every finding of one file shares: the file, its text and the problem id.
pub(super) struct Builder<'a> {
    pub(super) file: &'a str,
    pub(super) text: &'a str,
    pub(super) id: String,
    pub(super) id_line: usize,
}

impl Builder<'_> {
    /// A finding about the problem (not a part) at `line`.
    pub(super) fn fail(&self, line: usize, code: FindingCode, message: String) -> Finding {
        Finding {
            file: self.file.to_string(),
            problem: Some(self.id.clone()),
            part: None,
            line,
            code,
            message,
        }
    }
}

/// Reads the expressions of bodies and potentials in the declared symbols' context.
pub(super) struct Reader<'a> {
    pub(super) b: &'a Builder<'a>,
    pub(super) ctx: Context,
}

impl Reader<'_> {
    /// Reads each of `srcs` (see [`read`](Self::read)).
    pub(super) fn read_all(
        &self,
        pool: &mut Pool,
        srcs: &[String],
        line: usize,
        what: &str,
    ) -> Result<Vec<Id>, Finding> {
        srcs.iter()
            .map(|x| self.read(pool, x, line, what))
            .collect()
    }

    /// Reads `src` (the file's `what` at `line`); an unknown name is `undeclared-symbol`.
    pub(super) fn read(
        &self,
        pool: &mut Pool,
        src: &str,
        line: usize,
        what: &str,
    ) -> Result<Id, Finding> {
        read_expr(src, &self.ctx, pool).map_err(|e| {
            self.b.fail(
                line,
                if matches!(e.kind, crate::expr::ParseErrorKind::UnknownName { .. }) {
                    FindingCode::UndeclaredSymbol
                } else {
                    FindingCode::Unreadable
                },
                format!("{what} `{src}`: {e} ({})", e.help()),
            )
        })
    }

    /// The `[[bodies]]`: point masses, rotors and rigid bodies.
    pub(super) fn bodies(&self, pf: &ProblemFile, pool: &mut Pool) -> Result<Vec<Body>, Finding> {
        let mut bodies = Vec::new();
        for spec in &pf.bodies {
            let line = line_of(self.b.text, spec.span().start);
            bodies.push(self.body(spec.get_ref(), line, pool)?);
        }
        Ok(bodies)
    }

    fn body(&self, b: &BodySpec, line: usize, pool: &mut Pool) -> Result<Body, Finding> {
        let bad = |m: String| self.b.fail(line, FindingCode::BadBody, m);
        match b.kind.as_str() {
            "point" => {
                let (Some(m), Some(pos)) = (&b.mass, &b.position) else {
                    return Err(bad("a point body needs `mass` and `position`".into()));
                };
                if !(2..=3).contains(&pos.len()) {
                    return Err(bad("a position has 2 or 3 components".into()));
                }
                let mass = self.read(pool, m, line, "mass")?;
                let position = pos
                    .iter()
                    .map(|x| self.read(pool, x, line, "position"))
                    .collect::<Result<_, _>>()?;
                Ok(Body::Point { mass, position })
            }
            "rotor" => {
                let (Some(i), Some(a)) = (&b.inertia, &b.angle) else {
                    return Err(bad("a rotor needs `inertia` and `angle`".into()));
                };
                let inertia = self.read(pool, i, line, "inertia")?;
                let angle = self.read(pool, a, line, "angle")?;
                Ok(Body::Rotor { inertia, angle })
            }
            "rigid" => self.rigid(b, line, pool),
            other => Err(bad(format!(
                "unknown body kind `{other}` (use point, rotor or rigid)"
            ))),
        }
    }

    /// The `[[potentials]]`: gravity, springs between bodies or anchors, explicit V.
    pub(super) fn potentials(
        &self,
        pf: &ProblemFile,
        bodies: &[Body],
        pool: &mut Pool,
    ) -> Result<Vec<Potential>, Finding> {
        let mut potentials = Vec::new();
        for spec in &pf.potentials {
            let line = line_of(self.b.text, spec.span().start);
            potentials.push(self.potential(spec.get_ref(), line, bodies.len(), pool)?);
        }
        Ok(potentials)
    }

    fn potential(
        &self,
        p: &PotentialSpec,
        line: usize,
        n_bodies: usize,
        pool: &mut Pool,
    ) -> Result<Potential, Finding> {
        let bad = |m: String| self.b.fail(line, FindingCode::BadPotential, m);
        match p.kind.as_str() {
            "gravity" => {
                let g = self.read(pool, p.g.as_deref().unwrap_or("g"), line, "gravity")?;
                let axis = match p.axis.as_deref().unwrap_or("y") {
                    "x" => 0,
                    "y" => 1,
                    "z" => 2,
                    other => return Err(bad(format!("gravity axis `{other}` (use x, y or z)"))),
                };
                Ok(Potential::Gravity { g, axis })
            }
            "spring" => {
                let k = self.read(pool, p.k.as_deref().unwrap_or("k"), line, "spring constant")?;
                let natural = self.read(
                    pool,
                    p.natural.as_deref().unwrap_or("0"),
                    line,
                    "natural length",
                )?;
                let a = self.anchor(&p.from, line, n_bodies, pool)?;
                let b = self.anchor(&p.to, line, n_bodies, pool)?;
                Ok(Potential::Spring { k, natural, a, b })
            }
            "explicit" => {
                let Some(v) = &p.v else {
                    return Err(bad("an explicit potential needs `V`".into()));
                };
                Ok(Potential::Explicit(self.read(
                    pool,
                    v,
                    line,
                    "potential",
                )?))
            }
            other => Err(bad(format!(
                "unknown potential kind `{other}` (use gravity, spring or explicit)"
            ))),
        }
    }

    /// One end of a spring: a body number (1-based) or a fixed point.
    fn anchor(
        &self,
        a: &Option<AnchorSpec>,
        line: usize,
        n_bodies: usize,
        pool: &mut Pool,
    ) -> Result<Anchor, Finding> {
        match a {
            Some(AnchorSpec::Body(i)) if *i >= 1 && *i <= n_bodies => Ok(Anchor::Body(i - 1)),
            Some(AnchorSpec::Body(i)) => Err(self.b.fail(
                line,
                FindingCode::BadPotential,
                format!("spring end {i} is not a body number"),
            )),
            Some(AnchorSpec::Point(v)) => Ok(Anchor::Fixed(
                v.iter()
                    .map(|x| self.read(pool, x, line, "anchor"))
                    .collect::<Result<_, _>>()?,
            )),
            None => Err(self.b.fail(
                line,
                FindingCode::BadPotential,
                "a spring needs `from` and `to`".into(),
            )),
        }
    }
}

//! Building a problem from a parsed TOML file: coordinates, parameters, the system from the
//! Lagrangian or the bodies and potentials, assumptions and parts. Every error is a finding
//! with its line. This file holds the entry point and the problem-level steps; the shared
//! [`Builder`] and the expression [`Reader`] live in `build_reader.rs`, parts and id checks in
//! `build_part.rs`.

use crate::expr::{Context, Dimension, Dimensions, Pool, read_expr};
use crate::mechanics::System;
use crate::mechanics::system::{Coordinate, Parameter};
use crate::problem::Assumption;
use crate::problem::{Part, Problem};

use super::FindingCode;
use super::build_part::{build_part, check_id, reserved};
use super::build_reader::{Builder, Reader};
use super::finding::{Finding, line_of};
use super::schema::ProblemFile;

/// Builds a problem from a parsed file. Every error is a finding with a line.
pub fn build(file: &str, text: &str, pf: ProblemFile) -> Result<Problem, Finding> {
    check_id(pf.id.get_ref(), "problem").map_err(|why| Finding {
        file: file.to_string(),
        problem: None,
        part: None,
        line: line_of(text, pf.id.span().start),
        code: FindingCode::BadId,
        message: why,
    })?;
    let b = Builder {
        file,
        text,
        id: pf.id.get_ref().clone(),
        id_line: line_of(text, pf.id.span().start),
    };
    if pf.coordinates.is_empty() {
        return Err(b.fail(
            b.id_line,
            FindingCode::NoCoordinates,
            "the problem declares no coordinate".into(),
        ));
    }
    let mut pool = Pool::new();
    let mut dims = Dimensions::new();
    let mut coordinates = b.coordinates(&pf, &mut pool, &mut dims)?;
    let mut parameters = b.parameters(&pf, &mut pool, &mut dims)?;
    super::build_domain::domains(&b, &pf, &mut pool, &dims, &mut coordinates, &mut parameters)?;
    let reader = Reader {
        b: &b,
        ctx: system_context(&coordinates, &parameters),
    };
    let bodies = reader.bodies(&pf, &mut pool)?;
    let potentials = reader.potentials(&pf, &bodies, &mut pool)?;
    let stated = match &pf.lagrangian {
        Some(l) => Some(reader.read(
            &mut pool,
            l.get_ref(),
            line_of(text, l.span().start),
            "the Lagrangian",
        )?),
        None => None,
    };
    let lagrangian_line = lagrangian_line(text, &pf, b.id_line);
    let mut system = if !bodies.is_empty() {
        System::from_bodies(pool, coordinates, &bodies, &potentials)
    } else if let Some(l) = stated {
        System::from_parts(pool, coordinates, l)
    } else {
        return Err(b.fail(
            b.id_line,
            FindingCode::NoSystem,
            "give `lagrangian`, or `bodies` (and `potentials`)".into(),
        ));
    };
    // Declared parameters keep their ranges and dimensions; only they may appear.
    let mut declared = parameters;
    for p in &system.parameters {
        if !declared.iter().any(|d| d.sym == p.sym) {
            declared.push(p.clone());
        }
    }
    system.parameters = declared;
    system.check_first_order().map_err(|e| {
        b.fail(
            lagrangian_line,
            FindingCode::Engine(e.code()),
            e.to_string(),
        )
    })?;
    let assumptions = b.forces_constraints_assumptions(&pf, &mut system)?;
    // Before the parts, whose answers and hints may use the defined names.
    b.definitions(&pf, &mut system, &dims)?;
    // After `forces`, which set Qᵢ: a point force adds F·∂r/∂qᵢ to them.
    reader.point_forces(&pf, &mut system)?;
    let mut parts = b.parts(&pf, &mut system)?;
    super::build_numeric::numeric(&b, &pf, &mut parts, &system, &dims)?;
    Ok(Problem {
        // First: it reads `pf` and `system`, which the fields below move.
        simulation: b.simulation(&pf, &system)?,
        variants: b.variants(&pf, &system)?,
        file: file.to_string(),
        id: b.id,
        title: pf.title,
        source: pf.source,
        statement: pf.statement,
        axes: pf.axes.trim().to_string(),
        system,
        dims,
        assumptions,
        parts,
        stated_lagrangian: stated,
        lagrangian_line,
    })
}

/// The closed context the system's own text (L, positions, potentials) is read in: it may
/// be larger than an answer (a bicycle's T is 24 kB).
fn system_context(coordinates: &[Coordinate], parameters: &[Parameter]) -> Context {
    Context::new()
        .with_coordinates(coordinates.iter().map(|c| c.name.as_str()))
        .with_parameters(parameters.iter().map(|p| p.name.as_str()))
        .with_max_input(crate::expr::error::MAX_SYSTEM_INPUT_BYTES)
}

/// The line of the `lagrangian` key, else of the first body, else of the id.
fn lagrangian_line(text: &str, pf: &ProblemFile, id_line: usize) -> usize {
    pf.lagrangian
        .as_ref()
        .map(|l| line_of(text, l.span().start))
        .or_else(|| pf.bodies.first().map(|b| line_of(text, b.span().start)))
        .unwrap_or(id_line)
}

impl Builder<'_> {
    /// The declared coordinates, with their dimensions recorded in `dims`.
    fn coordinates(
        &self,
        pf: &ProblemFile,
        pool: &mut Pool,
        dims: &mut Dimensions,
    ) -> Result<Vec<Coordinate>, Finding> {
        let mut coordinates: Vec<Coordinate> = Vec::new();
        for c in &pf.coordinates {
            let name = crate::expr::names::normalize(&c.name);
            if let Err(why) = crate::mechanics::system::check_coordinate_name(&name) {
                return Err(self.fail(self.id_line, FindingCode::ReservedName, why.to_string()));
            }
            if coordinates.iter().any(|x| x.name == name) {
                return Err(self.fail(
                    self.id_line,
                    FindingCode::DuplicateCoordinate,
                    format!("coordinate `{name}` is declared twice"),
                ));
            }
            let d = match &c.dimension {
                Some(d) => Dimension::parse(d).map_err(|e| {
                    self.fail(self.id_line, FindingCode::BadDimension, e.to_string())
                })?,
                None if c.periodic => Dimension::NONE,
                None => Dimension::new(0, 1, 0),
            };
            dims.set_coordinate(&name, d);
            let range = match c.range.as_deref() {
                Some(&[a, b]) if a < b && a.is_finite() && b.is_finite() => (a, b),
                Some(r) => {
                    return Err(self.fail(
                        self.id_line,
                        FindingCode::BadRange,
                        format!(
                            "coordinate `{name}` has range {r:?}; it needs [low, high] with low < high"
                        ),
                    ));
                }
                None if c.periodic => (-std::f64::consts::PI, std::f64::consts::PI),
                None => crate::mechanics::system::DEFAULT_COORDINATE_RANGE,
            };
            coordinates.push(Coordinate {
                sym: pool.symbol(&name),
                name,
                periodic: c.periodic,
                range,
                domain: crate::mechanics::system::Domain::ANY,
            });
        }
        Ok(coordinates)
    }

    /// The declared parameters, with their dimensions recorded in `dims`.
    fn parameters(
        &self,
        pf: &ProblemFile,
        pool: &mut Pool,
        dims: &mut Dimensions,
    ) -> Result<Vec<Parameter>, Finding> {
        let mut parameters = Vec::new();
        for (name, p) in &pf.parameters {
            let name = crate::expr::names::normalize(name);
            if let Some(why) = reserved(&name) {
                return Err(self.fail(
                    self.id_line,
                    FindingCode::ReservedName,
                    format!("parameter `{name}`: {why}; rename the parameter"),
                ));
            }
            if pf
                .coordinates
                .iter()
                .any(|c| crate::expr::names::normalize(&c.name) == name)
            {
                return Err(self.fail(
                    self.id_line,
                    FindingCode::ReservedName,
                    format!("parameter `{name}` is also declared as a coordinate"),
                ));
            }
            let d = Dimension::parse(&p.dimension).map_err(|e| {
                self.fail(
                    self.id_line,
                    FindingCode::BadDimension,
                    format!("parameter `{name}`: {e}"),
                )
            })?;
            let (lo, hi) = match p.range[..] {
                [lo, hi] if lo > 0.0 && hi > lo && hi.is_finite() => (lo, hi),
                _ => {
                    return Err(self.fail(
                        self.id_line,
                        FindingCode::BadRange,
                        format!(
                            "parameter `{name}` has range {:?}; it needs a positive range [low, high]",
                            p.range
                        ),
                    ));
                }
            };
            dims.set(&name, d);
            parameters.push(Parameter {
                sym: pool.symbol(&name),
                name,
                dimension: Some(d),
                range: (lo, hi),
                domain: crate::mechanics::system::Domain::ANY,
            });
        }
        Ok(parameters)
    }

    /// Generalized forces, constraints and assumptions, read in the built system's context.
    fn forces_constraints_assumptions(
        &self,
        pf: &ProblemFile,
        system: &mut System,
    ) -> Result<Vec<Assumption>, Finding> {
        let ctx = system.context();
        for (i, f) in pf.forces.iter().enumerate() {
            if i >= system.n() {
                return Err(self.fail(
                    self.id_line,
                    FindingCode::BadForce,
                    "more forces than coordinates".into(),
                ));
            }
            system.forces[i] = read_expr(f, &ctx, &mut system.pool).map_err(|e| {
                self.fail(
                    self.id_line,
                    FindingCode::Unreadable,
                    format!("force `{f}`: {e}"),
                )
            })?;
        }
        for c in &pf.constraints {
            system.add_constraint(c).map_err(|e| {
                self.fail(
                    self.id_line,
                    FindingCode::BadConstraint,
                    format!("constraint `{c}`: {e}"),
                )
            })?;
        }
        // The multipliers are lambda1, lambda2, …: a parameter of that name would merge with one.
        system
            .check_multiplier_names(system.constraints.len())
            .map_err(|e| self.fail(self.id_line, FindingCode::Engine(e.code()), e.to_string()))?;
        let mut assumptions = Vec::new();
        for a in &pf.assume {
            assumptions.push(
                Assumption::parse(a, &ctx, system)
                    .map_err(|e| self.fail(self.id_line, FindingCode::BadAssumption, e))?,
            );
        }
        Ok(assumptions)
    }

    /// The parts, each a finding of its own on error; two parts may not share an id.
    fn parts(&self, pf: &ProblemFile, system: &mut System) -> Result<Vec<Part>, Finding> {
        let mut parts = Vec::new();
        let ctx = system.context();
        for sp in &pf.parts {
            let line = line_of(self.text, sp.span().start);
            if let Err(why) = check_id(&sp.get_ref().id, "part") {
                return Err(self.fail(line, FindingCode::BadId, why));
            }
            let in_part = |(code, m)| Finding {
                part: Some(sp.get_ref().id.clone()),
                ..self.fail(line, code, m)
            };
            let mut part = build_part(sp.get_ref(), line, system).map_err(in_part)?;
            for a in &sp.get_ref().assume {
                let a = Assumption::parse(a, &ctx, system)
                    .map_err(|e| in_part((FindingCode::BadAssumption, e)))?;
                part.assumptions.push(a);
            }
            parts.push(part);
        }
        let mut seen = std::collections::BTreeSet::new();
        for p in &parts {
            if !seen.insert(p.id.clone()) {
                return Err(Finding {
                    part: Some(p.id.clone()),
                    ..self.fail(
                        p.line,
                        FindingCode::DuplicatePart,
                        format!("two parts are called `{}`", p.id),
                    )
                });
            }
        }
        Ok(parts)
    }
}

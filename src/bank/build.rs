//! Building a problem from a parsed TOML file: coordinates, parameters, the system from the
//! Lagrangian or the bodies and potentials, assumptions and parts. Every error is a finding
//! with its line.

use crate::expr::{Context, Dimension, Dimensions, Id, Pool, read_expr};
use crate::mechanics::System;
use crate::mechanics::bodies::{Anchor, Body, Potential};
use crate::mechanics::system::{Coordinate, Parameter};
use crate::problem::Assumption;
use crate::problem::{Part, PartKind, Problem, Quantity};

use super::finding::{Finding, line_of};
use super::schema::{AnchorSpec, AnswerSpec, BodySpec, PartSpec, PotentialSpec, ProblemFile};

/// Builds a problem from a parsed file. Every error is a finding with a line.
pub fn build(file: &str, text: &str, pf: ProblemFile) -> Result<Problem, Finding> {
    check_id(pf.id.get_ref(), "problem").map_err(|why| Finding {
        file: file.to_string(),
        problem: None,
        part: None,
        line: line_of(text, pf.id.span().start),
        code: "bad-id",
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
            "no-coordinates",
            "the problem declares no coordinate".into(),
        ));
    }
    let mut pool = Pool::new();
    let mut dims = Dimensions::new();
    let coordinates = b.coordinates(&pf, &mut pool, &mut dims)?;
    let parameters = b.parameters(&pf, &mut pool, &mut dims)?;
    let reader = Reader {
        b: &b,
        ctx: Context::new()
            .with_coordinates(coordinates.iter().map(|c| c.name.as_str()))
            .with_parameters(parameters.iter().map(|p| p.name.as_str())),
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
            "no-system",
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
    let assumptions = b.forces_constraints_assumptions(&pf, &mut system)?;
    let parts = b.parts(&pf, &system)?;
    Ok(Problem {
        file: file.to_string(),
        id: b.id,
        title: pf.title,
        source: pf.source,
        statement: pf.statement,
        system,
        dims,
        assumptions,
        parts,
        stated_lagrangian: stated,
        lagrangian_line,
    })
}

/// The line of the `lagrangian` key, else of the first body, else of the id.
fn lagrangian_line(text: &str, pf: &ProblemFile, id_line: usize) -> usize {
    pf.lagrangian
        .as_ref()
        .map(|l| line_of(text, l.span().start))
        .or_else(|| pf.bodies.first().map(|b| line_of(text, b.span().start)))
        .unwrap_or(id_line)
}

/// What every finding of one file shares: the file, its text and the problem id.
struct Builder<'a> {
    file: &'a str,
    text: &'a str,
    id: String,
    id_line: usize,
}

impl Builder<'_> {
    /// A finding about the problem (not a part) at `line`.
    fn fail(&self, line: usize, code: &'static str, message: String) -> Finding {
        Finding {
            file: self.file.to_string(),
            problem: Some(self.id.clone()),
            part: None,
            line,
            code,
            message,
        }
    }

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
                return Err(self.fail(self.id_line, "reserved-name", why.to_string()));
            }
            if coordinates.iter().any(|x| x.name == name) {
                return Err(self.fail(
                    self.id_line,
                    "duplicate-coordinate",
                    format!("coordinate `{name}` is declared twice"),
                ));
            }
            let d = match &c.dimension {
                Some(d) => {
                    Dimension::parse(d).map_err(|e| self.fail(self.id_line, "bad-dimension", e))?
                }
                None if c.periodic => Dimension::NONE,
                None => Dimension::new(0, 1, 0),
            };
            dims.set(&name, d);
            let range = match c.range.as_deref() {
                Some(&[a, b]) if a < b && a.is_finite() && b.is_finite() => (a, b),
                Some(r) => {
                    return Err(self.fail(
                        self.id_line,
                        "bad-range",
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
                    "reserved-name",
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
                    "reserved-name",
                    format!("parameter `{name}` is also declared as a coordinate"),
                ));
            }
            let d = Dimension::parse(&p.dimension).map_err(|e| {
                self.fail(
                    self.id_line,
                    "bad-dimension",
                    format!("parameter `{name}`: {e}"),
                )
            })?;
            let (lo, hi) = match p.range[..] {
                [lo, hi] if lo > 0.0 && hi > lo && hi.is_finite() => (lo, hi),
                _ => {
                    return Err(self.fail(
                        self.id_line,
                        "bad-range",
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
                    "bad-force",
                    "more forces than coordinates".into(),
                ));
            }
            system.forces[i] = read_expr(f, &ctx, &mut system.pool)
                .map_err(|e| self.fail(self.id_line, "unreadable", format!("force `{f}`: {e}")))?;
        }
        for c in &pf.constraints {
            system.add_constraint(c).map_err(|e| {
                self.fail(
                    self.id_line,
                    "bad-constraint",
                    format!("constraint `{c}`: {e}"),
                )
            })?;
        }
        let mut assumptions = Vec::new();
        for a in &pf.assume {
            assumptions.push(
                Assumption::parse(a, &ctx, system)
                    .map_err(|e| self.fail(self.id_line, "bad-assumption", e))?,
            );
        }
        Ok(assumptions)
    }

    /// The parts, each a finding of its own on error; two parts may not share an id.
    fn parts(&self, pf: &ProblemFile, system: &System) -> Result<Vec<Part>, Finding> {
        let mut parts = Vec::new();
        for sp in &pf.parts {
            let line = line_of(self.text, sp.span().start);
            if let Err(why) = check_id(&sp.get_ref().id, "part") {
                return Err(self.fail(line, "bad-id", why));
            }
            parts.push(
                build_part(sp.get_ref(), line, system).map_err(|(code, m)| Finding {
                    part: Some(sp.get_ref().id.clone()),
                    ..self.fail(line, code, m)
                })?,
            );
        }
        let mut seen = std::collections::BTreeSet::new();
        for p in &parts {
            if !seen.insert(p.id.clone()) {
                return Err(Finding {
                    part: Some(p.id.clone()),
                    ..self.fail(
                        p.line,
                        "duplicate-part",
                        format!("two parts are called `{}`", p.id),
                    )
                });
            }
        }
        Ok(parts)
    }
}

/// Reads the expressions of bodies and potentials in the declared symbols' context.
struct Reader<'a> {
    b: &'a Builder<'a>,
    ctx: Context,
}

impl Reader<'_> {
    /// Reads `src` (the file's `what` at `line`); an unknown name is `undeclared-symbol`.
    fn read(&self, pool: &mut Pool, src: &str, line: usize, what: &str) -> Result<Id, Finding> {
        read_expr(src, &self.ctx, pool).map_err(|e| {
            self.b.fail(
                line,
                if matches!(e.kind, crate::expr::ParseErrorKind::UnknownName { .. }) {
                    "undeclared-symbol"
                } else {
                    "unreadable"
                },
                format!("{what} `{src}`: {e} ({})", e.help()),
            )
        })
    }

    /// The `[[bodies]]`: point masses and rotors.
    fn bodies(&self, pf: &ProblemFile, pool: &mut Pool) -> Result<Vec<Body>, Finding> {
        let mut bodies = Vec::new();
        for spec in &pf.bodies {
            let line = line_of(self.b.text, spec.span().start);
            bodies.push(self.body(spec.get_ref(), line, pool)?);
        }
        Ok(bodies)
    }

    fn body(&self, b: &BodySpec, line: usize, pool: &mut Pool) -> Result<Body, Finding> {
        let bad = |m: String| self.b.fail(line, "bad-body", m);
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
            other => Err(bad(format!(
                "unknown body kind `{other}` (use point or rotor)"
            ))),
        }
    }

    /// The `[[potentials]]`: gravity, springs between bodies or anchors, explicit V.
    fn potentials(
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
        let bad = |m: String| self.b.fail(line, "bad-potential", m);
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
                "bad-potential",
                format!("spring end {i} is not a body number"),
            )),
            Some(AnchorSpec::Point(v)) => Ok(Anchor::Fixed(
                v.iter()
                    .map(|x| self.read(pool, x, line, "anchor"))
                    .collect::<Result<_, _>>()?,
            )),
            None => Err(self.b.fail(
                line,
                "bad-potential",
                "a spring needs `from` and `to`".into(),
            )),
        }
    }
}

/// Smallest and largest relative tolerance a part may set: below 1e-15 is under the rounding
/// of f64; above 1e-2 a wrong answer (a constant off by 1 %, or `0` at 100 %) would pass.
const MIN_TOLERANCE: f64 = 1e-15;
const MAX_TOLERANCE: f64 = 1e-2;
/// Largest weight of a part.
const MAX_POINTS: f64 = 1e6;

/// Why `name` cannot be a parameter's name: it would read as time, π or a function.
fn reserved(name: &str) -> Option<String> {
    crate::mechanics::system::check_coordinate_name(name)
        .err()
        .map(|e| e.reason())
}

/// An id is used on the command line and printed in reports: it must be non-empty and made
/// of letters, digits, `-`, `_` and `.` only (no spaces, control or invisible characters).
fn check_id(id: &str, what: &str) -> Result<(), String> {
    const MAX_ID: usize = 100;
    if id.is_empty() {
        return Err(format!("the {what} id is empty"));
    }
    if id.chars().count() > MAX_ID {
        return Err(format!("the {what} id is longer than {MAX_ID} characters"));
    }
    if let Some(c) = id
        .chars()
        .find(|&c| !(c.is_alphanumeric() || matches!(c, '-' | '_' | '.')))
    {
        return Err(format!(
            "the {what} id `{}` has the {}; an id is letters, digits, `-`, `_` and `.`",
            crate::expr::error::visible(id),
            crate::expr::error::describe_char(c)
        ));
    }
    Ok(())
}

/// The part's tolerance and weight, each checked to be a number in its range (a NaN, a
/// negative or a huge tolerance would let `check` accept wrong answers).
fn tolerance_and_points(sp: &PartSpec) -> Result<(f64, f64), (&'static str, String)> {
    let tolerance = match sp.tolerance {
        None => crate::check::tolerance::TOLERANCE,
        Some(t) if (MIN_TOLERANCE..=MAX_TOLERANCE).contains(&t) => t,
        Some(t) => {
            return Err((
                "bad-tolerance",
                format!(
                    "tolerance = {t:?}: a relative tolerance lies between {MIN_TOLERANCE:e} and {MAX_TOLERANCE:e} (default 1e-9); a larger one would accept wrong answers"
                ),
            ));
        }
    };
    let points = match sp.points {
        None => 1.0,
        Some(p) if (0.0..=MAX_POINTS).contains(&p) => p,
        Some(p) => {
            return Err((
                "bad-points",
                format!("points = {p:?}: a part's weight is a number from 0 to {MAX_POINTS:e}"),
            ));
        }
    };
    Ok((tolerance, points))
}

fn build_part(sp: &PartSpec, line: usize, sys: &System) -> Result<Part, (&'static str, String)> {
    let kind = PartKind::parse(&sp.kind).ok_or_else(|| {
        ("bad-kind", format!("unknown part kind `{}` (expression, lagrangian, equation, equations, equilibria, frequencies, values, constraint-force)", sp.kind))
    })?;
    let answers = match &sp.answer {
        AnswerSpec::One(s) => vec![s.clone()],
        AnswerSpec::Many(v) => v.clone(),
    };
    if answers.is_empty() {
        return Err(("no-answer", "the part has an empty answer".into()));
    }
    let quantity = quantity_of(sp, sys)?;
    let (tolerance, points) = tolerance_and_points(sp)?;
    let up_to_constant = match sp.up_to.as_deref() {
        None => false,
        Some("constant") => true,
        Some(other) => {
            return Err((
                "bad-up-to",
                format!("up_to = \"{other}\" (only \"constant\")"),
            ));
        }
    };
    let dimension = sp
        .dimension
        .as_deref()
        .map(Dimension::parse)
        .transpose()
        .map_err(|e| ("bad-dimension", e))?;
    for s in &sp.stability {
        if !matches!(s.as_str(), "stable" | "unstable" | "marginal") {
            return Err((
                "bad-stability",
                format!("stability `{s}` (use stable, unstable or marginal)"),
            ));
        }
    }
    Ok(Part {
        id: sp.id.clone(),
        kind,
        prompt: sp.prompt.clone(),
        answers,
        hints: sp.hints.clone(),
        points,
        substitute: sp
            .substitute
            .iter()
            .map(|(k, v)| (k.clone(), v.clone()))
            .collect(),
        at: sp.at.iter().map(|(k, v)| (k.clone(), v.clone())).collect(),
        up_to_constant,
        wrong: sp.wrong.clone(),
        tolerance,
        stability: sp.stability.clone(),
        quantity,
        dimension,
        squared: sp.squared,
        line,
    })
}

/// The quantity an expression part asks for: stated, or implied by the part's id.
fn quantity_of(sp: &PartSpec, sys: &System) -> Result<Quantity, (&'static str, String)> {
    let coordinate = match &sp.coordinate {
        None => 0,
        Some(c) => sys
            .coordinates
            .iter()
            .position(|x| x.name == crate::expr::names::normalize(c))
            .ok_or_else(|| ("bad-coordinate", format!("`{c}` is not a coordinate")))?,
    };
    let q = sp.quantity.as_deref().unwrap_or(match sp.id.as_str() {
        "kinetic" => "kinetic",
        "potential" => "potential",
        "lagrangian" => "lagrangian",
        "momentum" => "momentum",
        "energy-function" => "energy-function",
        "tension" | "constraint-force" => "multiplier",
        _ => "none",
    });
    let quantity = match q {
        "kinetic" => Quantity::Kinetic,
        "potential" => Quantity::Potential,
        "lagrangian" => Quantity::Lagrangian,
        "momentum" => Quantity::Momentum(coordinate),
        "energy-function" => Quantity::EnergyFunction,
        "multiplier" => Quantity::Multiplier(sp.multiplier.unwrap_or(1).saturating_sub(1)),
        "acceleration" => Quantity::Acceleration(coordinate),
        "none" => Quantity::None,
        other => return Err(("bad-quantity", format!("unknown quantity `{other}`"))),
    };
    check_multiplier(sp.multiplier, quantity, sys.constraints.len())?;
    Ok(quantity)
}

/// The `multiplier` key and a multiplier quantity fit the problem's constraints: a multiplier
/// exists only for a constraint, numbered from 1, and the key only on a multiplier part.
fn check_multiplier(
    key: Option<usize>,
    quantity: Quantity,
    constraints: usize,
) -> Result<(), (&'static str, String)> {
    let bad = |m: String| Err(("bad-multiplier", m));
    match quantity {
        Quantity::Multiplier(_) if constraints == 0 => bad(
            "the problem has no constraints, so there is no multiplier to ask for: add `constraints`, or choose another quantity".into(),
        ),
        _ if key == Some(0) => bad("multiplier = 0: multipliers are numbered from 1".into()),
        Quantity::Multiplier(j) if j >= constraints => bad(format!(
            "multiplier = {}: the problem has {constraints} constraint(s)",
            j + 1
        )),
        Quantity::Multiplier(_) => Ok(()),
        _ if key.is_some() => bad(
            "`multiplier` applies only to a multiplier part (a constraint force, or quantity = \"multiplier\")".into(),
        ),
        _ => Ok(()),
    }
}

//! A mechanical system: coordinates, parameters, the Lagrangian (given, or derived from
//! bodies), optional generalized forces and constraints. The system owns the expression pool
//! everything about it lives in.

use rustc_hash::FxHashMap;

use super::bodies::{Body, Potential, kinetic_energy, potential_energy};
pub use super::coordinate::{
    Coordinate, DEFAULT_COORDINATE_RANGE, DEFAULT_PARAMETER_RANGE, Domain, Parameter,
};
use super::error::MechError;
use super::magnitude::{Magnitudes, non_finite_constant};
pub use super::naming::{NameError, check_coordinate_name, check_coordinate_names};
use super::sample::Sampler;
use super::state::Layout;
use crate::expr::error::MAX_SYSTEM_INPUT_BYTES;
use crate::expr::{Context, Id, Pool, Program, Sym, read_expr};

/// Holonomic (on positions) or nonholonomic (on velocities, not integrable).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConstraintKind {
    Holonomic,
    Nonholonomic,
}

/// A constraint `expr = 0`.
#[derive(Clone, Debug)]
pub struct Constraint {
    pub(crate) expr: Id,
    pub kind: ConstraintKind,
}

/// A system ready for analysis.
#[derive(Clone, Debug)]
pub struct System {
    pub pool: Pool,
    pub coordinates: Vec<Coordinate>,
    pub parameters: Vec<Parameter>,
    pub lagrangian: Id,
    /// T and V when known (from bodies, or given separately).
    pub kinetic: Option<Id>,
    pub potential: Option<Id>,
    /// Generalized non-conservative forces Qᵢ, one per coordinate (0 when absent).
    pub forces: Vec<Id>,
    pub constraints: Vec<Constraint>,
    /// The bodies T and V were built from (empty when L was given directly); the tutor's
    /// derivation ladder starts from their positions.
    pub bodies: Vec<Body>,
    /// Named quantities of the parameters the problem defines (`theta0`, cos θ₀ = g/(R ω²)):
    /// an answer may use the name, read as its value.
    pub(crate) definitions: Vec<(String, Id)>,
}

/// Sampling range of velocities and accelerations.
pub const RATE_RANGE: (f64, f64) = (-2.0, 2.0);

impl System {
    /// A system with `coordinates` whose Lagrangian is typed text. Every other symbol is a
    /// parameter. Angles (names like theta, phi, alpha, psi, …) are taken as periodic.
    pub fn from_lagrangian(text: &str, coordinates: &[&str]) -> Result<System, MechError> {
        check_coordinate_names(coordinates)?;
        let mut sys = System::empty(coordinates);
        let ctx = sys.open_context();
        sys.lagrangian = sys.read(text, "the Lagrangian", &ctx)?;
        sys.check_first_order()?;
        sys.collect_parameters();
        Ok(sys)
    }

    /// A system with T and V given separately (L = T − V).
    pub fn from_energies(t: &str, v: &str, coordinates: &[&str]) -> Result<System, MechError> {
        check_coordinate_names(coordinates)?;
        let mut sys = System::empty(coordinates);
        let ctx = sys.open_context();
        let t = sys.read(t, "the kinetic energy", &ctx)?;
        let v = sys.read(v, "the potential energy", &ctx)?;
        sys.kinetic = Some(t);
        sys.potential = Some(v);
        sys.lagrangian = sys.pool.sub(t, v);
        sys.check_first_order()?;
        sys.collect_parameters();
        Ok(sys)
    }

    /// A system from bodies and potentials, already built in `pool`.
    pub fn from_bodies(
        mut pool: Pool,
        coordinates: Vec<Coordinate>,
        bodies: &[Body],
        potentials: &[Potential],
    ) -> System {
        let t = kinetic_energy(&mut pool, &coordinates, bodies);
        let v = potential_energy(&mut pool, bodies, potentials);
        // A coordinate declared positive (a distance r) has |r| = r: a spring's length
        // √(r² cos²φ + r² sin²φ) is r, not |r|.
        let positive: Vec<Sym> = coordinates
            .iter()
            .filter(|c| {
                c.domain
                    .lower
                    .is_some_and(|l| pool.is_nonnegative_constant(l))
            })
            .map(|c| c.sym)
            .collect();
        let t = pool.simplify(t, &positive);
        let v = pool.simplify(v, &positive);
        let l = pool.sub(t, v);
        let mut sys = System::from_parts(pool, coordinates, l);
        sys.kinetic = Some(t);
        sys.potential = Some(v);
        sys.bodies = bodies.to_vec();
        sys
    }

    /// A system from an already-built Lagrangian in `pool` (used by the problem bank).
    pub(crate) fn from_parts(pool: Pool, coordinates: Vec<Coordinate>, lagrangian: Id) -> System {
        let n = coordinates.len();
        let zero = pool.zero();
        let mut sys = System {
            pool,
            coordinates,
            parameters: Vec::new(),
            lagrangian,
            kinetic: None,
            potential: None,
            forces: vec![zero; n],
            constraints: Vec::new(),
            bodies: Vec::new(),
            definitions: Vec::new(),
        };
        sys.collect_parameters();
        sys
    }

    fn empty(coordinates: &[&str]) -> System {
        let mut pool = Pool::new();
        let coords: Vec<Coordinate> = coordinates
            .iter()
            .map(|c| {
                let name = crate::expr::names::normalize(c.trim());
                Coordinate {
                    sym: pool.symbol(&name),
                    periodic: looks_like_angle(&name),
                    range: if looks_like_angle(&name) {
                        (-std::f64::consts::PI, std::f64::consts::PI)
                    } else {
                        DEFAULT_COORDINATE_RANGE
                    },
                    domain: Domain::ANY,
                    name,
                }
            })
            .collect();
        let zero = pool.zero();
        let n = coords.len();
        System {
            pool,
            coordinates: coords,
            parameters: Vec::new(),
            lagrangian: zero,
            kinetic: None,
            potential: None,
            forces: vec![zero; n],
            constraints: Vec::new(),
            bodies: Vec::new(),
            definitions: Vec::new(),
        }
    }

    /// The reading context: coordinates declared, any other name a parameter.
    pub fn open_context(&self) -> Context {
        Context::open()
            .with_coordinates(self.coordinates.iter().map(|c| c.name.as_str()))
            .with_parameters(self.parameters.iter().map(|p| p.name.as_str()))
            .with_max_input(MAX_SYSTEM_INPUT_BYTES)
    }

    /// The closed context: only this system's names (and the quantities it defines, each
    /// read as its value).
    pub fn context(&self) -> Context {
        Context::new()
            .with_coordinates(self.coordinates.iter().map(|c| c.name.as_str()))
            .with_parameters(self.parameters.iter().map(|p| p.name.as_str()))
            .with_definitions(
                self.definitions
                    .iter()
                    .map(|(n, v)| (n.as_str(), self.pool.plain(*v))),
            )
    }

    /// Reads text in `ctx` into this system's pool.
    pub fn read(&mut self, text: &str, what: &str, ctx: &Context) -> Result<Id, MechError> {
        read_expr(text, ctx, &mut self.pool).map_err(|error| MechError::Parse {
            what: what.to_string(),
            source_text: text.to_string(),
            error: Box::new(error),
        })
    }

    /// Sets the generalized forces from text, `Q1; Q2; …` (fewer entries are zero).
    pub fn set_forces(&mut self, text: &str) -> Result<(), MechError> {
        let ctx = self.open_context();
        let parts: Vec<&str> = text.split(';').collect();
        if parts.len() > self.coordinates.len() {
            return Err(MechError::TooManyForces {
                given: parts.len(),
                coordinates: self.coordinates.len(),
            });
        }
        for (i, p) in parts.iter().enumerate() {
            if !p.trim().is_empty() {
                let name = self.coordinates[i].name.clone();
                let q = self.read(p, &format!("the force on {name}"), &ctx)?;
                // A force with q'' would make the printed equation and M, f disagree: it is
                // an inertial term, refused with where it belongs.
                if let Some(&(s, o)) = self.pool.variables(q).iter().find(|v| v.1 >= 2) {
                    return Err(MechError::ForceWithAcceleration {
                        coordinate: name,
                        acceleration: format!("{}{}", self.pool.name(s), "'".repeat(o.into())),
                    });
                }
                self.forces[i] = q;
            }
        }
        self.collect_parameters();
        Ok(())
    }

    /// Adds a constraint `text = 0` (or `lhs = rhs`). It is holonomic when it involves no
    /// velocity, nonholonomic when it is linear in the velocities.
    pub fn add_constraint(&mut self, text: &str) -> Result<(), MechError> {
        let ctx = self.open_context();
        let (lhs, rhs) =
            crate::expr::read_equation(text, &ctx, &mut self.pool).map_err(|error| {
                MechError::Parse {
                    what: "a constraint".into(),
                    source_text: text.to_string(),
                    error: Box::new(error),
                }
            })?;
        let e = self.pool.sub(lhs, rhs);
        let vars = self.pool.variables(e);
        let max_order = vars.iter().map(|v| v.1).max().unwrap_or(0);
        let kind = match max_order {
            0 => ConstraintKind::Holonomic,
            1 => ConstraintKind::Nonholonomic,
            _ => {
                return Err(MechError::AccelerationInConstraint);
            }
        };
        if kind == ConstraintKind::Nonholonomic {
            // Must be affine in the velocities: every second velocity derivative vanishes.
            for c in &self.coordinates.clone() {
                let d1 = self.pool.diff(e, c.sym, 1);
                for c2 in &self.coordinates.clone() {
                    let d2 = self.pool.diff(d1, c2.sym, 1);
                    if !self.is_zero(d2) {
                        return Err(MechError::NonlinearVelocityConstraint);
                    }
                }
            }
        }
        self.constraints.push(Constraint { expr: e, kind });
        self.collect_parameters();
        Ok(())
    }

    /// Registers every non-coordinate symbol as a parameter (keeping existing ones).
    pub(crate) fn collect_parameters(&mut self) {
        let mut roots = vec![self.lagrangian];
        roots.extend(self.forces.iter().copied());
        roots.extend(self.constraints.iter().map(|c| c.expr));
        roots.extend(self.kinetic);
        roots.extend(self.potential);
        let time = self.pool.time();
        let mut names: Vec<(String, Sym)> = Vec::new();
        for r in roots {
            for (s, _) in self.pool.variables(r) {
                if s == time || self.coordinates.iter().any(|c| c.sym == s) {
                    continue;
                }
                let n = self.pool.name(s).to_string();
                if !names.iter().any(|(m, _)| *m == n) {
                    names.push((n, s));
                }
            }
        }
        crate::sort::sort_by(&mut names, |a, b| {
            crate::expr::order::natural_cmp(&a.0, &b.0)
        });
        for (name, sym) in names {
            if !self.parameters.iter().any(|p| p.sym == sym) {
                self.parameters.push(Parameter {
                    name,
                    sym,
                    dimension: None,
                    range: DEFAULT_PARAMETER_RANGE,
                    domain: Domain::ANY,
                });
            }
        }
    }

    /// Forgets parameters that nothing of the system uses (L, T, V, forces, constraints):
    /// a problem may declare a parameter for one part only, and a numeric analysis should
    /// not ask for its value.
    pub fn drop_unused_parameters(&mut self) {
        let mut roots = vec![self.lagrangian];
        roots.extend(self.forces.iter().copied());
        roots.extend(self.constraints.iter().map(|c| c.expr));
        roots.extend(self.kinetic);
        roots.extend(self.potential);
        let used: Vec<Sym> = roots
            .into_iter()
            .flat_map(|r| self.pool.variables(r))
            .map(|(s, _)| s)
            .collect();
        self.parameters.retain(|p| used.contains(&p.sym));
    }

    /// Number of coordinates.
    pub fn n(&self) -> usize {
        self.coordinates.len()
    }

    /// Coordinate symbols.
    pub(crate) fn coordinate_syms(&self) -> Vec<Sym> {
        self.coordinates.iter().map(|c| c.sym).collect()
    }

    /// Parameter symbols (treated as positive by the simplifier).
    pub(crate) fn parameter_syms(&self) -> Vec<Sym> {
        self.parameters.iter().map(|p| p.sym).collect()
    }

    /// The symbols simplification may take as positive: every parameter (displayed forms
    /// only; checking never relies on them) and each coordinate whose domain is positive.
    pub(crate) fn positive_syms(&self) -> Vec<Sym> {
        let mut out = self.parameter_syms();
        out.extend(
            self.coordinates
                .iter()
                .filter(|c| {
                    c.domain
                        .lower
                        .is_some_and(|l| self.pool.is_nonnegative_constant(l))
                })
                .map(|c| c.sym),
        );
        out
    }

    /// Each declared end of a coordinate's or parameter's domain: the slot of its value in
    /// a sample point ([`state_layout`](Self::state_layout)), the end, and whether it is the
    /// lower one. Every sample and probe stays strictly inside.
    pub fn domain_ends(&self) -> Vec<(usize, Id, bool)> {
        let at = self.state_layout();
        let coordinates = self
            .coordinates
            .iter()
            .enumerate()
            .map(|(i, c)| (at.q(i), c.domain));
        let parameters = self
            .parameters
            .iter()
            .enumerate()
            .map(|(j, p)| (at.param(j), p.domain));
        let mut out = Vec::new();
        for (slot, d) in coordinates.chain(parameters) {
            out.extend(d.lower.map(|l| (slot, l, true)));
            out.extend(d.upper.map(|u| (slot, u, false)));
        }
        out
    }

    /// Simplifies for display, with parameters taken as positive, and collects terms that
    /// differ only in parameters.
    pub fn simplify(&mut self, e: Id) -> Id {
        let positive = self.positive_syms();
        let s = self.pool.simplify(e, &positive);
        self.pool.collect(s, &positive)
    }

    /// Where t, each q, q', q'' and each parameter sit in a sample point.
    pub fn state_layout(&self) -> Layout {
        Layout::new(self.n())
    }

    /// The standard input layout of compiled programs, as variables in the order of
    /// [`state_layout`](Self::state_layout): t, then each coordinate's q, q', q'', then each
    /// parameter.
    pub fn layout(&self) -> Vec<(Sym, u8)> {
        let mut v = vec![(self.pool.time(), 0)];
        for c in &self.coordinates {
            for o in 0..3 {
                v.push((c.sym, o));
            }
        }
        for p in &self.parameters {
            v.push((p.sym, 0));
        }
        v
    }

    /// Compiles expressions over the standard layout. A constant part that overflows
    /// (`exp(1000)`) or has no value is refused by name: the program could not run anywhere.
    pub fn compile(&self, roots: &[Id]) -> Result<Program, MechError> {
        let program = Program::compile(&self.pool, roots, &self.layout())
            .map_err(|u| MechError::UnknownSymbol { name: u.name })?;
        match non_finite_constant(&self.pool, roots) {
            Some(e) => Err(e),
            None => Ok(program),
        }
    }

    /// Expressions over the standard layout evaluated with the sizes of their terms, for
    /// zero tests relative to those sizes.
    pub(crate) fn magnitudes(&self, roots: &[Id]) -> Result<Magnitudes, MechError> {
        Magnitudes::new(&self.pool, roots, &self.layout()).map_err(|s| MechError::UnknownSymbol {
            name: self.pool.name(s).to_string(),
        })
    }

    /// Why the expressions of `m` cannot be evaluated at the point `x`: the part that overflows (as
    /// [`MechError::Overflow`]) or is undefined there. For a result that was undefined at
    /// every sampled point, so that the error names the culprit instead of a consequence
    /// ("the mass matrix is singular", "no equilibrium was found").
    pub(crate) fn undefined_at(&self, m: &Magnitudes, x: &[f64], what: &str) -> MechError {
        let Some((id, overflow)) = m.failure(x) else {
            return MechError::Undefined { what: what.into() };
        };
        if overflow {
            MechError::Overflow {
                expr: self.pool.plain(id),
            }
        } else {
            MechError::Undefined {
                what: format!("`{}` (in {what})", self.pool.plain(id)),
            }
        }
    }

    /// A random point in the standard layout.
    pub fn sample_point(&self, s: &mut Sampler) -> Vec<f64> {
        // Draws happen in layout order, so a seed gives the same point as it always has.
        let layout = self.state_layout();
        let mut v = vec![0.0; layout.len(self.parameters.len())];
        v[layout.time()] = s.uniform(0.0, 2.0);
        for (i, c) in self.coordinates.iter().enumerate() {
            v[layout.q(i)] = s.uniform(c.range.0, c.range.1);
            v[layout.qdot(i)] = s.uniform(RATE_RANGE.0, RATE_RANGE.1);
            v[layout.qddot(i)] = s.uniform(RATE_RANGE.0, RATE_RANGE.1);
        }
        for (j, p) in self.parameters.iter().enumerate() {
            v[layout.param(j)] = s.uniform(p.range.0, p.range.1);
        }
        v
    }

    /// Whether `e` vanishes identically, decided at 12 seeded random points (points where
    /// it is undefined are skipped). At each point the value must be negligible relative to
    /// the size of its own terms (see `mechanics::magnitude`), never relative to 1:
    /// a mass of 1e-30 is not zero, rounding in a sum of terms of 1e30 is.
    pub fn is_zero(&self, e: Id) -> bool {
        if self.pool.is_zero(e) {
            return true;
        }
        let Ok(m) = self.magnitudes(&[e]) else {
            return false;
        };
        let mut sampler = Sampler::new(0x5eed_0001);
        let mut checked = 0;
        for _ in 0..48 {
            let x = self.sample_point(&mut sampler);
            let Some(v) = m.eval(&x) else {
                continue;
            };
            if !v[0].negligible() {
                return false;
            }
            checked += 1;
            if checked >= 12 {
                break;
            }
        }
        checked > 0
    }

    /// Values for the parameters from `name = expr` pairs; an expression may use the other
    /// parameters (`m1 = m`), and those that remain become the system's new parameters.
    pub fn substitute_parameters(
        &mut self,
        values: &[(String, String)],
    ) -> Result<FxHashMap<(Sym, u8), Id>, MechError> {
        let ctx = self.open_context();
        let mut map: FxHashMap<(Sym, u8), Id> = FxHashMap::default();
        for (name, text) in values {
            let name = crate::expr::names::normalize(name.trim());
            let Some(p) = self.parameters.iter().find(|p| p.name == name) else {
                if self.coordinates.iter().any(|c| c.name == name) {
                    return Err(MechError::ValueForCoordinate { name });
                }
                return Err(MechError::UnknownParameter { name });
            };
            let sym = p.sym;
            let v = self.read(text, &format!("the value of {name}"), &ctx)?;
            map.insert((sym, 0), v);
        }
        self.lagrangian = self.pool.substitute(self.lagrangian, &map);
        self.kinetic = self.kinetic.map(|t| self.pool.substitute(t, &map));
        self.potential = self.potential.map(|v| self.pool.substitute(v, &map));
        self.forces = self
            .forces
            .clone()
            .into_iter()
            .map(|f| self.pool.substitute(f, &map))
            .collect();
        self.constraints = self
            .constraints
            .clone()
            .into_iter()
            .map(|c| Constraint {
                expr: self.pool.substitute(c.expr, &map),
                kind: c.kind,
            })
            .collect();
        self.definitions = self
            .definitions
            .clone()
            .into_iter()
            .map(|(n, v)| (n, self.pool.substitute(v, &map)))
            .collect();
        self.parameters.retain(|p| !map.contains_key(&(p.sym, 0)));
        let bound = |pool: &mut Pool, d: Domain| Domain {
            lower: d.lower.map(|l| pool.substitute(l, &map)),
            upper: d.upper.map(|u| pool.substitute(u, &map)),
        };
        for c in &mut self.coordinates {
            c.domain = bound(&mut self.pool, c.domain);
        }
        for p in &mut self.parameters {
            p.domain = bound(&mut self.pool, p.domain);
        }
        self.collect_parameters();
        Ok(map)
    }
}

/// Names that are conventionally angles, and so periodic.
pub(crate) fn looks_like_angle(name: &str) -> bool {
    let (letters, _) = crate::expr::names::split_digits(name);
    matches!(
        letters,
        "theta" | "phi" | "psi" | "alpha" | "beta" | "gamma" | "varphi" | "chi" | "angle"
    ) || letters.starts_with("theta")
        || letters.starts_with("phi")
}

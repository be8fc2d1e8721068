//! The TOML schema of a problem file, read by `schema_read` (serde's rules and messages; how
//! a field is added: `schema_struct!`). Unknown keys are errors. See
//! `docs/problem-format.md` for the field-by-field description.

use std::collections::BTreeMap;

use serde::de::Unexpected;
use toml::Spanned;
use toml::de::DeValue;

use super::schema_read::{self as read, FromToml, ReadError, schema_struct};

schema_struct! {
/// A whole problem file.
pub struct ProblemFile {
    pub id: Spanned<String>,
    pub title: String,
    #[serde(default)]
    pub source: String,
    #[serde(default)]
    pub statement: String,
    /// The Cartesian axes, origin, sense of rotation and phase the bodies' positions use, in
    /// words; the tutor states it in every position step.
    #[serde(default)]
    pub axes: String,
    pub coordinates: Vec<CoordinateSpec>,
    #[serde(default)]
    pub parameters: BTreeMap<String, ParameterSpec>,
    #[serde(default)]
    pub lagrangian: Option<Spanned<String>>,
    #[serde(default)]
    pub assume: Vec<String>,
    /// Named quantities of the parameters (`theta0 = "acos(g/(R*omega^2))"`): an answer may
    /// use the name, read as its value.
    #[serde(default)]
    pub definitions: BTreeMap<String, Spanned<String>>,
    /// Generalized non-conservative forces, one per coordinate.
    #[serde(default)]
    pub forces: Vec<String>,
    /// Constraints `f = 0` (holonomic) or linear in the velocities (nonholonomic).
    #[serde(default)]
    pub constraints: Vec<String>,
    #[serde(default)]
    pub bodies: Vec<Spanned<BodySpec>>,
    #[serde(default)]
    pub potentials: Vec<Spanned<PotentialSpec>>,
    /// Forces given as a vector at a point: Qᵢ = F·∂r/∂qᵢ, added to `forces`.
    #[serde(default)]
    pub point_forces: Vec<Spanned<PointForceSpec>>,
    pub parts: Vec<Spanned<PartSpec>>,
    /// Starting values for `lagrange simulate PROBLEM` (parameters' values are on them).
    #[serde(default)]
    pub simulation: Option<Spanned<SimulationSpec>>,
    /// How parameters vary from student to student (`[variants.m] values = [1.5, 2]`).
    #[serde(default)]
    pub variants: BTreeMap<String, Spanned<VariantSpec>>,
}
}

schema_struct! {
/// How one parameter varies between students: `values` (a set), or `range` with `step` (a
/// grid) or `digits` (every number of so many significant digits in it); `unit` is shown
/// after the number.
pub struct VariantSpec {
    pub values: Option<Vec<f64>>,
    pub range: Option<Vec<f64>>,
    pub step: Option<f64>,
    pub digits: Option<u32>,
    #[serde(default)]
    pub unit: String,
}
}

schema_struct! {
/// The initial state and duration a simulation of the problem starts from by default.
pub struct SimulationSpec {
    /// Initial coordinates (`theta`) and velocities (`theta'`); others start at 0.
    #[serde(default)]
    pub init: BTreeMap<String, f64>,
    /// The end time.
    pub t_end: Option<f64>,
}
}

schema_struct! {
/// A generalized coordinate.
pub struct CoordinateSpec {
    pub name: String,
    #[serde(default)]
    pub periodic: bool,
    /// Sampling and equilibrium-search range (default [−π, π] for periodic ones, [−2, 2]
    /// otherwise). A list, not a pair, so that a list of another length is a finding that
    /// names the field rather than silently read.
    pub range: Option<Vec<f64>>,
    /// Dimension, e.g. "L" (default: dimensionless if periodic, L otherwise).
    pub dimension: Option<String>,
    pub description: Option<String>,
    /// Where the coordinate can physically be (default: anywhere).
    pub domain: Option<DomainSpec>,
}
}

/// A declared domain: `"positive"`, `"negative"`, `"any"`, or an open interval `[low, high]`
/// whose ends are numbers or expressions of the parameters.
#[derive(Debug)]
#[cfg_attr(test, derive(serde::Deserialize))]
#[cfg_attr(test, serde(untagged))]
pub enum DomainSpec {
    Word(String),
    Interval(Vec<BoundSpec>),
}

impl FromToml for DomainSpec {
    /// The first form that reads, as serde's `untagged` tries them.
    fn read(v: &Spanned<DeValue<'_>>) -> Result<Self, ReadError> {
        read::numbers_fit(v)?;
        String::read(v)
            .map(DomainSpec::Word)
            .or_else(|_| Vec::read(v).map(DomainSpec::Interval))
            .map_err(|_| untagged(v, "DomainSpec"))
    }
}

/// One end of a declared interval.
#[derive(Debug)]
#[cfg_attr(test, derive(serde::Deserialize))]
#[cfg_attr(test, serde(untagged))]
pub enum BoundSpec {
    Number(f64),
    Text(String),
}

impl FromToml for BoundSpec {
    fn read(v: &Spanned<DeValue<'_>>) -> Result<Self, ReadError> {
        read::numbers_fit(v)?;
        f64::read(v)
            .map(BoundSpec::Number)
            .or_else(|_| String::read(v).map(BoundSpec::Text))
            .map_err(|_| untagged(v, "BoundSpec"))
    }
}

/// serde's error for a value no form of the untagged enum `name` reads.
fn untagged(v: &Spanned<DeValue<'_>>, name: &str) -> ReadError {
    ReadError {
        message: format!("data did not match any variant of untagged enum {name}"),
        span: Some(v.span()),
    }
}

schema_struct! {
/// A parameter.
pub struct ParameterSpec {
    pub dimension: String,
    /// Positive sampling range (a list, checked to have two elements).
    pub range: Vec<f64>,
    pub description: Option<String>,
    /// A typical value, used when the problem is simulated.
    pub value: Option<f64>,
    /// Where the parameter can physically be (default: positive with a physical dimension).
    pub domain: Option<DomainSpec>,
}
}

schema_struct! {
/// A body: `kind = "point"` (mass, position), `kind = "rotor"` (inertia, angle) or
/// `kind = "rigid"` (mass, centre-of-mass position, inertia or moments or tensor, and one of
/// angle, omega_body, euler).
pub struct BodySpec {
    pub kind: String,
    pub mass: Option<String>,
    pub position: Option<Vec<String>>,
    pub inertia: Option<String>,
    pub angle: Option<String>,
    /// Principal moments about the centre of mass (rigid, 3-D).
    pub moments: Option<Vec<String>>,
    /// The inertia tensor about the centre of mass in the body frame, 3 rows of 3 (rigid).
    pub tensor: Option<Vec<Vec<String>>>,
    /// Body-frame angular-velocity components (rigid, 3-D).
    pub omega_body: Option<Vec<String>>,
    /// z-x-z Euler angles φ, θ, ψ (rigid, 3-D).
    pub euler: Option<Vec<String>>,
}
}

schema_struct! {
/// A force `vector` applied at the point `at`.
pub struct PointForceSpec {
    pub at: Vec<String>,
    pub vector: Vec<String>,
}
}

/// One end of a spring: a body number (1-based) or a fixed point.
#[derive(Debug)]
pub enum AnchorSpec {
    Body(usize),
    Point(Vec<String>),
}

impl FromToml for AnchorSpec {
    fn read(v: &Spanned<DeValue<'_>>) -> Result<Self, ReadError> {
        const EXPECTED: &str = "a body number (1, 2, …) or a point [\"x\", \"y\"]";
        if let DeValue::Array(_) = v.get_ref() {
            return Vec::read(v).map(AnchorSpec::Point);
        }
        match read::integer(v)? {
            Some(n) => usize::try_from(n)
                .map(AnchorSpec::Body)
                .map_err(|_| read::invalid_value(v, Unexpected::Signed(n), EXPECTED)),
            None => Err(read::wrong_type(v, EXPECTED)),
        }
    }
}

#[cfg(test)]
impl<'de> serde::Deserialize<'de> for AnchorSpec {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = AnchorSpec;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a body number (1, 2, …) or a point [\"x\", \"y\"]")
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<AnchorSpec, E> {
                usize::try_from(v)
                    .map(AnchorSpec::Body)
                    .map_err(|_| E::invalid_value(serde::de::Unexpected::Signed(v), &self))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<AnchorSpec, A::Error> {
                let mut v = Vec::new();
                while let Some(x) = seq.next_element::<String>()? {
                    v.push(x);
                }
                Ok(AnchorSpec::Point(v))
            }
        }
        d.deserialize_any(V)
    }
}

schema_struct! {
/// A potential: `gravity` (g, axis), `spring` (k, natural, from, to) or `explicit` (V).
pub struct PotentialSpec {
    pub kind: String,
    pub g: Option<String>,
    /// "x", "y" or "z": gravity points down this axis.
    pub axis: Option<String>,
    pub k: Option<String>,
    pub natural: Option<String>,
    pub from: Option<AnchorSpec>,
    pub to: Option<AnchorSpec>,
    #[serde(rename = "V")]
    pub v: Option<String>,
}
}

/// A reference answer: one string, or a list for systems and lists.
#[derive(Debug, Clone)]
pub enum AnswerSpec {
    One(String),
    Many(Vec<String>),
}

impl FromToml for AnswerSpec {
    fn read(v: &Spanned<DeValue<'_>>) -> Result<Self, ReadError> {
        match v.get_ref() {
            DeValue::String(s) => Ok(AnswerSpec::One(s.to_string())),
            DeValue::Array(_) => Vec::read(v).map(AnswerSpec::Many),
            _ => Err(read::wrong_type(v, "a string or a list of strings")),
        }
    }
}

#[cfg(test)]
impl<'de> serde::Deserialize<'de> for AnswerSpec {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> serde::de::Visitor<'de> for V {
            type Value = AnswerSpec;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a string or a list of strings")
            }
            fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<AnswerSpec, E> {
                Ok(AnswerSpec::One(v.to_string()))
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                mut seq: A,
            ) -> Result<AnswerSpec, A::Error> {
                let mut v = Vec::new();
                while let Some(x) = seq.next_element::<String>()? {
                    v.push(x);
                }
                Ok(AnswerSpec::Many(v))
            }
        }
        d.deserialize_any(V)
    }
}

schema_struct! {
/// A part of a problem.
pub struct PartSpec {
    pub id: String,
    pub kind: String,
    pub prompt: String,
    pub answer: AnswerSpec,
    #[serde(default)]
    pub hints: Vec<String>,
    pub points: Option<f64>,
    #[serde(default)]
    pub substitute: BTreeMap<String, String>,
    #[serde(default)]
    pub at: BTreeMap<String, String>,
    pub up_to: Option<String>,
    #[serde(default)]
    pub wrong: Vec<String>,
    pub tolerance: Option<f64>,
    /// For equilibria: "stable", "unstable" or "marginal", one per answer item.
    #[serde(default)]
    pub stability: Vec<String>,
    /// What physical quantity the answer is (default from the part id): kinetic, potential,
    /// lagrangian, momentum, energy-function, multiplier, acceleration.
    pub quantity: Option<String>,
    /// The coordinate a momentum or acceleration belongs to (default: the first).
    pub coordinate: Option<String>,
    /// Which constraint's multiplier (1-based, default 1).
    pub multiplier: Option<usize>,
    /// The dimension the answer must have, where the kind does not imply one.
    pub dimension: Option<String>,
    /// For frequencies: the answers are ω² rather than ω.
    #[serde(default)]
    pub squared: bool,
    /// Inequalities on the parameters for this part only, besides the problem's.
    #[serde(default)]
    pub assume: Vec<String>,
    /// What else a part accepts: `"same-motion"` (a Lagrangian part) accepts any L with the
    /// right equations of motion.
    pub accept: Option<String>,
    /// For equilibria: each point's stability must be stated.
    #[serde(default)]
    pub require_stability: bool,
    /// The point a linearized part expands about (`about = { theta = 0 }`): the answer is the
    /// quantity's Taylor polynomial of second order there (equations: linear).
    pub about: Option<BTreeMap<String, BoundSpec>>,
    /// For frequencies: the zero modes (free motions) are left out of the list.
    #[serde(default)]
    pub omit_zero_modes: bool,
    /// For frequencies: the answers are the growth rates λ (q ~ e^{λt}) of the unstable modes.
    #[serde(default)]
    pub growth: bool,
    /// A numeric part: a number (with a unit in brackets, `"50 [cm]"`) for every parameter;
    /// answers are then numbers, with units in brackets.
    #[serde(default)]
    pub values: BTreeMap<String, BoundSpec>,
    /// The answer may use the student's numbers instead of the varied parameters' symbols.
    #[serde(default)]
    pub numbers: bool,
}
}

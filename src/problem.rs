//! A problem as data: its system (built by the mechanics engine), dimensions, assumptions and
//! parts. The bank builds problems from TOML; the checker checks answers against them. Data
//! only: nothing here knows the checker.

use crate::expr::{Context, Dimension, Dimensions, Id, read_expr};
use crate::mechanics::System;

pub mod variant;

/// An inequality between two expressions of the parameters.
#[derive(Clone, Debug)]
pub struct Assumption {
    pub(crate) text: String,
    pub(crate) lhs: Id,
    pub(crate) rhs: Id,
    /// `>` (or `>=`) when true; `<` (or `<=`) when false.
    pub(crate) greater: bool,
}

impl Assumption {
    /// Reads `lhs > rhs`, `lhs < rhs`, `>=`, `<=` (also `≥`, `≤`).
    pub(crate) fn parse(text: &str, ctx: &Context, sys: &mut System) -> Result<Assumption, String> {
        let ops: [(&str, bool); 6] = [
            (">=", true),
            ("<=", false),
            ("≥", true),
            ("≤", false),
            (">", true),
            ("<", false),
        ];
        for (op, greater) in ops {
            if let Some((a, b)) = text.split_once(op) {
                let lhs =
                    read_expr(a, ctx, &mut sys.pool).map_err(|e| format!("in `{text}`: {e}"))?;
                let rhs =
                    read_expr(b, ctx, &mut sys.pool).map_err(|e| format!("in `{text}`: {e}"))?;
                // Assumptions restrict the parameters' samples; a coordinate (or time) in one
                // would be ignored when sampling, and wrongly narrow the proof's claim.
                let time = sys.pool.time();
                let mut vars = sys.pool.variables(lhs);
                vars.extend(sys.pool.variables(rhs));
                if let Some((s, _)) = vars
                    .iter()
                    .find(|(s, _)| *s == time || sys.coordinates.iter().any(|c| c.sym == *s))
                {
                    return Err(format!(
                        "`{text}` involves `{}`, which is not a parameter: `assume` restricts parameters only",
                        sys.pool.name(*s)
                    ));
                }
                return Ok(Assumption {
                    text: text.to_string(),
                    lhs,
                    rhs,
                    greater,
                });
            }
        }
        Err(format!("`{text}` is not an inequality (use > or <)"))
    }
}

/// The kinds of part.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PartKind {
    Expression,
    Lagrangian,
    Equation,
    Equations,
    Equilibria,
    Frequencies,
    Values,
    ConstraintForce,
    /// A steady motion: the coordinates `at` names stay put, the one it leaves out moves
    /// uniformly at the stated rate.
    SteadyMotion,
}

impl PartKind {
    /// The kind named `s` in a problem file.
    pub fn parse(s: &str) -> Option<PartKind> {
        Some(match s {
            "expression" => PartKind::Expression,
            "lagrangian" => PartKind::Lagrangian,
            "equation" => PartKind::Equation,
            "equations" => PartKind::Equations,
            "equilibria" => PartKind::Equilibria,
            "frequencies" => PartKind::Frequencies,
            "values" => PartKind::Values,
            "constraint-force" => PartKind::ConstraintForce,
            "steady-motion" => PartKind::SteadyMotion,
            _ => return None,
        })
    }

    /// The name used in problem files.
    pub fn name(self) -> &'static str {
        match self {
            PartKind::Expression => "expression",
            PartKind::Lagrangian => "lagrangian",
            PartKind::Equation => "equation",
            PartKind::Equations => "equations",
            PartKind::Equilibria => "equilibria",
            PartKind::Frequencies => "frequencies",
            PartKind::Values => "values",
            PartKind::ConstraintForce => "constraint-force",
            PartKind::SteadyMotion => "steady-motion",
        }
    }
}

/// The physical quantity an expression part asks for, which verification derives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quantity {
    Kinetic,
    Potential,
    Lagrangian,
    /// The momentum conjugate to coordinate i.
    Momentum(usize),
    EnergyFunction,
    /// The multiplier of constraint j.
    Multiplier(usize),
    /// The acceleration of coordinate i.
    Acceleration(usize),
    /// The cyclic coordinates (a `values` part listing their names).
    Cyclic,
    /// Nothing the engine derives (checked against the reference answer only).
    None,
}

/// The answer that states an empty list (no equilibrium, no cyclic coordinate).
pub const NONE_ANSWER: &str = "none";

/// Whether `text` is the explicit empty answer `none`.
pub fn is_none_answer(text: &str) -> bool {
    text.trim().eq_ignore_ascii_case(NONE_ANSWER)
}

/// A part of a problem.
#[derive(Clone, Debug)]
pub struct Part {
    pub id: String,
    pub kind: PartKind,
    pub prompt: String,
    /// Reference answer items (one for a single expression or equation).
    pub answers: Vec<String>,
    pub hints: Vec<String>,
    pub points: f64,
    pub substitute: Vec<(String, String)>,
    pub at: Vec<(String, String)>,
    pub up_to_constant: bool,
    pub wrong: Vec<String>,
    pub tolerance: f64,
    pub stability: Vec<String>,
    pub quantity: Quantity,
    pub(crate) dimension: Option<Dimension>,
    /// For frequencies: the answers are ω² rather than ω.
    pub squared: bool,
    /// For a Lagrangian: any L with the right motion is accepted (a constant factor, V − T,
    /// a total time derivative), not only T − V up to a constant and a total derivative.
    pub(crate) same_motion: bool,
    /// For equilibria: each point's stability must be stated; an answer without it gets
    /// partial credit.
    pub require_stability: bool,
    /// Assumptions of this part only, in addition to the problem's (e.g. the regime in which
    /// the stated equilibria are the ones).
    pub(crate) assumptions: Vec<Assumption>,
    /// A linearized part: the point to expand about, one value per named coordinate (the
    /// others about 0); the answer is the second-order Taylor polynomial in q − q₀ and q̇.
    pub about: Option<Vec<(String, String)>>,
    /// For frequencies: the zero modes (free motions) are not listed.
    pub(crate) omit_zero_modes: bool,
    /// For frequencies: the answers are growth rates λ (q ~ e^{λt}), not frequencies.
    pub growth: bool,
    /// A numeric part (`values` give every parameter a number): the dimension of the answer,
    /// whose units are read in square brackets (`4.43 [rad/s]`) and converted to SI.
    pub units: Option<Dimension>,
    /// The parameters' values as the file gives them (`l = 50 [cm]`), for display.
    pub(crate) values: Vec<(String, String)>,
    /// A numeric part's reference answers as the file writes them, with their units
    /// (`answers` holds them in SI).
    pub(crate) answers_with_units: Vec<String>,
    /// Line of the part in its file.
    pub(crate) line: usize,
    /// The answer may be written with the student's numbers (`1.5*9.81*1.2`) as well as in
    /// symbols: it is judged against the problem pinned to the student's variant.
    pub numbers: bool,
}

impl Part {
    /// The reference answer as a student would type it in one line (`none` for an
    /// explicitly empty list), each point's stability stated where the part requires it
    /// (`r = 0 (unstable)`).
    pub fn reference_text(&self, coordinates: usize) -> String {
        if self.answers.is_empty() {
            return NONE_ANSWER.to_string();
        }
        let sep = match self.kind {
            PartKind::Equations => "; ",
            PartKind::Equilibria if coordinates > 1 => "; ",
            _ => ", ",
        };
        self.reference_items().join(sep)
    }

    /// The reference answer's items as a student writes them: an equilibrium with the
    /// stability the part requires (`r = 0 (unstable)`).
    pub fn reference_items(&self) -> Vec<String> {
        if !self.answers_with_units.is_empty() {
            return self.answers_with_units.clone();
        }
        if self.require_stability {
            return self
                .answers
                .iter()
                .zip(&self.stability)
                .map(|(a, s)| format!("{a} ({s})"))
                .collect();
        }
        self.answers.clone()
    }

    /// Whether the prompt asks about stability (`stable`, `stability`, `unstable`), so that an
    /// equilibria part should require it.
    pub fn prompt_asks_stability(&self) -> bool {
        self.prompt.to_ascii_lowercase().contains("stab")
    }
}

/// A problem ready to check answers against.
#[derive(Clone, Debug)]
pub struct Problem {
    pub file: String,
    pub id: String,
    pub title: String,
    pub(crate) source: String,
    pub statement: String,
    /// The Cartesian axes, origin, sense of rotation and phase of the bodies' positions, in
    /// words (empty when the file does not say).
    pub axes: String,
    pub system: System,
    pub dims: Dimensions,
    pub(crate) assumptions: Vec<Assumption>,
    pub parts: Vec<Part>,
    /// L as written in the file, when it gives one.
    pub(crate) stated_lagrangian: Option<Id>,
    /// Line of the `lagrangian` key (or of the first body).
    pub(crate) lagrangian_line: usize,
    /// What `simulate` starts from when the user gives nothing else.
    pub simulation: SimulationDefaults,
    /// How parameters vary from student to student (`[variants]`; empty: one set of symbols
    /// for everyone).
    pub variants: Vec<variant::Varied>,
}

/// A problem's suggested numbers for simulating it: parameter values, an initial state and a
/// duration, each overridden by what the user gives.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct SimulationDefaults {
    /// Parameter values, in the system's parameter order.
    pub params: Vec<(String, f64)>,
    /// Initial coordinates and velocities (`theta`, `theta'`).
    pub init: Vec<(String, f64)>,
    /// The end time.
    pub t_end: Option<f64>,
}

impl SimulationDefaults {
    /// The user's numbers over these suggestions: a given parameter replaces the suggested one
    /// by name, a given start (`Some`) replaces the suggested start whole, a given end time
    /// the suggested one.
    pub fn complete(
        &self,
        mut params: Vec<(String, f64)>,
        init: Option<Vec<(String, f64)>>,
        t_end: Option<f64>,
    ) -> SimulationDefaults {
        for (name, v) in &self.params {
            if !params.iter().any(|(n, _)| n == name) {
                params.push((name.clone(), *v));
            }
        }
        SimulationDefaults {
            params,
            init: init.unwrap_or_else(|| self.init.clone()),
            t_end: t_end.or(self.t_end),
        }
    }
}

impl Problem {
    /// The part with this id.
    pub fn part(&self, id: &str) -> Option<&Part> {
        self.parts.iter().find(|p| p.id == id)
    }

    /// The closed reading context of the problem (its coordinates and parameters).
    pub fn context(&self) -> Context {
        self.system.context()
    }
}

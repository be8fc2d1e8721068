//! The derivation ladder: the guided Euler–Lagrange derivation of a problem, generated from its
//! system by the mechanics engine (never written in the problem file). Each rung is a [`Step`]
//! whose [`Part`] carries the engine's result as its reference answer, so the ordinary checker
//! judges a step with all its diagnoses.
//!
//! Order: for a system built from bodies, each body's position and speed squared, then T, V
//! and L (a system given by L alone starts at L); for each coordinate q, p = ∂L/∂q', d/dt p,
//! ∂L/∂q and the equation of motion; then, when the problem asks for them, the equilibria, the
//! linearized equations at the stable equilibrium its `frequencies` part names, the roots ω² of
//! det(K − ω² M) = 0 and the frequencies.
//!
//! [`check_step`] checks one answer; a session keeps a [`StepChecker`], which prepares each
//! step once. A step judged against another system than the problem's (the linearized one, or
//! the unconstrained one for a constrained problem's `eom:Q`) carries it in [`Step::against`].
//!
//! Choices:
//! - A position is a `values` part, one item per Cartesian component. The list checker matches
//!   items unordered, so [`check_step`] also checks the components in order (an exchanged x
//!   and y is `swapped-symbols`). The student types `x, y` (no brackets).
//! - The momentum-rate and generalized-force (∂L/∂q) steps are `expression` parts containing
//!   accelerations and velocities; the checker samples those as independent variables (over
//!   [−2, 2]) with the coordinates, so they are compared numerically like any expression, with
//!   the usual diagnoses (`velocity-term` for a missing θ̇₁θ̇₂ term, `sign-error`, …).
//! - Equilibria, ω² and ω are not solved symbolically by the engine (it finds them
//!   numerically); their steps take the problem's own verified answers (`lagrange problems
//!   verify` proves them against the engine's search and eigen-solver). The `characteristic`
//!   step asks for the roots ω² of det(K − ω² M) = 0 (a `frequencies` part with `squared`).
//!   The equilibria step checks the points only: the checker does not read a stability.

use std::borrow::Cow;
use std::collections::hash_map::Entry;

use rustc_hash::FxHashMap;

use crate::check::answer::check_prepared;
use crate::check::prepare::{Prepared, prepare};
use crate::check::{self, CheckError, Code, Diagnosis, Status, Verdict};
use crate::expr::{Id, Style, Sym, read_expr};
use crate::mechanics::{Body, MechError, System};
use crate::problem::{Part, PartKind, Problem, Quantity};

/// One rung of the ladder: what is asked, and the part that checks it.
#[derive(Clone, Debug)]
pub struct Step {
    /// Stable id: `position:1`, `kinetic`, `momentum:theta`, `eom:theta`, `frequencies`, …
    pub id: String,
    /// The question, a plain sentence.
    pub prompt: String,
    /// The part the checker judges the answer against; its `answers` are the reference.
    pub part: Part,
    /// The system an equation step is judged against when it is not the problem's own (the
    /// checker compares an equation with the motion of a system): the linearized system for
    /// `linearized`, the system without its constraints for the `eom:Q` steps of a
    /// constrained problem (whose Euler–Lagrange equations lack the constraint forces).
    pub against: Option<Box<System>>,
}

impl Step {
    /// The reference answer as a student would type it in one line.
    pub fn reference_text(&self, coordinates: usize) -> String {
        self.part.reference_text(coordinates)
    }
}

/// Why a ladder cannot be built.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum LadderError {
    /// The engine could not derive the equations of motion.
    #[error("cannot derive the equations of motion: {0}")]
    Mechanics(#[from] MechError),
    /// A point named by the problem (a `frequencies` part's `at`) cannot be read.
    #[error("cannot read the equilibrium `{text}` of part `{part}`")]
    BadPoint { part: String, text: String },
}

/// The ladder of `problem`, in the order a student climbs it.
pub fn ladder(problem: &Problem) -> Result<Vec<Step>, LadderError> {
    let mut b = Builder {
        problem,
        sys: problem.system.clone(),
        steps: Vec::new(),
    };
    b.energies();
    b.coordinates()?;
    b.statics()?;
    Ok(b.steps)
}

/// Checks `input` against one step. A position is also checked component by component, in
/// order (the list checker alone would accept x and y exchanged).
pub fn check_step(problem: &Problem, step: &Step, input: &str) -> Result<Verdict, CheckError> {
    StepChecker::new(problem).check(step, input)
}

/// Checks answers to the steps of one problem's ladder, preparing each step once (the first
/// answer to a step samples its points and derives what it needs; later answers reuse that).
/// This is what a session keeps while a student climbs the ladder.
pub struct StepChecker<'a> {
    problem: Cow<'a, Problem>,
    /// Per step id: the problem as the step sees it (when it is judged against its own
    /// system) and the prepared part.
    prepared: FxHashMap<String, (Option<Problem>, Prepared)>,
}

impl<'a> StepChecker<'a> {
    /// A checker for the steps of `problem`'s ladder.
    pub fn new(problem: &'a Problem) -> Self {
        StepChecker {
            problem: Cow::Borrowed(problem),
            prepared: FxHashMap::default(),
        }
    }

    /// A checker that owns its problem (what a session keeps while the bank it borrows from
    /// is its own).
    pub fn owned(problem: Problem) -> StepChecker<'static> {
        StepChecker {
            problem: Cow::Owned(problem),
            prepared: FxHashMap::default(),
        }
    }

    /// The problem whose ladder this checker judges.
    pub fn problem(&self) -> &Problem {
        &self.problem
    }

    /// Checks `input` against `step` (a step of this problem's ladder). Errors are usage
    /// errors (a part that cannot be prepared), never a judgement of the input.
    pub fn check(&mut self, step: &Step, input: &str) -> Result<Verdict, CheckError> {
        let problem: &Problem = &self.problem;
        let (own, prepared) = match self.prepared.entry(step.id.clone()) {
            Entry::Occupied(o) => o.into_mut(),
            Entry::Vacant(v) => {
                let own = step.against.as_ref().map(|sys| {
                    let mut own = problem.clone();
                    own.system = (**sys).clone();
                    own
                });
                let prepared = prepare(own.as_ref().unwrap_or(problem), &step.part)?;
                v.insert((own, prepared))
            }
        };
        let judged = own.as_ref().unwrap_or(problem);
        let mut v = check_prepared(judged, &step.part, prepared, input);
        if step.id.starts_with("position:") && v.status == Status::Correct {
            order_of_components(problem, step, input, &mut v)?;
        }
        Ok(v)
    }
}

/// Turns a correct but reordered position into an incorrect one.
fn order_of_components(
    problem: &Problem,
    step: &Step,
    input: &str,
    v: &mut Verdict,
) -> Result<(), CheckError> {
    let items = split_top_level(input);
    if items.len() != step.part.answers.len() {
        return Ok(());
    }
    for (i, (item, answer)) in items.iter().zip(&step.part.answers).enumerate() {
        let mut part = step.part.clone();
        part.kind = PartKind::Expression;
        part.answers = vec![answer.clone()];
        let c = check::check(problem, &part, item)?;
        if c.status != Status::Correct {
            v.status = Status::Incorrect;
            v.score = 0.0;
            v.diagnoses.push(Diagnosis::new(
                Code::SwappedSymbols,
                format!(
                    "these are the right components in the wrong order: component {} should be {}",
                    i + 1,
                    answer
                ),
            ));
            return Ok(());
        }
    }
    Ok(())
}

/// Splits `a, b, (c, d)` at the commas outside brackets (also `;`).
fn split_top_level(input: &str) -> Vec<&str> {
    let mut out = Vec::new();
    let (mut depth, mut start) = (0i32, 0usize);
    let trimmed = input.trim();
    let inner = match (trimmed.strip_prefix('('), trimmed.strip_suffix(')')) {
        (Some(_), Some(_)) if trimmed.len() >= 2 => &trimmed[1..trimmed.len() - 1],
        _ => trimmed,
    };
    for (i, ch) in inner.char_indices() {
        match ch {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            ',' | ';' if depth == 0 => {
                out.push(inner[start..i].trim());
                start = i + ch.len_utf8();
            }
            _ => {}
        }
    }
    out.push(inner[start..].trim());
    out
}

/// Builds the steps in order.
struct Builder<'a> {
    problem: &'a Problem,
    sys: System,
    steps: Vec<Step>,
}

impl Builder<'_> {
    /// A step whose part has the defaults of a problem file.
    fn push(
        &mut self,
        id: String,
        prompt: String,
        kind: PartKind,
        answers: Vec<String>,
    ) -> &mut Part {
        let part = Part {
            id: id.clone(),
            kind,
            prompt: prompt.clone(),
            answers,
            hints: Vec::new(),
            points: 1.0,
            substitute: Vec::new(),
            at: Vec::new(),
            up_to_constant: false,
            wrong: Vec::new(),
            tolerance: 1e-9,
            stability: Vec::new(),
            quantity: Quantity::None,
            dimension: None,
            squared: false,
            line: self.problem.lagrangian_line,
        };
        self.steps.push(Step {
            id,
            prompt,
            part,
            against: None,
        });
        let last = self.steps.len() - 1;
        &mut self.steps[last].part
    }

    fn plain(&self, e: Id) -> String {
        self.sys.pool.plain(e)
    }

    /// The coordinates as a person reads them: `θ₁, θ₂`.
    fn coordinate_list(&self) -> String {
        let names: Vec<String> = (0..self.sys.n()).map(|i| self.name(i, 0)).collect();
        names.join(", ")
    }

    /// Coordinate `i` (or its `order`-th derivative) in Unicode: `θ`, `θ̇`.
    fn name(&self, i: usize, order: u8) -> String {
        let sym = self.sys.coordinates[i].sym;
        self.sys.pool.var_name(sym, order, Style::Unicode)
    }

    /// Positions and speeds of the bodies, T, V and L.
    fn energies(&mut self) {
        let bodies = self.sys.bodies.clone();
        for (i, body) in bodies.iter().enumerate() {
            self.body(i + 1, body);
        }
        if let Some(t) = self.sys.kinetic {
            let answer = self.plain(t);
            let p = self.push(
                "kinetic".into(),
                "Write the total kinetic energy T.".into(),
                PartKind::Expression,
                vec![answer],
            );
            p.quantity = Quantity::Kinetic;
        }
        if let Some(v) = self.sys.potential {
            let answer = self.plain(v);
            let p = self.push(
                "potential".into(),
                "Write the potential energy V (any zero level).".into(),
                PartKind::Expression,
                vec![answer],
            );
            p.quantity = Quantity::Potential;
            p.up_to_constant = true;
        }
        let prompt = if self.sys.kinetic.is_some() {
            "Write the Lagrangian L = T − V.".to_string()
        } else {
            format!(
                "Write the Lagrangian in terms of {}.",
                self.coordinate_list()
            )
        };
        let answer = self.plain(self.sys.lagrangian);
        let p = self.push(
            "lagrangian".into(),
            prompt,
            PartKind::Lagrangian,
            vec![answer],
        );
        p.quantity = Quantity::Lagrangian;
    }

    /// The position and speed-squared steps of body `n` (1-based). A rotor has no position;
    /// its step is its angular speed squared.
    fn body(&mut self, n: usize, body: &Body) {
        let coords = self.sys.coordinate_syms();
        let positive = self.sys.parameter_syms();
        match body {
            Body::Point { position, .. } => {
                let axes = ["x", "y", "z"];
                let names = axes[..position.len().min(3)].join(", ");
                let answers = position.iter().map(|&x| self.plain(x)).collect();
                let prompt = format!(
                    "Write the Cartesian position of body {n} (its {names} components, in that order) in terms of {}, separated by commas.",
                    self.coordinate_list()
                );
                self.push(format!("position:{n}"), prompt, PartKind::Values, answers);
                let mut squares = Vec::new();
                for &x in position {
                    let vx = self.sys.pool.dt(x, &coords);
                    squares.push(self.sys.pool.powi(vx, 2));
                }
                let v2 = self.sys.pool.sum(squares);
                let v2 = self.sys.pool.simplify(v2, &positive);
                let answer = self.plain(v2);
                let prompt = format!(
                    "Differentiate the position in time: write the square of body {n}'s speed (the sum of the squares of its velocity components)."
                );
                self.push(
                    format!("speed-squared:{n}"),
                    prompt,
                    PartKind::Expression,
                    vec![answer],
                );
            }
            Body::Rotor { angle, .. } => {
                let w = self.sys.pool.dt(*angle, &coords);
                let w2 = self.sys.pool.powi(w, 2);
                let w2 = self.sys.pool.simplify(w2, &positive);
                let answer = self.plain(w2);
                let prompt = format!(
                    "Body {n} turns about a fixed axis: write the square of its angular velocity."
                );
                self.push(
                    format!("speed-squared:{n}"),
                    prompt,
                    PartKind::Expression,
                    vec![answer],
                );
            }
        }
    }

    /// For each coordinate: p, d/dt p, ∂L/∂q and the equation of motion.
    fn coordinates(&mut self) -> Result<(), LadderError> {
        let d = self.sys.derive()?;
        for (i, (c, s)) in self
            .sys
            .coordinates
            .clone()
            .iter()
            .zip(d.steps.iter())
            .enumerate()
        {
            let q = &c.name;
            let (u, v) = (self.name(i, 0), self.name(i, 1));
            let answer = self.plain(s.momentum);
            let p = self.push(
                format!("momentum:{q}"),
                format!("Write the momentum conjugate to {u}, p = ∂L/∂{v}."),
                PartKind::Expression,
                vec![answer],
            );
            p.quantity = Quantity::Momentum(i);
            let answer = self.plain(s.momentum_dt);
            self.push(
                format!("momentum-rate:{q}"),
                format!("Differentiate in time: write d/dt (∂L/∂{v})."),
                PartKind::Expression,
                vec![answer],
            );
            let answer = self.plain(s.force);
            self.push(
                format!("generalized-force:{q}"),
                format!("Write the generalized force ∂L/∂{u}."),
                PartKind::Expression,
                vec![answer],
            );
            let answer = format!("{} = 0", self.plain(s.equation));
            let forced = !self.sys.is_zero(s.generalized_force);
            let prompt = if !self.sys.constraints.is_empty() {
                format!(
                    "Put them together: write d/dt (∂L/∂{v}) − ∂L/∂{u} = 0, leaving out the constraint force for now."
                )
            } else if forced {
                format!(
                    "Put them together with the non-conservative force: write the equation of motion for {u}."
                )
            } else {
                format!("Put them together: write the equation of motion for {u}.")
            };
            self.push(format!("eom:{q}"), prompt, PartKind::Equation, vec![answer]);
            if !self.sys.constraints.is_empty() {
                let mut free = self.sys.clone();
                free.constraints.clear();
                let last = self.steps.len() - 1;
                self.steps[last].against = Some(Box::new(free));
            }
        }
        Ok(())
    }

    /// Equilibria, linearized equations, characteristic roots and frequencies, where the
    /// problem has the parts that ask for them.
    fn statics(&mut self) -> Result<(), LadderError> {
        let problem = self.problem;
        if let Some(eq) = problem
            .parts
            .iter()
            .find(|p| p.kind == PartKind::Equilibria)
        {
            // The checker reads the points only; stability is not typed by the student (yet).
            let q = self
                .sys
                .coordinates
                .first()
                .map_or("q", |c| c.name.as_str());
            let form = if self.sys.n() > 1 {
                format!("`{q} = …, …`, the points separated by `;`")
            } else {
                format!("`{q} = …`, separated by commas")
            };
            let prompt = format!(
                "Find every equilibrium, where all the generalized forces vanish at rest; write each as {form}."
            );
            self.adopt(eq, "equilibria", prompt);
        }
        let Some(freq) = problem
            .parts
            .iter()
            .find(|p| p.kind == PartKind::Frequencies && !p.squared)
        else {
            return Ok(());
        };
        self.linearized(freq)?;
        let with = conditions(freq);
        let squared = problem
            .parts
            .iter()
            .find(|p| p.kind == PartKind::Frequencies && p.squared && p.at == freq.at);
        let mut part = match squared {
            Some(s) => s.clone(),
            None => {
                let mut s = freq.clone();
                s.squared = true;
                s.answers = squares(problem, freq);
                s
            }
        };
        part.stability.clear();
        self.adopt(
            &part,
            "characteristic",
            format!(
                "Solve the characteristic equation det(K − ω² M) = 0{with}: give its roots ω²."
            ),
        );
        self.adopt(
            freq,
            "frequencies",
            format!("Give the angular frequencies ω of the small oscillations{with}."),
        );
        Ok(())
    }

    /// A step that asks a problem part's question in the ladder's words (its hints and
    /// `wrong` examples belong to the part, not to the step).
    fn adopt(&mut self, part: &Part, id: &str, prompt: String) {
        let mut part = part.clone();
        part.id = id.to_string();
        part.prompt = prompt.clone();
        part.wrong.clear();
        part.hints.clear();
        self.steps.push(Step {
            id: id.to_string(),
            prompt,
            part,
            against: None,
        });
    }

    /// The linearized equations M (q − q₀)'' + K (q − q₀) = 0 at the point of `freq`, with
    /// M = ∂²L/∂q'∂q' and K = −∂²L/∂q∂q at rest there (parameters substituted as the part
    /// says), judged against the linearized system L = ½ q'ᵀ M q' − ½ (q − q₀)ᵀ K (q − q₀).
    fn linearized(&mut self, freq: &Part) -> Result<(), LadderError> {
        let mut sys = self.problem.system.clone();
        sys.substitute_parameters(&freq.substitute)?;
        let point = point_of(&mut sys, freq)?;
        let (m, k) = mass_and_stiffness(&mut sys, &point);
        let coords = sys.coordinate_syms();
        let n = coords.len();
        let half = sys.pool.ratio(1, 2);
        let mut equations = Vec::new();
        let mut lagrangian = Vec::new();
        for i in 0..n {
            let mut terms = Vec::new();
            for j in 0..n {
                let acc = sys.pool.var(coords[j], 2);
                terms.push(sys.pool.product([m[i][j], acc]));
                let dqj = displacement(&mut sys, coords[j], point[j]);
                let stiff = sys.pool.product([k[i][j], dqj]);
                terms.push(sys.pool.neg(stiff));
                let (vi, vj) = (sys.pool.var(coords[i], 1), sys.pool.var(coords[j], 1));
                lagrangian.push(sys.pool.product([half, m[i][j], vi, vj]));
                let dqi = displacement(&mut sys, coords[i], point[i]);
                lagrangian.push(sys.pool.product([half, k[i][j], dqi, dqj]));
            }
            let e = sys.pool.sum(terms);
            equations.push(format!("{} = 0", sys.pool.plain(e)));
        }
        let l = sys.pool.sum(lagrangian);
        sys.lagrangian = sys.simplify(l);
        sys.kinetic = None;
        sys.potential = None;
        sys.bodies.clear();
        sys.constraints.clear();
        sys.forces = vec![sys.pool.zero(); n];
        let kind = if n == 1 {
            PartKind::Equation
        } else {
            PartKind::Equations
        };
        let prompt = format!(
            "Linearize about the stable equilibrium {}{}: write M q'' + K (q − q₀) = 0 for {}{}.",
            at_text(&sys, &point),
            conditions(freq),
            self.coordinate_list(),
            if n > 1 {
                " (separate the equations with `;`)"
            } else {
                ""
            }
        );
        self.push("linearized".into(), prompt, kind, equations);
        let last = self.steps.len() - 1;
        self.steps[last].against = Some(Box::new(sys));
        Ok(())
    }
}

/// q − q₀ (just q when q₀ is 0).
fn displacement(sys: &mut System, c: Sym, q0: Id) -> Id {
    let q = sys.pool.var(c, 0);
    sys.pool.sub(q, q0)
}

/// M = ∂²L/∂q'∂q' and ∂²L/∂q∂q (that is −K) at rest at `point`.
fn mass_and_stiffness(sys: &mut System, point: &[Id]) -> (Vec<Vec<Id>>, Vec<Vec<Id>>) {
    let coords = sys.coordinate_syms();
    let zero = sys.pool.zero();
    let mut at_rest: FxHashMap<(Sym, u8), Id> = FxHashMap::default();
    for (&c, &q0) in coords.iter().zip(point) {
        at_rest.insert((c, 0), q0);
        at_rest.insert((c, 1), zero);
    }
    let l = sys.lagrangian;
    let (mut m, mut k) = (Vec::new(), Vec::new());
    for &ci in &coords {
        let mut mr = Vec::new();
        let mut kr = Vec::new();
        for &cj in &coords {
            mr.push(second(sys, l, (ci, 1), (cj, 1), &at_rest));
            kr.push(second(sys, l, (ci, 0), (cj, 0), &at_rest));
        }
        m.push(mr);
        k.push(kr);
    }
    (m, k)
}

/// ∂²L/∂a∂b evaluated at `at`, simplified.
fn second(
    sys: &mut System,
    l: Id,
    a: (Sym, u8),
    b: (Sym, u8),
    at: &FxHashMap<(Sym, u8), Id>,
) -> Id {
    let d = sys.pool.diff(l, a.0, a.1);
    let d = sys.pool.diff(d, b.0, b.1);
    let d = sys.pool.substitute(d, at);
    sys.simplify(d)
}

/// The equilibrium of a frequencies part, one expression per coordinate (0 where unnamed).
fn point_of(sys: &mut System, part: &Part) -> Result<Vec<Id>, LadderError> {
    let ctx = sys.context();
    let names: Vec<String> = sys.coordinates.iter().map(|c| c.name.clone()).collect();
    let mut point = Vec::new();
    for name in &names {
        let id = match part.at.iter().find(|(n, _)| n == name) {
            None => sys.pool.zero(),
            Some((_, text)) => {
                read_expr(text, &ctx, &mut sys.pool).map_err(|_| LadderError::BadPoint {
                    part: part.id.clone(),
                    text: text.clone(),
                })?
            }
        };
        point.push(id);
    }
    Ok(point)
}

/// ` (with m1 = m, l1 = l)` when a part substitutes parameters, else nothing.
fn conditions(part: &Part) -> String {
    if part.substitute.is_empty() {
        return String::new();
    }
    let each: Vec<String> = part
        .substitute
        .iter()
        .map(|(n, v)| format!("{n} = {v}"))
        .collect();
    format!(" (with {})", each.join(", "))
}

/// The squares ω² of a frequencies part's answers, simplified (`(sqrt(g/l))^2` is `g/l`).
fn squares(problem: &Problem, part: &Part) -> Vec<String> {
    let mut sys = problem.system.clone();
    let substituted = sys.substitute_parameters(&part.substitute).is_ok();
    let ctx = sys.context();
    let positive = sys.parameter_syms();
    part.answers
        .iter()
        .map(|a| match read_expr(a, &ctx, &mut sys.pool) {
            Ok(w) if substituted => {
                let w2 = sys.pool.powi(w, 2);
                let w2 = sys.pool.simplify(w2, &positive);
                sys.pool.plain(w2)
            }
            _ => format!("({a})^2"),
        })
        .collect()
}

/// The point `θ₁ = 0, θ₂ = 0` in Unicode.
fn at_text(sys: &System, point: &[Id]) -> String {
    sys.coordinates
        .iter()
        .zip(point)
        .map(|(c, &v)| {
            let name = sys.pool.var_name(c.sym, 0, Style::Unicode);
            format!("{name} = {}", sys.pool.unicode(v))
        })
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bank::load_str;

    const ONLY_L: &str = r#"
id = "oscillator"
title = "Harmonic oscillator"
coordinates = [{ name = "x" }]
lagrangian = "1/2*m*x'^2 - 1/2*k*x^2"

[parameters]
m = { dimension = "M", range = [0.5, 2.0] }
k = { dimension = "M T^-2", range = [0.5, 2.0] }

[[parts]]
id = "eom"
kind = "equation"
prompt = "EOM?"
answer = "m*x'' + k*x = 0"
"#;

    #[test]
    fn a_problem_with_only_l_starts_at_l() {
        let p = load_str("oscillator.toml", ONLY_L).unwrap();
        let steps = ladder(&p).unwrap();
        let ids: Vec<&str> = steps.iter().map(|s| s.id.as_str()).collect();
        assert_eq!(
            ids,
            [
                "lagrangian",
                "momentum:x",
                "momentum-rate:x",
                "generalized-force:x",
                "eom:x"
            ]
        );
        assert_eq!(steps[1].part.answers, ["m*x'"]);
        assert_eq!(steps[3].part.answers, ["-k*x"]);
        let v = check_step(&p, &steps[4], "x'' = -k/m*x").unwrap();
        assert_eq!(v.status, Status::Correct);
    }

    #[test]
    fn a_degenerate_system_is_an_error_not_a_panic() {
        let text = ONLY_L.replace("1/2*m*x'^2 - 1/2*k*x^2", "m*x'*x - 1/2*k*x^2");
        // The bank loads it (verification, not loading, would reject it).
        let p = load_str("degenerate.toml", &text).unwrap();
        assert!(matches!(ladder(&p), Err(LadderError::Mechanics(_))));
    }

    /// The roots ω² of det(K − ω² M) = 0 in closed form, for one or two coordinates.
    fn roots(sys: &mut System, m: &[Vec<Id>], k: &[Vec<Id>]) -> Vec<Id> {
        let p = &mut sys.pool;
        // k holds ∂²L/∂q∂q = −K.
        let kk: Vec<Vec<Id>> = k
            .iter()
            .map(|r| r.iter().map(|&x| p.neg(x)).collect())
            .collect();
        if m.len() == 1 {
            return vec![p.div(kk[0][0], m[0][0])];
        }
        let det = |p: &mut crate::expr::Pool, a: &[Vec<Id>]| {
            let d1 = p.mul(a[0][0], a[1][1]);
            let d2 = p.mul(a[0][1], a[1][0]);
            p.sub(d1, d2)
        };
        let a = det(p, m);
        let c = det(p, &kk);
        let terms = [
            p.mul(kk[0][0], m[1][1]),
            p.mul(kk[1][1], m[0][0]),
            p.mul(kk[0][1], m[1][0]),
            p.mul(kk[1][0], m[0][1]),
        ];
        let (t0, t1) = (p.add(terms[0], terms[1]), p.add(terms[2], terms[3]));
        let b = p.sub(t0, t1);
        let b2 = p.powi(b, 2);
        let four = p.ratio(4, 1);
        let ac = p.product([four, a, c]);
        let disc = p.sub(b2, ac);
        let root = p.sqrt(disc);
        let two_a = p.add(a, a);
        let lo = p.sub(b, root);
        let hi = p.add(b, root);
        vec![p.div(lo, two_a), p.div(hi, two_a)]
    }

    /// The engine's M and K give the ω² the problem states (a check that the linearized step
    /// and the characteristic step agree).
    #[test]
    fn m_and_k_give_the_problems_frequencies() {
        for p in &crate::bank::embedded::bank().problems {
            let steps = ladder(p).unwrap();
            let Some(freq) = p.parts.iter().find(|x| x.kind == PartKind::Frequencies) else {
                continue;
            };
            let mut sys = p.system.clone();
            sys.substitute_parameters(&freq.substitute).unwrap();
            let point = point_of(&mut sys, freq).unwrap();
            let (m, k) = mass_and_stiffness(&mut sys, &point);
            let w2 = roots(&mut sys, &m, &k);
            let text: Vec<String> = w2.iter().map(|&w| sys.pool.plain(w)).collect();
            let step = steps.iter().find(|s| s.id == "characteristic").unwrap();
            let v = check_step(p, step, &text.join(", ")).unwrap();
            assert_eq!(
                v.status,
                Status::Correct,
                "{}: {text:?} {:?}",
                p.id,
                v.diagnoses
            );
        }
    }

    #[test]
    fn splits_at_top_level_commas() {
        assert_eq!(split_top_level("(a, f(b, c))"), vec!["a", "f(b, c)"]);
        assert_eq!(split_top_level("x; y"), vec!["x", "y"]);
    }
}

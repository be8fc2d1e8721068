//! Building the ladder from the problem's system: [`ladder`] climbs the energies, each
//! coordinate's Euler–Lagrange steps and the statics (equilibria, linearized equations,
//! characteristic roots, frequencies), with the engine's results as reference answers.

use super::step::{LadderError, Pitfall, Step};
use crate::check::Code;
use crate::expr::{Id, Style, read_expr};
use crate::mechanics::System;
use crate::problem::{Part, PartKind, Problem, Quantity};

mod bodies;
mod statics;
mod teach;
mod velocity_terms;

use statics::point_of;
use statics::{at_text, displacement, mass_and_stiffness};

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
    b.hints();
    // A quantity the problem defines is named in the prompts as the statement names it (the
    // hoop's linearize step says θ = θ₀, not θ = acos(g/(R·ω²))).
    let pool = &problem.system.pool;
    for (name, value) in &problem.system.definitions {
        let (value, name) = (pool.unicode(*value), crate::expr::names::unicode_name(name));
        for s in &mut b.steps {
            s.prompt = s.prompt.replace(&value, &name);
            s.part.prompt = s.prompt.clone();
        }
    }
    Ok(b.steps)
}

/// A frequencies part whose list is every root of det(K − ω² M) = 0 in symbols (not only
/// the nonzero ones, not growth rates, not numbers with units), which the characteristic
/// and frequencies steps can adopt.
fn plain_frequencies(p: &Part) -> bool {
    !p.omit_zero_modes && !p.growth && p.units.is_none()
}

/// A frequencies part the ladder can end on: every root in symbols, or (where the problem asks
/// only for those, as for a free cart) the nonzero roots; not growth rates nor numbers with
/// units, which the linearized equations and det(K − ω² M) do not lead to.
fn ladder_frequencies(p: &Part) -> bool {
    !p.growth && p.units.is_none()
}

/// The problem's frequencies part the ladder ends on: a plain one, else one that omits the
/// zero modes (so that a problem asking only for the nonzero frequencies still gets the
/// linearized, characteristic and frequencies steps).
fn frequencies_part(problem: &Problem) -> Option<&Part> {
    let unsquared = |p: &&Part| p.kind == PartKind::Frequencies && !p.squared;
    let parts = || problem.parts.iter().filter(unsquared);
    parts()
        .find(|p| plain_frequencies(p))
        .or_else(|| parts().find(|p| ladder_frequencies(p)))
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
            same_motion: false,
            require_stability: false,
            assumptions: Vec::new(),
            about: None,
            omit_zero_modes: false,
            growth: false,
            units: None,
            values: Vec::new(),
            answers_with_units: Vec::new(),
            line: self.problem.lagrangian_line,
            numbers: false,
        };
        self.steps.push(Step {
            id,
            prompt,
            part,
            against: None,
            pitfalls: Vec::new(),
        });
        let last = self.steps.len() - 1;
        &mut self.steps[last].part
    }

    /// The step pushed last.
    fn last_mut(&mut self) -> &mut Step {
        let last = self.steps.len().saturating_sub(1);
        &mut self.steps[last]
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
            let l = self.plain(self.sys.lagrangian);
            self.last_mut().pitfalls = vec![Pitfall {
                answers: vec![l],
                code: Code::GaveLagrangian,
                message: format!(
                    "that is the Lagrangian L itself; the momentum is its derivative with respect to the velocity, p = ∂L/∂{v}"
                ),
            }];
            let answer = self.plain(s.momentum_dt);
            self.push(
                format!("momentum-rate:{q}"),
                format!("Differentiate in time: write d/dt (∂L/∂{v})."),
                PartKind::Expression,
                vec![answer],
            );
            let pitfalls = self.rate_pitfalls(i, s);
            self.last_mut().pitfalls = pitfalls;
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
            let pitfalls = self.eom_pitfalls(i, &d.steps);
            self.last_mut().pitfalls = pitfalls;
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
            let q = self.sys.coordinates.first().map_or_else(
                || "q".to_string(),
                |c| crate::expr::names::unicode_name(&c.name),
            );
            let form = if self.sys.n() > 1 {
                format!("`{q} = …, …`, the points separated by `;`")
            } else {
                format!("`{q} = …`, separated by commas")
            };
            let prompt = format!(
                "Find every equilibrium, where all the generalized forces vanish at rest; write each as {form}."
            );
            // This step's prompt asks for the points only.
            let mut eq = eq.clone();
            eq.require_stability = false;
            self.adopt(&eq, "equilibria", prompt);
        }
        let Some(freq) = frequencies_part(problem) else {
            return Ok(());
        };
        // Where the problem omits the zero modes, so do its last two steps.
        let (nonzero, omitted) = if freq.omit_zero_modes {
            (
                "nonzero ",
                " (leave out ω = 0, the free motion nothing pulls back)",
            )
        } else {
            ("", "")
        };
        let with = conditions(freq);
        let w = frequency_symbol(&self.sys);
        if velocity_terms::gyroscopic_at(self.problem, freq)? {
            // M q'' + K q = 0 and det(K − ω² M) would drop the Coriolis terms: ask for ω only.
            self.adopt(
                freq,
                "frequencies",
                format!(
                    "Give the {nonzero}angular frequencies {w} of the small oscillations{with}{omitted}; the terms linear in the velocities stay in the linearized equations (M q'' + G q' + K q = 0)."
                ),
            );
            return Ok(());
        }
        self.linearized(freq)?;
        let squared = problem.parts.iter().find(|p| {
            p.kind == PartKind::Frequencies
                && p.squared
                && p.at == freq.at
                && ladder_frequencies(p)
                && p.omit_zero_modes == freq.omit_zero_modes
        });
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
                "Solve the characteristic equation det(K − {w}² M) = 0{with}: give its {nonzero}roots {w}²{omitted}."
            ),
        );
        self.adopt(
            freq,
            "frequencies",
            format!(
                "Give the {nonzero}angular frequencies {w} of the small oscillations{with}{omitted}."
            ),
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
            pitfalls: Vec::new(),
        });
    }

    /// The linearized equations M (q − q₀)'' + K (q − q₀) = 0 at the point of `freq`, with
    /// M = ∂²L/∂q'∂q' and K = −∂²L/∂q∂q at rest there (parameters substituted as the part
    /// says), judged against the linearized system L = ½ q'ᵀ M q' − ½ (q − q₀)ᵀ K (q − q₀).
    fn linearized(&mut self, freq: &Part) -> Result<(), LadderError> {
        let mut sys = self.problem.system.clone();
        sys.substitute_parameters(&freq.substitute)?;
        let point = point_of(&mut sys, freq)?;
        let pitfalls = self.linear_pitfalls(&sys, &point);
        let (m, k) = mass_and_stiffness(&mut sys, &point);
        // A coordinate no force restores (a cyclic x) is free, not stable.
        let free: Vec<String> = (0..k.len())
            .filter(|&i| k[i].iter().all(|&x| sys.is_zero(x)))
            .map(|i| self.name(i, 0))
            .collect();
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
        let at = at_text(&sys, &point);
        let which = if free.is_empty() {
            format!("the stable equilibrium {at}")
        } else {
            format!(
                "the equilibrium {at} ({} moves freely: no force restores it)",
                free.join(", ")
            )
        };
        let prompt = format!(
            "Linearize about {which}{}: write M q'' + K (q − q₀) = 0 for {}{}.",
            conditions(freq),
            self.coordinate_list(),
            if n > 1 {
                " (separate the equations with `;`)"
            } else {
                ""
            }
        );
        self.push("linearized".into(), prompt, kind, equations);
        let last = self.last_mut();
        last.against = Some(Box::new(sys));
        last.pitfalls = pitfalls;
        Ok(())
    }
}

/// The name the ladder gives the frequency of small oscillations: ω, unless the problem
/// already uses ω for something else (the spin of a hoop or a wire), then Ω, else ω₀, else ν.
/// A step never reuses a problem's symbol for another quantity.
pub fn frequency_symbol(sys: &System) -> &'static str {
    let names: Vec<String> = sys
        .parameters
        .iter()
        .map(|p| p.sym)
        .chain(sys.coordinates.iter().map(|c| c.sym))
        .map(|s| sys.pool.var_name(s, 0, Style::Unicode))
        .collect();
    // A name the problem defines (ω₀ = √(k/m) in the rotating traps) is taken too.
    [
        ("ω", "omega"),
        ("Ω", "Omega"),
        ("ω₀", "omega0"),
        ("ν", "nu"),
    ]
    .into_iter()
    .find(|(w, plain)| {
        !names.iter().any(|n| n == w) && !sys.definitions.iter().any(|(d, _)| d == plain)
    })
    .map_or("ν", |(w, _)| w)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::Status;
    use crate::tutor::ladder::check_step;

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

    /// Whether `w` is 0 at a generic point (every slot 1.1, 1.2, …).
    fn vanishes(sys: &System, w: Id) -> bool {
        let prog = sys.compile(&[w]).unwrap();
        let n = sys.state_layout().len(sys.parameters.len());
        let x: Vec<f64> = (0..n).map(|i| 1.1 + 0.1 * i as f64).collect();
        let mut scratch = prog.scratch();
        prog.run(&x, &mut scratch)
            .is_ok_and(|_| prog.output(0, &scratch).abs() < 1e-9)
    }

    /// The engine's M and K give the ω² the problem states (a check that the linearized step
    /// and the characteristic step agree).
    #[test]
    fn m_and_k_give_the_problems_frequencies() {
        for p in &crate::bank::embedded::bank().problems {
            let steps = ladder(p).unwrap();
            let Some(freq) = frequencies_part(p) else {
                continue;
            };
            let mut sys = p.system.clone();
            sys.substitute_parameters(&freq.substitute).unwrap();
            let point = point_of(&mut sys, freq).unwrap();
            let (m, k) = mass_and_stiffness(&mut sys, &point);
            // A cyclic coordinate (the cart-pendulum's x) gives the free mode ω² = 0, which the
            // problem lists (0 is a frequency) and so the characteristic step asks for.
            // A root that vanishes only after simplification is written as the 0 it is.
            let w2: Vec<Id> = roots(&mut sys, &m, &k);
            // A part that omits the zero modes (the free cart) leaves the root 0 out.
            let text: Vec<String> = w2
                .iter()
                .filter_map(|&w| {
                    if !vanishes(&sys, w) {
                        Some(sys.pool.plain(w))
                    } else if freq.omit_zero_modes {
                        None
                    } else {
                        Some("0".into())
                    }
                })
                .collect();
            // A gyroscopic problem (the rotating trap) has no det(K − ω² M) step.
            let Some(step) = steps.iter().find(|s| s.id == "characteristic") else {
                assert!(
                    p.id.starts_with("rotating-trap"),
                    "{}: no characteristic step",
                    p.id
                );
                continue;
            };
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
}

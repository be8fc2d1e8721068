//! What the ladder teaches besides its questions: the common wrong answers of the
//! Euler–Lagrange steps with their reasons ([`Pitfall`]s — a chain-rule term lost in
//! d/dt ∂L/∂q̇, the other coordinate's equation, the Euler–Lagrange sign, a linearization about
//! the wrong point), and the hints of every step, generated from the step's physics.

use super::{Builder, at_text, displacement, mass_and_stiffness};
use crate::check::Code;
use crate::expr::Id;
use crate::mechanics::System;
use crate::mechanics::derive::CoordinateSteps;
use crate::tutor::ladder::step::Pitfall;

impl Builder<'_> {
    /// The pitfalls of d/dt (∂L/∂q̇ᵢ): the chain-rule terms lost (all, or one coordinate's),
    /// the velocities' rate lost, the chain-rule terms with the wrong sign.
    pub(super) fn rate_pitfalls(&mut self, i: usize, s: &CoordinateSteps) -> Vec<Pitfall> {
        let v = self.name(i, 1);
        let coords = self.sys.coordinate_syms();
        let pool = &mut self.sys.pool;
        let mut chain_terms = Vec::new();
        let mut rate_terms = Vec::new();
        for &c in &coords {
            let dq = pool.diff(s.momentum, c, 0);
            let qdot = pool.var(c, 1);
            chain_terms.push(pool.mul(dq, qdot));
            let dv = pool.diff(s.momentum, c, 1);
            let qddot = pool.var(c, 2);
            rate_terms.push(pool.mul(dv, qddot));
        }
        let chain = self.sys.pool.sum(chain_terms.clone());
        let chain = self.sys.simplify(chain);
        if self.sys.is_zero(chain) {
            return Vec::new();
        }
        let rate = self.sys.pool.sum(rate_terms);
        let rate = self.sys.simplify(rate);
        let mut out = Vec::new();
        let without = |b: &mut Self, term: Id| {
            let e = b.sys.pool.sub(s.momentum_dt, term);
            let e = b.sys.simplify(e);
            vec![b.plain(e)]
        };
        let chain_text = self.sys.pool.unicode(chain);
        out.push(Pitfall {
            answers: without(self, chain),
            code: Code::DerivativeRule,
            message: format!(
                "derivative rule: you differentiated only the velocities, but ∂L/∂{v} also depends on the coordinates, so the chain rule adds the term {chain_text} (d/dt cos u = −sin u · u̇)"
            ),
        });
        if coords.len() > 1 {
            for (j, &term) in chain_terms.iter().enumerate() {
                let term = self.sys.simplify(term);
                let rest = self.sys.pool.sub(term, chain);
                if self.sys.is_zero(term) || self.sys.is_zero(rest) {
                    continue;
                }
                let u = self.name(j, 0);
                let text = self.sys.pool.unicode(term);
                out.push(Pitfall {
                    answers: without(self, term),
                    code: Code::DerivativeRule,
                    message: format!(
                        "derivative rule: the chain rule's term from {u} is missing: {text} (∂L/∂{v} depends on {u}, which changes in time)"
                    ),
                });
            }
        }
        if !self.sys.is_zero(rate) {
            let text = self.sys.pool.unicode(rate);
            out.push(Pitfall {
                answers: without(self, rate),
                code: Code::DerivativeRule,
                message: format!(
                    "derivative rule: you differentiated only the coordinates in ∂L/∂{v}; its velocities change too (d/dt {v} = its acceleration), which adds {text}"
                ),
            });
        }
        let twice = self.sys.pool.add(chain, chain);
        out.push(Pitfall {
            answers: without(self, twice),
            code: Code::SignError,
            message: format!(
                "sign error in the chain rule: its terms are {chain_text} (d/dt cos u = −sin u · u̇, d/dt sin u = cos u · u̇)"
            ),
        });
        out
    }

    /// The pitfalls of the equation of motion for coordinate `i`: another coordinate's
    /// equation, ∂L/∂q added, d/dt ∂L/∂q̇ without its chain-rule terms.
    pub(super) fn eom_pitfalls(&mut self, i: usize, steps: &[CoordinateSteps]) -> Vec<Pitfall> {
        let (u, v) = (self.name(i, 0), self.name(i, 1));
        let mut out = Vec::new();
        let el = |u: &str, v: &str| format!("d/dt(∂L/∂{v}) − ∂L/∂{u} = 0");
        for (k, other) in steps.iter().enumerate() {
            if k == i {
                continue;
            }
            let (uk, vk) = (self.name(k, 0), self.name(k, 1));
            out.push(Pitfall {
                answers: vec![format!("{} = 0", self.plain(other.equation))],
                code: Code::WrongEquation,
                message: format!(
                    "that is the {uk} equation ({}); this step asks for the {u} equation, {}",
                    el(&uk, &vk),
                    el(&u, &v)
                ),
            });
        }
        let s = &steps[i];
        if !self.sys.is_zero(s.force) {
            let twice = self.sys.pool.add(s.force, s.force);
            let e = self.sys.pool.add(s.equation, twice);
            let e = self.sys.simplify(e);
            out.push(Pitfall {
                answers: vec![format!("{} = 0", self.plain(e))],
                code: Code::SignError,
                message: format!(
                    "sign error: Euler–Lagrange is {}; your equation adds ∂L/∂{u} instead of subtracting it",
                    el(&u, &v)
                ),
            });
        }
        if !self.sys.is_zero(s.force) {
            let e = self.sys.pool.add(s.equation, s.force);
            let e = self.sys.simplify(e);
            out.push(Pitfall {
                answers: vec![format!("{} = 0", self.plain(e))],
                code: Code::MissingTerm,
                message: format!(
                    "missing term: your equation has d/dt(∂L/∂{v}) but not ∂L/∂{u}; Euler–Lagrange is {}",
                    el(&u, &v)
                ),
            });
        }
        if !self.sys.is_zero(s.momentum_dt) {
            let e = self.sys.pool.sub(s.equation, s.momentum_dt);
            let e = self.sys.simplify(e);
            out.push(Pitfall {
                answers: vec![format!("{} = 0", self.plain(e))],
                code: Code::MissingTerm,
                message: format!(
                    "missing term: your equation has ∂L/∂{u} but not d/dt(∂L/∂{v}); Euler–Lagrange is {}",
                    el(&u, &v)
                ),
            });
        }
        for p in self.rate_pitfalls(i, s) {
            if p.code != Code::DerivativeRule {
                continue;
            }
            // The same lost term, now inside the equation.
            let lost = format!("({}) - ({})", self.plain(s.momentum_dt), p.answers[0]);
            out.push(Pitfall {
                answers: vec![format!("{} - ({lost}) = 0", self.plain(s.equation))],
                code: p.code,
                message: p.message.replacen(
                    "derivative rule: ",
                    &format!("derivative rule in d/dt(∂L/∂{v}): "),
                    1,
                ),
            });
        }
        out
    }

    /// The pitfalls of the linearized equations at `point`: linearized about another point
    /// (the origin, or an angle turned by π), or written in q where the displacement q − q₀
    /// belongs.
    pub(super) fn linear_pitfalls(&self, sys: &System, point: &[Id]) -> Vec<Pitfall> {
        let mut out = Vec::new();
        let here = at_text(sys, point);
        let mut candidates: Vec<Vec<Id>> = Vec::new();
        let mut s = sys.clone();
        let zero = s.pool.zero();
        let pi = s.pool.pi();
        if point.iter().any(|&q| !s.is_zero(q)) {
            candidates.push(vec![zero; point.len()]);
        }
        for k in 0..point.len() {
            let mut c = point.to_vec();
            c[k] = s.pool.add(point[k], pi);
            c[k] = s.simplify(c[k]);
            candidates.push(c);
        }
        for c in candidates {
            let eqs = linear_equations(&mut s, &c, &c);
            out.push(Pitfall {
                answers: eqs,
                code: Code::ExpansionPoint,
                message: format!(
                    "expansion point: these are the equations linearized about {}; this step expands about the equilibrium {here}",
                    at_text(&s, &c)
                ),
            });
        }
        if point.iter().any(|&q| !s.is_zero(q)) {
            let zeros = vec![zero; point.len()];
            let eqs = linear_equations(&mut s, point, &zeros);
            out.push(Pitfall {
                answers: eqs,
                code: Code::ExpansionPoint,
                message: format!(
                    "expansion point: expand in the displacement from the equilibrium {here}: write q − q₀, not q"
                ),
            });
        }
        out
    }

    /// The hints of every step that has none yet, from what the step asks.
    pub(super) fn hints(&mut self) {
        let n = self.sys.n();
        let coords = self.coordinate_list();
        for step in &mut self.steps {
            if !step.part.hints.is_empty() {
                continue;
            }
            let kind = step.id.split(':').next().unwrap_or_default();
            let hints: Vec<String> = match kind {
                "position" => vec![
                    "Go from the origin to the body one segment at a time: a rod or string of length l at angle θ adds l times the unit vector along it; write each component in the axes the step states.".into(),
                    format!("Check each component at {coords} = 0, where you can see where the body is."),
                ],
                "speed-squared" | "angular-speed-squared" => vec![
                    "Differentiate each component in time with the chain rule (d/dt sin θ = cos θ · θ̇), then add the squares of the velocity components.".into(),
                    "Simplify with sin² + cos² = 1 and cos a cos b + sin a sin b = cos(a − b).".into(),
                ],
                "kinetic" => vec![
                    "T = Σ ½ m v² over the bodies (plus ½ I ω² for a body that turns), with the speeds squared of the earlier steps.".into(),
                ],
                "potential" => vec![
                    "V = Σ m g h, with h each body's height above a level of your choice (plus ½ k x² for each spring, x its extension).".into(),
                    "A body lower down has less potential energy: with y up, h = y.".into(),
                ],
                "lagrangian" => vec![
                    "L = T − V: the kinetic energy minus the potential energy (not plus).".into(),
                ],
                "momentum" => vec![
                    "Differentiate L with respect to the velocity, holding the coordinates and the other velocities fixed: only the terms of T with that velocity contribute.".into(),
                ],
                "momentum-rate" => vec![
                    "Differentiate every factor in time: a velocity gives an acceleration (d/dt θ̇ = θ̈), and a function of the coordinates gives its chain-rule term (d/dt cos(θ₁ − θ₂) = −sin(θ₁ − θ₂)·(θ̇₁ − θ̇₂)).".into(),
                ],
                "generalized-force" => vec![
                    "Differentiate L with respect to the coordinate, holding every velocity fixed: V contributes −∂V/∂q, and T too where it depends on that coordinate.".into(),
                ],
                "eom" => vec![
                    "Euler–Lagrange: d/dt(∂L/∂q̇) − ∂L/∂q = 0 (minus, not plus), with your last two steps' answers.".into(),
                ],
                "equilibria" => vec![
                    "At rest every velocity and acceleration is 0: set them to 0 in the equations of motion and solve for the coordinates.".into(),
                    "Do not divide by a factor like sin θ: its zeros are equilibria too.".into(),
                ],
                "linearized" => vec![
                    "Write each coordinate as its equilibrium value plus a small displacement and keep first-order terms only: M = ∂²L/∂q̇² and K = −∂²L/∂q² at the equilibrium.".into(),
                    "Near θ₀ = 0: sin θ ≈ θ, cos θ ≈ 1; near θ₀ = π: sin θ ≈ −(θ − π).".into(),
                ],
                "characteristic" => vec![
                    "Put q = A cos(ωt) into M q'' + K q = 0: a nonzero A needs det(K − ω² M) = 0, a polynomial in ω².".into(),
                    if n > 1 {
                        "For two coordinates, the determinant is a quadratic in ω²: solve it with the quadratic formula.".into()
                    } else {
                        "For one coordinate, ω² = K/M.".into()
                    },
                ],
                "frequencies" => vec![
                    "Each angular frequency is the positive square root of a root ω² of det(K − ω² M) = 0.".into(),
                ],
                _ => vec!["Write out what the step asks one term at a time; `:show` reveals the step's answer.".into()],
            };
            step.part.hints = hints;
        }
    }
}

/// The linearized equations M q'' + K (q − q₀) = 0 with M and K taken at `at`, written as
/// displacements from `from` (each a plain-syntax equation).
fn linear_equations(sys: &mut System, at: &[Id], from: &[Id]) -> Vec<String> {
    let (m, k) = mass_and_stiffness(sys, at);
    let coords = sys.coordinate_syms();
    let n = coords.len();
    (0..n)
        .map(|i| {
            let mut terms = Vec::new();
            for j in 0..n {
                let acc = sys.pool.var(coords[j], 2);
                terms.push(sys.pool.product([m[i][j], acc]));
                let d = displacement(sys, coords[j], from[j]);
                let stiff = sys.pool.product([k[i][j], d]);
                terms.push(sys.pool.neg(stiff));
            }
            let e = sys.pool.sum(terms);
            format!("{} = 0", sys.pool.plain(e))
        })
        .collect()
}

//! [`DerivationReport`]: what `derive` shows — every step of the Euler–Lagrange equations,
//! the mass matrix and forcing, the energy function, conserved momenta, and the constraint
//! rows with their multipliers — built by [`derivation`] and rendered by
//! [`DerivationReport::render`].
//!
//! The serialized fields are in alphabetical order: that is the order of the JSON the command
//! has always printed, which scripts may compare textually.

use std::fmt::{self, Write as _};

use serde::{Serialize, Serializer};

use super::{Formula, Paint, text};
use crate::expr::{Factored, Id, Style};
use crate::mechanics::{Conservation, ConstraintKind, MechError, System};

/// Everything `derive` shows about a system.
#[derive(Clone, Debug, Serialize)]
#[non_exhaustive]
pub struct DerivationReport {
    /// The accelerations and multipliers at the state given (`derive --at`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at: Option<StateSolution>,
    /// The equations with multipliers λ, when there are constraints.
    pub(crate) augmented_equations: Option<Vec<Formula>>,
    /// The momentum of each cyclic coordinate.
    pub(crate) conserved_momenta: Vec<ConservedMomentum>,
    /// The constraints, each `= 0`.
    pub(crate) constraints: Vec<ConstraintLine>,
    /// Coordinate names.
    pub(crate) coordinates: Vec<String>,
    /// Names of the cyclic coordinates.
    pub(crate) cyclic: Vec<String>,
    /// Whether h is conserved.
    pub(crate) energy_conserved: bool,
    /// h = Σ q̇ ∂L/∂q̇ − L.
    pub(crate) energy_function: Formula,
    /// Whether h = T + V; `null` when only L was given (T and V are not known, so it cannot
    /// be told from L alone).
    pub(crate) energy_is_total: Option<bool>,
    /// L₂, L₁, L₀: the parts of L of degree 2, 1 and 0 in the velocities (h = L₂ − L₀);
    /// `null` when L is not quadratic in the velocities.
    pub(crate) energy_parts: Option<EnergyParts>,
    /// The Euler–Lagrange expressions, each `= 0`.
    pub equations: Vec<Formula>,
    /// f in M q̈ = f.
    pub(crate) forcing: Vec<Formula>,
    /// ∂L/∂q for each coordinate.
    pub(crate) generalized_forces: Vec<Formula>,
    /// L.
    pub(crate) lagrangian: Formula,
    /// M in M q̈ = f.
    pub(crate) mass_matrix: Vec<Vec<Formula>>,
    /// p = ∂L/∂q̇ for each coordinate.
    pub(crate) momenta: Vec<Formula>,
    /// d/dt p for each coordinate.
    pub(crate) momenta_dt: Vec<Formula>,
    /// The multipliers in closed form; `None` without constraints or when the system is too
    /// large for a closed form.
    pub multipliers: Option<Vec<Formula>>,
    /// Parameter names.
    pub(crate) parameters: Vec<String>,
    /// How the text shows each coordinate: (q, q̇).
    #[serde(skip)]
    pub(crate) coordinate_labels: Vec<(Formula, Formula)>,
    /// How the text shows each parameter.
    #[serde(skip)]
    pub(crate) parameter_labels: Vec<Formula>,
    /// The non-conservative force Q of each coordinate, when it is not zero.
    #[serde(skip)]
    pub(crate) applied_forces: Vec<Option<Formula>>,
    /// The equations with common factors taken out, as the text shows them.
    #[serde(skip)]
    pub(crate) factored_equations: Vec<Formula>,
    /// T + V when T and V are known, shown when it differs from h.
    #[serde(skip)]
    pub(crate) total_energy: Option<Formula>,
    /// Why h is or is not conserved.
    #[serde(skip)]
    pub(crate) conservation: Conservation,
    /// T is known and not a quadratic form in the velocities (why h ≠ T + V).
    #[serde(skip)]
    pub(crate) kinetic_not_quadratic: bool,
}

/// The accelerations and multipliers at a state.
#[derive(Clone, Debug, Serialize)]
pub struct StateSolution {
    /// Time at the state.
    pub(crate) t: f64,
    /// The coordinates there, in coordinate order.
    pub(crate) positions: Vec<f64>,
    /// The velocities there.
    pub(crate) velocities: Vec<f64>,
    /// The accelerations q̈ there.
    pub accelerations: Vec<f64>,
    /// λ₁, λ₂, … there (the constraint forces); empty without constraints.
    pub multipliers: Vec<f64>,
    /// How the text shows each q̈.
    #[serde(skip)]
    pub(crate) acceleration_labels: Vec<Formula>,
}

/// L split by degree in the velocities.
#[derive(Clone, Debug, Serialize)]
pub struct EnergyParts {
    /// The velocity-free part L₀.
    pub(crate) l0: Formula,
    /// The part linear in the velocities L₁ (it does not enter h).
    pub(crate) l1: Formula,
    /// The quadratic part L₂.
    pub(crate) l2: Formula,
}

/// A cyclic coordinate and its conserved momentum.
#[derive(Clone, Debug, Serialize)]
pub struct ConservedMomentum {
    /// The coordinate's name.
    pub(crate) coordinate: String,
    /// Its momentum.
    pub(crate) momentum: Formula,
    /// The coordinate's position in the system, for its label.
    #[serde(skip)]
    pub(crate) index: usize,
}

/// A constraint `constraint = 0`.
#[derive(Clone, Debug, Serialize)]
pub struct ConstraintLine {
    /// The constraint expression.
    pub(crate) constraint: Formula,
    /// Holonomic or nonholonomic (serialized in lower case).
    #[serde(serialize_with = "lowercase_kind")]
    pub(crate) kind: ConstraintKind,
}

fn lowercase_kind<S: Serializer>(k: &ConstraintKind, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&format!("{k:?}").to_ascii_lowercase())
}

/// Derives `sys` and gathers everything `derive` shows. `sys` itself is left unchanged.
pub fn derivation(sys: &System) -> Result<DerivationReport, MechError> {
    let mut sys = sys.clone();
    let d = sys.derive()?;
    let energy = sys.energy(&d);
    let rows = (!sys.constraints.is_empty()).then(|| sys.constraint_rows());
    let augmented = rows.as_ref().map(|r| sys.augmented_equations(&d, r));
    let multipliers = rows.as_ref().and_then(|r| sys.multipliers_symbolic(&d, r));
    let factored: Vec<Factored> = d
        .steps
        .iter()
        .map(|s| sys.pool.factored(s.equation))
        .collect();
    let (coordinate_labels, parameter_labels) = labels(&mut sys);
    let pool = &sys.pool;
    let f = |e: Id| Formula::new(pool, e);
    let all = |es: &[Id]| es.iter().map(|&e| f(e)).collect::<Vec<_>>();
    let names: Vec<String> = sys.coordinates.iter().map(|c| c.name.clone()).collect();
    let step = |pick: fn(&crate::mechanics::CoordinateSteps) -> Id| {
        d.steps.iter().map(|s| f(pick(s))).collect::<Vec<_>>()
    };
    Ok(DerivationReport {
        at: None,
        augmented_equations: augmented.as_deref().map(all),
        conserved_momenta: energy
            .cyclic
            .iter()
            .map(|&i| ConservedMomentum {
                coordinate: names[i].clone(),
                momentum: f(d.steps[i].momentum),
                index: i,
            })
            .collect(),
        constraints: sys
            .constraints
            .iter()
            .map(|c| ConstraintLine {
                constraint: f(c.expr),
                kind: c.kind,
            })
            .collect(),
        cyclic: energy.cyclic.iter().map(|&i| names[i].clone()).collect(),
        energy_conserved: energy.conserved,
        energy_function: f(energy.function),
        energy_is_total: energy.is_total,
        energy_parts: energy.parts.map(|p| EnergyParts {
            l0: f(p.l0),
            l1: f(p.l1),
            l2: f(p.l2),
        }),
        equations: step(|s| s.equation),
        forcing: all(&d.forcing),
        generalized_forces: step(|s| s.force),
        lagrangian: f(sys.lagrangian),
        mass_matrix: d.mass.iter().map(|r| all(r)).collect(),
        momenta: step(|s| s.momentum),
        momenta_dt: step(|s| s.momentum_dt),
        multipliers: multipliers.as_deref().map(all),
        parameters: sys.parameters.iter().map(|p| p.name.clone()).collect(),
        coordinate_labels,
        parameter_labels,
        applied_forces: d
            .steps
            .iter()
            .map(|s| (!pool.is_zero(s.generalized_force)).then(|| f(s.generalized_force)))
            .collect(),
        factored_equations: factored
            .iter()
            .map(|x| Formula::factored(pool, x))
            .collect(),
        total_energy: energy.total.map(f),
        conservation: energy.conservation,
        kinetic_not_quadratic: energy.kinetic_not_quadratic,
        coordinates: names,
    })
}

/// How each coordinate (q, q̇) and each parameter is shown.
fn labels(sys: &mut System) -> (Vec<(Formula, Formula)>, Vec<Formula>) {
    let coordinates = sys
        .coordinates
        .clone()
        .iter()
        .map(|c| {
            let q = sys.pool.var(c.sym, 0);
            let qd = sys.pool.var(c.sym, 1);
            (Formula::new(&sys.pool, q), Formula::new(&sys.pool, qd))
        })
        .collect();
    let parameters = sys
        .parameters
        .clone()
        .iter()
        .map(|p| {
            let v = sys.pool.var(p.sym, 0);
            Formula::new(&sys.pool, v)
        })
        .collect();
    (coordinates, parameters)
}

impl DerivationReport {
    /// The report as text: with `Style::Latex` an `align*` block of the steps and h; otherwise
    /// the full report with expressions in `style`, marked up by `paint`.
    pub fn render(&self, style: Style, paint: &dyn Paint) -> String {
        text(|o| {
            if style == Style::Latex {
                return self.render_latex(o);
            }
            self.render_steps(style, paint, o)?;
            self.render_energy(style, paint, o)?;
            self.render_constraints(style, paint, o)?;
            self.render_state(style, paint, o)
        })
    }

    fn render_latex(&self, o: &mut String) -> fmt::Result {
        writeln!(o, "\\begin{{align*}}")?;
        writeln!(o, "L &= {} \\\\", self.lagrangian.latex)?;
        for (i, (q, qd)) in self.coordinate_labels.iter().enumerate() {
            let (q, qd) = (&q.latex, &qd.latex);
            writeln!(
                o,
                "p_{{{q}}} = \\frac{{\\partial L}}{{\\partial {qd}}} &= {} \\\\",
                self.momenta[i].latex
            )?;
            writeln!(
                o,
                "\\frac{{d}}{{dt}} p_{{{q}}} &= {} \\\\",
                self.momenta_dt[i].latex
            )?;
            writeln!(
                o,
                "\\frac{{\\partial L}}{{\\partial {q}}} &= {} \\\\",
                self.generalized_forces[i].latex
            )?;
            if let Some(force) = &self.applied_forces[i] {
                writeln!(o, "Q_{{{q}}} &= {} \\\\", force.latex)?;
            }
            writeln!(o, "{} &= 0 \\\\", self.factored_equations[i].latex)?;
        }
        self.render_latex_constraints(o)?;
        self.render_latex_state(o)?;
        writeln!(o, "h &= {}", self.energy_function.latex)?;
        writeln!(o, "\\end{{align*}}")
    }

    /// The constraints, the equations with multipliers and the multipliers' closed forms.
    fn render_latex_constraints(&self, o: &mut String) -> fmt::Result {
        let Some(aug) = &self.augmented_equations else {
            return Ok(());
        };
        for c in &self.constraints {
            let kind = match c.kind {
                ConstraintKind::Holonomic => "holonomic",
                ConstraintKind::Nonholonomic => "nonholonomic",
            };
            writeln!(
                o,
                "{} &= 0 && \\text{{({kind} constraint)}} \\\\",
                c.constraint.latex
            )?;
        }
        for e in aug {
            writeln!(o, "{} &= 0 \\\\", e.latex)?;
        }
        if let Some(ms) = &self.multipliers {
            for (j, m) in ms.iter().enumerate() {
                writeln!(o, "\\lambda_{{{}}} &= {} \\\\", j + 1, m.latex)?;
            }
        }
        Ok(())
    }

    fn render_steps(&self, style: Style, paint: &dyn Paint, o: &mut String) -> fmt::Result {
        writeln!(
            o,
            "{} L = {}",
            paint.heading("Lagrangian:"),
            self.lagrangian.get(style)
        )?;
        let coords: Vec<&str> = self
            .coordinate_labels
            .iter()
            .map(|l| l.0.get(style))
            .collect();
        let params: Vec<&str> = self.parameter_labels.iter().map(|p| p.get(style)).collect();
        writeln!(
            o,
            "{} {}    {} {}",
            paint.heading("coordinates:"),
            coords.join(", "),
            paint.heading("parameters:"),
            if params.is_empty() {
                "none".to_string()
            } else {
                params.join(", ")
            }
        )?;
        for (i, (q, qd)) in self.coordinate_labels.iter().enumerate() {
            let (q, qd) = (q.get(style), qd.get(style));
            writeln!(o, "\n{} {q}", paint.heading("Coordinate"))?;
            writeln!(o, "  p = ∂L/∂{qd} = {}", self.momenta[i].get(style))?;
            writeln!(o, "  d/dt p = {}", self.momenta_dt[i].get(style))?;
            writeln!(o, "  ∂L/∂{q} = {}", self.generalized_forces[i].get(style))?;
            if let Some(force) = &self.applied_forces[i] {
                writeln!(o, "  Q = {}", force.get(style))?;
            }
            writeln!(
                o,
                "  {} {} = 0",
                if self.applied_forces[i].is_none() {
                    "d/dt p − ∂L/∂q:"
                } else {
                    "d/dt p − ∂L/∂q − Q:"
                },
                paint.good(self.factored_equations[i].get(style))
            )?;
        }
        writeln!(
            o,
            "\n{} (M q̈ = f)",
            paint.heading("Mass matrix M and forcing f")
        )?;
        for (row, f) in self.mass_matrix.iter().zip(&self.forcing) {
            let cells: Vec<&str> = row.iter().map(|m| m.get(style)).collect();
            writeln!(o, "  [ {} ]   [ {} ]", cells.join(", "), f.get(style))?;
        }
        Ok(())
    }

    fn render_energy(&self, style: Style, paint: &dyn Paint, o: &mut String) -> fmt::Result {
        writeln!(
            o,
            "\n{} h = Σ q̇ ∂L/∂q̇ − L = {}",
            paint.heading("Energy function:"),
            self.energy_function.get(style)
        )?;
        if let Some(p) = &self.energy_parts {
            let l1 = if p.l1.plain == "0" {
                String::new()
            } else {
                format!("; L₁ = {} does not enter h", p.l1.get(style))
            };
            writeln!(
                o,
                "  h = L₂ − L₀ with L₂ = {}, L₀ = {}{l1}",
                p.l2.get(style),
                p.l0.get(style)
            )?;
        }
        writeln!(o, "  conserved: {}", conservation_text(self.conservation))?;
        let total = match (self.energy_is_total, &self.total_energy) {
            (Some(true), _) => "yes".to_string(),
            (Some(false), Some(t)) if self.kinetic_not_quadratic => format!(
                "no (T + V = {}): T is not a quadratic form in the velocities (a moving frame or support)",
                t.get(style)
            ),
            (Some(false), Some(t)) => format!("no (T + V = {})", t.get(style)),
            _ => "cannot tell from L alone: it holds if the velocity-free part of L is −V (no moving frame)".to_string(),
        };
        writeln!(o, "  h = T + V: {total}")?;
        if self.conserved_momenta.is_empty() {
            writeln!(o, "{} none", paint.heading("Cyclic coordinates:"))?;
        }
        for c in &self.conserved_momenta {
            writeln!(
                o,
                "{} {} — conserved momentum {}",
                paint.heading("Cyclic coordinate:"),
                self.coordinate_labels[c.index].0.get(style),
                c.momentum.get(style)
            )?;
        }
        Ok(())
    }

    fn render_constraints(&self, style: Style, paint: &dyn Paint, o: &mut String) -> fmt::Result {
        let Some(aug) = &self.augmented_equations else {
            return Ok(());
        };
        writeln!(o, "\n{}", paint.heading("Constraints"))?;
        for c in &self.constraints {
            writeln!(o, "  {} = 0 ({:?})", c.constraint.get(style), c.kind)?;
        }
        writeln!(o, "  with multipliers λ:")?;
        for e in aug {
            writeln!(o, "  {} = 0", e.get(style))?;
        }
        match &self.multipliers {
            Some(ms) => {
                for (j, m) in ms.iter().enumerate() {
                    writeln!(o, "  λ{} = {}", j + 1, m.get(style))?;
                }
            }
            None => {
                writeln!(
                    o,
                    "  (too large for a closed form: the multipliers are solved numerically at a state given with --at)"
                )?;
            }
        }
        Ok(())
    }
}

/// Why h is or is not conserved, as the text says it.
fn conservation_text(c: Conservation) -> &'static str {
    match c {
        Conservation::Conserved => "yes (∂L/∂t = 0 and no generalized force doing work)",
        Conservation::ConservedPowerlessForces => {
            "yes (∂L/∂t = 0 and the forces do no work: Σ Q q̇ = 0)"
        }
        Conservation::ExplicitTime => "no (L depends explicitly on t)",
        Conservation::ForcesDoWork => {
            "no (the generalized forces given do work; a conservative force belongs in V, where it would be counted)"
        }
        Conservation::MovingConstraint => "no (a constraint depends on t: its force does work)",
    }
}

impl DerivationReport {
    /// The accelerations and multipliers at the state given (`derive --at`), as LaTeX rows.
    fn render_latex_state(&self, o: &mut String) -> fmt::Result {
        let Some(s) = &self.at else {
            return Ok(());
        };
        for (label, a) in s.acceleration_labels.iter().zip(&s.accelerations) {
            writeln!(o, "{} &= {a} && \\text{{(at the state)}} \\\\", label.latex)?;
        }
        for (j, l) in s.multipliers.iter().enumerate() {
            writeln!(
                o,
                "\\lambda_{{{}}} &= {l} && \\text{{(at the state)}} \\\\",
                j + 1
            )?;
        }
        Ok(())
    }

    /// The accelerations and multipliers at the state given, when there is one.
    fn render_state(&self, style: Style, paint: &dyn Paint, o: &mut String) -> fmt::Result {
        let Some(s) = &self.at else {
            return Ok(());
        };
        writeln!(
            o,
            "\n{}",
            paint.heading(&format!("At the state (t = {})", s.t))
        )?;
        for (i, (q, qd)) in self.coordinate_labels.iter().enumerate() {
            writeln!(
                o,
                "  {} = {}, {} = {}: {} = {}",
                q.get(style),
                s.positions[i],
                qd.get(style),
                s.velocities[i],
                s.acceleration_labels[i].get(style),
                s.accelerations[i]
            )?;
        }
        for (j, l) in s.multipliers.iter().enumerate() {
            writeln!(o, "  λ{} = {l}", j + 1)?;
        }
        Ok(())
    }
}

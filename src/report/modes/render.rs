//! The text of a [`ModesReport`]: each equilibrium's stability, rates, frequencies, damped
//! and free motions and mode shapes, then what the search covered and the closed forms.

use std::fmt::{self, Write as _};

use super::shown::{point_text, write_coverage, write_shape};
use super::{EquilibriumModes, ModesReport};
use crate::check::compare::fmt_value;
use crate::expr::Style;
use crate::mechanics::equilibria::Stability;
use crate::report::{Paint, text};

impl ModesReport {
    /// The report as text, expressions and coordinates in `style`, marked up by `paint`.
    pub fn render(&self, style: Style, paint: &dyn Paint) -> String {
        text(|o| self.write_text(style, paint, o))
    }

    fn write_text(&self, style: Style, paint: &dyn Paint, o: &mut String) -> fmt::Result {
        if let Some(s) = &self.steady {
            s.write_text(style, paint, o)?;
        }
        if self.continuum {
            writeln!(
                o,
                "every point in the search range is an equilibrium: they are not isolated (neutral)"
            )?;
        }
        if self.constraints > 0 && !self.equilibria.is_empty() {
            writeln!(
                o,
                "linearized on the constraint manifold ({} constraint{}): the shapes are tangent to it",
                self.constraints,
                if self.constraints == 1 { "" } else { "s" }
            )?;
        }
        for m in &self.equilibria {
            self.render_equilibrium(m, style, paint, o)?;
        }
        if let Some(c) = &self.search {
            write_coverage(c, self.equilibria.len(), o)?;
        }
        if let (Some(p), Some(ws)) = (&self.characteristic_polynomial, &self.omega_squared) {
            let det = if self.gyroscopic_closed_form {
                "det(K − ω²M − iωC)"
            } else {
                "det(K − ω²M)"
            };
            writeln!(
                o,
                "{} {det} = {}",
                paint.heading("characteristic polynomial:"),
                p.get(style)
            )?;
            for w in ws {
                writeln!(o, "ω² = {}", paint.good(w.get(style)))?;
            }
            if ws.is_empty() {
                writeln!(
                    o,
                    "(no closed-form roots: ω² = 0 and the decoupled roots do not split the polynomial into factors of degree ≤ 2 in ω²)"
                )?;
            }
        }
        Ok(())
    }

    fn render_equilibrium(
        &self,
        m: &EquilibriumModes,
        style: Style,
        paint: &dyn Paint,
        o: &mut String,
    ) -> fmt::Result {
        let point = point_text(&self.coordinate_labels, m, style);
        let st = match m.stability {
            Stability::Stable => paint.good("stable"),
            Stability::Unstable => paint.bad("unstable"),
            Stability::Marginal => paint.warn("marginal"),
        };
        writeln!(
            o,
            "{} {}: {st}",
            paint.heading("equilibrium"),
            point.join(", ")
        )?;
        for (name, v) in &m.rates {
            writeln!(o, "  {name} = {}", fmt_value(*v))?;
        }
        write_shape(m, paint, o)?;
        render_velocity_terms(m, o)?;
        let list = |xs: &[f64]| xs.iter().map(|x| fmt_value(*x)).collect::<Vec<_>>();
        if !m.frequencies.is_empty() {
            writeln!(o, "  frequencies ω: {}", list(&m.frequencies).join(", "))?;
        }
        if !m.growth_rates.is_empty() {
            writeln!(o, "  growth rates: {}", list(&m.growth_rates).join(", "))?;
        }
        for d in &m.damped {
            writeln!(
                o,
                "  damped oscillation: ω = {}, decay rate γ = {}, damping ratio ζ = {}",
                fmt_value(d.frequency),
                fmt_value(d.decay_rate),
                fmt_value(d.damping_ratio)
            )?;
        }
        if !m.decay_rates.is_empty() {
            writeln!(
                o,
                "  decay without oscillation, rates: {}",
                list(&m.decay_rates).join(", ")
            )?;
        }
        if m.modes.is_empty() {
            for f in &m.free_directions {
                writeln!(
                    o,
                    "  ω = 0: a displacement along ({}) is not restored",
                    list(f).join(", ")
                )?;
            }
        }
        render_shapes(m, o)
    }
}

/// Which velocity terms survive at the equilibrium, and how they were solved.
fn render_velocity_terms(m: &EquilibriumModes, o: &mut String) -> fmt::Result {
    let what = match (m.gyroscopic, m.damping) {
        (true, true) => "gyroscopic and damping terms survive here",
        (true, false) => "gyroscopic (velocity-coupling) terms survive here",
        (false, true) => "damping terms survive here",
        (false, false) => return Ok(()),
    };
    writeln!(o, "  {what}: solved as M ẍ + C ẋ + K x = 0 (C = G + D)")
}

/// One line per normal mode: ω = 0 as a free motion, otherwise ω², the shape and what the
/// shape means where it means something.
fn render_shapes(m: &EquilibriumModes, o: &mut String) -> fmt::Result {
    let list = |xs: &[f64]| xs.iter().map(|x| fmt_value(*x)).collect::<Vec<_>>();
    for (k, (w2, shape)) in m.omega_squared.iter().zip(&m.modes).enumerate() {
        if *w2 == 0.0 {
            // A zero mode across a degenerate point (V = x⁴) is not a free motion: there is a
            // restoring force, only not a linear one.
            let free = !m.not_harmonic || m.free.iter().any(|d| parallel(d, shape));
            let what = if free {
                "free motion"
            } else {
                "no linear restoring force (not harmonic, not free)"
            };
            writeln!(
                o,
                "  mode {}: ω = 0: {what} along ({})",
                k + 1,
                list(shape).join(", ")
            )?;
            continue;
        }
        let desc = m.descriptions.get(k).map_or("", String::as_str);
        writeln!(
            o,
            "  mode {}: ω² = {}, shape ({}){}",
            k + 1,
            fmt_value(*w2),
            list(shape).join(", "),
            if desc.is_empty() {
                String::new()
            } else {
                format!(" — {desc}")
            }
        )?;
    }
    Ok(())
}

/// Whether two directions are parallel (to rounding).
fn parallel(a: &[f64], b: &[f64]) -> bool {
    let dot: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    let aa: f64 = a.iter().map(|x| x * x).sum();
    let bb: f64 = b.iter().map(|x| x * x).sum();
    aa > 0.0 && bb > 0.0 && (aa * bb - dot * dot).abs() <= 1e-9 * aa * bb
}

//! Charts of a simulation, drawn once for every backend (see [`backend`](super::backend)):
//! q(t) and the phase portrait, one panel per coordinate, and the energy error.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::backend::{DrawResult, Picture, write};
use super::{Curves, range};
use lagrange::report::SimulationReport;

/// One panel's axes and curve.
struct Panel<'a> {
    x_desc: String,
    y_desc: String,
    points: &'a [(f64, f64)],
}

/// Panels one under another.
struct Panels<'a>(Vec<Panel<'a>>);

/// q(t) for every coordinate, one panel each, to `path` (PNG or SVG by its name).
pub fn qt_svg(r: &SimulationReport, path: &Path) -> Result<(), String> {
    let c = Curves::of(r);
    let panels: Vec<Panel> = c
        .q_labels
        .iter()
        .zip(&c.qt)
        .map(|(label, points)| Panel {
            x_desc: c.t_label.clone(),
            y_desc: label.clone(),
            points,
        })
        .collect();
    write(path, &Panels(panels))
}

/// The phase portrait q vs q̇ for every coordinate, one panel each, to `path`.
pub fn phase_svg(r: &SimulationReport, path: &Path) -> Result<(), String> {
    let c = Curves::of(r);
    let panels: Vec<Panel> = c
        .q_labels
        .iter()
        .zip(&c.qdot_labels)
        .zip(&c.phase)
        .map(|((q, qdot), points)| Panel {
            x_desc: q.clone(),
            y_desc: qdot.clone(),
            points,
        })
        .collect();
    write(path, &Panels(panels))
}

/// The relative energy error (h − h₀)/|h₀| over time, to `path`.
pub fn energy_svg(r: &SimulationReport, path: &Path) -> Result<(), String> {
    let c = Curves::of(r);
    let panel = Panel {
        x_desc: c.t_label.clone(),
        // With h₀ = 0 the error is absolute (the report's drift is too).
        y_desc: if r.h_start == 0.0 {
            "h − h₀ (h₀ = 0)".into()
        } else {
            "(h − h₀)/|h₀|".into()
        },
        points: &c.energy,
    };
    write(path, &Panels(vec![panel]))
}

impl Picture for Panels<'_> {
    fn size(&self) -> (u32, u32) {
        (800, 360 * u32::try_from(self.0.len().max(1)).unwrap_or(1))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let areas = root.split_evenly((self.0.len().max(1), 1));
        for (area, panel) in areas.iter().zip(&self.0) {
            draw_panel(area, panel)?;
        }
        Ok(())
    }
}

/// One panel: the mesh with its axis labels, and the curve as one polyline.
fn draw_panel<DB: DrawingBackend>(area: &DrawingArea<DB, Shift>, panel: &Panel) -> DrawResult<DB> {
    let (x0, x1) = range(panel.points.iter().map(|p| p.0));
    let (y0, y1) = range(panel.points.iter().map(|p| p.1));
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    let (x_fmt, y_fmt) = (tick_format(x0, x1), tick_format(y0, y1));
    chart
        .configure_mesh()
        .x_desc(panel.x_desc.as_str())
        .y_desc(panel.y_desc.as_str())
        .x_label_formatter(&|v| x_fmt(*v))
        .y_label_formatter(&|v| y_fmt(*v))
        .axis_desc_style(("sans-serif", 18))
        .draw()?;
    for piece in super::rightward_pieces(panel.points) {
        chart.draw_series(LineSeries::new(piece, &BLUE))?;
    }
    Ok(())
}

/// How to print the ticks of an axis over [lo, hi]: enough decimals to tell neighbouring
/// ticks apart, or scientific notation for a tiny span (an energy error of 1e-9) or huge
/// values — plotters' default prints every tick of a 1e-9 span as "0.0".
pub(super) fn tick_format(lo: f64, hi: f64) -> impl Fn(f64) -> String {
    let span = (hi - lo).abs();
    let big = lo.abs().max(hi.abs());
    let scientific = span > 0.0 && (span < 1e-3 || big >= 1e5);
    // Ticks are about span/10 apart: the decimals that spacing needs.
    let decimals = if span > 0.0 {
        (-(span / 10.0).log10().floor()).clamp(0.0, 6.0) as usize
    } else {
        1
    };
    move |v: f64| {
        if scientific {
            format!("{v:.2e}")
        } else {
            format!("{v:.decimals$}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::tick_format;

    #[test]
    fn ticks_of_a_tiny_span_are_scientific_and_others_have_the_decimals_they_need() {
        assert_eq!(tick_format(-3e-9, 1e-9)(-2e-9), "-2.00e-9");
        assert_eq!(tick_format(0.0, 20.0)(12.0), "12");
        assert_eq!(tick_format(0.0, 5.0)(2.5), "2.5");
        assert_eq!(tick_format(-0.02, 0.03)(0.015), "0.015");
        assert_eq!(tick_format(0.0, 1e6)(5e5), "5.00e5");
    }
}

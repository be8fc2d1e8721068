//! SVG pictures with plotters (its SVG backend writes text as `<text>`, so no font library is
//! needed): q(t) and the phase portrait, one panel per coordinate, and the energy error.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::{Curves, range};
use lagrange::report::SimulationReport;

/// One panel's axes and curve.
struct Panel<'a> {
    x_desc: String,
    y_desc: String,
    points: &'a [(f64, f64)],
}

/// q(t) for every coordinate, one panel each, to `path`.
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
    draw(path, &panels)
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
    draw(path, &panels)
}

/// The relative energy error (h − h₀)/|h₀| over time, to `path`.
pub fn energy_svg(r: &SimulationReport, path: &Path) -> Result<(), String> {
    let c = Curves::of(r);
    let panel = Panel {
        x_desc: c.t_label.clone(),
        y_desc: "(h − h₀)/|h₀|".into(),
        points: &c.energy,
    };
    draw(path, &[panel])
}

/// Draws the panels one under another and writes the file.
fn draw(path: &Path, panels: &[Panel]) -> Result<(), String> {
    let height = 360 * u32::try_from(panels.len().max(1)).unwrap_or(1);
    let root = SVGBackend::new(path, (800, height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let areas = root.split_evenly((panels.len().max(1), 1));
    for (area, panel) in areas.iter().zip(panels) {
        draw_panel(area, panel).map_err(|e| e.to_string())?;
    }
    root.present().map_err(|e| e.to_string())
}

type DrawResult<'a> =
    Result<(), DrawingAreaErrorKind<<SVGBackend<'a> as DrawingBackend>::ErrorType>>;

/// One panel: the mesh with its axis labels, and the curve as one polyline.
fn draw_panel<'a>(area: &DrawingArea<SVGBackend<'a>, Shift>, panel: &Panel) -> DrawResult<'a> {
    let (x0, x1) = range(panel.points.iter().map(|p| p.0));
    let (y0, y1) = range(panel.points.iter().map(|p| p.1));
    let mut chart = ChartBuilder::on(area)
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(x0..x1, y0..y1)?;
    chart
        .configure_mesh()
        .x_desc(panel.x_desc.as_str())
        .y_desc(panel.y_desc.as_str())
        .axis_desc_style(("sans-serif", 18))
        .draw()?;
    chart.draw_series(LineSeries::new(panel.points.iter().copied(), &BLUE))?;
    Ok(())
}

//! The pictures of `lagrange chaos`: the separation of two nearby motions on a log scale above
//! the running Lyapunov estimate, and the Poincaré section as points (q₂, q̇₂), one colour per
//! orbit.

use std::path::Path;

use plotters::prelude::*;

use super::backend::draw_on;

use super::label::{axis, unicode};
use super::range;
use lagrange::report::chaos::ChaosReport;
use lagrange::report::units::AxisUnits;

/// The separation |Δy|(t) (log scale) and the running estimate λ(t), one panel each.
pub fn chaos_svg(r: &ChaosReport, path: &Path) -> Result<(), String> {
    draw_chaos(r, path).map_err(|e| e.to_string())
}

fn draw_chaos(r: &ChaosReport, path: &Path) -> Result<(), Box<dyn std::error::Error>> {
    draw_on!(path, (800, 720), |root| {
        root.fill(&WHITE)?;
        let (top, bottom) = root.split_vertically(360);
        let positive: Vec<(f64, f64)> = r
            .separation
            .iter()
            .copied()
            .filter(|p| p.1 > 0.0 && p.1.is_finite())
            .collect();
        // log₁₀ on a linear axis: plotters' log axis crowds its labels within a decade.
        let logs: Vec<(f64, f64)> = positive.iter().map(|p| (p.0, p.1.log10())).collect();
        let (x0, x1) = range(logs.iter().map(|p| p.0));
        let (lo, hi) = range(logs.iter().map(|p| p.1));
        let t_desc = axis("t", r.time_unit.as_deref());
        let mut chart = ChartBuilder::on(&top)
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, lo..hi)?;
        chart
            .configure_mesh()
            .x_desc(t_desc.as_str())
            .y_desc("|Δy| (log scale)")
            .y_label_formatter(&|v| {
                if (v - v.round()).abs() < 1e-9 {
                    format!("1e{}", v.round())
                } else {
                    format!("{:.1e}", 10f64.powf(*v))
                }
            })
            .axis_desc_style(("sans-serif", 18))
            .draw()?;
        chart.draw_series(LineSeries::new(logs.iter().copied(), &BLUE))?;
        let (x0, x1) = range(r.running.iter().map(|p| p.0));
        let (y0, y1) = range(r.running.iter().map(|p| p.1).chain([0.0]));
        let mut chart = ChartBuilder::on(&bottom)
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        let rate = r.time_unit.as_deref().map(|u| format!("{u}⁻¹"));
        let lambda_desc = axis("running λ estimate", rate.as_deref());
        chart
            .configure_mesh()
            .x_desc(t_desc.as_str())
            .y_desc(lambda_desc.as_str())
            .axis_desc_style(("sans-serif", 18))
            .draw()?;
        chart.draw_series(LineSeries::new(r.running.iter().copied(), &BLUE))?;
        root.present()?;
        Ok(())
    })
}

/// The Poincaré section's points (q₂, q̇₂); an error when no section was computed.
/// Axes in the problem's units when `units` knows them.
pub fn poincare_svg(r: &ChaosReport, units: &AxisUnits, path: &Path) -> Result<(), String> {
    draw_poincare(r, units, path).map_err(|e| e.to_string())
}

fn draw_poincare(
    r: &ChaosReport,
    units: &AxisUnits,
    path: &Path,
) -> Result<(), Box<dyn std::error::Error>> {
    let s = r.section.as_ref().ok_or("no section was computed")?;
    // The section's plane is the second coordinate's.
    let unit = |v: &[Option<String>]| v.get(1).cloned().flatten();
    let x_desc = axis(&unicode(&s.q2), unit(&units.coordinates).as_deref());
    let y_desc = axis(
        &unicode(&format!("{}'", s.q2)),
        unit(&units.velocities).as_deref(),
    );
    let energy_unit = units
        .energy
        .as_deref()
        .map_or(String::new(), |u| format!(" {u}"));
    let all = || s.orbits.iter().flat_map(|o| o.points.iter().copied());
    let (x0, x1) = range(all().map(|p| p.0));
    let (y0, y1) = range(all().map(|p| p.1));
    draw_on!(path, (800, 720), |root| {
        root.fill(&WHITE)?;
        let caption = format!(
            "Poincaré section {} = 0, {} > 0, h = {:.4}{energy_unit}",
            unicode(&s.q1),
            unicode(&format!("{}'", s.q1)),
            s.energy
        );
        let mut chart = ChartBuilder::on(&root)
            .margin(12)
            .caption(caption, ("sans-serif", 20))
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        chart
            .configure_mesh()
            .x_desc(x_desc.as_str())
            .y_desc(y_desc.as_str())
            .axis_desc_style(("sans-serif", 18))
            .draw()?;
        for (k, orbit) in s.orbits.iter().enumerate() {
            let colour = Palette99::pick(k).filled();
            chart.draw_series(
                orbit
                    .points
                    .iter()
                    .map(|&(x, y)| Circle::new((x, y), 1, colour)),
            )?;
        }
        root.present()?;
        Ok(())
    })
}

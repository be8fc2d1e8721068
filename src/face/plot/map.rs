//! The flip-time map: one cell per start of a grid over one or two initial values, coloured
//! by the time until an angle first went over the top, on a log scale (the famous picture
//! of the double pendulum), with a colour bar; white where nothing flipped by t_end, grey
//! where the motion could not be followed (singular M, divergence).

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::backend::{DrawResult, Picture, write};
use lagrange::simulate::Outcome;

/// A grid's outcomes to draw.
pub struct FlipMap<'a> {
    /// The first axis: its label (Unicode) and values.
    pub x: (String, &'a [f64]),
    /// The second axis, or `None` for a one-dimensional grid (drawn as one row).
    pub y: Option<(String, &'a [f64])>,
    /// One outcome per cell, row-major: the cell (i, j) is `i * ny + j` (i along x).
    pub cells: &'a [Outcome],
    /// The end time (the top of the scale) and the step (its bottom).
    pub t_end: f64,
    pub dt: f64,
    /// The unit of t when the system declares one.
    pub time_unit: Option<String>,
}

const NO_FLIP: RGBColor = RGBColor(255, 255, 255);
const FAILED: RGBColor = RGBColor(150, 150, 150);

/// Draws the map to `path` (PNG or SVG by its name).
pub fn flip_map(map: &FlipMap, path: &Path) -> Result<(), String> {
    write(path, map)
}

/// The colour of a flip time on the log scale from `lo` to `hi` (viridis-like anchors).
fn colour(t: f64, lo: f64, hi: f64) -> RGBColor {
    const STOPS: [(u8, u8, u8); 6] = [
        (253, 231, 37),
        (122, 209, 81),
        (34, 168, 132),
        (42, 120, 142),
        (65, 68, 135),
        (68, 1, 84),
    ];
    let u = ((t.max(lo).ln() - lo.ln()) / (hi.ln() - lo.ln())).clamp(0.0, 1.0);
    let x = u * (STOPS.len() - 1) as f64;
    let k = (x.floor() as usize).min(STOPS.len() - 2);
    let w = x - k as f64;
    let mix = |a: u8, b: u8| (f64::from(a) + w * (f64::from(b) - f64::from(a))).round() as u8;
    let (a, b) = (STOPS[k], STOPS[k + 1]);
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

impl FlipMap<'_> {
    /// The bottom and top of the colour scale: from the power of ten at or below the
    /// shortest flip (not below the step) to t_end.
    fn scale(&self) -> (f64, f64) {
        let shortest = self
            .cells
            .iter()
            .filter_map(Outcome::flip_time)
            .filter(|&t| t > 0.0)
            .fold(self.t_end, f64::min);
        let lo = 10f64.powf(shortest.log10().floor()).max(self.dt);
        let lo = if lo < self.t_end {
            lo
        } else {
            self.dt.min(self.t_end / 10.0)
        };
        (lo, self.t_end)
    }

    fn cell_colour(&self, o: &Outcome, (lo, hi): (f64, f64)) -> RGBColor {
        match o.flip_time() {
            Some(t) => colour(t, lo, hi),
            None if matches!(o, Outcome::Stayed) => NO_FLIP,
            None => FAILED,
        }
    }

    /// The cells' rectangles: centred on the grid values, as wide as their spacing.
    fn draw_cells<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let xs = self.x.1;
        let ys: &[f64] = self.y.as_ref().map_or(&[0.0], |y| y.1);
        let (hx, (x0, x1)) = half_step_and_span(xs);
        let (hy, (y0, y1)) = half_step_and_span(ys);
        let mut chart = ChartBuilder::on(area)
            .margin(16)
            .x_label_area_size(50)
            .y_label_area_size(60)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        let y_desc = self.y.as_ref().map_or("", |y| y.0.as_str());
        let mut mesh = chart.configure_mesh();
        mesh.disable_mesh()
            .x_desc(self.x.0.as_str())
            .y_desc(y_desc)
            .axis_desc_style(("sans-serif", 22))
            .label_style(("sans-serif", 15));
        if self.y.is_none() {
            // One row: the vertical extent means nothing.
            mesh.disable_y_axis();
        }
        mesh.draw()?;
        let ny = ys.len();
        let scale = self.scale();
        chart.draw_series(self.cells.iter().enumerate().map(|(c, o)| {
            let (x, y) = (xs[c / ny], ys[c % ny]);
            Rectangle::new(
                [(x - hx, y - hy), (x + hx, y + hy)],
                self.cell_colour(o, scale).filled(),
            )
        }))?;
        Ok(())
    }

    /// The colour bar: the log scale of flip times, with the two other colours' meaning.
    fn draw_bar<DB: DrawingBackend>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let (lo, hi) = self.scale();
        let mut chart = ChartBuilder::on(area)
            .margin_top(16)
            .margin_bottom(66)
            .margin_right(8)
            .y_label_area_size(60)
            .build_cartesian_2d(
                0.0..1.0,
                (lo..hi).log_scale().with_key_points(decades(lo, hi)),
            )?;
        chart
            .configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .y_desc(super::label::axis(
                "time to flip",
                self.time_unit.as_deref(),
            ))
            .axis_desc_style(("sans-serif", 18))
            .label_style(("sans-serif", 14))
            .draw()?;
        let slices = 200;
        let ratio = hi / lo;
        chart.draw_series((0..slices).map(|k| {
            let a = lo * ratio.powf(f64::from(k) / f64::from(slices));
            let b = lo * ratio.powf(f64::from(k + 1) / f64::from(slices));
            Rectangle::new([(0.0, a), (1.0, b)], colour(a, lo, hi).filled())
        }))?;
        let (w, h) = area.dim_in_pixel();
        let y = i32::try_from(h).unwrap_or(0) - 56;
        let x = i32::try_from(w / 8).unwrap_or(0);
        let style = ("sans-serif", 14).into_font();
        area.draw(&Rectangle::new(
            [(x, y), (x + 14, y + 14)],
            NO_FLIP.filled(),
        ))?;
        area.draw(&Rectangle::new(
            [(x, y), (x + 14, y + 14)],
            BLACK.stroke_width(1),
        ))?;
        area.draw_text(
            &format!(
                "no flip by t = {hi}{}",
                self.time_unit
                    .as_deref()
                    .map_or(String::new(), |u| format!(" {u}"))
            ),
            &style.color(&BLACK),
            (x + 20, y),
        )?;
        let y = y + 22;
        area.draw(&Rectangle::new([(x, y), (x + 14, y + 14)], FAILED.filled()))?;
        area.draw_text("not followed", &style.color(&BLACK), (x + 20, y))?;
        Ok(())
    }
}

/// The powers of ten from `lo` to `hi`, with both ends: the colour bar's labels (plotters'
/// own log axis leaves the decades below 1 unlabelled).
fn decades(lo: f64, hi: f64) -> Vec<f64> {
    let mut v = vec![lo];
    let first = lo.log10().floor() as i32 + 1;
    let last = hi.log10().ceil() as i32;
    for e in first..last.max(first) {
        let p = 10f64.powi(e);
        if p > lo * (1.0 + 1e-9) && p < hi * (1.0 - 1e-9) {
            v.push(p);
        }
    }
    v.push(hi);
    v
}

/// Half the spacing of evenly spaced values (½ for a single value) and the span they cover.
fn half_step_and_span(v: &[f64]) -> (f64, (f64, f64)) {
    let (first, last) = (
        v.first().copied().unwrap_or(0.0),
        v.last().copied().unwrap_or(0.0),
    );
    let h = if v.len() > 1 && last != first {
        (last - first).abs() / (v.len() - 1) as f64 / 2.0
    } else {
        0.5
    };
    (h, (first.min(last) - h, first.max(last) + h))
}

impl Picture for FlipMap<'_> {
    fn size(&self) -> (u32, u32) {
        (960, 800)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        let (map, bar) = root.split_horizontally(780);
        self.draw_cells(&map)?;
        self.draw_bar(&bar)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scale_runs_from_yellow_to_purple_on_a_log_axis() {
        assert_eq!(colour(1e-3, 1e-3, 10.0), RGBColor(253, 231, 37));
        assert_eq!(colour(10.0, 1e-3, 10.0), RGBColor(68, 1, 84));
        assert_eq!(colour(0.0, 1e-3, 10.0), colour(1e-3, 1e-3, 10.0));
        assert_eq!(half_step_and_span(&[-1.0, 0.0, 1.0]), (0.5, (-1.5, 1.5)));
        assert_eq!(decades(1e-3, 10.0).len(), 5);
        assert_eq!(decades(0.1, 3.0).len(), 3);
    }
}

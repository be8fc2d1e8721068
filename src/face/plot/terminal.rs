//! q(t) for every coordinate as a terminal chart (textplots, braille dots), one chart per
//! coordinate under its Unicode name.

use textplots::{Chart, Plot, Shape};

use super::{Curves, label::unicode, range};
use lagrange::report::SimulationReport;

/// The charts of q(t), one per coordinate, as text.
pub fn terminal_chart(r: &SimulationReport) -> String {
    let curves = Curves::of(r);
    let mut out = String::new();
    for ((name, pts), q_label) in curves.names.iter().zip(&curves.qt).zip(&curves.q_labels) {
        let pts: Vec<(f32, f32)> = pts.iter().map(|&(t, q)| (t as f32, q as f32)).collect();
        let (lo, hi) = range(pts.iter().map(|p| f64::from(p.1)));
        let shape = Shape::Lines(&pts);
        let mut chart = Chart::new_with_y_range(120, 40, 0.0, r.t_end as f32, lo as f32, hi as f32);
        let chart = chart.lineplot(&shape);
        chart.axis();
        chart.figures();
        let bare = unicode(name);
        let units = if *q_label == bare && curves.t_label == "t" {
            String::new()
        } else {
            format!(" ({q_label} against {})", curves.t_label)
        };
        out.push_str(&format!("{bare}(t){units}\n{chart}\n"));
    }
    out
}

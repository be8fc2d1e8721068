//! Pictures of a simulation (a face, like `grade/`): q(t), phase portraits, the relative
//! energy error and the flip-time map as SVG or PNG files (plotters), and q(t) as a terminal chart (textplots). Labels are
//! the coordinates' names in Unicode (`theta1'` is drawn θ̇₁).

mod backend;
mod label;
mod map;
mod svg;
mod terminal;

pub use label::unicode;
pub use map::{FlipMap, flip_map};
pub use svg::{energy_svg, phase_svg, qt_svg};
pub use terminal::terminal_chart;

use lagrange::report::SimulationReport;

/// The coordinates' curves on the report's even grid: per coordinate, (t, q) and (q, q̇).
struct Curves {
    /// The coordinates' names (`theta1`), in order.
    names: Vec<String>,
    /// `(t, q_i)` for each coordinate i.
    qt: Vec<Vec<(f64, f64)>>,
    /// `(q_i, q̇_i)` for each coordinate i.
    phase: Vec<Vec<(f64, f64)>>,
    /// `(t, (h − h₀)/|h₀|)`, or the absolute error when h₀ = 0.
    energy: Vec<(f64, f64)>,
}

impl Curves {
    fn of(r: &SimulationReport) -> Self {
        let n = r.names.len() / 2;
        let h0 = r.grid.first().map_or(0.0, |row| row.2);
        let scale = if h0 == 0.0 { 1.0 } else { h0.abs() };
        let qt = (0..n)
            .map(|i| r.grid.iter().map(|(t, y, _)| (*t, y[i])).collect())
            .collect();
        let phase = (0..n)
            .map(|i| r.grid.iter().map(|(_, y, _)| (y[i], y[n + i])).collect())
            .collect();
        let energy = r
            .grid
            .iter()
            .map(|(t, _, h)| (*t, (h - h0) / scale))
            .collect();
        Curves {
            names: r.names[..n].to_vec(),
            qt,
            phase,
            energy,
        }
    }
}

/// The smallest and largest of some numbers, widened when they are equal or not finite.
fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if lo > hi {
        (-1.0, 1.0)
    } else if hi - lo < 1e-300_f64.max(1e-12 * hi.abs()) {
        let pad = if lo == 0.0 { 1.0 } else { lo.abs() * 0.1 };
        (lo - pad, hi + pad)
    } else {
        let pad = 0.05 * (hi - lo);
        (lo - pad, hi + pad)
    }
}

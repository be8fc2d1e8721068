//! A simulation's pictures as data, drawn the same way by every face: q(t) of every
//! coordinate, the phase portrait (q, q̇) of each and the relative energy error, built from a
//! [`SimulationReport`]'s even grid. A [`Figure`] is one or more [`Chart`]s stacked; each has
//! two axes with round ticks ([`Ticks`]), labels naming the coordinates in Unicode with their
//! units (`θ₁ / rad`), one polyline per series and a legend when there are several.
//!
//! [`Figure::marks`] lays a figure out in pixels as a list of [`Mark`]s, and
//! [`Figure::to_svg`] writes them as a self-contained SVG document (no script, no external
//! reference, every text escaped, coordinates to a tenth of a pixel), so the same run gives the
//! same bytes in the command line's `--plot`/`--phase` files and in the browser page. A face
//! that draws pixels itself (the CLI's PNG files) draws the same marks.
//!
//! ```
//! let t: Vec<f64> = (0..=20).map(|i| f64::from(i) / 10.0).collect();
//! let chart = lagrange::chart::Chart::new(
//!     "x = t²",
//!     "t / s",
//!     "x / m",
//!     vec![lagrange::chart::Series::new("x", t.iter().map(|&t| (t, t * t)).collect())],
//! );
//! let svg = lagrange::chart::Figure::new("x = t²", vec![chart]).to_svg();
//! assert!(svg.starts_with("<svg ") && svg.contains(">t / s</text>"));
//! ```

mod label;
mod layout;
mod svg;
mod ticks;

pub use label::{axis, unicode};
pub use layout::{Anchor, LABEL_SIZE, Mark, Rgb, TICK_SIZE};
pub use svg::escape;
pub use ticks::{Ticks, nice, ticks};

use crate::report::SimulationReport;

/// One panel: two axes and the series drawn on them.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Chart {
    /// What the panel shows, in words (for a screen reader).
    pub(crate) title: String,
    /// The horizontal axis' label (`t / s`).
    pub x_label: String,
    /// The vertical axis' label (`θ / rad`).
    pub y_label: String,
    /// The horizontal axis' range and ticks, covering every series.
    pub x: Ticks,
    /// The vertical axis' range and ticks.
    pub y: Ticks,
    /// The curves, each one polyline (broken where a point is not finite).
    pub(crate) series: Vec<Series>,
}

/// One named curve.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Series {
    /// Its name in the legend (`θ₁`).
    pub(crate) name: String,
    /// Its points (x, y) in order.
    pub(crate) points: Vec<(f64, f64)>,
}

/// Charts one under another, drawn as one picture.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Figure {
    /// The picture's title (the SVG's `<title>`).
    pub(crate) title: String,
    /// The panels, top first.
    pub charts: Vec<Chart>,
}

impl Series {
    /// A named curve.
    pub fn new(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            name: name.into(),
            points,
        }
    }
}

impl Chart {
    /// A panel whose axes cover every finite point of `series`.
    pub fn new(title: &str, x_label: &str, y_label: &str, series: Vec<Series>) -> Self {
        let all = || series.iter().flat_map(|s| s.points.iter());
        Chart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            x: ticks(all().map(|p| p.0)),
            y: ticks(all().map(|p| p.1)),
            series,
        }
    }
}

impl Figure {
    /// A picture of `charts`, one under another.
    pub fn new(title: &str, charts: Vec<Chart>) -> Self {
        Figure {
            title: title.into(),
            charts,
        }
    }
}

/// The names, labels and columns of a report's grid, read once for every picture.
struct Columns<'a> {
    report: &'a SimulationReport,
    /// The number of coordinates.
    n: usize,
}

impl<'a> Columns<'a> {
    fn of(report: &'a SimulationReport) -> Self {
        let n = report.names.len() / 2;
        Columns { report, n }
    }

    /// Entry `i` of the state against entry `j` (`None`: against t).
    fn points(&self, x: Option<usize>, y: usize) -> Vec<(f64, f64)> {
        let at = |v: &[f64], i: usize| v.get(i).copied().unwrap_or(f64::NAN);
        self.report
            .grid
            .iter()
            .map(|(t, v, _)| (x.map_or(*t, |i| at(v, i)), at(v, y)))
            .collect()
    }

    /// The Unicode name of state entry `i` (`θ₁`, `θ̇₁`).
    fn name(&self, i: usize) -> String {
        self.report
            .names
            .get(i)
            .map_or_else(String::new, |n| unicode(n))
    }

    /// The unit of coordinate `i` (`rate`: of its velocity), when known.
    fn unit(&self, i: usize, rate: bool) -> Option<&'a str> {
        let u = &self.report.units;
        let units = if rate { &u.velocities } else { &u.coordinates };
        units.get(i).and_then(|u| u.as_deref())
    }

    /// "t / s" when the time's unit is known.
    fn t_label(&self) -> String {
        axis("t", self.report.units.time.as_deref())
    }
}

/// q(t) of every coordinate in one chart, a legend naming them when there are several. The
/// vertical axis names them with their unit (`θ₁, θ₂ / rad`), or each with its own when the
/// units differ (`x / m, θ / rad`).
pub fn qt(report: &SimulationReport) -> Figure {
    let c = Columns::of(report);
    let names: Vec<String> = (0..c.n).map(|i| c.name(i)).collect();
    let units: Vec<Option<&str>> = (0..c.n).map(|i| c.unit(i, false)).collect();
    let y_label = if units.windows(2).all(|w| w[0] == w[1]) {
        axis(&names.join(", "), units.first().copied().flatten())
    } else {
        let each: Vec<String> = names.iter().zip(&units).map(|(n, u)| axis(n, *u)).collect();
        each.join(", ")
    };
    let series = names
        .iter()
        .enumerate()
        .map(|(i, n)| Series::new(n.clone(), c.points(None, i)))
        .collect();
    let title = ["The coordinates against time: ", &names.join(", ")].concat();
    let chart = Chart::new(&title, &c.t_label(), &y_label, series);
    Figure::new(&title, vec![chart])
}

/// The phase portrait (q, q̇) of each coordinate, one chart each, one under another.
pub fn phase(report: &SimulationReport) -> Figure {
    let c = Columns::of(report);
    let charts: Vec<Chart> = (0..c.n)
        .map(|i| {
            let (q, v) = (c.name(i), c.name(c.n + i));
            let title = ["Phase portrait of ", &q, ": ", &v, " against ", &q].concat();
            let x_label = axis(&q, c.unit(i, false));
            let y_label = axis(&v, c.unit(i, true));
            let series = vec![Series::new(q, c.points(Some(i), c.n + i))];
            Chart::new(&title, &x_label, &y_label, series)
        })
        .collect();
    let names: Vec<String> = (0..c.n).map(|i| c.name(i)).collect();
    Figure::new(&["Phase portraits of ", &names.join(", ")].concat(), charts)
}

/// The relative energy error (h − h₀)/|h₀| over time (absolute when h₀ = 0, as the report's
/// drift is).
pub fn energy(report: &SimulationReport) -> Figure {
    let c = Columns::of(report);
    let h0 = report.grid.first().map_or(0.0, |row| row.2);
    let scale = if h0 == 0.0 { 1.0 } else { h0.abs() };
    let points = report
        .grid
        .iter()
        .map(|(t, _, h)| (*t, (h - h0) / scale))
        .collect();
    let y_label = if h0 == 0.0 {
        "h − h₀ (h₀ = 0)"
    } else {
        "(h − h₀)/|h₀|"
    };
    let title = "The energy error against time";
    let chart = Chart::new(title, &c.t_label(), y_label, vec![Series::new("h", points)]);
    Figure::new(title, vec![chart])
}

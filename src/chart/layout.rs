//! A figure laid out in pixels: frames, grid lines, ticks and their texts, axis labels,
//! curves and legends as [`Mark`]s, in drawing order. Every face draws these marks (the SVG
//! writer here, the CLI's PNG through plotters), so a chart's ticks, labels and colours are
//! chosen once.

use super::{Chart, Figure};

/// A colour.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rgb(pub u8, pub u8, pub u8);

/// Where a text's position is along its line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Anchor {
    Start,
    Middle,
    End,
}

/// One thing drawn, in pixels from the picture's top-left corner.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Mark {
    /// A rectangle's outline, filled when `fill` is given.
    Rect {
        x: f64,
        y: f64,
        width: f64,
        height: f64,
        stroke: Rgb,
        fill: Option<Rgb>,
    },
    /// A straight line (a grid line, a tick, a legend's sample).
    Line {
        from: (f64, f64),
        to: (f64, f64),
        stroke: Rgb,
        width: f64,
    },
    /// A data curve: its pieces, each a polyline (a curve breaks where a point is not finite).
    Curve {
        pieces: Vec<Vec<(f64, f64)>>,
        stroke: Rgb,
        width: f64,
    },
    /// A text whose baseline passes through `at`; `vertical` texts read bottom to top.
    Text {
        at: (f64, f64),
        text: String,
        anchor: Anchor,
        vertical: bool,
        /// An axis label (larger than a tick's text).
        label: bool,
    },
}

/// The picture's width, and each panel's height, in pixels.
pub(super) const WIDTH: f64 = 640.0;
pub(super) const PANEL: f64 = 340.0;
/// The plot area's margins inside a panel: room for tick texts and axis labels.
const LEFT: f64 = 78.0;
const RIGHT: f64 = 18.0;
const TOP: f64 = 16.0;
const BOTTOM: f64 = 50.0;
/// A tick text's size in pixels (the SVG's font size; a face drawing the marks uses it too).
pub const TICK_SIZE: f64 = 12.0;
/// An axis label's size in pixels.
pub const LABEL_SIZE: f64 = 14.0;

/// The curves' colours, in the order of the series (distinct for colour-blind readers too).
const PALETTE: [Rgb; 6] = [
    Rgb(0x1f, 0x5f, 0xa8),
    Rgb(0xb3, 0x40, 0x1b),
    Rgb(0x2b, 0x7a, 0x3d),
    Rgb(0x7a, 0x3e, 0x9d),
    Rgb(0x8a, 0x6d, 0x00),
    Rgb(0x00, 0x73, 0x8a),
];
const FRAME: Rgb = Rgb(0x77, 0x77, 0x77);
const GRID: Rgb = Rgb(0xe4, 0xe6, 0xea);
const WHITE: Rgb = Rgb(0xff, 0xff, 0xff);
const LEGEND_EDGE: Rgb = Rgb(0xc9, 0xcc, 0xd1);

impl Figure {
    /// Width and height in pixels (a panel per chart, at least one).
    pub fn size(&self) -> (u32, u32) {
        let panels = u32::try_from(self.charts.len().max(1)).unwrap_or(1);
        (WIDTH as u32, PANEL as u32 * panels)
    }

    /// Every mark of the figure in drawing order, panel by panel.
    pub fn marks(&self) -> Vec<Mark> {
        let mut marks = Vec::new();
        for (i, chart) in self.charts.iter().enumerate() {
            panel(chart, PANEL * i as f64, &mut marks);
        }
        marks
    }
}

/// A panel `top` pixels down: grid, frame, ticks, labels, curves, legend.
fn panel(c: &Chart, top: f64, marks: &mut Vec<Mark>) {
    let (x0, x1) = (LEFT, WIDTH - RIGHT);
    let (y0, y1) = (top + TOP, top + PANEL - BOTTOM);
    let sx = |x: f64| x0 + (x - c.x.lo) / (c.x.hi - c.x.lo) * (x1 - x0);
    let sy = |y: f64| y1 - (y - c.y.lo) / (c.y.hi - c.y.lo) * (y1 - y0);
    let line = |from, to, stroke| Mark::Line {
        from,
        to,
        stroke,
        width: 1.0,
    };
    let text = |at, text: &str, anchor| Mark::Text {
        at,
        text: text.to_string(),
        anchor,
        vertical: false,
        label: false,
    };
    for (v, t) in c.x.values.iter().zip(&c.x.texts) {
        let x = sx(*v);
        marks.push(line((x, y0), (x, y1), GRID));
        marks.push(line((x, y1), (x, y1 + 5.0), FRAME));
        marks.push(text((x, y1 + 19.0), t, Anchor::Middle));
    }
    for (v, t) in c.y.values.iter().zip(&c.y.texts) {
        let y = sy(*v);
        marks.push(line((x0, y), (x1, y), GRID));
        marks.push(line((x0 - 5.0, y), (x0, y), FRAME));
        marks.push(text((x0 - 8.0, y + 4.0), t, Anchor::End));
    }
    marks.push(Mark::Rect {
        x: x0,
        y: y0,
        width: x1 - x0,
        height: y1 - y0,
        stroke: FRAME,
        fill: None,
    });
    marks.push(Mark::Text {
        at: ((x0 + x1) / 2.0, top + PANEL - 10.0),
        text: c.x_label.clone(),
        anchor: Anchor::Middle,
        vertical: false,
        label: true,
    });
    marks.push(Mark::Text {
        at: (18.0, (y0 + y1) / 2.0),
        text: c.y_label.clone(),
        anchor: Anchor::Middle,
        vertical: true,
        label: true,
    });
    for (k, s) in c.series.iter().enumerate() {
        let mut pieces: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
        for &(x, y) in &s.points {
            if x.is_finite() && y.is_finite() {
                // Pixels stay near the panel however far a blown-up motion goes.
                let p = (sx(x).clamp(-1e6, 1e6), sy(y).clamp(-1e6, 1e6));
                if let Some(piece) = pieces.last_mut() {
                    piece.push(p);
                }
            } else if pieces.last().is_some_and(|p| !p.is_empty()) {
                pieces.push(Vec::new());
            }
        }
        pieces.retain(|p| !p.is_empty());
        marks.push(Mark::Curve {
            pieces,
            stroke: PALETTE[k % PALETTE.len()],
            width: 1.6,
        });
    }
    if c.series.len() > 1 {
        legend(c, (x1, y0), marks);
    }
}

/// The series' names on a white card in the plot area's top-right corner, each beside a
/// sample of its colour (the card hides the curves passing under the names).
fn legend(c: &Chart, (right, top): (f64, f64), marks: &mut Vec<Mark>) {
    let longest = c.series.iter().map(|s| s.name.chars().count()).max();
    let width = 40.0 + 8.0 * longest.unwrap_or(1) as f64;
    let x = right - width - 6.0;
    marks.push(Mark::Rect {
        x,
        y: top + 6.0,
        width,
        height: 18.0 * c.series.len() as f64 + 6.0,
        stroke: LEGEND_EDGE,
        fill: Some(WHITE),
    });
    for (k, s) in c.series.iter().enumerate() {
        let y = top + 24.0 + 18.0 * k as f64;
        marks.push(Mark::Line {
            from: (x + 6.0, y - 4.0),
            to: (x + 28.0, y - 4.0),
            stroke: PALETTE[k % PALETTE.len()],
            width: 2.0,
        });
        marks.push(Mark::Text {
            at: (x + 34.0, y),
            text: s.name.clone(),
            anchor: Anchor::Start,
            vertical: false,
            label: false,
        });
    }
}

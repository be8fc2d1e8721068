//! The phase-portrait family as one SVG picture (plotters): every curve of
//! [`Portrait`] in the (q, q̇) plane, coloured by its energy from blue (lowest) to red
//! (highest), the separatrix in black and thicker, with a caption naming the colours' energies.
//! An angle is wrapped into one period centred on the potential's minimum, each curve broken
//! where it wraps.

use std::path::Path;

use plotters::prelude::*;

use super::backend::draw_on;

use super::label::{axis, unicode};
use super::range;
use lagrange::report::units::AxisUnits;
use lagrange::simulate::portrait::{CurveKind, Portrait};

/// A curve's pieces, broken where an angle wraps.
type Segments = Vec<Vec<(f64, f64)>>;

/// Draws the family to `path`, with the axes' and energies' units when known.
pub fn portrait_svg(p: &Portrait, units: &AxisUnits, path: &Path) -> Result<(), String> {
    let unit = |v: &[Option<String>]| v.first().cloned().flatten();
    let x_desc = axis(&unicode(&p.name), unit(&units.coordinates).as_deref());
    let y_desc = axis(
        &unicode(&format!("{}'", p.name)),
        unit(&units.velocities).as_deref(),
    );
    let curves: Vec<(f64, bool, Segments)> = p
        .curves
        .iter()
        .map(|c| {
            let separatrix = c.kind == CurveKind::Separatrix;
            (c.energy, separatrix, segments(&c.points, p.window))
        })
        .collect();
    let (x0, x1) = p.window.unwrap_or_else(|| {
        range(
            curves
                .iter()
                .flat_map(|c| c.2.iter().flatten().map(|q| q.0)),
        )
    });
    let (y0, y1) = range(
        curves
            .iter()
            .flat_map(|c| c.2.iter().flatten().map(|q| q.1)),
    );
    let caption = caption(p, units.energy.as_deref());
    draw_on!(path, (900, 640), |root| {
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut chart = ChartBuilder::on(&root)
            .caption(caption, ("sans-serif", 16))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc(x_desc)
            .y_desc(y_desc)
            .axis_desc_style(("sans-serif", 18))
            .draw()
            .map_err(|e| e.to_string())?;
        let (e_lo, e_hi) = energy_range(p);
        for (energy, separatrix, segs) in &curves {
            let style = if *separatrix {
                BLACK.stroke_width(2)
            } else {
                colour(*energy, e_lo, e_hi).stroke_width(1)
            };
            for seg in segs {
                chart
                    .draw_series(
                        super::rightward_pieces(seg)
                            .into_iter()
                            .map(|piece| PathElement::new(piece, style)),
                    )
                    .map_err(|e| e.to_string())?;
            }
        }
        root.present().map_err(|e| e.to_string())
    })
}

/// The lowest and highest energy of the family.
fn energy_range(p: &Portrait) -> (f64, f64) {
    p.curves
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), c| {
            (a.min(c.energy), b.max(c.energy))
        })
}

/// Blue for the lowest energy through green to red for the highest.
fn colour(energy: f64, lo: f64, hi: f64) -> HSLColor {
    let f = if hi > lo {
        ((energy - lo) / (hi - lo)).clamp(0.0, 1.0)
    } else {
        0.0
    };
    HSLColor((1.0 - f) * 240.0 / 360.0, 0.85, 0.45)
}

/// "Colour: h from −29.4 J (blue) to 76.5 J (red); black: the separatrix, h = 29.4 J".
fn caption(p: &Portrait, unit: Option<&str>) -> String {
    let (lo, hi) = energy_range(p);
    // An energy at rounding distance from 0 on the family's scale is 0 (a separatrix at
    // h = −7.6e-42 reads as noise).
    let scale = lo.abs().max(hi.abs());
    let e = |v: f64| {
        let v = if v.abs() <= 1e-12 * scale { 0.0 } else { v };
        match unit {
            Some(u) => format!("{} {u}", number(v)),
            None => number(v),
        }
    };
    let mut s = format!(
        "{} curves; colour: h from {} (blue) to {} (red)",
        p.curves.len(),
        e(lo),
        e(hi)
    );
    if let Some(sep) = p.separatrix {
        s.push_str(&format!("; black: separatrix, h = {}", e(sep)));
    }
    s
}

/// Four significant digits, a true minus sign.
fn number(v: f64) -> String {
    let s = if v != 0.0 && (v.abs() >= 1e5 || v.abs() < 1e-3) {
        format!("{v:.3e}")
    } else {
        format!("{}", (v * 1e4).round() / 1e4)
    };
    s.replace('-', "−")
}

/// The curve's points, an angle wrapped into `window` and broken where it wraps.
fn segments(points: &[(f64, f64)], window: Option<(f64, f64)>) -> Segments {
    let Some((lo, hi)) = window else {
        return vec![points.to_vec()];
    };
    let period = hi - lo;
    let mut out: Segments = Vec::new();
    let mut turn = None;
    for &(q, v) in points {
        let k = ((q - lo) / period).floor();
        if turn != Some(k) {
            out.push(Vec::new());
            turn = Some(k);
        }
        if let Some(seg) = out.last_mut() {
            seg.push((q - k * period, v));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rotation_is_broken_where_it_wraps() {
        let pi = std::f64::consts::PI;
        let points: Vec<(f64, f64)> = (0..=8).map(|k| (k as f64 * pi / 4.0, 1.0)).collect();
        let segs = segments(&points, Some((-pi, pi)));
        assert_eq!(segs.len(), 2);
        assert!(segs.iter().flatten().all(|p| (-pi..pi).contains(&p.0)));
        assert_eq!(number(-29.43), "−29.43");
    }
}

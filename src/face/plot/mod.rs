//! Pictures of a simulation (a face, like `grade/`): q(t), phase portraits and their
//! energy families, the relative energy error, the flip-time map, and `chaos`'s separation,
//! Lyapunov estimate and Poincaré section, as SVG or PNG files (plotters, chosen by the file's
//! extension), and q(t) as a terminal chart (textplots). Labels are the coordinates' names in
//! Unicode (`theta1'` is drawn θ̇₁).

mod backend;
mod chaos;
mod label;
mod map;
mod portrait;
mod svg;
mod terminal;

pub use chaos::{chaos_svg, poincare_svg};
pub use label::{axis, unicode};
pub use map::{FlipMap, flip_map};
pub use portrait::portrait_svg;
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
    /// The time axis' label, "t / s" when the unit is known.
    t_label: String,
    /// Each coordinate's and each rate's axis label, "θ₁ / rad", "θ̇₁ / rad s⁻¹".
    q_labels: Vec<String>,
    qdot_labels: Vec<String>,
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
        let u = &r.units;
        let unit = |units: &[Option<String>], i: usize| units.get(i).cloned().flatten();
        let q_labels = (0..n)
            .map(|i| {
                label::axis(
                    &label::unicode(&r.names[i]),
                    unit(&u.coordinates, i).as_deref(),
                )
            })
            .collect();
        let qdot_labels = (0..n)
            .map(|i| {
                label::axis(
                    &label::unicode(&r.names[n + i]),
                    unit(&u.velocities, i).as_deref(),
                )
            })
            .collect();
        Curves {
            t_label: label::axis("t", u.time.as_deref()),
            q_labels,
            qdot_labels,
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

/// Refuses a picture path that cannot work, before any work is done: `-` where the picture
/// has no terminal form, a name that is neither `.svg` nor `.png` (a `.jpg` would silently
/// hold SVG), a folder that does not exist, a name that holds a link or a folder.
pub fn check_picture_path(
    flag: &str,
    path: &std::path::Path,
    terminal: bool,
) -> Result<(), String> {
    if path == std::path::Path::new("-") {
        return if terminal {
            Ok(())
        } else {
            Err(format!(
                "{flag} draws to a file, not to the terminal: give it a .svg or .png name"
            ))
        };
    }
    let ext = path
        .extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase());
    if !matches!(ext.as_deref(), Some("svg" | "png")) {
        return Err(format!(
            "{flag} {}: the picture's name must end in .svg or .png",
            path.display()
        ));
    }
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty());
    if let Some(dir) = dir.filter(|d| !d.is_dir()) {
        return Err(format!(
            "{flag} {}: there is no folder {}",
            path.display(),
            dir.display()
        ));
    }
    // A link, a folder or a socket at the name is refused before any work is done.
    crate::face::outfile::check(path, true).map_err(|e| format!("{flag}: {e}"))
}

/// A curve cut where its x turns back, each piece drawn left to right: plotters' bitmap
/// backend draws a line whose x decreases as a thin dotted trail (seen on the lower half of
/// every phase portrait), so runs going left are reversed — the same points, the same picture.
pub(crate) fn rightward_pieces(points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let mut pieces: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut run: Vec<(f64, f64)> = Vec::new();
    let mut leftward = false;
    for &p in points {
        if let Some(&last) = run.last() {
            let left = p.0 < last.0;
            if run.len() >= 2 && left != leftward {
                // The turning point ends this run and starts the next.
                let mut done = std::mem::replace(&mut run, vec![last]);
                if leftward {
                    done.reverse();
                }
                pieces.push(done);
            }
            leftward = left;
        }
        run.push(p);
    }
    if leftward {
        run.reverse();
    }
    if !run.is_empty() {
        pieces.push(run);
    }
    pieces
}

#[cfg(test)]
mod pieces_tests {
    use super::rightward_pieces;

    #[test]
    fn a_loop_is_cut_at_its_turning_points_and_every_piece_runs_rightward() {
        let pts = [
            (0.0, 0.0),
            (1.0, 1.0),
            (2.0, 0.0),
            (1.0, -1.0),
            (0.0, 0.0),
            (1.0, 1.0),
        ];
        let pieces = rightward_pieces(&pts);
        assert_eq!(
            pieces,
            vec![
                vec![(0.0, 0.0), (1.0, 1.0), (2.0, 0.0)],
                vec![(0.0, 0.0), (1.0, -1.0), (2.0, 0.0)],
                vec![(0.0, 0.0), (1.0, 1.0)],
            ]
        );
        for p in &pieces {
            assert!(p.windows(2).all(|w| w[0].0 <= w[1].0));
        }
    }
}

//! q(t), the phase portrait and the energy error to a file: the library's [`lagrange::chart`]
//! figures, written as its SVG text, or drawn as PNG from the same marks (see
//! `marks.rs`) — the same ticks, labels and colours either way.

use std::path::Path;

use super::backend::{is_png, save, write};
use lagrange::chart::{self, Figure};
use lagrange::report::SimulationReport;

/// q(t) for every coordinate ([`chart::qt`]) to `path` (PNG or SVG by its name).
pub fn qt_svg(r: &SimulationReport, path: &Path) -> Result<(), String> {
    figure(&chart::qt(r), path)
}

/// The phase portrait q vs q̇ for every coordinate ([`chart::phase`]), one panel each, to
/// `path`.
pub fn phase_svg(r: &SimulationReport, path: &Path) -> Result<(), String> {
    figure(&chart::phase(r), path)
}

/// The relative energy error (h − h₀)/|h₀| over time ([`chart::energy`]), to `path`.
pub fn energy_svg(r: &SimulationReport, path: &Path) -> Result<(), String> {
    figure(&chart::energy(r), path)
}

/// The figure's SVG text as the library writes it (the browser page shows the same bytes),
/// or its marks drawn as PNG.
fn figure(f: &Figure, path: &Path) -> Result<(), String> {
    if is_png(path) {
        write(path, f)
    } else {
        save(path, f.to_svg().as_bytes())
    }
}

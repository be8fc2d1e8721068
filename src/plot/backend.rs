//! The picture's file format by its name: `.png` is drawn by plotters' bitmap backend (text
//! through ab_glyph with the embedded DejaVu Sans, so no system font library), anything else
//! is SVG (the default; text stays `<text>`). Drawing code is written once, generic over the
//! backend, as a [`Picture`].

use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;

/// What a drawing function returns on a backend.
pub(super) type DrawResult<DB> =
    Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// Something drawn the same way on every backend.
pub(super) trait Picture {
    /// Width and height in pixels.
    fn size(&self) -> (u32, u32);
    /// Draws onto the whole area.
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB>;
}

/// Whether `path` names a PNG file (by its extension, any case).
pub(super) fn is_png(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"))
}

/// Draws `picture` into `path`: PNG when the name ends in `.png`, SVG otherwise.
pub(super) fn write(path: &Path, picture: &impl Picture) -> Result<(), String> {
    let size = picture.size();
    register_font()?;
    if is_png(path) {
        let root = BitMapBackend::new(path, size).into_drawing_area();
        finish(&root, picture)
    } else {
        let root = SVGBackend::new(path, size).into_drawing_area();
        finish(&root, picture)
    }
}

fn finish<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    picture: &impl Picture,
) -> Result<(), String> {
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    picture.draw(root).map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}

/// Runs the drawing `$body` with `$root` the whole area of `$path` at `$size`: a PNG bitmap
/// when the name ends in `.png`, SVG otherwise (the body is compiled for both backends; for
/// drawings not written as a [`Picture`]). The body returns a `Result` whose error a
/// `String` converts into.
macro_rules! draw_on {
    ($path:expr, $size:expr, |$root:ident| $body:block) => {{
        super::backend::register_font()?;
        if super::backend::is_png($path) {
            let $root = BitMapBackend::new($path, $size).into_drawing_area();
            $body
        } else {
            let $root = SVGBackend::new($path, $size).into_drawing_area();
            $body
        }
    }};
}
pub(super) use draw_on;

/// Registers DejaVu Sans as plotters' "sans-serif" once: without a system font library,
/// plotters (its `ab_glyph` text) has no font of its own, for measuring text on any backend
/// or drawing it on a bitmap.
pub(super) fn register_font() -> Result<(), String> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let ok = *REGISTERED.get_or_init(|| {
        plotters::style::register_font("sans-serif", FontStyle::Normal, dejavu::sans::regular())
            .is_ok()
    });
    if ok {
        Ok(())
    } else {
        Err("the embedded font could not be read".into())
    }
}

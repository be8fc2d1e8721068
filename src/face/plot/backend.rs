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

/// Draws `picture` into `path`: PNG when the name ends in `.png`, SVG otherwise. The picture
/// is drawn in memory and written whole through [`crate::face::outfile::write_named`] (a temporary
/// file renamed over the name), so a full disk or a killed run never leaves half a picture.
pub(super) fn write(path: &Path, picture: &impl Picture) -> Result<(), String> {
    let size = picture.size();
    register_font()?;
    if is_png(path) {
        let mut rgb = rgb_buffer(size);
        {
            let root = BitMapBackend::with_buffer(&mut rgb, size).into_drawing_area();
            finish(&root, picture)?;
        }
        save_png(path, &rgb, size)
    } else {
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
            finish(&root, picture)?;
        }
        save(path, svg.as_bytes())
    }
}

/// A white RGB buffer of `size` pixels for plotters' bitmap backend.
pub(super) fn rgb_buffer(size: (u32, u32)) -> Vec<u8> {
    vec![255; size.0 as usize * size.1 as usize * 3]
}

/// Writes a drawn picture's bytes to `path` (see [`crate::face::outfile::write_named`]).
pub(super) fn save(path: &Path, bytes: &[u8]) -> Result<(), String> {
    crate::face::outfile::write_named(path, bytes)
}

/// Encodes an RGB buffer as PNG and writes it to `path`.
pub(super) fn save_png(path: &Path, rgb: &[u8], size: (u32, u32)) -> Result<(), String> {
    let mut bytes = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut bytes, size.0, size.1);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut w = encoder.write_header().map_err(|e| e.to_string())?;
        w.write_image_data(rgb).map_err(|e| e.to_string())?;
    }
    save(path, &bytes)
}

fn finish<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    picture: &impl Picture,
) -> Result<(), String> {
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    picture.draw(root).map_err(|e| e.to_string())?;
    root.present().map_err(|e| e.to_string())
}

/// Runs the drawing `$body` with `$root` the whole area of a picture of `$size`, drawn in
/// memory and then written to `$path` whole (see [`write`]): a PNG bitmap when the name ends
/// in `.png`, SVG otherwise (the body is compiled for both backends; for drawings not written
/// as a [`Picture`]). The body returns a `Result` whose error a `String` converts into; the
/// file is written only when it is `Ok`.
macro_rules! draw_on {
    ($path:expr, $size:expr, |$root:ident| $body:block) => {{
        super::backend::register_font()?;
        if super::backend::is_png($path) {
            let mut rgb = super::backend::rgb_buffer($size);
            let drawn = {
                let $root = BitMapBackend::with_buffer(&mut rgb, $size).into_drawing_area();
                $body
            };
            if drawn.is_ok() {
                super::backend::save_png($path, &rgb, $size)?;
            }
            drawn
        } else {
            let mut svg = String::new();
            let drawn = {
                let $root = SVGBackend::with_string(&mut svg, $size).into_drawing_area();
                $body
            };
            if drawn.is_ok() {
                super::backend::save($path, svg.as_bytes())?;
            }
            drawn
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

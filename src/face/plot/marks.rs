//! The library's chart marks ([`lagrange::chart::Mark`]) drawn through plotters, so a PNG
//! shows what the SVG does: a `Figure` is a `Picture` whose every mark is drawn at the
//! library's pixels with its colours and texts (DejaVu Sans at the SVG's font sizes).

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::backend::{DrawResult, Picture};
use lagrange::chart::{Anchor, Figure, LABEL_SIZE, Mark, Rgb, TICK_SIZE};

impl Picture for Figure {
    fn size(&self) -> (u32, u32) {
        Figure::size(self)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        for mark in self.marks() {
            draw(root, &mark)?;
        }
        Ok(())
    }
}

/// One mark on the whole picture's area (pixels from its top-left corner).
fn draw<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, mark: &Mark) -> DrawResult<DB> {
    let at = |p: (f64, f64)| (p.0.round() as i32, p.1.round() as i32);
    match mark {
        Mark::Rect {
            x,
            y,
            width,
            height,
            stroke,
            fill,
        } => {
            let corners = [at((*x, *y)), at((x + width, y + height))];
            if let Some(fill) = fill {
                root.draw(&Rectangle::new(corners, colour(*fill).filled()))?;
            }
            root.draw(&Rectangle::new(corners, colour(*stroke)))
        }
        Mark::Line {
            from,
            to,
            stroke,
            width,
        } => root.draw(&PathElement::new(
            vec![at(*from), at(*to)],
            colour(*stroke).stroke_width(*width as u32),
        )),
        Mark::Curve {
            pieces,
            stroke,
            width,
        } => {
            let style = colour(*stroke).stroke_width(width.round() as u32);
            for piece in pieces {
                // The bitmap backend draws a leftward line dotted: each run drawn rightward.
                for run in super::rightward_pieces(piece) {
                    root.draw(&PathElement::new(
                        run.into_iter().map(at).collect::<Vec<_>>(),
                        style,
                    ))?;
                }
            }
            Ok(())
        }
        Mark::Text {
            at: p,
            text,
            anchor,
            vertical,
            label,
        } => {
            let size = if *label { LABEL_SIZE } else { TICK_SIZE };
            let h = match anchor {
                Anchor::Start => HPos::Left,
                Anchor::Middle => HPos::Center,
                Anchor::End => HPos::Right,
            };
            let mut style = ("sans-serif", size)
                .into_font()
                .color(&BLACK.mix(0.85))
                .pos(Pos::new(h, VPos::Bottom));
            if *vertical {
                style = style.transform(FontTransform::Rotate270);
            }
            root.draw(&Text::new(text.as_str(), at(*p), style))
        }
        _ => Ok(()),
    }
}

/// A library colour as plotters'.
fn colour(c: Rgb) -> RGBColor {
    RGBColor(c.0, c.1, c.2)
}

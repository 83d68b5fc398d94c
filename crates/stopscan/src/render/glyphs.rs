//! Text for bitmap charts, drawn so that no glyph loses its left edge.
//!
//! plotters' `ttf` text rasterises each glyph into its own square canvas with the pen at
//! x = 0 (plotters 0.3.7 `style/font/ttf.rs`), and font-kit 0.14 clips a glyph bitmap that
//! starts left of the canvas without skipping the clipped source columns (`Canvas::blit_from`
//! reads from column 0). A glyph whose ink starts left of its origin is then cut and shifted:
//! DejaVu Sans's `j` (one pixel left of the origin at 12 px) renders as `¸`, and `J`, `T`,
//! `Y` and `_` lose a column. [`PaddedText`] wraps a backend and draws text itself with the
//! same fonts, metrics, kerning and layout as plotters, but places the pen `PAD` pixels into
//! each glyph's canvas and draws the canvas `PAD` pixels further left. Everything else is
//! passed to the wrapped backend. SVG output is unaffected (it writes text, not pixels).

use std::cell::RefCell;
use std::collections::HashMap;

use font_kit::canvas::{Canvas, Format, RasterizationOptions};
use font_kit::family_name::FamilyName;
use font_kit::font::Font;
use font_kit::handle::Handle;
use font_kit::hinting::HintingOptions;
use font_kit::properties::{Properties, Style, Weight};
use font_kit::source::SystemSource;
use pathfinder_geometry::transform2d::Transform2F;
use pathfinder_geometry::vector::{Vector2F, Vector2I};
use plotters::prelude::DrawingBackend;
use plotters_backend::text_anchor::{HPos, VPos};
use plotters_backend::{
    BackendColor, BackendCoord, BackendStyle, BackendTextStyle, DrawingErrorKind, FontFamily,
    FontStyle,
};

/// Pixels of room left of each glyph's origin (DejaVu Sans reaches 1 px left at 12–22 px).
const PAD: i32 = 4;

/// A backend whose text keeps the ink left of each glyph's origin; see the module docs.
pub(super) struct PaddedText<B>(pub(super) B);

/// A loaded font and its file's bytes (for the kerning table, as plotters reads it).
#[derive(Clone)]
struct Loaded {
    font: Font,
    data: std::sync::Arc<Vec<u8>>,
    index: u32,
}

thread_local! {
    static FONTS: RefCell<HashMap<String, Option<Loaded>>> = RefCell::new(HashMap::new());
}

/// The font plotters would pick for a family and style (the same system query).
fn font(family: FontFamily<'_>, style: FontStyle) -> Option<Loaded> {
    let key = format!("{}|{}", family.as_str(), style.as_str());
    FONTS.with(|cache| {
        cache
            .borrow_mut()
            .entry(key)
            .or_insert_with(|| {
                let mut properties = Properties::new();
                match style {
                    FontStyle::Normal => properties.style(Style::Normal),
                    FontStyle::Italic => properties.style(Style::Italic),
                    FontStyle::Oblique => properties.style(Style::Oblique),
                    FontStyle::Bold => properties.weight(Weight::BOLD),
                };
                let name = match family {
                    FontFamily::Serif => FamilyName::Serif,
                    FontFamily::SansSerif => FamilyName::SansSerif,
                    FontFamily::Monospace => FamilyName::Monospace,
                    FontFamily::Name(n) => FamilyName::Title(n.to_owned()),
                };
                let handle = SystemSource::new()
                    .select_best_match(&[name, FamilyName::SansSerif], &properties)
                    .ok()?;
                let font = handle.load().ok()?;
                let (data, index) = match font.handle()? {
                    Handle::Memory { bytes, font_index } => (bytes, font_index),
                    Handle::Path { .. } => (font.copy_font_data()?, 0),
                };
                Some(Loaded { font, data, index })
            })
            .clone()
    })
}

impl Loaded {
    /// plotters' kerning: the first horizontal, non-variable `kern` subtable's value.
    fn kerning(face: Option<&ttf_parser::Face<'_>>, prev: u32, next: u32) -> f32 {
        let Some(kern) = face.and_then(|f| f.tables().kern) else { return 0.0 };
        kern.subtables
            .into_iter()
            .filter(|st| st.horizontal && !st.variable)
            .find_map(|st| {
                st.glyphs_kerning(
                    ttf_parser::GlyphId(prev as u16),
                    ttf_parser::GlyphId(next as u16),
                )
            })
            .map_or(0.0, f32::from)
    }

    /// Calls `draw(x, y, alpha)` for every inked pixel of `text` with its pen at (0, 0),
    /// in plotters' layout (em = size / 1.24, baseline 0.24 em above the box's bottom).
    fn draw(&self, size: f64, text: &str, mut draw: impl FnMut(i32, i32, f32)) {
        let em = (size / 1.24) as f32;
        let units = self.font.metrics().units_per_em as f32;
        let face = ttf_parser::Face::parse(&self.data, self.index).ok();
        let canvas_size = size as i32;
        let base_y = -((0.24 * em) as i32);
        let place_holder = self.font.glyph_for_char('�');
        let mut x = 0f32;
        let mut prev = None;
        for c in text.chars() {
            let Some(glyph) = self.font.glyph_for_char(c).or(place_holder) else { continue };
            if let Some(p) = prev {
                x += Self::kerning(face.as_ref(), p, glyph) * em / units;
            }
            let mut canvas =
                Canvas::new(Vector2I::new(canvas_size + 2 * PAD, canvas_size), Format::A8);
            let at = Transform2F::from_translation(Vector2F::new(PAD as f32, em));
            if self
                .font
                .rasterize_glyph(
                    &mut canvas,
                    glyph,
                    em,
                    at,
                    HintingOptions::None,
                    RasterizationOptions::GrayscaleAa,
                )
                .is_ok()
            {
                let width = canvas.stride;
                for (k, &a) in canvas.pixels.iter().enumerate() {
                    if a > 0 {
                        let (dx, dy) = ((k % width) as i32, (k / width) as i32);
                        draw(x as i32 + dx - PAD, base_y + dy, f32::from(a) / 255.0);
                    }
                }
            }
            x += self.font.advance(glyph).map_or(0.0, Vector2F::x) * em / units;
            prev = Some(glyph);
        }
    }
}

impl<B: DrawingBackend> DrawingBackend for PaddedText<B> {
    type ErrorType = B::ErrorType;

    fn get_size(&self) -> (u32, u32) {
        self.0.get_size()
    }
    fn ensure_prepared(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.ensure_prepared()
    }
    fn present(&mut self) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.present()
    }
    fn draw_pixel(
        &mut self,
        point: BackendCoord,
        color: BackendColor,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_pixel(point, color)
    }
    fn draw_line<S: BackendStyle>(
        &mut self,
        from: BackendCoord,
        to: BackendCoord,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_line(from, to, style)
    }
    fn draw_rect<S: BackendStyle>(
        &mut self,
        upper_left: BackendCoord,
        bottom_right: BackendCoord,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_rect(upper_left, bottom_right, style, fill)
    }
    fn draw_path<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        path: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_path(path, style)
    }
    fn draw_circle<S: BackendStyle>(
        &mut self,
        center: BackendCoord,
        radius: u32,
        style: &S,
        fill: bool,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.draw_circle(center, radius, style, fill)
    }
    fn fill_polygon<S: BackendStyle, I: IntoIterator<Item = BackendCoord>>(
        &mut self,
        vert: I,
        style: &S,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.fill_polygon(vert, style)
    }
    fn blit_bitmap(
        &mut self,
        pos: BackendCoord,
        size: (u32, u32),
        src: &[u8],
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        self.0.blit_bitmap(pos, size, src)
    }

    /// plotters' default `draw_text` (anchor, rotation, clipping to the image) over
    /// [`Loaded::draw`]; falls back to the wrapped backend when no system font is found.
    fn draw_text<S: BackendTextStyle>(
        &mut self,
        text: &str,
        style: &S,
        pos: BackendCoord,
    ) -> Result<(), DrawingErrorKind<Self::ErrorType>> {
        let color = style.color();
        if color.alpha == 0.0 {
            return Ok(());
        }
        let Some(font) = font(style.family(), style.style()) else {
            return self.0.draw_text(text, style, pos);
        };
        let ((min_x, min_y), (max_x, max_y)) =
            style.layout_box(text).map_err(|e| DrawingErrorKind::FontError(Box::new(e)))?;
        let (width, height) = (max_x - min_x, max_y - min_y);
        let dx = match style.anchor().h_pos {
            HPos::Left => 0,
            HPos::Right => -width,
            HPos::Center => -width / 2,
        };
        let dy = match style.anchor().v_pos {
            VPos::Top => 0,
            VPos::Center => -height / 2,
            VPos::Bottom => -height,
        };
        let trans = style.transform();
        let (w, h) = self.get_size();
        let mut result = Ok(());
        font.draw(style.size(), text, |x, y, a| {
            let (x, y) = trans.transform(x + dx - min_x, y + dy - min_y);
            let (x, y) = (pos.0 + x, pos.1 + y);
            if result.is_ok() && x >= 0 && x < w as i32 && y >= 0 && y < h as i32 {
                let c = BackendColor { alpha: color.alpha * f64::from(a), rgb: color.rgb };
                result = self.0.draw_pixel((x, y), c);
            }
        });
        result
    }
}

#[cfg(test)]
mod tests {
    use plotters::prelude::*;

    use super::PaddedText;

    /// The inked pixels `(x, y)` of `text` at `size` px, drawn with its box's corner at (10, 4).
    fn ink(text: &str, size: u32, padded: bool) -> Vec<(usize, usize)> {
        let (w, h) = (60u32, 40u32);
        let mut buf = vec![255u8; (w * h * 3) as usize];
        {
            let backend = BitMapBackend::with_buffer(&mut buf, (w, h));
            let style = ("sans-serif", size).into_font().color(&BLACK);
            if padded {
                let area = PaddedText(backend).into_drawing_area();
                area.draw_text(text, &style, (10, 4)).unwrap();
                area.present().unwrap();
            } else {
                let area = backend.into_drawing_area();
                area.draw_text(text, &style, (10, 4)).unwrap();
                area.present().unwrap();
            }
        }
        let (w, h) = (w as usize, h as usize);
        (0..h)
            .flat_map(|y| (0..w).map(move |x| (x, y)))
            .filter(|&(x, y)| buf[(y * w + x) * 3] < 160)
            .collect()
    }

    fn rows(ink: &[(usize, usize)]) -> (usize, usize) {
        (ink.iter().map(|p| p.1).min().unwrap(), ink.iter().map(|p| p.1).max().unwrap())
    }

    #[test]
    fn j_keeps_its_stem_and_dot() {
        // The chart sizes: axis labels, subtitles, titles. Without the pad, plotters +
        // font-kit cut `j` at 12 px down to its hook below the baseline (a `¸`).
        for size in [12, 13, 14, 15, 22] {
            let (j_top, j_bottom) = rows(&ink("j", size, true));
            let (i_top, i_bottom) = rows(&ink("i", size, true));
            assert!(j_top <= i_top + 1, "{size} px: the dot of j is missing ({j_top} vs {i_top})");
            assert!(j_bottom > i_bottom, "{size} px: the hook of j is missing");
        }
    }

    #[test]
    fn plain_text_draws_where_plotters_draws_it() {
        // Glyphs with no ink left of their origin land on the same pixels.
        for size in [12, 22] {
            assert_eq!(ink("stop i", size, true), ink("stop i", size, false));
        }
    }

    #[test]
    #[ignore = "documents the upstream clipping; fails once plotters or font-kit fix it"]
    fn unpadded_j_loses_its_dot_at_12_px() {
        let (j_top, _) = rows(&ink("j", 12, false));
        let (i_top, _) = rows(&ink("i", 12, false));
        assert!(j_top > i_top + 1);
    }
}

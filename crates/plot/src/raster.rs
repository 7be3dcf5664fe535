//! PNG rendering of SVG documents.

use resvg::{tiny_skia, usvg};
use std::sync::{Arc, OnceLock};
use thiserror::Error;

/// Why a figure could not be written.
#[derive(Debug, Error)]
pub enum PlotError {
    /// The SVG text did not parse (the parser's message).
    #[error("SVG could not be parsed: {0}")]
    Svg(String),
    /// A pixmap of this width and height could not be allocated.
    #[error("figure of {0} x {1} pixels could not be rendered")]
    Size(u32, u32),
    /// The PNG encoder failed (its message).
    #[error("PNG encoding failed: {0}")]
    Png(String),
    /// The file could not be written.
    #[error(transparent)]
    Io(#[from] std::io::Error),
}

/// The embedded font, loaded once.
fn fonts() -> Arc<usvg::fontdb::Database> {
    static DB: OnceLock<Arc<usvg::fontdb::Database>> = OnceLock::new();
    DB.get_or_init(|| {
        let mut db = usvg::fontdb::Database::new();
        db.load_font_data(include_bytes!("../../../data/fonts/DejaVuSans.ttf").to_vec());
        Arc::new(db)
    })
    .clone()
}

/// Renders an SVG document to PNG bytes at `scale` pixels per SVG unit.
pub fn png(svg: &str, scale: f32) -> Result<Vec<u8>, PlotError> {
    let options = usvg::Options {
        fontdb: fonts(),
        font_family: "DejaVu Sans".to_string(),
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(svg, &options).map_err(|e| PlotError::Svg(e.to_string()))?;
    let size = tree.size();
    let (w, h) = (
        (size.width() * scale).ceil() as u32,
        (size.height() * scale).ceil() as u32,
    );
    let mut pixmap = tiny_skia::Pixmap::new(w.max(1), h.max(1)).ok_or(PlotError::Size(w, h))?;
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    pixmap
        .encode_png()
        .map_err(|e| PlotError::Png(e.to_string()))
}

/// A PNG of `width x height` pixels (row-major, top row first).
pub fn raster_png(width: u32, height: u32, pixels: &[crate::Colour]) -> Result<Vec<u8>, PlotError> {
    let mut pixmap = tiny_skia::Pixmap::new(width.max(1), height.max(1))
        .ok_or(PlotError::Size(width, height))?;
    for (dst, c) in pixmap.pixels_mut().iter_mut().zip(pixels) {
        *dst = tiny_skia::PremultipliedColorU8::from_rgba(c.0, c.1, c.2, 255).unwrap_or(*dst);
    }
    pixmap
        .encode_png()
        .map_err(|e| PlotError::Png(e.to_string()))
}

/// An SVG `<image>` element embedding `png` as a data URI, placed at
/// `(x, y)` with size `w x h` and drawn with crisp (nearest) pixels.
pub fn embedded_image(png: &[u8], x: f64, y: f64, w: f64, h: f64) -> String {
    use base64::Engine as _;
    format!(
        r#"<image x="{x:.2}" y="{y:.2}" width="{w:.2}" height="{h:.2}" preserveAspectRatio="none" style="image-rendering:pixelated" href="data:image/png;base64,{}"/>"#,
        base64::engine::general_purpose::STANDARD.encode(png)
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::svg::{Anchor, Svg};

    #[test]
    fn renders_text_with_the_embedded_font() {
        let mut s = Svg::new(120.0, 40.0);
        s.text(10.0, 25.0, "e = 0.7", 16.0, Anchor::Start, "");
        let with_text = png(&s.finish(), 1.0).unwrap();
        let blank = png(&Svg::new(120.0, 40.0).finish(), 1.0).unwrap();
        assert_eq!(&with_text[1..4], b"PNG");
        // glyphs were drawn: the images differ
        assert_ne!(with_text, blank);
    }
}

//! Figures as plain SVG (vector, real text), and PNG renderings of them.
//!
//! Nothing here knows about impacts: a heatmap is a grid of numbers, a line
//! plot is a set of series. PNGs are rendered with `resvg` and the DejaVu Sans
//! font embedded from `data/fonts`, so they look the same on every machine and
//! need no system library.

#![warn(missing_docs)]

mod axis;
mod colour;
mod contour;
mod heatmap;
mod lines;
mod raster;
mod svg;

pub use axis::{Axis, Scale};
pub use colour::{Colour, Colourmap};
pub use contour::contour;
pub use heatmap::{Category, Heatmap};
/// The one text escape (`impact-output`), for figure code that writes markup.
pub use impact_output::escape;
pub use lines::{LinePlot, Marker, Series};
pub use raster::{PlotError, embedded_image, png, raster_png};
pub use svg::{Anchor, Svg};

/// Writes `stem.svg` and `stem.png` for an SVG document.
pub fn write_svg_and_png(stem: &std::path::Path, svg: &str) -> Result<(), PlotError> {
    std::fs::write(stem.with_extension("svg"), svg)?;
    std::fs::write(stem.with_extension("png"), png(svg, 2.0)?)?;
    Ok(())
}

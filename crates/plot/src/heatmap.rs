//! Heatmaps over a rectangular grid, with a colour bar or a category legend.

use crate::axis::Axis;
use crate::colour::{Colour, Colourmap};
use crate::svg::{Anchor, Svg};

/// A named colour for categorical heatmaps.
#[derive(Debug, Clone, PartialEq)]
pub struct Category {
    /// Name shown in the legend.
    pub name: String,
    /// Fill of the cells in this category.
    pub colour: Colour,
}

/// Values on a grid: `values[row * columns.len() + column]`, rows bottom to
/// top. NaN cells are drawn grey (missing).
#[derive(Debug, Clone, PartialEq)]
pub struct Heatmap {
    /// Title above the map.
    pub title: String,
    /// Label of the horizontal axis (the columns).
    pub x_label: String,
    /// Label of the vertical axis (the rows).
    pub y_label: String,
    /// Centres of the columns (increasing, evenly spaced).
    pub columns: Vec<f64>,
    /// Centres of the rows (increasing, evenly spaced).
    pub rows: Vec<f64>,
    /// Cell values, row by row from the bottom; NaN for missing.
    pub values: Vec<f64>,
    /// How values become colours (ignored for categories).
    pub colourmap: Colourmap,
    /// Colour scale; ignored for categories.
    pub range: (f64, f64),
    /// Title of the colour bar.
    pub colourbar_label: String,
    /// When set, `values` are indices into these categories.
    pub categories: Option<Vec<Category>>,
    /// Polylines drawn over the map in data coordinates (e.g. isolines or
    /// regime boundaries), with their stroke colour.
    pub overlays: Vec<(Vec<(f64, f64)>, Colour)>,
}

const LEFT: f64 = 70.0;
const TOP: f64 = 40.0;
const SIZE: f64 = 420.0;

fn half_step(c: &[f64]) -> f64 {
    if c.len() > 1 {
        0.5 * (c[c.len() - 1] - c[0]) / (c.len() - 1) as f64
    } else {
        0.5
    }
}

impl Heatmap {
    fn cell_colour(&self, v: f64) -> Colour {
        match &self.categories {
            Some(cats) if v.is_finite() && v >= 0.0 => {
                cats.get(v as usize).map_or(Colour::GREY, |c| c.colour)
            }
            Some(_) => Colour::GREY,
            None => self.colourmap.colour(v, self.range.0, self.range.1),
        }
    }

    /// The figure as an SVG document.
    pub fn to_svg(&self) -> String {
        let mut svg = Svg::new(LEFT + SIZE + 190.0, TOP + SIZE + 60.0);
        let (hx, hy) = (half_step(&self.columns), half_step(&self.rows));
        let x = Axis::linear(
            self.columns.first().copied().unwrap_or(0.0) - hx,
            self.columns.last().copied().unwrap_or(1.0) + hx,
            &self.x_label,
        );
        let y = Axis::linear(
            self.rows.first().copied().unwrap_or(0.0) - hy,
            self.rows.last().copied().unwrap_or(1.0) + hy,
            &self.y_label,
        );
        let px = |v: f64| LEFT + SIZE * x.fraction(v);
        let py = |v: f64| TOP + SIZE * (1.0 - y.fraction(v));
        let nc = self.columns.len();
        let (cw, ch) = (
            SIZE / nc.max(1) as f64,
            SIZE / self.rows.len().max(1) as f64,
        );
        svg.raw(r#"<g shape-rendering="crispEdges">"#);
        let dense = nc * self.rows.len() > 10_000;
        if dense {
            // one pixel per cell, embedded: keeps dense maps small
            let nr = self.rows.len();
            let mut pixels = Vec::with_capacity(nc * nr);
            for r in (0..nr).rev() {
                for c in 0..nc {
                    let v = self.values.get(r * nc + c).copied().unwrap_or(f64::NAN);
                    pixels.push(self.cell_colour(v));
                }
            }
            if let Ok(png) = crate::raster::raster_png(nc as u32, nr as u32, &pixels) {
                svg.raw(&crate::raster::embedded_image(&png, LEFT, TOP, SIZE, SIZE));
            }
        }
        for (r, &yc) in self.rows.iter().enumerate().filter(|_| !dense) {
            // merge runs of equal colour along a row: far smaller files
            let mut c = 0;
            while c < nc {
                let colour =
                    self.cell_colour(self.values.get(r * nc + c).copied().unwrap_or(f64::NAN));
                let mut end = c + 1;
                while end < nc
                    && self.cell_colour(self.values.get(r * nc + end).copied().unwrap_or(f64::NAN))
                        == colour
                {
                    end += 1;
                }
                let x0 = px(self.columns[c] - hx);
                svg.rect(
                    x0,
                    py(yc) - 0.5 * ch,
                    cw * (end - c) as f64 + 0.3,
                    ch + 0.3,
                    &colour.hex(),
                    "",
                );
                c = end;
            }
        }
        svg.raw("</g>");
        for (line, colour) in &self.overlays {
            let pts: Vec<(f64, f64)> = line.iter().map(|&(a, b)| (px(a), py(b))).collect();
            svg.polyline(&pts, &colour.hex(), 1.2, "");
        }
        frame(&mut svg, &x, &y, px, py);
        svg.title(LEFT + SIZE / 2.0, 24.0, &self.title);
        let bx = LEFT + SIZE + 25.0;
        match &self.categories {
            Some(cats) => {
                for (i, cat) in cats.iter().enumerate() {
                    let yy = TOP + 10.0 + 24.0 * i as f64;
                    svg.rect(
                        bx,
                        yy,
                        16.0,
                        16.0,
                        &cat.colour.hex(),
                        r#"stroke="black" stroke-width="0.5""#,
                    );
                    svg.text(bx + 22.0, yy + 13.0, &cat.name, 12.0, Anchor::Start, "");
                }
            }
            None => {
                let steps = 60;
                for k in 0..steps {
                    let t = k as f64 / steps as f64;
                    let v = self.range.0 + t * (self.range.1 - self.range.0);
                    let yy = TOP + SIZE * (1.0 - t) - SIZE / steps as f64;
                    svg.rect(
                        bx,
                        yy,
                        20.0,
                        SIZE / steps as f64 + 0.5,
                        &self.colourmap.colour(v, self.range.0, self.range.1).hex(),
                        "",
                    );
                }
                svg.rect(
                    bx,
                    TOP,
                    20.0,
                    SIZE,
                    "none",
                    r#"stroke="black" stroke-width="0.8""#,
                );
                let bar = Axis::linear(self.range.0, self.range.1, "");
                for (v, label) in bar.ticks() {
                    let yy = TOP + SIZE * (1.0 - bar.fraction(v));
                    svg.line((bx + 20.0, yy), (bx + 25.0, yy), "black", 0.8, "");
                    svg.text(bx + 28.0, yy + 4.0, &label, 11.0, Anchor::Start, "");
                }
                svg.vertical_text(bx + 95.0, TOP + SIZE / 2.0, &self.colourbar_label, 13.0);
            }
        }
        svg.finish()
    }
}

/// Plot frame, ticks and axis labels.
pub(crate) fn frame(
    svg: &mut Svg,
    x: &Axis,
    y: &Axis,
    px: impl Fn(f64) -> f64,
    py: impl Fn(f64) -> f64,
) {
    Axis::draw_box(svg, (LEFT, TOP, SIZE, SIZE), (x, &px), (y, &py), 11.0);
    svg.text(
        LEFT + SIZE / 2.0,
        TOP + SIZE + 42.0,
        &x.label,
        13.0,
        Anchor::Middle,
        "",
    );
    svg.vertical_text(20.0, TOP + SIZE / 2.0, &y.label, 13.0);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merges_equal_cells_and_labels_everything() {
        let map = Heatmap {
            title: "t".into(),
            x_label: "x".into(),
            y_label: "alpha".into(),
            columns: vec![0.1, 0.2, 0.3],
            rows: vec![0.5, 0.6],
            values: vec![0.0, 0.0, 0.0, 1.0, f64::NAN, -1.0],
            colourmap: Colourmap::Diverging,
            range: (-1.0, 1.0),
            colourbar_label: "de".into(),
            categories: None,
            overlays: vec![],
        };
        let svg = map.to_svg();
        // first row: one merged white rect; second row: three different cells
        let cells = svg
            .split(r#"<g shape-rendering="crispEdges">"#)
            .nth(1)
            .unwrap()
            .split("</g>")
            .next()
            .unwrap();
        assert_eq!(cells.matches("<rect").count(), 4);
        assert!(svg.contains(">alpha</text>") && svg.contains(">de</text>"));
    }
}

#[cfg(test)]
mod dense_tests {
    use super::*;

    #[test]
    fn dense_maps_are_embedded_rasters() {
        let n = 120;
        let axis: Vec<f64> = (0..n).map(|i| f64::from(i) / f64::from(n)).collect();
        let map = Heatmap {
            title: "dense".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            columns: axis.clone(),
            rows: axis,
            values: (0..n * n).map(|k| f64::from(k % 7)).collect(),
            colourmap: Colourmap::Sequential,
            range: (0.0, 6.0),
            colourbar_label: "v".into(),
            categories: None,
            overlays: vec![],
        };
        let svg = map.to_svg();
        assert_eq!(svg.matches("<image").count(), 1);
        assert!(svg.len() < 200_000, "{}", svg.len());
    }
}

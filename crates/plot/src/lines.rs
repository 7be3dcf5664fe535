//! Line and scatter plots, linear or logarithmic axes, with a legend.

use crate::axis::{Axis, Scale};
use crate::colour::Colour;
use crate::heatmap::frame;
use crate::svg::{Anchor, Svg};

/// Point marker of a series.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    /// No marker: a line only.
    None,
    /// A filled circle at each point.
    Circle,
    /// A filled square at each point.
    Square,
}

/// One named data series.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Name shown in the legend.
    pub name: String,
    /// Data points `(x, y)`, in the order they are joined.
    pub points: Vec<(f64, f64)>,
    /// Colour of the line and markers.
    pub colour: Colour,
    /// Marker drawn at each point.
    pub marker: Marker,
    /// Join the points with a line.
    pub line: bool,
    /// Dashed line (for fits and closed forms).
    pub dashed: bool,
}

impl Series {
    /// A solid line through `points`, no markers.
    pub fn line(name: &str, points: Vec<(f64, f64)>, colour: Colour) -> Self {
        Self {
            name: name.into(),
            points,
            colour,
            marker: Marker::None,
            line: true,
            dashed: false,
        }
    }

    /// Circles at `points`, not joined.
    pub fn markers(name: &str, points: Vec<(f64, f64)>, colour: Colour) -> Self {
        Self {
            name: name.into(),
            points,
            colour,
            marker: Marker::Circle,
            line: false,
            dashed: false,
        }
    }

    /// The same series with a dashed line (for fits and closed forms).
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }
}

/// A plot of series against two axes.
#[derive(Debug, Clone, PartialEq)]
pub struct LinePlot {
    /// Title above the plot.
    pub title: String,
    /// Horizontal axis.
    pub x: Axis,
    /// Vertical axis.
    pub y: Axis,
    /// The series, drawn in order and listed in the legend.
    pub series: Vec<Series>,
}

const LEFT: f64 = 70.0;
const TOP: f64 = 40.0;
const SIZE: f64 = 420.0;

impl LinePlot {
    /// The plot as a complete SVG document, with axes, ticks and legend.
    pub fn to_svg(&self) -> String {
        let mut svg = Svg::new(LEFT + SIZE + 220.0, TOP + SIZE + 60.0);
        let (x, y) = (&self.x, &self.y);
        let px = |v: f64| LEFT + SIZE * x.fraction(v);
        let py = |v: f64| TOP + SIZE * (1.0 - y.fraction(v));
        let visible = |(a, b): (f64, f64)| {
            a.is_finite()
                && b.is_finite()
                && (x.scale == Scale::Linear || a > 0.0)
                && (y.scale == Scale::Linear || b > 0.0)
        };
        svg.raw(&format!(
            r#"<clipPath id="plot-area"><rect x="{LEFT}" y="{TOP}" width="{SIZE}" height="{SIZE}"/></clipPath><g clip-path="url(#plot-area)">"#
        ));
        for s in &self.series {
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .copied()
                .filter(|p| visible(*p))
                .map(|(a, b)| (px(a), py(b)))
                .collect();
            let colour = s.colour.hex();
            if s.line {
                svg.polyline(
                    &pts,
                    &colour,
                    1.6,
                    if s.dashed {
                        r#"stroke-dasharray="6 4""#
                    } else {
                        ""
                    },
                );
            }
            for &(a, b) in &pts {
                match s.marker {
                    Marker::None => {}
                    Marker::Circle => svg.circle(a, b, 3.0, &colour, ""),
                    Marker::Square => svg.rect(a - 3.0, b - 3.0, 6.0, 6.0, &colour, ""),
                }
            }
        }
        svg.raw("</g>");
        frame(&mut svg, x, y, px, py);
        svg.title(LEFT + SIZE / 2.0, 24.0, &self.title);
        for (i, s) in self.series.iter().enumerate() {
            let yy = TOP + 12.0 + 20.0 * i as f64;
            let xx = LEFT + SIZE + 15.0;
            if s.line {
                svg.line(
                    (xx, yy),
                    (xx + 24.0, yy),
                    &s.colour.hex(),
                    2.0,
                    if s.dashed {
                        r#"stroke-dasharray="6 4""#
                    } else {
                        ""
                    },
                );
            }
            if s.marker != Marker::None {
                svg.circle(xx + 12.0, yy, 3.0, &s.colour.hex(), "");
            }
            svg.text(xx + 30.0, yy + 4.0, &s.name, 11.0, Anchor::Start, "");
        }
        svg.finish()
    }
}

//! A minimal SVG writer: shapes and text appended to a document.

use impact_output::escape;
use std::fmt::Write as _;

/// Horizontal text anchor.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Anchor {
    /// Text starts at the point.
    Start,
    /// Text is centred on the point.
    Middle,
    /// Text ends at the point.
    End,
}

impl Anchor {
    fn as_str(self) -> &'static str {
        match self {
            Anchor::Start => "start",
            Anchor::Middle => "middle",
            Anchor::End => "end",
        }
    }
}

/// An SVG document being written. Coordinates in pixels, y down.
#[derive(Debug, Clone)]
pub struct Svg {
    /// Document width, in pixels.
    pub width: f64,
    /// Document height, in pixels.
    pub height: f64,
    body: String,
}

/// Formats a coordinate with two decimals (enough at any output size).
fn n(v: f64) -> String {
    let s = format!("{v:.2}");
    s.trim_end_matches('0').trim_end_matches('.').to_string()
}

impl Svg {
    /// An empty document of the given size in pixels.
    pub fn new(width: f64, height: f64) -> Self {
        Self {
            width,
            height,
            body: String::new(),
        }
    }

    /// Appends raw SVG markup (already escaped).
    pub fn raw(&mut self, markup: &str) {
        self.body.push_str(markup);
        self.body.push('\n');
    }

    /// A rectangle with top-left corner `(x, y)`, width `w` and height `h`; `extra` holds further attributes.
    pub fn rect(&mut self, x: f64, y: f64, w: f64, h: f64, fill: &str, extra: &str) {
        let _ = writeln!(
            self.body,
            r#"<rect x="{}" y="{}" width="{}" height="{}" fill="{fill}" {extra}/>"#,
            n(x),
            n(y),
            n(w),
            n(h)
        );
    }

    /// A straight line from `from` to `to`, `width` pixels wide; `extra` holds further attributes.
    pub fn line(
        &mut self,
        from: (f64, f64),
        to: (f64, f64),
        stroke: &str,
        width: f64,
        extra: &str,
    ) {
        let _ = writeln!(
            self.body,
            r#"<line x1="{}" y1="{}" x2="{}" y2="{}" stroke="{stroke}" stroke-width="{}" {extra}/>"#,
            n(from.0),
            n(from.1),
            n(to.0),
            n(to.1),
            n(width)
        );
    }

    /// An open polyline; `extra` may carry e.g. `stroke-dasharray`.
    pub fn polyline(&mut self, points: &[(f64, f64)], stroke: &str, width: f64, extra: &str) {
        if points.len() < 2 {
            return;
        }
        let mut d = String::with_capacity(points.len() * 14);
        for (i, (x, y)) in points.iter().enumerate() {
            let _ = write!(d, "{}{},{}", if i == 0 { "M" } else { " L" }, n(*x), n(*y));
        }
        let _ = writeln!(
            self.body,
            r#"<path d="{d}" fill="none" stroke="{stroke}" stroke-width="{}" stroke-linejoin="round" {extra}/>"#,
            n(width)
        );
    }

    /// A circle of radius `r` centred on `(x, y)`; `extra` holds further attributes.
    pub fn circle(&mut self, x: f64, y: f64, r: f64, fill: &str, extra: &str) {
        let _ = writeln!(
            self.body,
            r#"<circle cx="{}" cy="{}" r="{}" fill="{fill}" {extra}/>"#,
            n(x),
            n(y),
            n(r)
        );
    }

    /// Text at `(x, y)` (baseline), escaped here.
    pub fn text(&mut self, x: f64, y: f64, text: &str, size: f64, anchor: Anchor, extra: &str) {
        let _ = writeln!(
            self.body,
            r#"<text x="{}" y="{}" font-size="{}" text-anchor="{}" {extra}>{}</text>"#,
            n(x),
            n(y),
            n(size),
            anchor.as_str(),
            escape(text)
        );
    }

    /// A bold title centred on `centre` where it fits, else moved (and, if
    /// need be, shrunk) to stay inside the canvas: a long title centred over
    /// the plot lost its first letters at the left edge.
    pub fn title(&mut self, centre: f64, y: f64, text: &str) {
        const SIZE: f64 = 15.0;
        const MARGIN: f64 = 10.0;
        // DejaVu Sans Bold averages about 0.63 em per character
        let width_at = |size: f64| 0.63 * size * text.chars().count() as f64;
        let room = self.width - 2.0 * MARGIN;
        let size = if width_at(SIZE) > room {
            SIZE * room / width_at(SIZE)
        } else {
            SIZE
        };
        let half = width_at(size) / 2.0;
        let x = centre.clamp(
            MARGIN + half,
            (self.width - MARGIN - half).max(MARGIN + half),
        );
        self.text(x, y, text, size, Anchor::Middle, r#"font-weight="bold""#);
    }

    /// Text rotated by -90 degrees around its anchor (for vertical axis labels).
    pub fn vertical_text(&mut self, x: f64, y: f64, text: &str, size: f64) {
        let extra = format!(r#"transform="rotate(-90 {} {})""#, n(x), n(y));
        self.text(x, y, text, size, Anchor::Middle, &extra);
    }

    /// The complete document.
    pub fn finish(self) -> String {
        format!(
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="DejaVu Sans, Arial, sans-serif">
<rect x="0" y="0" width="{w}" height="{h}" fill="white"/>
{}</svg>
"#,
            self.body,
            w = n(self.width),
            h = n(self.height)
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A title too long to centre over the plot stays inside the canvas.
    #[test]
    fn long_titles_stay_inside_the_canvas() {
        let long = "Appendix C: e(x), rigid-bottom model vs exact engine at alpha = 0.001";
        for (text, canvas) in [(long, 710.0), (long, 300.0), ("short", 710.0)] {
            let mut svg = Svg::new(canvas, 500.0);
            svg.title(280.0, 24.0, text);
            let out = svg.finish();
            let attribute = |name: &str| -> f64 {
                let open = format!("{name}=\"");
                let value = out.split(open.as_str()).nth(1).unwrap();
                value.split('"').next().unwrap().parse().unwrap()
            };
            let (x, size) = (attribute("<text x"), attribute("font-size"));
            let half = 0.63 * size * text.chars().count() as f64 / 2.0;
            assert!(
                x - half >= 9.9 && x + half <= canvas - 9.9,
                "{text} at {x}, size {size}"
            );
        }
    }

    #[test]
    fn text_is_escaped_and_numbers_are_short() {
        let mut s = Svg::new(100.0, 50.0);
        s.text(1.0, 2.5, "a < b & \"c\"", 10.0, Anchor::Start, "");
        let doc = s.finish();
        assert!(doc.contains("a &lt; b &amp; &quot;c&quot;"));
        assert!(doc.contains(r#"x="1" y="2.5""#));
        assert!(doc.starts_with("<svg xmlns=\"http://www.w3.org/2000/svg\""));
    }
}

//! The colour scale and the key to the marks.

use super::{TOP, strain_colour};
use impact_plot::{Anchor, Svg};

/// A mark in the key: a line `(stroke, width, attributes)` or a circle
/// `(fill, attributes)`.
enum Mark {
    Line(&'static str, f64, &'static str),
    Circle(&'static str, &'static str),
}

/// The strain colour bar `±scale` and the key, at `x` right of the panels.
pub(super) fn legend(svg: &mut Svg, x: f64, scale: f64) {
    svg.raw(r#"<g class="legend">"#);
    let (top, h) = (TOP + 20.0, 160.0);
    for k in 0..40 {
        let v = -scale * (1.0 - 2.0 * f64::from(k) / 40.0);
        svg.rect(
            x,
            top + h * f64::from(k) / 40.0,
            16.0,
            h / 40.0 + 0.5,
            &strain_colour(v, scale).hex(),
            "",
        );
    }
    svg.rect(
        x,
        top,
        16.0,
        h,
        "none",
        r#"stroke="black" stroke-width="0.6""#,
    );
    svg.text(
        x + 20.0,
        top + 8.0,
        &format!("-{scale:.3} compression"),
        9.0,
        Anchor::Start,
        "",
    );
    svg.text(x + 20.0, top + h / 2.0 + 3.0, "0", 9.0, Anchor::Start, "");
    svg.text(
        x + 20.0,
        top + h,
        &format!("+{scale:.3} tension"),
        9.0,
        Anchor::Start,
        "",
    );
    svg.text(x, top - 8.0, "strain ε c_i / v_b", 11.0, Anchor::Start, "");
    let y = top + h + 30.0;
    // the key: each mark as the panels draw it, 20 pixels apart
    let marks = [
        (Mark::Line("#333", 0.8, ""), "front"),
        (
            Mark::Line("#1a9850", 2.6, r#"stroke-dasharray="2 3""#),
            "takeoff wave",
        ),
        (Mark::Circle("#777", r#"stroke="black""#), "separation"),
        (
            Mark::Circle("white", r##"stroke="#555" stroke-width="1.5""##),
            "reconnection",
        ),
        (
            Mark::Line("#444", 1.0, r#"stroke-dasharray="5 3""#),
            "interface",
        ),
    ];
    for (i, (mark, label)) in marks.into_iter().enumerate() {
        let y = y + 20.0 * i as f64;
        match mark {
            Mark::Line(stroke, width, extra) => {
                svg.line((x, y), (x + 22.0, y), stroke, width, extra)
            }
            Mark::Circle(fill, extra) => svg.circle(x + 11.0, y, 5.0, fill, extra),
        }
        svg.text(x + 28.0, y + 4.0, label, 10.0, Anchor::Start, "");
    }
    svg.raw("</g>");
}

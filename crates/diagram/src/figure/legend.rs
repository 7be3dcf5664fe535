//! The colour scale and the key to the marks.

use super::{TOP, strain_colour};
use impact_plot::{Anchor, Svg};

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
    svg.line((x, y), (x + 22.0, y), "#333", 0.8, "");
    svg.text(x + 28.0, y + 4.0, "front", 10.0, Anchor::Start, "");
    svg.line(
        (x, y + 20.0),
        (x + 22.0, y + 20.0),
        "#1a9850",
        2.6,
        r#"stroke-dasharray="2 3""#,
    );
    svg.text(x + 28.0, y + 24.0, "takeoff wave", 10.0, Anchor::Start, "");
    svg.circle(x + 11.0, y + 40.0, 5.0, "#777", r#"stroke="black""#);
    svg.text(x + 28.0, y + 44.0, "separation", 10.0, Anchor::Start, "");
    svg.circle(
        x + 11.0,
        y + 60.0,
        5.0,
        "white",
        r##"stroke="#555" stroke-width="1.5""##,
    );
    svg.text(x + 28.0, y + 64.0, "reconnection", 10.0, Anchor::Start, "");
    svg.line(
        (x, y + 80.0),
        (x + 22.0, y + 80.0),
        "#444",
        1.0,
        r#"stroke-dasharray="5 3""#,
    );
    svg.text(x + 28.0, y + 84.0, "interface", 10.0, Anchor::Start, "");
    svg.raw("</g>");
}

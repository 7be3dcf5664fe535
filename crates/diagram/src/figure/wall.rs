//! The wall panel below the space-time pictures: the wall strain against
//! time, with the contact intervals shaded.

use super::{Diagram, LEFT, NOTES, PANEL_H, TOP, WALL_H};
use impact_plot::{Anchor, Axis, Svg};

impl Diagram {
    /// `eps0 c1 / v_b` against time, with the contact intervals shaded.
    pub(super) fn wall_panel(&self, svg: &mut Svg, window: (f64, f64), width: f64) {
        let top = TOP + PANEL_H + 60.0 + NOTES;
        let w = width - LEFT - 150.0;
        let c0 = self.rod.layers()[0].wave_speed;
        let unit = self.rod.impact_speed() / c0;
        let values: Vec<(f64, f64)> = self.wall.iter().map(|&(t, s)| (t, s / unit)).collect();
        let lo = values.iter().fold(-1.0f64, |m, v| m.min(v.1));
        let hi = values.iter().fold(0.0f64, |m, v| m.max(v.1));
        let y = Axis::linear(lo * 1.08, (hi + 0.05 * (hi - lo)).max(0.1), "ε0 c1 / v_b");
        let t = Axis::linear(window.0, window.1, "time");
        let px = |v: f64| LEFT + w * t.fraction(v);
        let py = |v: f64| top + WALL_H * (1.0 - y.fraction(v));
        svg.raw(r#"<g class="wall-panel">"#);
        for c in &self.outcome.contacts {
            let (a, b) = (px(c[0].max(window.0)), px(c[1].min(window.1)));
            if b > a {
                svg.rect(a, top, b - a, WALL_H, "#dde8f0", r#"class="contact""#);
            }
        }
        svg.line((LEFT, py(0.0)), (LEFT + w, py(0.0)), "#999", 0.6, "");
        let mut pts = Vec::new();
        for (i, &(tt, v)) in values.iter().enumerate() {
            if tt > window.1 {
                break;
            }
            if i > 0 {
                pts.push((px(tt), py(values[i - 1].1)));
            }
            pts.push((px(tt), py(v)));
        }
        if let Some(&(_, v)) = values.iter().rfind(|(tt, _)| *tt <= window.1) {
            pts.push((px(window.1), py(v)));
        }
        svg.polyline(&pts, "#b2182b", 1.4, r#"class="wall-strain""#);
        Axis::draw_box(svg, (LEFT, top, w, WALL_H), (&t, &px), (&y, &py), 10.0);
        svg.vertical_text(LEFT - 45.0, top + WALL_H / 2.0, &y.label, 11.0);
        svg.text(
            LEFT + w,
            top - 6.0,
            "shaded: in contact",
            10.0,
            Anchor::End,
            r##"fill="#345""##,
        );
        svg.raw("</g>");
    }
}

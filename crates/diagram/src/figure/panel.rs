//! One space-time panel: where it sits, what window of time and colour
//! scale it shows, and the drawing of everything in it.

use super::ticks::transit_ticks;
use super::{Diagram, DiagramOptions, PANEL_H, PANEL_W, Picture, TOP, l_name};
use impact_plot::{Anchor, Axis, Svg, escape};

/// A panel being drawn. Everything its layers (field, fronts, events,
/// frame) share lives here, so each drawing step takes only the SVG.
pub(super) struct Panel<'a> {
    pub diagram: &'a Diagram,
    pub options: &'a DiagramOptions,
    /// The time window shown.
    pub window: (f64, f64),
    /// The colour scale: normalised strains `±scale` are full colour.
    pub scale: f64,
    /// The panel's left edge.
    pub x0: f64,
    pub t_axis: &'a Axis,
    pub y_axis: &'a Axis,
}

impl Panel<'_> {
    /// The SVG abscissa of time `t`.
    pub(super) fn px(&self, t: f64) -> f64 {
        self.x0 + PANEL_W * self.t_axis.fraction(t)
    }

    /// The SVG ordinate of height `y` in the rod.
    pub(super) fn py(&self, y: f64) -> f64 {
        TOP + PANEL_H * (1.0 - self.y_axis.fraction(y))
    }

    /// Draws the picture `k` (titled `label`) into its place: the field,
    /// fronts and takeoff path clipped to the panel, the interfaces, the
    /// wall events, the frame, and the notes on what was simplified.
    pub(super) fn draw(&self, svg: &mut Svg, k: usize, label: &str, picture: &Picture) {
        let x0 = self.x0;
        svg.raw(&format!(
            r#"<g class="picture" data-engine="{}">"#,
            escape(label)
        ));
        svg.text(
            x0 + PANEL_W / 2.0,
            TOP - 26.0,
            label,
            13.0,
            Anchor::Middle,
            "",
        );
        svg.raw(&format!(
            r#"<clipPath id="clip{k}"><rect x="{x0}" y="{TOP}" width="{PANEL_W}" height="{PANEL_H}"/></clipPath><g clip-path="url(#clip{k})">"#
        ));
        let note = match picture {
            Picture::Exact {
                field,
                fronts,
                path,
            } => {
                let mut note = self.draw_exact_field(svg, field);
                if self.options.draw_fronts {
                    note.push_str(&self.draw_fronts(svg, fronts));
                }
                self.draw_path(svg, fronts, path);
                note
            }
            Picture::Chain(c) => self.draw_chain(svg, c),
        };
        self.draw_interfaces(svg);
        svg.raw("</g>");
        self.draw_events(svg);
        self.frame(svg);
        self.write_notes(svg, &note);
        svg.raw("</g>");
    }

    /// Dashed lines at the interfaces between layers.
    fn draw_interfaces(&self, svg: &mut Svg) {
        let layers = self.diagram.rod.layers();
        for l in &layers[..layers.len() - 1] {
            svg.line(
                (self.x0, self.py(l.top)),
                (self.x0 + PANEL_W, self.py(l.top)),
                "#444",
                1.0,
                r#"class="interface" stroke-dasharray="5 3""#,
            );
        }
    }

    /// The notes on what was simplified, one sentence a line under the panel.
    fn write_notes(&self, svg: &mut Svg, note: &str) {
        for (i, sentence) in note
            .split_terminator(". ")
            .filter(|s| !s.trim().is_empty())
            .enumerate()
        {
            let line = if sentence.ends_with('.') {
                sentence.to_string()
            } else {
                format!("{sentence}.")
            };
            svg.text(
                self.x0 + 4.0,
                TOP + PANEL_H + 44.0 + 12.0 * i as f64,
                &line,
                10.0,
                Anchor::Start,
                r##"class="note" fill="#555""##,
            );
        }
    }

    fn draw_events(&self, svg: &mut Svg) {
        svg.raw(r#"<g class="events">"#);
        let contacts = &self.diagram.outcome.contacts;
        for (i, c) in contacts.iter().enumerate() {
            let last = i + 1 == contacts.len();
            if i > 0 {
                let tip = if self.options.tooltips {
                    format!("<title>reconnection at t = {:.6}</title>", c[0])
                } else {
                    String::new()
                };
                svg.raw(&format!(
                    r##"<circle class="event reconnection" cx="{:.2}" cy="{:.2}" r="5" fill="white" stroke="#555" stroke-width="1.5">{tip}</circle>"##,
                    self.px(c[0]),
                    self.py(0.0)
                ));
            }
            if last
                && self.diagram.outcome.stop_reason == impact_model::StopReason::HorizonInContact
            {
                continue;
            }
            let kind = if last { "takeoff" } else { "separation" };
            let tip = if self.options.tooltips {
                format!("<title>{kind} at t = {:.6}</title>", c[1])
            } else {
                String::new()
            };
            svg.raw(&format!(
                r##"<circle class="event {kind}" cx="{:.2}" cy="{:.2}" r="{}" fill="#777" stroke="black" stroke-width="1">{tip}</circle>"##,
                self.px(c[1]),
                self.py(0.0),
                if last { 6.5 } else { 5.0 }
            ));
        }
        svg.raw("</g>");
    }

    fn frame(&self, svg: &mut Svg) {
        svg.rect(
            self.x0,
            TOP,
            PANEL_W,
            PANEL_H,
            "none",
            r#"stroke="black" stroke-width="1""#,
        );
        self.t_axis
            .draw_below(svg, &|t| self.px(t), TOP + PANEL_H, 10.0);
        svg.text(
            self.x0 + PANEL_W / 2.0,
            TOP + PANEL_H + 31.0,
            &self.t_axis.label,
            11.0,
            Anchor::Middle,
            "",
        );
        for (v, label) in transit_ticks(
            &self.diagram.outcome.transit_times,
            self.t_axis.min,
            self.t_axis.max,
        ) {
            svg.line(
                (self.px(v), TOP - 5.0),
                (self.px(v), TOP),
                "#1a5276",
                1.0,
                "",
            );
            svg.text(
                self.px(v),
                TOP - 8.0,
                &label,
                10.0,
                Anchor::Middle,
                r##"class="transit-tick" fill="#1a5276""##,
            );
        }
        self.y_axis.draw_left(svg, &|y| self.py(y), self.x0, 10.0);
        svg.vertical_text(
            self.x0 - 45.0,
            TOP + PANEL_H / 2.0,
            &self.y_axis.label,
            11.0,
        );
        for (i, l) in self.diagram.rod.layers().iter().enumerate() {
            svg.text(
                self.x0 + PANEL_W + 4.0,
                self.py(0.5 * (l.bottom + l.top)) + 4.0,
                &l_name(&self.diagram.rod, i),
                10.0,
                Anchor::Start,
                r#"class="layer-name""#,
            );
        }
    }
}

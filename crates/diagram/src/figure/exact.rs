//! The exact picture: the strain field as polygons (or exact values at
//! pixel centres when there are too many), the fronts as lines, and the
//! takeoff wave's path.

use super::panel::Panel;
use super::{PANEL_H, PANEL_W, RASTER_H, RASTER_W, TOP, l_name, strain_colour};
use crate::field::ExactField;
use impact_plot::{Colour, Svg, embedded_image, raster_png};
use impact_wave::{Direction, FrontRecord};
use std::fmt::Write as _;

impl Panel<'_> {
    pub(super) fn draw_exact_field(&self, svg: &mut Svg, field: &ExactField) -> String {
        let count = field.cell_count(self.window.1, self.options.max_cells);
        if count <= self.options.max_cells {
            svg.raw(r#"<g class="field" shape-rendering="crispEdges">"#);
            for cell in field.cells(self.window.1) {
                let colour =
                    strain_colour(self.diagram.normalise(cell.layer, cell.strain), self.scale);
                if colour == Colour::WHITE {
                    continue;
                }
                let mut d = String::new();
                for (i, (t, y)) in cell.corners.iter().enumerate() {
                    let _ = write!(
                        d,
                        "{}{:.2},{:.2}",
                        if i == 0 { "M" } else { "L" },
                        self.px(*t),
                        self.py(*y)
                    );
                }
                svg.raw(&format!(
                    r#"<path d="{d}Z" fill="{}" stroke="{}" stroke-width="0.3"/>"#,
                    colour.hex(),
                    colour.hex()
                ));
            }
            svg.raw("</g>");
            String::new()
        } else {
            // exact values at every pixel centre: what the output can show
            let mut pixels = Vec::with_capacity((RASTER_W * RASTER_H) as usize);
            self.diagram.for_each_pixel(self.window, |t, y| {
                pixels.push(strain_colour(
                    self.diagram
                        .normalise(self.diagram.layer_at(y), field.strain(t, y)),
                    self.scale,
                ))
            });
            let x0 = self.px(self.window.0);
            if let Ok(png) = raster_png(RASTER_W, RASTER_H, &pixels) {
                svg.raw(&format!(
                    r#"<g class="field">{}</g>"#,
                    embedded_image(&png, x0, TOP, PANEL_W, PANEL_H)
                ));
            }
            format!(
                "field: over {} exact polygons, drawn as exact values at {RASTER_W} x {RASTER_H} pixel centres. ",
                self.options.max_cells
            )
        }
    }

    pub(super) fn draw_fronts(&self, svg: &mut Svg, fronts: &[FrontRecord]) -> String {
        let layers = self.diagram.rod.layers();
        let in_window: Vec<&FrontRecord> = fronts
            .iter()
            .filter(|f| f.born < self.window.1 && f.arrives > self.window.0)
            .collect();
        let total = in_window.len();
        // Lines closer than 3 pixels cannot be told apart: one line (the
        // strongest) per lane and 3-pixel bucket of birth time. Fronts under
        // 1/200 of the colour self.scale cannot be seen at all.
        let bucket = 3.0 * (self.window.1 - self.window.0) / PANEL_W;
        let mut best: std::collections::BTreeMap<(usize, bool, i64), &FrontRecord> =
            std::collections::BTreeMap::new();
        for f in in_window {
            if self.diagram.normalise(f.layer, f.jump).abs() < self.scale / 200.0 {
                continue;
            }
            let key = (
                f.layer,
                f.direction == Direction::Up,
                (f.born / bucket).floor() as i64,
            );
            best.entry(key)
                .and_modify(|g| {
                    if f.jump.abs() > g.jump.abs() {
                        *g = f;
                    }
                })
                .or_insert(f);
        }
        let mut visible: Vec<&FrontRecord> = best.into_values().collect();
        visible.sort_by(|a, b| b.jump.abs().total_cmp(&a.jump.abs()).then(a.id.cmp(&b.id)));
        visible.truncate(self.options.max_fronts);
        visible.sort_by_key(|f| f.id);
        svg.raw(r##"<g class="fronts" stroke="#333" stroke-opacity="0.55" stroke-width="0.6">"##);
        for f in &visible {
            let l = &layers[f.layer];
            let (y0, y1) = match f.direction {
                Direction::Up => (l.bottom, l.top),
                Direction::Down => (l.top, l.bottom),
            };
            let title = if self.options.tooltips {
                format!(
                    "<title>front {}: {} {}, born t = {:.6}, arrives t = {:.6}, strain jump {:.4e}, parents {:?}</title>",
                    f.id,
                    l_name(&self.diagram.rod, f.layer),
                    if f.direction == Direction::Up {
                        "up"
                    } else {
                        "down"
                    },
                    f.born,
                    f.arrives,
                    f.jump,
                    f.parents
                )
            } else {
                String::new()
            };
            svg.raw(&format!(
                r#"<line class="front" data-id="{}" x1="{:.2}" y1="{:.2}" x2="{:.2}" y2="{:.2}">{title}</line>"#,
                f.id,
                self.px(f.born),
                self.py(y0),
                self.px(f.arrives),
                self.py(y1)
            ));
        }
        svg.raw("</g>");
        if visible.len() < total {
            format!(
                "fronts: {} lines for {total} fronts (one per 3 pixels of birth time and layer, the strongest; weaker than self.scale/200 left out).",
                visible.len()
            )
        } else {
            String::new()
        }
    }

    pub(super) fn draw_path(&self, svg: &mut Svg, fronts: &[FrontRecord], path: &[u32]) {
        let layers = self.diagram.rod.layers();
        let mut pts = Vec::new();
        for &id in path {
            let Some(f) = fronts.get(id as usize) else {
                continue;
            };
            let l = &layers[f.layer];
            let (y0, y1) = match f.direction {
                Direction::Up => (l.bottom, l.top),
                Direction::Down => (l.top, l.bottom),
            };
            pts.push((self.px(f.born), self.py(y0)));
            pts.push((self.px(f.arrives), self.py(y1)));
        }
        svg.raw(r#"<g class="takeoff-path">"#);
        svg.polyline(
            &pts,
            "#1a9850",
            2.6,
            r#"stroke-dasharray="2 3" stroke-linecap="round""#,
        );
        svg.raw("</g>");
    }
}

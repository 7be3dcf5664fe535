//! The space-time figure: one or two pictures (exact, chain) sharing axes and
//! colour scale, and the wall-strain panel below.

use crate::field::ExactField;
use impact_chain::RasterFrame;
use impact_model::{Outcome, Rod};
use impact_plot::{Anchor, Axis, Colour, Colourmap, Svg, embedded_image, escape, raster_png};

use impact_wave::{Direction, FrontRecord};
use std::fmt::Write as _;

/// The chain's strain field: frames in time, rows of equal height.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainPicture {
    pub frames: Vec<RasterFrame>,
}

/// What one panel shows.
#[derive(Debug, Clone)]
pub enum Picture {
    /// The exact field, its fronts, and the takeoff path (front ids).
    Exact {
        field: ExactField,
        fronts: Vec<FrontRecord>,
        path: Vec<u32>,
    },
    Chain(ChainPicture),
}

/// Drawing options.
#[derive(Debug, Clone, PartialEq)]
pub struct DiagramOptions {
    /// Time window; `None`: from 0 to a little after the final takeoff.
    pub window: Option<(f64, f64)>,
    /// Colour scale `±strain_scale`; `None`: the largest strain shown.
    pub strain_scale: Option<f64>,
    /// Draw the fronts as thin lines.
    pub draw_fronts: bool,
    /// Exact fields with more polygons than this are drawn as an exact
    /// per-pixel raster instead (and the figure says so).
    pub max_cells: usize,
    /// At most this many fronts are drawn, the strongest first (the figure
    /// says how many were left out).
    pub max_fronts: usize,
    /// Add `<title>` tooltips (amplitude, ancestry) to fronts and events.
    pub tooltips: bool,
}

impl Default for DiagramOptions {
    fn default() -> Self {
        Self {
            window: None,
            strain_scale: None,
            draw_fronts: true,
            max_cells: 40_000,
            max_fronts: 3_000,
            tooltips: false,
        }
    }
}

/// A run to draw: the rod, its outcome, its wall history and the pictures.
#[derive(Debug, Clone)]
pub struct Diagram {
    pub title: String,
    pub rod: Rod,
    pub outcome: Outcome,
    /// `(time, wall strain)` after each wall event (exact) or sample (chain).
    pub wall: Vec<(f64, f64)>,
    pub pictures: Vec<(String, Picture)>,
}

const PANEL_W: f64 = 620.0;
const PANEL_H: f64 = 360.0;
const WALL_H: f64 = 140.0;
/// Room under the space-time panels for their notes.
const NOTES: f64 = 24.0;
const LEFT: f64 = 70.0;
const TOP: f64 = 78.0;
const GAP: f64 = 60.0;
const RASTER_W: u32 = 620;
const RASTER_H: u32 = 360;

/// Tick labels at the rod's characteristic times: `2 t1`, `2 t1 + 2 t2`, ...
fn transit_ticks(transits: &[f64], t0: f64, t1: f64) -> Vec<(f64, String)> {
    let mut out: Vec<(f64, String, u32)> = Vec::new();
    let sum: f64 = transits.iter().sum();
    match transits {
        [a, b] => {
            for i in 0..=8u32 {
                for j in 0..=4u32 {
                    let t = f64::from(i) * a + f64::from(j) * b;
                    if i + j == 0 || i % 2 == 1 && j == 0 || j % 2 == 1 {
                        continue;
                    }
                    let label = match (i, j) {
                        (i, 0) => format!("{i}t1"),
                        (0, j) => format!("{j}t2"),
                        (1, j) => format!("t1+{j}t2"),
                        (i, j) => format!("{i}t1+{j}t2"),
                    };
                    out.push((t, label, i + j));
                }
            }
        }
        _ => {
            out.push((2.0 * transits[0], "2t1".into(), 1));
            for k in 1..=4u32 {
                out.push((2.0 * f64::from(k) * sum, format!("{}Σt", 2 * k), k + 1));
            }
        }
    }
    out.retain(|(t, _, _)| *t >= t0 && *t <= t1);
    out.sort_by(|a, b| a.2.cmp(&b.2).then(a.0.total_cmp(&b.0)));
    // keep labels at least 7% of the window apart, simplest first
    let mut kept: Vec<(f64, String)> = Vec::new();
    for (t, label, _) in out {
        if kept.iter().all(|(k, _)| (k - t).abs() > 0.07 * (t1 - t0)) {
            kept.push((t, label));
        }
    }
    kept.sort_by(|a, b| a.0.total_cmp(&b.0));
    kept
}

/// The colour of a normalised strain `s = eps c_i / v_b` on the scale
/// `±scale`: compression red, tension blue, zero white (the paper's).
fn strain_colour(s: f64, scale: f64) -> Colour {
    Colourmap::Diverging.colour(-s, -scale, scale)
}

impl Diagram {
    /// `eps c_i / v_b` in layer `i`: -1 for the impact compression in every
    /// layer, so stiff and soft layers are both visible on one scale.
    fn normalise(&self, layer: usize, strain: f64) -> f64 {
        strain * self.rod.layers()[layer].wave_speed / self.rod.impact_speed()
    }

    fn layer_at(&self, y: f64) -> usize {
        let layers = self.rod.layers();
        layers
            .iter()
            .position(|l| y < l.top)
            .unwrap_or(layers.len() - 1)
    }

    /// Calls `f(t, y)` at the centre of every pixel of the raster.
    fn for_each_pixel(&self, window: (f64, f64), mut f: impl FnMut(f64, f64)) {
        let total = self.rod.total_length();
        for row in 0..RASTER_H {
            let y = total * (1.0 - (f64::from(row) + 0.5) / f64::from(RASTER_H));
            for col in 0..RASTER_W {
                let t =
                    window.0 + (window.1 - window.0) * (f64::from(col) + 0.5) / f64::from(RASTER_W);
                f(t.max(0.0), y);
            }
        }
    }

    fn window(&self, options: &DiagramOptions) -> (f64, f64) {
        options.window.unwrap_or((
            0.0,
            (1.12 * self.outcome.contact_time)
                .min(self.outcome.end_time.max(self.outcome.contact_time)),
        ))
    }

    /// Largest |strain| any picture shows in the window (the default scale).
    fn strain_scale(&self, options: &DiagramOptions, window: (f64, f64)) -> f64 {
        if let Some(s) = options.strain_scale {
            return s;
        }
        let mut m: f64 = 0.0;
        for (_, p) in &self.pictures {
            match p {
                Picture::Exact { field, .. }
                    if field.cell_count(window.1, options.max_cells) <= options.max_cells =>
                {
                    for c in field.cells(window.1) {
                        m = m.max(self.normalise(c.layer, c.strain).abs());
                    }
                }
                Picture::Exact { field, .. } => {
                    // too many polygons: the largest exact value at the pixels drawn
                    self.for_each_pixel(window, |t, y| {
                        m = m.max(self.normalise(self.layer_at(y), field.strain(t, y)).abs())
                    });
                }
                Picture::Chain(c) => {
                    let total = self.rod.total_length();
                    for f in c.frames.iter().filter(|f| f.time <= window.1) {
                        let rows = f.strain.len() as f64;
                        for (r, s) in f.strain.iter().enumerate() {
                            let layer = self.layer_at(total * (r as f64 + 0.5) / rows);
                            m = m.max(self.normalise(layer, *s).abs());
                        }
                    }
                }
            }
        }
        if m > 0.0 { m } else { 1.0 }
    }

    /// The whole figure as SVG.
    pub fn to_svg(&self, options: &DiagramOptions) -> String {
        let window = self.window(options);
        let scale = self.strain_scale(options, window);
        let n = self.pictures.len().max(1) as f64;
        let width = LEFT + n * PANEL_W + (n - 1.0) * GAP + 175.0;
        let height = TOP + PANEL_H + 50.0 + NOTES + WALL_H + 60.0;
        let mut svg = Svg::new(width, height);
        svg.text(
            width / 2.0,
            22.0,
            &self.title,
            15.0,
            Anchor::Middle,
            r#"font-weight="bold""#,
        );
        let t_axis = Axis::linear(window.0, window.1, "time (scene units)");
        let y_axis = Axis::linear(0.0, self.rod.total_length(), "height in the rod");
        for (k, (label, picture)) in self.pictures.iter().enumerate() {
            let x0 = LEFT + k as f64 * (PANEL_W + GAP);
            let px = |t: f64| x0 + PANEL_W * t_axis.fraction(t);
            let py = |y: f64| TOP + PANEL_H * (1.0 - y_axis.fraction(y));
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
                    let mut note =
                        self.draw_exact_field(&mut svg, field, window, scale, options, &px, &py);
                    if options.draw_fronts {
                        note.push_str(
                            &self.draw_fronts(&mut svg, fronts, window, scale, options, &px, &py),
                        );
                    }
                    self.draw_path(&mut svg, fronts, path, &px, &py);
                    note
                }
                Picture::Chain(c) => self.draw_chain(&mut svg, c, window, scale, x0),
            };
            // interfaces
            for l in &self.rod.layers()[..self.rod.layers().len() - 1] {
                svg.line(
                    (x0, py(l.top)),
                    (x0 + PANEL_W, py(l.top)),
                    "#444",
                    1.0,
                    r#"class="interface" stroke-dasharray="5 3""#,
                );
            }
            svg.raw("</g>");
            self.draw_events(&mut svg, &px, &py, options);
            self.frame(&mut svg, &t_axis, &y_axis, x0, &px, &py);
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
                    x0 + 4.0,
                    TOP + PANEL_H + 44.0 + 12.0 * i as f64,
                    &line,
                    10.0,
                    Anchor::Start,
                    r##"class="note" fill="#555""##,
                );
            }
            svg.raw("</g>");
        }
        self.legend(&mut svg, LEFT + n * PANEL_W + (n - 1.0) * GAP + 40.0, scale);
        self.wall_panel(&mut svg, window, width);
        svg.finish()
    }

    #[allow(clippy::too_many_arguments)]
    fn draw_exact_field(
        &self,
        svg: &mut Svg,
        field: &ExactField,
        window: (f64, f64),
        scale: f64,
        options: &DiagramOptions,
        px: &dyn Fn(f64) -> f64,
        py: &dyn Fn(f64) -> f64,
    ) -> String {
        let count = field.cell_count(window.1, options.max_cells);
        if count <= options.max_cells {
            svg.raw(r#"<g class="field" shape-rendering="crispEdges">"#);
            for cell in field.cells(window.1) {
                let colour = strain_colour(self.normalise(cell.layer, cell.strain), scale);
                if colour == Colour::WHITE {
                    continue;
                }
                let mut d = String::new();
                for (i, (t, y)) in cell.corners.iter().enumerate() {
                    let _ = write!(
                        d,
                        "{}{:.2},{:.2}",
                        if i == 0 { "M" } else { "L" },
                        px(*t),
                        py(*y)
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
            self.for_each_pixel(window, |t, y| {
                pixels.push(strain_colour(
                    self.normalise(self.layer_at(y), field.strain(t, y)),
                    scale,
                ))
            });
            let x0 = px(window.0);
            if let Ok(png) = raster_png(RASTER_W, RASTER_H, &pixels) {
                svg.raw(&format!(
                    r#"<g class="field">{}</g>"#,
                    embedded_image(&png, x0, TOP, PANEL_W, PANEL_H)
                ));
            }
            format!(
                "field: over {} exact polygons, drawn as exact values at {RASTER_W} x {RASTER_H} pixel centres. ",
                options.max_cells
            )
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn draw_fronts(
        &self,
        svg: &mut Svg,
        fronts: &[FrontRecord],
        window: (f64, f64),
        scale: f64,
        options: &DiagramOptions,
        px: &dyn Fn(f64) -> f64,
        py: &dyn Fn(f64) -> f64,
    ) -> String {
        let layers = self.rod.layers();
        let in_window: Vec<&FrontRecord> = fronts
            .iter()
            .filter(|f| f.born < window.1 && f.arrives > window.0)
            .collect();
        let total = in_window.len();
        // Lines closer than 3 pixels cannot be told apart: one line (the
        // strongest) per lane and 3-pixel bucket of birth time. Fronts under
        // 1/200 of the colour scale cannot be seen at all.
        let bucket = 3.0 * (window.1 - window.0) / PANEL_W;
        let mut best: std::collections::BTreeMap<(usize, bool, i64), &FrontRecord> =
            std::collections::BTreeMap::new();
        for f in in_window {
            if self.normalise(f.layer, f.jump).abs() < scale / 200.0 {
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
        visible.truncate(options.max_fronts);
        visible.sort_by_key(|f| f.id);
        svg.raw(r##"<g class="fronts" stroke="#333" stroke-opacity="0.55" stroke-width="0.6">"##);
        for f in &visible {
            let l = &layers[f.layer];
            let (y0, y1) = match f.direction {
                Direction::Up => (l.bottom, l.top),
                Direction::Down => (l.top, l.bottom),
            };
            let title = if options.tooltips {
                format!(
                    "<title>front {}: {} {}, born t = {:.6}, arrives t = {:.6}, strain jump {:.4e}, parents {:?}</title>",
                    f.id,
                    l_name(&self.rod, f.layer),
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
                px(f.born),
                py(y0),
                px(f.arrives),
                py(y1)
            ));
        }
        svg.raw("</g>");
        if visible.len() < total {
            format!(
                "fronts: {} lines for {total} fronts (one per 3 pixels of birth time and layer, the strongest; weaker than scale/200 left out).",
                visible.len()
            )
        } else {
            String::new()
        }
    }

    fn draw_path(
        &self,
        svg: &mut Svg,
        fronts: &[FrontRecord],
        path: &[u32],
        px: &dyn Fn(f64) -> f64,
        py: &dyn Fn(f64) -> f64,
    ) {
        let layers = self.rod.layers();
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
            pts.push((px(f.born), py(y0)));
            pts.push((px(f.arrives), py(y1)));
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

    fn draw_chain(
        &self,
        svg: &mut Svg,
        c: &ChainPicture,
        window: (f64, f64),
        scale: f64,
        x0: f64,
    ) -> String {
        let frames: Vec<&RasterFrame> = c
            .frames
            .iter()
            .filter(|f| f.time >= window.0 && f.time <= window.1)
            .collect();
        let rows = frames.first().map_or(0, |f| f.strain.len());
        if frames.is_empty() || rows == 0 {
            return "no chain frames in the window".into();
        }
        let mut pixels = Vec::with_capacity((RASTER_W * RASTER_H) as usize);
        let total = self.rod.total_length();
        for row in 0..RASTER_H {
            let r = rows
                - 1
                - ((f64::from(row) + 0.5) / f64::from(RASTER_H) * rows as f64)
                    .floor()
                    .min(rows as f64 - 1.0) as usize;
            let layer = self.layer_at(total * (r as f64 + 0.5) / rows as f64);
            for col in 0..RASTER_W {
                let t =
                    window.0 + (window.1 - window.0) * (f64::from(col) + 0.5) / f64::from(RASTER_W);
                let k = frames.partition_point(|f| f.time <= t).saturating_sub(1);
                pixels.push(strain_colour(
                    self.normalise(layer, frames[k].strain[r]),
                    scale,
                ));
            }
        }
        if let Ok(png) = raster_png(RASTER_W, RASTER_H, &pixels) {
            svg.raw(&format!(
                r#"<g class="field">{}</g>"#,
                embedded_image(&png, x0, TOP, PANEL_W, PANEL_H)
            ));
        }
        format!("chain field: {} frames x {rows} rows.", frames.len())
    }

    fn draw_events(
        &self,
        svg: &mut Svg,
        px: &dyn Fn(f64) -> f64,
        py: &dyn Fn(f64) -> f64,
        options: &DiagramOptions,
    ) {
        svg.raw(r#"<g class="events">"#);
        let contacts = &self.outcome.contacts;
        for (i, c) in contacts.iter().enumerate() {
            let last = i + 1 == contacts.len();
            if i > 0 {
                let tip = if options.tooltips {
                    format!("<title>reconnection at t = {:.6}</title>", c[0])
                } else {
                    String::new()
                };
                svg.raw(&format!(
                    r##"<circle class="event reconnection" cx="{:.2}" cy="{:.2}" r="5" fill="white" stroke="#555" stroke-width="1.5">{tip}</circle>"##,
                    px(c[0]),
                    py(0.0)
                ));
            }
            if last && self.outcome.stop_reason == impact_model::StopReason::HorizonInContact {
                continue;
            }
            let kind = if last { "takeoff" } else { "separation" };
            let tip = if options.tooltips {
                format!("<title>{kind} at t = {:.6}</title>", c[1])
            } else {
                String::new()
            };
            svg.raw(&format!(
                r##"<circle class="event {kind}" cx="{:.2}" cy="{:.2}" r="{}" fill="#777" stroke="black" stroke-width="1">{tip}</circle>"##,
                px(c[1]),
                py(0.0),
                if last { 6.5 } else { 5.0 }
            ));
        }
        svg.raw("</g>");
    }

    fn frame(
        &self,
        svg: &mut Svg,
        t: &Axis,
        y: &Axis,
        x0: f64,
        px: &dyn Fn(f64) -> f64,
        py: &dyn Fn(f64) -> f64,
    ) {
        svg.rect(
            x0,
            TOP,
            PANEL_W,
            PANEL_H,
            "none",
            r#"stroke="black" stroke-width="1""#,
        );
        t.draw_below(svg, px, TOP + PANEL_H, 10.0);
        svg.text(
            x0 + PANEL_W / 2.0,
            TOP + PANEL_H + 31.0,
            &t.label,
            11.0,
            Anchor::Middle,
            "",
        );
        for (v, label) in transit_ticks(&self.outcome.transit_times, t.min, t.max) {
            svg.line((px(v), TOP - 5.0), (px(v), TOP), "#1a5276", 1.0, "");
            svg.text(
                px(v),
                TOP - 8.0,
                &label,
                10.0,
                Anchor::Middle,
                r##"class="transit-tick" fill="#1a5276""##,
            );
        }
        y.draw_left(svg, py, x0, 10.0);
        svg.vertical_text(x0 - 45.0, TOP + PANEL_H / 2.0, &y.label, 11.0);
        for (i, l) in self.rod.layers().iter().enumerate() {
            svg.text(
                x0 + PANEL_W + 4.0,
                py(0.5 * (l.bottom + l.top)) + 4.0,
                &l_name(&self.rod, i),
                10.0,
                Anchor::Start,
                r#"class="layer-name""#,
            );
        }
    }

    fn legend(&self, svg: &mut Svg, x: f64, scale: f64) {
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

    /// `eps0 c1 / v_b` against time, with the contact intervals shaded.
    fn wall_panel(&self, svg: &mut Svg, window: (f64, f64), width: f64) {
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
        svg.rect(
            LEFT,
            top,
            w,
            WALL_H,
            "none",
            r#"stroke="black" stroke-width="1""#,
        );
        t.draw_below(svg, &px, top + WALL_H, 10.0);
        y.draw_left(svg, &py, LEFT, 10.0);
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

fn l_name(rod: &Rod, i: usize) -> String {
    rod.scene().layers[i]
        .name
        .clone()
        .unwrap_or_else(|| format!("layer {}", i + 1))
}

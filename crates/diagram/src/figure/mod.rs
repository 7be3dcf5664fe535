//! The space-time figure: one or two pictures (exact, chain) sharing axes and
//! colour scale, and the wall-strain panel below.

//!
//! The pieces: each picture is a [`panel::Panel`] (`panel.rs`) drawing the
//! exact field, fronts and takeoff path (`exact.rs`) or the chain's raster
//! (`chain.rs`), its wall events and its frame with ticks at the rod's
//! transit times (`ticks.rs`); the colour key (`legend.rs`) and the wall
//! panel (`wall.rs`) are drawn once for the figure.

mod chain;
mod exact;
mod legend;
mod panel;
mod ticks;
mod wall;

use crate::field::ExactField;
use impact_chain::RasterFrame;
use impact_model::{Outcome, Rod};
use impact_plot::{Anchor, Axis, Colour, Colourmap, Svg};
use impact_wave::FrontRecord;
use legend::legend;
use panel::Panel;

/// The chain's strain field: frames in time, rows of equal height.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainPicture {
    /// Strain frames in time order, rows bottom first.
    pub frames: Vec<RasterFrame>,
}

/// What one panel shows.
#[derive(Debug, Clone)]
pub enum Picture {
    /// The exact field, its fronts, and the takeoff path (front ids).
    Exact {
        /// The exact strain field, as polygons.
        field: ExactField,
        /// Every front of the run.
        fronts: Vec<FrontRecord>,
        /// Ids of the fronts on the path that triggers the final takeoff, from its origin (the impact or a landing) on.
        path: Vec<u32>,
    },
    /// The chain's strain field, averaged into rows.
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
    /// Title above the figure.
    pub title: String,
    /// The rod drawn (its layers give the interfaces and transit-time ticks).
    pub rod: Rod,
    /// The run's outcome (contacts, `e`, `t_c`).
    pub outcome: Outcome,
    /// `(time, wall strain)` after each wall event (exact) or sample (chain).
    pub wall: Vec<(f64, f64)>,
    /// The panels, each with its caption.
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
            let panel = Panel {
                diagram: self,
                options,
                window,
                scale,
                x0: LEFT + k as f64 * (PANEL_W + GAP),
                t_axis: &t_axis,
                y_axis: &y_axis,
            };
            panel.draw(&mut svg, k, label, picture);
        }
        legend(&mut svg, LEFT + n * PANEL_W + (n - 1.0) * GAP + 40.0, scale);
        self.wall_panel(&mut svg, window, width);
        svg.finish()
    }
}

fn l_name(rod: &Rod, i: usize) -> String {
    rod.scene().layers[i]
        .name
        .clone()
        .unwrap_or_else(|| format!("layer {}", i + 1))
}

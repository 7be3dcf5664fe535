//! The chain's picture: its strain frames as a raster, one row of pixels
//! per mass row and the frame in force at each pixel's time.

use super::panel::Panel;
use super::{PANEL_H, PANEL_W, RASTER_H, RASTER_W, TOP, strain_colour};
use impact_chain::RasterFrame;
use impact_plot::{Svg, embedded_image, raster_png};

impl Panel<'_> {
    pub(super) fn draw_chain(&self, svg: &mut Svg, c: &super::ChainPicture) -> String {
        let frames: Vec<&RasterFrame> = c
            .frames
            .iter()
            .filter(|f| f.time >= self.window.0 && f.time <= self.window.1)
            .collect();
        let rows = frames.first().map_or(0, |f| f.strain.len());
        if frames.is_empty() || rows == 0 {
            return "no chain frames in the window".into();
        }
        let mut pixels = Vec::with_capacity((RASTER_W * RASTER_H) as usize);
        let total = self.diagram.rod.total_length();
        for row in 0..RASTER_H {
            let r = rows
                - 1
                - ((f64::from(row) + 0.5) / f64::from(RASTER_H) * rows as f64)
                    .floor()
                    .min(rows as f64 - 1.0) as usize;
            let layer = self
                .diagram
                .layer_at(total * (r as f64 + 0.5) / rows as f64);
            for col in 0..RASTER_W {
                let t = self.window.0
                    + (self.window.1 - self.window.0) * (f64::from(col) + 0.5)
                        / f64::from(RASTER_W);
                let k = frames.partition_point(|f| f.time <= t).saturating_sub(1);
                pixels.push(strain_colour(
                    self.diagram.normalise(layer, frames[k].strain[r]),
                    self.scale,
                ));
            }
        }
        if let Ok(png) = raster_png(RASTER_W, RASTER_H, &pixels) {
            svg.raw(&format!(
                r#"<g class="field">{}</g>"#,
                embedded_image(&png, self.x0, TOP, PANEL_W, PANEL_H)
            ));
        }
        format!("chain field: {} frames x {rows} rows.", frames.len())
    }
}

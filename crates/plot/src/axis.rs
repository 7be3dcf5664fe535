//! Axes: value-to-pixel maps and "nice" ticks.

/// Linear or logarithmic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scale {
    /// Values map linearly to pixels.
    Linear,
    /// Logarithms of the values map linearly to pixels (positive values only).
    Log,
}

/// A data range drawn onto a pixel range.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    /// Value at the start of the axis (left, or bottom).
    pub min: f64,
    /// Value at the end of the axis (right, or top).
    pub max: f64,
    /// Linear or logarithmic.
    pub scale: Scale,
    /// Axis title, plain text (escaped when drawn).
    pub label: String,
}

impl Axis {
    /// A linear axis from `min` to `max`.
    pub fn linear(min: f64, max: f64, label: &str) -> Self {
        Self {
            min,
            max,
            scale: Scale::Linear,
            label: label.to_string(),
        }
    }

    /// A logarithmic axis from `min` to `max` (both positive).
    pub fn log(min: f64, max: f64, label: &str) -> Self {
        Self {
            min,
            max,
            scale: Scale::Log,
            label: label.to_string(),
        }
    }

    /// An axis spanning `values` (finite ones; positive ones for log), with a
    /// margin of `pad` of the span on each side (a factor for log axes).
    pub fn fit(values: impl IntoIterator<Item = f64>, scale: Scale, label: &str, pad: f64) -> Self {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for v in values {
            if v.is_finite() && (scale == Scale::Linear || v > 0.0) {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        if !lo.is_finite() {
            (lo, hi) = if scale == Scale::Log {
                (0.1, 10.0)
            } else {
                (0.0, 1.0)
            };
        }
        match scale {
            Scale::Linear => {
                let span = if hi > lo { hi - lo } else { hi.abs().max(1.0) };
                Self::linear(lo - pad * span, hi + pad * span, label)
            }
            Scale::Log => {
                let (lo, hi) = if hi > lo {
                    (lo, hi)
                } else {
                    (lo / 2.0, hi * 2.0)
                };
                let f = (hi / lo).powf(pad);
                Self::log(lo / f, hi * f, label)
            }
        }
    }

    /// Fraction `[0, 1]` of the way from `min` to `max`.
    pub fn fraction(&self, v: f64) -> f64 {
        match self.scale {
            Scale::Linear => (v - self.min) / (self.max - self.min),
            Scale::Log => (v.ln() - self.min.ln()) / (self.max.ln() - self.min.ln()),
        }
    }

    /// Ticks inside the range, with their labels.
    pub fn ticks(&self) -> Vec<(f64, String)> {
        match self.scale {
            Scale::Linear => {
                let span = self.max - self.min;
                if span.is_nan() || span <= 0.0 {
                    return vec![(self.min, short(self.min))];
                }
                let raw = span / 5.0;
                let mag = 10f64.powf(raw.log10().floor());
                let step = [1.0, 2.0, 2.5, 5.0, 10.0]
                    .iter()
                    .map(|m| m * mag)
                    .find(|s| span / s <= 6.0)
                    .unwrap_or(10.0 * mag);
                let first = (self.min / step).ceil() as i64;
                let last = (self.max / step).floor() as i64;
                (first..=last)
                    .map(|k| k as f64 * step)
                    .map(|v| (v, short(v)))
                    .collect()
            }
            Scale::Log => {
                let (a, b) = (
                    self.min.log10().ceil() as i32,
                    self.max.log10().floor() as i32,
                );
                let every = ((b - a) / 6 + 1).max(1);
                (a..=b)
                    .filter(|k| (k - a) % every == 0)
                    .map(|k| (10f64.powi(k), format!("1e{k}")))
                    .collect()
            }
        }
    }
}

impl Axis {
    /// Ticks and their labels below a horizontal axis at height `y` (pixels),
    /// `px` mapping values to pixels.
    pub fn draw_below(&self, svg: &mut crate::Svg, px: &dyn Fn(f64) -> f64, y: f64, font: f64) {
        for (v, label) in self.ticks() {
            svg.line((px(v), y), (px(v), y + 5.0), "black", 0.8, "");
            svg.text(
                px(v),
                y + font + 7.0,
                &label,
                font,
                crate::Anchor::Middle,
                "",
            );
        }
    }

    /// The plot box `(left, top, width, height)` (pixels) outlined, with
    /// `x`'s ticks below it and `y`'s left of it: the frame every figure
    /// draws the same way.
    pub fn draw_box(
        svg: &mut crate::Svg,
        (left, top, width, height): (f64, f64, f64, f64),
        (x, px): (&Axis, &dyn Fn(f64) -> f64),
        (y, py): (&Axis, &dyn Fn(f64) -> f64),
        font: f64,
    ) {
        svg.rect(
            left,
            top,
            width,
            height,
            "none",
            r#"stroke="black" stroke-width="1""#,
        );
        x.draw_below(svg, px, top + height, font);
        y.draw_left(svg, py, left, font);
    }

    /// Ticks and their labels left of a vertical axis at `x` (pixels).
    pub fn draw_left(&self, svg: &mut crate::Svg, py: &dyn Fn(f64) -> f64, x: f64, font: f64) {
        for (v, label) in self.ticks() {
            svg.line((x - 5.0, py(v)), (x, py(v)), "black", 0.8, "");
            svg.text(x - 8.0, py(v) + 4.0, &label, font, crate::Anchor::End, "");
        }
    }
}

/// Shortest readable form of a tick value.
fn short(v: f64) -> String {
    if v == 0.0 {
        return "0".into();
    }
    let s = format!("{:.6}", v);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s.len() > 8 {
        format!("{v:.2e}")
    } else {
        s.to_string()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_ticks_are_round() {
        let t = Axis::linear(0.0, 1.0, "x").ticks();
        assert_eq!(
            t.iter().map(|t| t.1.as_str()).collect::<Vec<_>>(),
            ["0", "0.2", "0.4", "0.6", "0.8", "1"]
        );
        assert!(Axis::linear(0.005, 0.995, "x").ticks().len() >= 4);
    }

    #[test]
    fn log_ticks_are_decades() {
        let t = Axis::log(0.5e-3, 2.0, "t").ticks();
        assert_eq!(
            t.iter().map(|t| t.1.as_str()).collect::<Vec<_>>(),
            ["1e-3", "1e-2", "1e-1", "1e0"]
        );
        assert!((Axis::log(1.0, 100.0, "").fraction(10.0) - 0.5).abs() < 1e-12);
    }
}

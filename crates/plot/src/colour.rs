//! Colours and colour maps.

/// An sRGB colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Colour(pub u8, pub u8, pub u8);

impl Colour {
    /// White: zero on the diverging map.
    pub const WHITE: Colour = Colour(255, 255, 255);
    /// Light grey: missing values (NaN cells, unknown categories).
    pub const GREY: Colour = Colour(200, 200, 200);
    /// Red: the positive end of the diverging map (compression, when it
    /// shows strain). Named because every figure reuses it, so that a curve
    /// and the strain map it sits beside speak the same colours.
    pub const RED: Colour = Colour(178, 24, 43);
    /// Blue: the negative end of the diverging map (tension), reused by the
    /// figures for the same reason as [`Colour::RED`].
    pub const BLUE: Colour = Colour(33, 102, 172);
    /// Near-black: marks and lines that must read as "the data itself".
    pub const INK: Colour = Colour(20, 20, 20);

    /// `#rrggbb`.
    pub fn hex(self) -> String {
        format!("#{:02x}{:02x}{:02x}", self.0, self.1, self.2)
    }

    fn lerp(a: Colour, b: Colour, t: f64) -> Colour {
        let m = |x: u8, y: u8| (f64::from(x) + t * (f64::from(y) - f64::from(x))).round() as u8;
        Colour(m(a.0, b.0), m(a.1, b.1), m(a.2, b.2))
    }
}

/// Maps a number in `[min, max]` to a colour.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Colourmap {
    /// Blue (negative) - white (zero) - red (positive), symmetric about 0:
    /// tension blue, compression red when used for strain (the paper's).
    Diverging,
    /// Perceptually ordered dark blue - green - yellow (viridis-like).
    Sequential,
}

const VIRIDIS: [Colour; 6] = [
    Colour(68, 1, 84),
    Colour(65, 68, 135),
    Colour(42, 120, 142),
    Colour(34, 168, 132),
    Colour(122, 209, 81),
    Colour(253, 231, 37),
];

impl Colourmap {
    /// Colour of `v` on the scale `[min, max]` (clamped).
    pub fn colour(self, v: f64, min: f64, max: f64) -> Colour {
        if !v.is_finite() {
            return Colour::GREY;
        }
        match self {
            Colourmap::Diverging => {
                let m = min.abs().max(max.abs()).max(f64::MIN_POSITIVE);
                let t = (v / m).clamp(-1.0, 1.0);
                if t >= 0.0 {
                    Colour::lerp(Colour::WHITE, Colour::RED, t)
                } else {
                    Colour::lerp(Colour::WHITE, Colour::BLUE, -t)
                }
            }
            Colourmap::Sequential => {
                let t = if max > min {
                    ((v - min) / (max - min)).clamp(0.0, 1.0)
                } else {
                    0.5
                };
                let s = t * (VIRIDIS.len() - 1) as f64;
                let i = (s.floor() as usize).min(VIRIDIS.len() - 2);
                Colour::lerp(VIRIDIS[i], VIRIDIS[i + 1], s - i as f64)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diverging_is_white_at_zero_and_signed() {
        let m = Colourmap::Diverging;
        assert_eq!(m.colour(0.0, -1.0, 1.0), Colour::WHITE);
        let red = m.colour(1.0, -1.0, 1.0);
        let blue = m.colour(-1.0, -1.0, 1.0);
        assert!(red.0 > red.2 && blue.2 > blue.0);
        assert_eq!(m.colour(f64::NAN, 0.0, 1.0), Colour::GREY);
    }
}

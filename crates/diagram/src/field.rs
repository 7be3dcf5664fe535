//! The exact strain field of a recorded run.

use impact_model::Rod;
use impact_wave::{Direction, Recording};

/// Why a field cannot be built from a recording.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum FieldError {
    /// The run did not record its fronts.
    NoFronts,
}

/// Step function of one component in one layer: value after each birth.
#[derive(Debug, Clone, Default)]
struct Steps {
    /// Birth times, increasing.
    times: Vec<f64>,
    /// Value for characteristics born at or after `times[k]` (and before the
    /// next); `initial` before the first.
    values: Vec<f64>,
    initial: f64,
}

impl Steps {
    fn at(&self, tau: f64) -> f64 {
        // characteristics born exactly at a front's birth carry its jump
        let k = self.times.partition_point(|&t| t <= tau);
        if k == 0 {
            self.initial
        } else {
            self.values[k - 1]
        }
    }
}

/// One layer's geometry and its two components.
#[derive(Debug, Clone)]
struct LayerField {
    bottom: f64,
    top: f64,
    speed: f64,
    transit: f64,
    up: Steps,
    down: Steps,
}

/// The exact strain field `eps(t, y)` of a run, from its recorded fronts.
#[derive(Debug, Clone)]
pub struct ExactField {
    layers: Vec<LayerField>,
}

/// A convex polygon in `(t, y)` on which the strain is `strain`.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    pub layer: usize,
    pub strain: f64,
    pub corners: Vec<(f64, f64)>,
}

impl ExactField {
    /// Builds the field from a recording made with `Record { fronts: true }`.
    pub fn new(rod: &Rod, recording: &Recording) -> Result<Self, FieldError> {
        if recording.fronts.is_empty() {
            return Err(FieldError::NoFronts);
        }
        let vb = rod.impact_speed();
        let mut layers: Vec<LayerField> = rod
            .layers()
            .iter()
            .map(|l| LayerField {
                bottom: l.bottom,
                top: l.top,
                speed: l.wave_speed,
                transit: l.transit_time,
                // at rest relative to the rod moving at -v_b: a = v_b/2c, b = -v_b/2c
                up: Steps {
                    initial: vb / (2.0 * l.wave_speed),
                    ..Steps::default()
                },
                down: Steps {
                    initial: -vb / (2.0 * l.wave_speed),
                    ..Steps::default()
                },
            })
            .collect();
        let mut fronts: Vec<_> = recording.fronts.iter().collect();
        fronts.sort_by(|a, b| a.born.total_cmp(&b.born).then(a.id.cmp(&b.id)));
        for f in fronts {
            let steps = match f.direction {
                Direction::Up => &mut layers[f.layer].up,
                Direction::Down => &mut layers[f.layer].down,
            };
            let before = steps.values.last().copied().unwrap_or(steps.initial);
            // the value behind a front is the value ahead plus its jump
            steps.times.push(f.born);
            steps.values.push(before + f.jump);
        }
        Ok(Self { layers })
    }

    fn layer_at(&self, y: f64) -> &LayerField {
        self.layers
            .iter()
            .find(|l| y < l.top)
            .unwrap_or(&self.layers[self.layers.len() - 1])
    }

    /// Strain at height `y` (undeformed) and time `t >= 0`.
    pub fn strain(&self, t: f64, y: f64) -> f64 {
        let l = self.layer_at(y);
        let u = t - (y - l.bottom) / l.speed;
        let d = t - (l.top - y) / l.speed;
        l.up.at(u) + l.down.at(d)
    }

    /// Velocity at `(t, y)`: `c (b - a)`.
    pub fn velocity(&self, t: f64, y: f64) -> f64 {
        let l = self.layer_at(y);
        let u = t - (y - l.bottom) / l.speed;
        let d = t - (l.top - y) / l.speed;
        l.speed * (l.down.at(d) - l.up.at(u))
    }

    /// Number of polygons [`ExactField::cells`] would make over `[0, t_end]`,
    /// counted only up to `cap + 1` (the corner has tens of millions).
    pub fn cell_count(&self, t_end: f64, cap: usize) -> usize {
        let mut n = 0;
        for l in &self.layers {
            n += Self::layer_cells(l, t_end, cap.saturating_sub(n) + 1, &mut |_| {});
            if n > cap {
                break;
            }
        }
        n
    }

    /// The exact field over `[0, t_end]` as constant-strain polygons.
    pub fn cells(&self, t_end: f64) -> Vec<Cell> {
        let mut out = Vec::new();
        for (i, l) in self.layers.iter().enumerate() {
            Self::layer_cells(l, t_end, usize::MAX, &mut |mut c| {
                c.layer = i;
                out.push(c)
            });
        }
        out
    }

    /// Cells of one layer: rectangles `[u_k, u_k+1) x [d_m, d_m+1)` of the
    /// characteristic birth times, clipped to the layer (`|d - u| <= T`) and
    /// to `0 <= t <= t_end`, mapped to `t = (u + d + T)/2`,
    /// `y = y_b + c (d - u + T)/2`.
    fn layer_cells(l: &LayerField, t_end: f64, limit: usize, emit: &mut dyn FnMut(Cell)) -> usize {
        let big = t_end + 2.0 * l.transit + 1.0;
        let bounds = |s: &Steps| {
            let mut b = Vec::with_capacity(s.times.len() + 2);
            b.push(-big);
            b.extend_from_slice(&s.times);
            b.push(big);
            b
        };
        let (ub, db) = (bounds(&l.up), bounds(&l.down));
        let t = l.transit;
        let mut count = 0;
        for k in 0..ub.len() - 1 {
            let (u0, u1) = (ub[k], ub[k + 1]);
            // a cell needs u <= t_end (take d = u - T in t = (u + d + T)/2 <= t_end)
            if u0 >= t_end || u1 <= -t {
                continue;
            }
            let a = if k == 0 {
                l.up.initial
            } else {
                l.up.values[k - 1]
            };
            // down intervals meeting the band |d - u| <= T for u in [u0, u1]
            let first = db.partition_point(|&d| d <= u0 - t).saturating_sub(1);
            for m in first..db.len() - 1 {
                let (d0, d1) = (db[m], db[m + 1]);
                if d0 >= u1 + t {
                    break;
                }
                let mut poly = vec![(u0, d0), (u1, d0), (u1, d1), (u0, d1)];
                // band and time window as half-planes a*u + b*d <= c
                for (hu, hd, c) in [
                    (-1.0, 1.0, t),
                    (1.0, -1.0, t),
                    (-1.0, -1.0, t),
                    (1.0, 1.0, 2.0 * t_end - t),
                ] {
                    poly = clip(&poly, hu, hd, c);
                    if poly.len() < 3 {
                        break;
                    }
                }
                if poly.len() < 3 {
                    continue;
                }
                count += 1;
                if count >= limit {
                    return count;
                }
                let b = if m == 0 {
                    l.down.initial
                } else {
                    l.down.values[m - 1]
                };
                let corners = poly
                    .iter()
                    .map(|&(u, d)| (0.5 * (u + d + t), l.bottom + l.speed * 0.5 * (d - u + t)))
                    .collect();
                emit(Cell {
                    layer: 0,
                    strain: a + b,
                    corners,
                });
            }
        }
        count
    }
}

/// Sutherland-Hodgman clip of a convex polygon to `hu u + hd d <= c`.
fn clip(poly: &[(f64, f64)], hu: f64, hd: f64, c: f64) -> Vec<(f64, f64)> {
    let inside = |p: (f64, f64)| hu * p.0 + hd * p.1 <= c + 1e-12 * c.abs().max(1.0);
    let mut out = Vec::with_capacity(poly.len() + 2);
    for i in 0..poly.len() {
        let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
        let (pi, qi) = (inside(p), inside(q));
        if pi {
            out.push(p);
        }
        if pi != qi {
            let fp = hu * p.0 + hd * p.1 - c;
            let fq = hu * q.0 + hd * q.1 - c;
            let s = fp / (fp - fq);
            out.push((p.0 + s * (q.0 - p.0), p.1 + s * (q.1 - p.1)));
        }
    }
    // drop degenerate slivers
    out.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-15 && (a.1 - b.1).abs() < 1e-15);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression: windows shorter than a layer's transit time lost the
    /// cells behind every up front born in the window's second half.
    #[test]
    fn cells_tile_the_whole_window_even_when_it_is_shorter_than_a_transit() {
        use impact_wave::{Record, WaveConfig, WaveEngine};
        let rod = impact_model::Bilayer::new(0.3, 0.01)
            .unwrap()
            .scene()
            .validate()
            .unwrap();
        let mut e = WaveEngine::new(
            &rod,
            WaveConfig {
                record: Record {
                    wall: false,
                    fronts: true,
                },
                ..WaveConfig::default()
            },
        )
        .unwrap();
        e.run().unwrap();
        let field = ExactField::new(&rod, e.recording()).unwrap();
        let t2 = rod.layers()[1].transit_time;
        for t_end in [0.3 * t2, 0.9 * t2, 2.5 * t2] {
            let area: f64 = field
                .cells(t_end)
                .iter()
                .map(|c| {
                    let p = &c.corners;
                    0.5 * (0..p.len())
                        .map(|i| p[i].0 * p[(i + 1) % p.len()].1 - p[(i + 1) % p.len()].0 * p[i].1)
                        .sum::<f64>()
                        .abs()
                })
                .sum();
            let expected = t_end * rod.total_length();
            assert!(
                (area - expected).abs() < 1e-9 * expected,
                "t_end = {t_end}: area {area} vs {expected}"
            );
        }
    }

    #[test]
    fn clipping_a_square_by_a_diagonal_keeps_a_triangle() {
        let sq = vec![(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)];
        let tri = clip(&sq, 1.0, 1.0, 1.0);
        assert_eq!(tri.len(), 3);
    }
}

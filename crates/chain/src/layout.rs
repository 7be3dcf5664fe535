//! Mapping a rod onto `N` masses, in the scene's units.

use crate::error::ChainError;
use impact_model::Rod;

/// The discrete chain: element `j` is the spring (and dashpot) below mass `j`;
/// element 0 joins mass 0 to the wall and acts only in compression.
#[derive(Debug, Clone, PartialEq)]
pub struct ChainLayout {
    /// Masses per layer, bottom first.
    pub per_layer: Vec<usize>,
    /// Layer of each element (and of the mass on top of it).
    pub layer_of: Vec<usize>,
    /// Rest length of each element.
    pub rest_length: Vec<f64>,
    /// Stiffness `E / l0` of each element.
    pub stiffness: Vec<f64>,
    /// Dashpot constant `eta / l0 = tau E / l0` of each element.
    pub viscosity: Vec<f64>,
    /// Mass on top of each element: `rho l0`.
    pub mass: Vec<f64>,
    /// Height of each mass in the undeformed rod (top of its element).
    pub height: Vec<f64>,
}

impl ChainLayout {
    /// Spreads `n` masses over the layers in proportion to their lengths (the
    /// paper's equal `l0` for one length scale), with at least one per layer;
    /// rounding leftovers go to the layers with the largest remainders.
    pub fn new(rod: &Rod, n: usize) -> Result<Self, ChainError> {
        let layers = rod.layers();
        if n < layers.len() {
            return Err(ChainError::TooFewMasses {
                masses: n,
                layers: layers.len(),
            });
        }
        let total = rod.total_length();
        let ideal: Vec<f64> = layers.iter().map(|l| n as f64 * l.length / total).collect();
        let mut per_layer: Vec<usize> = ideal.iter().map(|v| (v.floor() as usize).max(1)).collect();
        while per_layer.iter().sum::<usize>() > n {
            // take from the layer that is most over its share (and has spare)
            let i = (0..per_layer.len())
                .filter(|&i| per_layer[i] > 1)
                .max_by(|&a, &b| {
                    (per_layer[a] as f64 - ideal[a]).total_cmp(&(per_layer[b] as f64 - ideal[b]))
                })
                .unwrap_or(0);
            per_layer[i] -= 1;
        }
        while per_layer.iter().sum::<usize>() < n {
            let i = (0..per_layer.len())
                .max_by(|&a, &b| {
                    (ideal[a] - per_layer[a] as f64).total_cmp(&(ideal[b] - per_layer[b] as f64))
                })
                .unwrap_or(0);
            per_layer[i] += 1;
        }
        let mut layout = ChainLayout {
            per_layer: per_layer.clone(),
            layer_of: Vec::with_capacity(n),
            rest_length: Vec::with_capacity(n),
            stiffness: Vec::with_capacity(n),
            viscosity: Vec::with_capacity(n),
            mass: Vec::with_capacity(n),
            height: Vec::with_capacity(n),
        };
        for (i, (l, &count)) in layers.iter().zip(&per_layer).enumerate() {
            let l0 = l.length / count as f64;
            let tau = rod.relaxation_time(i);
            for k in 0..count {
                layout.layer_of.push(i);
                layout.rest_length.push(l0);
                layout.stiffness.push(l.modulus / l0);
                layout.viscosity.push(tau * l.modulus / l0);
                layout.mass.push(l.density * l0);
                layout.height.push(l.bottom + (k + 1) as f64 * l0);
            }
        }
        Ok(layout)
    }

    /// Number of masses `N`.
    pub fn len(&self) -> usize {
        self.mass.len()
    }

    /// Whether there are no masses (never, for a layout built by [`ChainLayout::new`]).
    pub fn is_empty(&self) -> bool {
        self.mass.is_empty()
    }

    /// Whether any element has a dashpot (a viscous layer).
    pub fn is_viscous(&self) -> bool {
        self.viscosity.iter().any(|&c| c > 0.0)
    }

    /// The paper's time step `min(2 pi sqrt(m / k)) / 100` over elements (for
    /// each element `sqrt(m/k) = l0 / c`).
    pub fn paper_time_step(&self) -> f64 {
        self.mass
            .iter()
            .zip(&self.stiffness)
            .map(|(m, k)| 2.0 * std::f64::consts::PI * (m / k).sqrt() / 100.0)
            .fold(f64::INFINITY, f64::min)
    }

    /// `sum_j M_j^2 / k_j` over the springs between masses, with `M_j` the
    /// mass above spring `j`: bounds how far mass 0 can sit below the centre
    /// of mass for a given internal energy.
    pub fn compliance_moment(&self) -> f64 {
        let mut above = 0.0;
        let mut sum = 0.0;
        for j in (1..self.len()).rev() {
            above += self.mass[j];
            sum += above * above / self.stiffness[j];
        }
        sum
    }

    /// Layers with fewer than 50 masses (the paper's Appendix A minimum for
    /// ~1% accuracy).
    pub fn thin_layers(&self) -> Vec<(usize, usize)> {
        self.per_layer
            .iter()
            .enumerate()
            .filter(|(_, c)| **c < 50)
            .map(|(i, c)| (i, *c))
            .collect()
    }
}

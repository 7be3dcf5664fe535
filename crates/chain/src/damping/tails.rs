//! The fix-ups of the blocked sweeps: how the values just outside a block
//! carry into it (`Tail`), and the same for all blocks side by side in the
//! lanes (`LaneTails`).

use super::quad::{LANES, Quad};

/// How the homogeneous solutions of a sweep's recurrence carry the two
/// values just outside a block into it.
///
/// A block's sweep is started from zero; by linearity the true values in
/// it are the local ones plus `p1 h1 + p2 h2`, where `p1`, `p2` are the
/// true values at the two masses just outside the block (on the side the
/// sweep comes from) and `h1`, `h2` the recurrence's solutions with no
/// right-hand side started from `(1, 0)` and `(0, 1)` there. They depend on
/// the factorisation only, and decay geometrically into the block (`P` is
/// diagonally dominant; inside an elastic layer `L` is the identity and
/// they vanish at once), so they are stored only while they matter, plus
/// their exact values at the block's far edge, which carry the true values
/// on to the next block.
#[derive(Debug, Clone, Default)]
pub(super) struct Tail {
    /// `h1`, `h2` at the block's masses nearest the edge they start from,
    /// in mass order (both of one length).
    pub(super) near: [Vec<f64>; 2],
    /// `h1`, `h2` at the block's two masses farthest from that edge, in the
    /// order the sweep carries them (nearest the next block first).
    pub(super) far: [[f64; 2]; 2],
}

impl Tail {
    /// The true values at the block's far edge from the local ones `ends`
    /// and the true values `p` outside its near edge.
    pub(super) fn carry(&self, ends: [f64; 2], p: [f64; 2]) -> [f64; 2] {
        let [h1, h2] = self.far;
        [
            ends[0] + (p[0] * h1[0] + p[1] * h2[0]),
            ends[1] + (p[0] * h1[1] + p[1] * h2[1]),
        ]
    }

    /// Adds `p1 h1 + p2 h2` to `x` (the block's masses nearest the edge,
    /// in mass order): three equal-length slices, no index arithmetic, so
    /// the loop compiles to packed `mulpd`/`addpd`.
    pub(super) fn fix(&self, x: &mut [f64], p: [f64; 2]) {
        let [h1, h2] = &self.near;
        for ((x, a), b) in x.iter_mut().zip(h1).zip(h2) {
            *x += p[0] * a + p[1] * b;
        }
    }
}

/// A sweep's tails with their near parts side by side, block `k` in lane
/// `k` (zero where a block has no tail or its tail has ended): one pass
/// fixes every block up.
#[derive(Debug, Clone, Default)]
pub(super) struct LaneTail {
    pub(super) near: [Vec<Quad>; 2],
}

impl LaneTail {
    /// The tails `tails[k]` of the blocks `first + k`, their near parts
    /// starting at the blocks' first steps (`top`: ending at their last).
    fn new(tails: &[Tail], first: usize, top: bool) -> Self {
        let longest = tails.iter().map(|t| t.near[0].len()).max().unwrap_or(0);
        let mut near = [vec![Quad::ZERO; longest], vec![Quad::ZERO; longest]];
        for (k, tail) in tails.iter().enumerate() {
            let len = tail.near[0].len();
            let from = if top { longest - len } else { 0 };
            for (lanes, h) in near.iter_mut().zip(&tail.near) {
                for (q, h) in lanes[from..].iter_mut().zip(h) {
                    q.0[first + k] = *h;
                }
            }
        }
        Self { near }
    }

    /// Adds `p_k1 h1 + p_k2 h2` to the steps' `x` (as many steps as the
    /// near parts are long), `p[k]` the true values outside block `k`, and
    /// calls `then` on each step so fixed (what was computed from `x` can
    /// be computed again in the same pass).
    pub(super) fn fix<S>(
        &self,
        steps: &mut [S],
        x: impl Fn(&mut S) -> &mut Quad,
        p: [[f64; 2]; LANES],
        mut then: impl FnMut(&mut S),
    ) {
        let p1 = Quad(std::array::from_fn(|k| p[k][0]));
        let p2 = Quad(std::array::from_fn(|k| p[k][1]));
        let [h1, h2] = &self.near;
        for ((step, &h1), &h2) in steps.iter_mut().zip(h1).zip(h2) {
            let x = x(step);
            *x = *x + (p1 * h1 + p2 * h2);
            then(step);
        }
    }
}

/// Both sweeps' [`LaneTail`]s.
#[derive(Debug, Clone, Default)]
pub(super) struct LaneTails {
    /// The forward sweep's, blocks `1..LANES`.
    pub(super) down: LaneTail,
    /// The backward sweep's, blocks `0..LANES - 1`, ending at their tops.
    pub(super) up: LaneTail,
}

impl LaneTails {
    pub(super) fn new(down: &[Tail], up: &[Tail]) -> Self {
        Self {
            down: LaneTail::new(down, 1, false),
            up: LaneTail::new(up, 0, true),
        }
    }
}

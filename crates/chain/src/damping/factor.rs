//! The blocked `L D L^T` sweeps of the dashpot step's pentadiagonal
//! solve: the factor of `P = A M^-1 A`, its sweeps run as `LANES`
//! interleaved blocks, and the homogeneous solutions (`Tail`) that fix the
//! blocks up exactly.

use std::borrow::Cow;

use super::GAMMA;
use super::quad::{LANES, Quad};
use super::tails::{LaneTails, Tail};

/// A chain shorter than `LANES * MIN_LANE` masses sweeps in one piece: its
/// fix-ups would cost about what the blocks save.
const MIN_LANE: usize = 64;

/// A fix-up term is dropped where it is below this fraction of the value it
/// corrects: far below rounding, so the blocked sweeps give the one-piece
/// sweep's result to rounding.
const NEGLIGIBLE: f64 = 1e-20;

/// Homogeneous solutions below this are flushed to zero: they only decay
/// further, and subnormal numbers are slow.
const FLUSH: f64 = 1e-200;

/// `L D L^T` factors of `P = A M^-1 A`, `A = M - g h D` for one wall
/// dashpot constant, stored for streaming sweeps.
///
/// The sweeps of a solve are latency-bound recurrences. A long chain is
/// cut into [`LANES`] blocks of `lane` masses (the last takes the rest),
/// each block swept from zero, all in one loop so that their recurrences
/// overlap; the blocks' [`Tail`]s then add, block after block, what the
/// masses before them contribute. That is exact algebra, not an iteration:
/// the result is the one-piece sweep's to rounding (tested against
/// [`Factor::solve`]).
#[derive(Debug, Clone)]
pub(crate) struct Factor {
    /// `L[i][i-1]`, `L[i][i-2]`, two zeros past the end: the backward
    /// sweep reads `L[j+1][j]`, `L[j+2][j]` as `l1[j+1]`, `l2[j+2]`.
    l1: Vec<f64>,
    l2: Vec<f64>,
    /// `1 / D[i]`.
    inv_d: Vec<f64>,
    /// Masses per block, 0 for a one-piece sweep (at least 2 otherwise).
    lane: usize,
    /// Step `i` of the forward sweep in the blocks: `[l1, l2]` of masses
    /// `k lane + i`, `k < LANES`.
    fwd: Vec<[Quad; 2]>,
    /// Step `i` of the backward sweep: `1 / d` of masses `k lane + i`. Its
    /// other coefficients, `l1[j + 1]` and `l2[j + 2]`, are the forward
    /// sweep's at steps `i + 1` and `i + 2`: at a block's last two steps
    /// they are the next block's, but there they multiply the zeros the
    /// block's sweep starts from (the last block's top is a chain's top,
    /// or its last masses are swept apart, see `solve_into`), so none are
    /// stored twice.
    bwd: Vec<Quad>,
    /// For a tridiagonal matrix (`l2 = 0`), `l1` of masses `k lane + i`
    /// and `k lane + i - 1` multiplied, at step `i >= 1` (empty otherwise):
    /// the sweeps then go two masses a link (see [`Factor::solve_into`]).
    pairs: Vec<Quad>,
    /// Forward sweep: blocks `1..LANES`, from their bottoms up.
    down: Vec<Tail>,
    /// Backward sweep: blocks `0..LANES - 1`, from their tops down.
    up: Vec<Tail>,
    /// The same tails' near parts side by side in the lanes.
    lane_tails: LaneTails,
    /// `M A^-1 e_0` while not negligible: its dot product with `v` is the
    /// first stage's velocity of mass 0, `V1_0 = (A^-1 M v)_0`, which the
    /// wall impulse needs. It decays from mass 0 like the sweeps' tails.
    first_stage_0: Vec<f64>,
}

/// `P`'s factors for a run's two steady wall states, the wall dashpot off
/// and fully on (the same twice unless the run starts at the wall).
#[derive(Debug, Clone)]
pub(crate) struct WallFactors {
    pub(crate) free: Factor,
    with_wall: Factor,
    h: f64,
    lane: usize,
}

impl WallFactors {
    /// For masses `mass` and dashpot constants `c` (`c[0]` the wall's when
    /// in full contact) over a step `h`, blocks of `lane` masses.
    pub(crate) fn new(mass: &[f64], c: &[f64], h: f64, lane: usize) -> Self {
        Self {
            free: Factor::with_lane(mass, c, h, 0.0, lane),
            with_wall: Factor::with_lane(mass, c, h, c[0], lane),
            h,
            lane,
        }
    }

    /// The factor for a step whose wall dashpot acts as `wall`: a kept one
    /// in steady states; when a contact begins or ends within the step
    /// (`wall` a fraction of `c[0]`, rare) one factorised for the occasion.
    pub(crate) fn for_wall(&self, wall: f64, mass: &[f64], c: &[f64]) -> Cow<'_, Factor> {
        if wall == 0.0 {
            Cow::Borrowed(&self.free)
        } else if wall == c[0] {
            Cow::Borrowed(&self.with_wall)
        } else {
            Cow::Owned(Factor::with_lane(mass, c, self.h, wall, self.lane))
        }
    }
}

/// The block length for `n` masses: 0 (one piece) below `LANES * MIN_LANE`.
pub(crate) fn lane_length(n: usize) -> usize {
    if n >= LANES * MIN_LANE { n / LANES } else { 0 }
}

impl Factor {
    /// Factorises for dashpot constants `c` (element `j` below mass `j`),
    /// the wall element's replaced by `wall`, over a step `h`, cut into
    /// blocks of `lane` masses (0: one piece; otherwise `2 <= lane`,
    /// `LANES * lane <= n`).
    pub(crate) fn with_lane(mass: &[f64], c: &[f64], h: f64, wall: f64, lane: usize) -> Self {
        let n = mass.len();
        let gh = GAMMA * h;
        let below = |i: usize| if i == 0 { wall } else { c[i] };
        let above = |i: usize| if i + 1 < n { c[i + 1] } else { 0.0 };
        // A: diagonal and super-diagonal
        let a: Vec<f64> = (0..n)
            .map(|i| mass[i] + gh * (below(i) + above(i)))
            .collect();
        let b: Vec<f64> = (0..n).map(|i| -gh * above(i)).collect();
        // P = A M^-1 A: diagonal, first and second off-diagonals
        let p0: Vec<f64> = (0..n)
            .map(|i| {
                let left = if i > 0 {
                    b[i - 1] * b[i - 1] / mass[i - 1]
                } else {
                    0.0
                };
                let right = if i + 1 < n {
                    b[i] * b[i] / mass[i + 1]
                } else {
                    0.0
                };
                a[i] * a[i] / mass[i] + left + right
            })
            .collect();
        let p1: Vec<f64> = (0..n)
            .map(|i| {
                if i + 1 < n {
                    a[i] * b[i] / mass[i] + b[i] * a[i + 1] / mass[i + 1]
                } else {
                    0.0
                }
            })
            .collect();
        let p2: Vec<f64> = (0..n)
            .map(|i| {
                if i + 2 < n {
                    b[i] * b[i + 1] / mass[i + 1]
                } else {
                    0.0
                }
            })
            .collect();
        let mut f = Self::from_bands(&p0, &p1, &p2, lane);
        // A^-1 e_0 = P^-1 A M^-1 e_0, and A^-1 is symmetric
        let mut w = vec![0.0; n];
        w[0] = a[0] / mass[0];
        if n > 1 {
            w[1] = b[0] / mass[0];
        }
        f.solve(&mut w);
        let w: Vec<f64> = w.iter().zip(mass).map(|(w, m)| w * m).collect();
        let largest = w.iter().fold(0.0f64, |x, w| x.max(w.abs()));
        let keep = w
            .iter()
            .rposition(|w| w.abs() > NEGLIGIBLE * largest)
            .map_or(0, |i| i + 1);
        f.first_stage_0 = w[..keep].to_vec();
        f
    }

    /// The `L D L^T` factor of the symmetric pentadiagonal matrix of
    /// diagonal `p0` and off-diagonals `p1` (`p1[i]` at `(i, i + 1)`) and
    /// `p2` (`p2[i]` at `(i, i + 2)`), blocks of `lane` masses as in
    /// [`Factor::with_lane`]. A tridiagonal matrix is one with `p2 = 0`
    /// (the implicit chain's, `crate::implicit`).
    pub(crate) fn from_bands(p0: &[f64], p1: &[f64], p2: &[f64], lane: usize) -> Self {
        let n = p0.len();
        let (mut l1, mut l2, mut d) = (vec![0.0; n + 2], vec![0.0; n + 2], vec![0.0; n]);
        for i in 0..n {
            if i >= 2 {
                l2[i] = p2[i - 2] / d[i - 2];
            }
            if i >= 1 {
                let back = if i >= 2 {
                    l2[i] * l1[i - 1] * d[i - 2]
                } else {
                    0.0
                };
                l1[i] = (p1[i - 1] - back) / d[i - 1];
            }
            let d1 = if i >= 1 {
                l1[i] * l1[i] * d[i - 1]
            } else {
                0.0
            };
            let d2 = if i >= 2 {
                l2[i] * l2[i] * d[i - 2]
            } else {
                0.0
            };
            d[i] = p0[i] - d1 - d2;
        }
        let mut f = Self {
            inv_d: d.iter().map(|d| 1.0 / d).collect(),
            l1,
            l2,
            lane,
            fwd: vec![],
            bwd: vec![],
            pairs: vec![],
            down: vec![],
            up: vec![],
            lane_tails: LaneTails::default(),
            first_stage_0: vec![],
        };
        if lane > 0 {
            let at = |x: &[f64], shift: usize, i: usize| -> Quad {
                Quad(std::array::from_fn(|k| x[k * lane + i + shift]))
            };
            f.fwd = (0..lane)
                .map(|i| [at(&f.l1, 0, i), at(&f.l2, 0, i)])
                .collect();
            f.bwd = (0..lane).map(|i| at(&f.inv_d, 0, i)).collect();
            if p2.iter().all(|&p| p == 0.0) {
                f.pairs = (0..lane)
                    .map(|i| match i {
                        0 => Quad::ZERO,
                        _ => at(&f.l1, 0, i) * at(&f.l1, 0, i - 1),
                    })
                    .collect();
            }
            f.down = (1..LANES).map(|k| f.down_tail(k)).collect();
            f.up = (0..LANES - 1).map(|k| f.up_tail(k)).collect();
            f.lane_tails = LaneTails::new(&f.down, &f.up);
        }
        f
    }

    /// Masses `start..end` of block `k`.
    fn block(&self, k: usize) -> (usize, usize) {
        let end = if k + 1 == LANES {
            self.inv_d.len()
        } else {
            (k + 1) * self.lane
        };
        (k * self.lane, end)
    }

    /// The forward sweep's tail of block `k >= 1`: `y_i = -l1_i y_{i-1} -
    /// l2_i y_{i-2}` from `(y_{s-1}, y_{s-2}) = (1, 0)` and `(0, 1)`. The
    /// true `y_{s-1}`, `y_{s-2}` it multiplies are of the size of `d_{s-1}`,
    /// `d_{s-2}` (`y = D L^T x`), and `y_i` of `d_i`, which scales the cut.
    fn down_tail(&self, k: usize) -> Tail {
        let (start, end) = self.block(k);
        let mut tail = Tail::default();
        let mut keep = 0;
        for (q, (near, far)) in tail.near.iter_mut().zip(&mut tail.far).enumerate() {
            let scale = 1.0 / self.inv_d[start - 1 - q];
            let (mut y1, mut y2) = if q == 0 { (1.0, 0.0) } else { (0.0, 1.0) };
            for i in start..end {
                let mut y = (0.0 - self.l2[i] * y2) - self.l1[i] * y1;
                if y.abs() < FLUSH {
                    y = 0.0;
                }
                near.push(y);
                if (y * scale * self.inv_d[i]).abs() > NEGLIGIBLE {
                    keep = keep.max(near.len());
                }
                y2 = y1;
                y1 = y;
            }
            *far = [y1, y2];
        }
        for near in &mut tail.near {
            near.truncate(keep);
        }
        tail
    }

    /// The backward sweep's tail of block `k <= LANES - 2`: `z_j = -l1_{j+1}
    /// z_{j+1} - l2_{j+2} z_{j+2}` from `(z_e, z_{e+1}) = (1, 0)` and
    /// `(0, 1)`; `z` are velocities, all of one size.
    fn up_tail(&self, k: usize) -> Tail {
        let (start, end) = self.block(k);
        let mut tail = Tail::default();
        let mut keep = 0;
        for (q, (near, far)) in tail.near.iter_mut().zip(&mut tail.far).enumerate() {
            let (mut z1, mut z2) = if q == 0 { (1.0, 0.0) } else { (0.0, 1.0) };
            for j in (start..end).rev() {
                let mut z = (0.0 - self.l2[j + 2] * z2) - self.l1[j + 1] * z1;
                if z.abs() < FLUSH {
                    z = 0.0;
                }
                near.push(z);
                if z.abs() > NEGLIGIBLE {
                    keep = keep.max(near.len());
                }
                z2 = z1;
                z1 = z;
            }
            *far = [z1, z2];
        }
        for near in &mut tail.near {
            near.truncate(keep);
            near.reverse();
        }
        tail
    }

    /// Solves `P x = r` in place, one mass at a time (set-up, and the
    /// reference the blocked sweeps are tested against).
    pub(crate) fn solve(&self, x: &mut [f64]) {
        let n = x.len();
        let (mut y1, mut y2) = (0.0, 0.0);
        for ((x, l1), l2) in x.iter_mut().zip(&self.l1).zip(&self.l2) {
            let y = (*x - l2 * y2) - l1 * y1;
            *x = y;
            y2 = y1;
            y1 = y;
        }
        let (u1, u2) = (&self.l1[1..n + 1], &self.l2[2..n + 2]);
        let (mut x1, mut x2) = (0.0, 0.0);
        for (((x, d), u1), u2) in x.iter_mut().zip(&self.inv_d).zip(u1).zip(u2).rev() {
            let z = (*x * d - u2 * x2) - u1 * x1;
            *x = z;
            x2 = x1;
            x1 = z;
        }
    }

    /// Solves `P x = r`, `t` (`lane` long) the sweeps' scratch; `r` is
    /// overwritten.
    ///
    /// The blocks' recurrences run in the lanes of [`Quad`]s: the forward
    /// sweep gathers `r` from the blocks into `t`, the backward sweep
    /// scatters its result into `x`, and in between every operation is
    /// elementwise on `LANES` numbers with the steps' coefficients (`fwd`,
    /// `bwd`), which the compiler packs into `mulpd`/`subpd` (two lanes per
    /// SSE2 register) and the core overlaps (independent recurrences). The
    /// chain's long segments do not come here: the viscous kernel runs
    /// these sweeps in its own passes, its state in the lanes
    /// (`crate::viscous::blocked`); this is their reference in the chain's
    /// arrays, for any segment and any block length.
    pub(crate) fn solve_into(&self, r: &mut [f64], t: &mut [Quad], x: &mut [f64]) {
        if self.lane == 0 {
            x.copy_from_slice(r);
            self.solve(x);
            return;
        }
        let (n, s) = (r.len(), self.lane);
        let whole = LANES * s;
        let (t, fwd, bwd) = (&mut t[..s], &self.fwd[..s], &self.bwd[..s]);
        let (l1, l2, inv_d) = (&self.l1, &self.l2, &self.inv_d);
        // forward, the blocks side by side
        let mut y1 = [0.0; LANES];
        let mut y2 = [0.0; LANES];
        if !self.pairs.is_empty() {
            [y1, y2] = self.forward_in_pairs(r, t);
        } else {
            let rs = lanes(r, s);
            for (i, (t, [a, b])) in t.iter_mut().zip(fwd).enumerate() {
                let (a, b) = (a.0, b.0);
                let y: [f64; LANES] =
                    std::array::from_fn(|k| (rs[k][i] - b[k] * y2[k]) - a[k] * y1[k]);
                *t = Quad(y);
                y2 = y1;
                y1 = y;
            }
        }
        // the last block's rest, in place in `r`
        let (mut a, mut b) = (y1[LANES - 1], y2[LANES - 1]);
        for i in whole..n {
            let y = (r[i] - l2[i] * b) - l1[i] * a;
            r[i] = y;
            b = a;
            a = y;
        }
        self.fix_forward_blocks(t, r, [y1[0], y2[0]]);
        // backward: the last block's rest from the top, then the blocks
        let (mut a, mut b) = (0.0, 0.0);
        for j in (whole..n).rev() {
            let z = (r[j] * inv_d[j] - l2[j + 2] * b) - l1[j + 1] * a;
            x[j] = z;
            b = a;
            a = z;
        }
        let mut z1 = [0.0; LANES];
        let mut z2 = [0.0; LANES];
        z1[LANES - 1] = a;
        z2[LANES - 1] = b;
        if !self.pairs.is_empty() {
            self.backward_in_pairs(t, z1, x);
        } else {
            let mut xs = lanes_mut(x, s);
            for (i, (y, d)) in t.iter().zip(bwd).enumerate().rev() {
                // the last block's top steps take the rest's coefficients
                let upper = |q: usize| -> [f64; LANES] {
                    if i + q < s {
                        fwd[i + q][q - 1].0
                    } else {
                        std::array::from_fn(|k| [l1, l2][q - 1][k * s + i + q])
                    }
                };
                let (y, d, u1, u2) = (y.0, d.0, upper(1), upper(2));
                let z: [f64; LANES] =
                    std::array::from_fn(|k| (y[k] * d[k] - u2[k] * z2[k]) - u1[k] * z1[k]);
                for (x, z) in xs.iter_mut().zip(z) {
                    x[i] = z;
                }
                z2 = z1;
                z1 = z;
            }
        }
        self.fix_backward_blocks(x);
    }

    /// The forward sweep's fix-ups, block after block: `t` holds the
    /// blocks' local sweeps (each from zero), `rest` the last block's
    /// masses past `LANES lane` (in the chain's indices), `p` the first
    /// block's last two values.
    fn fix_forward_blocks(&self, t: &mut [Quad], rest: &mut [f64], mut p: [f64; 2]) {
        let s = self.lane;
        for (k, tail) in (1..LANES).zip(&self.down) {
            let (start, end) = self.block(k);
            let ends = {
                let mut at = |j: usize| *slot(t, rest, s, j);
                tail.carry([at(end - 1), at(end - 2)], p)
            };
            for (i, (h1, h2)) in tail.near[0].iter().zip(&tail.near[1]).enumerate() {
                *slot(t, rest, s, start + i) += p[0] * h1 + p[1] * h2;
            }
            *slot(t, rest, s, end - 1) = ends[0];
            *slot(t, rest, s, end - 2) = ends[1];
            p = ends;
        }
    }

    /// The backward sweep's fix-ups, block after block from the top: `x`
    /// holds the blocks' local sweeps (each from zero at its top, the last
    /// from the true values above it).
    fn fix_backward_blocks(&self, x: &mut [f64]) {
        let top = (LANES - 1) * self.lane;
        let mut q = [x[top], x[top + 1]];
        for (k, tail) in (0..LANES - 1).zip(&self.up).rev() {
            let (start, end) = self.block(k);
            let ends = tail.carry([x[start], x[start + 1]], q);
            let near = tail.near[0].len();
            tail.fix(&mut x[end - near..end], q);
            [x[start], x[start + 1]] = ends;
            q = ends;
        }
    }

    /// The blocks' forward sweeps of a tridiagonal factor, `y_i = r_i -
    /// l_i y_{i-1}`, two masses a link of the recurrence:
    /// `y_{i+1} = (r_{i+1} - l_{i+1} r_i) + (l_{i+1} l_i) y_{i-1}`. A link
    /// costs a multiply and an addition on the critical path whether it
    /// advances one mass or two, and four lanes of one mass a link were
    /// bound by that latency: two a link made the implicit chain's step
    /// 19 % faster (`cargo bench -p impact-chain --bench chain`). The same
    /// algebra, rounded differently from the one-piece sweep (tested
    /// against Gaussian elimination). Returns the last two values,
    /// `[y_{s-1}, y_{s-2}]`.
    fn forward_in_pairs(&self, r: &[f64], t: &mut [Quad]) -> [[f64; LANES]; 2] {
        let s = self.lane;
        let (fwd, pairs) = (&self.fwd[..s], &self.pairs[..s]);
        let rs = lanes(r, s);
        let (mut y1, mut y2) = ([0.0; LANES], [0.0; LANES]);
        let mut i = 0;
        while i + 1 < s {
            let (l0, l1, p) = (fwd[i][0].0, fwd[i + 1][0].0, pairs[i + 1].0);
            let r0: [f64; LANES] = std::array::from_fn(|k| rs[k][i]);
            let r1: [f64; LANES] = std::array::from_fn(|k| rs[k][i + 1]);
            let y0: [f64; LANES] = std::array::from_fn(|k| r0[k] - l0[k] * y1[k]);
            let y: [f64; LANES] = std::array::from_fn(|k| (r1[k] - l1[k] * r0[k]) + p[k] * y1[k]);
            t[i] = Quad(y0);
            t[i + 1] = Quad(y);
            (y2, y1) = (y0, y);
            i += 2;
        }
        if i < s {
            let l0 = fwd[i][0].0;
            let y: [f64; LANES] = std::array::from_fn(|k| rs[k][i] - l0[k] * y1[k]);
            t[i] = Quad(y);
            (y2, y1) = (y1, y);
        }
        [y1, y2]
    }

    /// The blocks' backward sweeps of a tridiagonal factor, `z_j = y_j / d_j
    /// - l_{j+1} z_{j+1}`, two masses a link as [`Factor::forward_in_pairs`]
    /// goes, from `[z1, z2]` above each block's top (zero but in the last,
    /// which continues the sweep of the masses above the blocks); the
    /// results go to `x` block by block.
    fn backward_in_pairs(&self, t: &[Quad], z1: [f64; LANES], x: &mut [f64]) {
        let s = self.lane;
        let (fwd, bwd, pairs) = (&self.fwd[..s], &self.bwd[..s], &self.pairs[..s]);
        let mut xs = lanes_mut(x, s);
        // the top step's `l_{j+1}` is the next block's first (the last
        // block's, the rest's first): only the last lane's z1 is not zero
        let top = s - 1;
        let above: [f64; LANES] = std::array::from_fn(|k| self.l1[k * s + s]);
        let (y, d) = (t[top].0, bwd[top].0);
        let mut z1: [f64; LANES] = std::array::from_fn(|k| y[k] * d[k] - above[k] * z1[k]);
        for (x, z) in xs.iter_mut().zip(z1) {
            x[top] = z;
        }
        let mut j = top;
        while j >= 2 {
            // masses j - 1 and j - 2 from z_j
            let (hi, lo) = (j - 1, j - 2);
            let (u_hi, u_lo, p) = (fwd[j][0].0, fwd[hi][0].0, pairs[j].0);
            let (y_hi, d_hi, y_lo, d_lo) = (t[hi].0, bwd[hi].0, t[lo].0, bwd[lo].0);
            let w_hi: [f64; LANES] = std::array::from_fn(|k| y_hi[k] * d_hi[k]);
            let w_lo: [f64; LANES] = std::array::from_fn(|k| y_lo[k] * d_lo[k]);
            let z_hi: [f64; LANES] = std::array::from_fn(|k| w_hi[k] - u_hi[k] * z1[k]);
            let z_lo: [f64; LANES] =
                std::array::from_fn(|k| (w_lo[k] - u_lo[k] * w_hi[k]) + p[k] * z1[k]);
            for ((x, a), b) in xs.iter_mut().zip(z_hi).zip(z_lo) {
                x[hi] = a;
                x[lo] = b;
            }
            z1 = z_lo;
            j = lo;
        }
        if j == 1 {
            let (u, y, d) = (fwd[1][0].0, t[0].0, bwd[0].0);
            let z: [f64; LANES] = std::array::from_fn(|k| y[k] * d[k] - u[k] * z1[k]);
            for (x, z) in xs.iter_mut().zip(z) {
                x[0] = z;
            }
        }
    }

    /// The forward sweep's steps in the blocks' lanes: `[l1, l2]` of the
    /// masses `k lane + i` at step `i`.
    pub(crate) fn forward_steps(&self) -> &[[Quad; 2]] {
        &self.fwd
    }

    /// The backward sweep's steps in the blocks' lanes: `1 / d` of the
    /// masses `k lane + i` at step `i` (its `l1[j + 1]`, `l2[j + 2]` are
    /// the forward steps' `i + 1` and `i + 2`, zero past a block's top).
    pub(crate) fn backward_steps(&self) -> &[Quad] {
        &self.bwd
    }

    /// The forward sweep's fix-ups when every mass is in a lane (`LANES
    /// lane` masses): `t[i]` holds the blocks' local sweeps at step `i`,
    /// each started from zero, and leaves with the true `y = L^-1 r`. The
    /// values each block's tails carry are found first (they need the
    /// blocks' far ends alone), so the fix-ups of all blocks then go side
    /// by side in the lanes.
    pub(crate) fn fix_forward<S>(&self, steps: &mut [S], t: impl Fn(&mut S) -> &mut Quad) {
        let s = self.lane;
        let (mut p, mut ends) = ([[0.0; 2]; LANES], [[0.0; 2]; LANES]);
        let (last, before) = (t(&mut steps[s - 1]).0, t(&mut steps[s - 2]).0);
        let mut carried = [last[0], before[0]];
        for (k, tail) in (1..LANES).zip(&self.down) {
            p[k] = carried;
            ends[k] = tail.carry([last[k], before[k]], carried);
            carried = ends[k];
        }
        self.lane_tails.down.fix(steps, &t, p, |_| {});
        for (k, [last, before]) in ends.into_iter().enumerate().skip(1) {
            t(&mut steps[s - 1]).0[k] = last;
            t(&mut steps[s - 2]).0[k] = before;
        }
    }

    /// The backward sweep's fix-ups when every mass is in a lane: `x[i]`
    /// holds the blocks' local sweeps at step `i`, each started from zero
    /// at its top (the last block's from the true values above it), and
    /// leaves with the true `x = P^-1 r`; `then` is called on every step
    /// whose `x` changed (each block's top steps while its tail lasts, and
    /// its steps 0 and 1), so that what was computed from `x` there can be
    /// computed again.
    pub(crate) fn fix_backward<S>(
        &self,
        steps: &mut [S],
        x: impl Fn(&mut S) -> &mut Quad,
        mut then: impl FnMut(&mut S),
    ) {
        let (mut q, mut ends) = ([[0.0; 2]; LANES], [[0.0; 2]; LANES]);
        let (first, second) = (x(&mut steps[0]).0, x(&mut steps[1]).0);
        let mut carried = [first[LANES - 1], second[LANES - 1]];
        for (k, tail) in (0..LANES - 1).zip(&self.up).rev() {
            q[k] = carried;
            ends[k] = tail.carry([first[k], second[k]], carried);
            carried = ends[k];
        }
        let near = self.lane_tails.up.near[0].len();
        let s = steps.len();
        self.lane_tails
            .up
            .fix(&mut steps[s - near..], &x, q, &mut then);
        for (k, [first, second]) in ends.into_iter().enumerate().take(LANES - 1) {
            x(&mut steps[0]).0[k] = first;
            x(&mut steps[1]).0[k] = second;
        }
        steps[..2].iter_mut().for_each(then);
    }

    /// `M A^-1 e_0` while not negligible (see [`Factor::first_stage_0`]).
    pub(crate) fn first_stage_weights(&self) -> &[f64] {
        &self.first_stage_0
    }

    /// `(A^-1 M v)_0`, the first stage's velocity of mass 0: a dot product
    /// over the masses where `M A^-1 e_0` is not negligible, four partial
    /// sums so that it pipelines (and packs into two `mulpd`/`addpd`).
    pub(super) fn first_stage_0(&self, v: &[f64]) -> f64 {
        let w = &self.first_stage_0;
        let v = &v[..w.len()];
        let mut sums = [0.0; 4];
        let (wc, vc) = (w.chunks_exact(4), v.chunks_exact(4));
        let (wr, vr) = (wc.remainder(), vc.remainder());
        for (w, v) in wc.zip(vc) {
            for k in 0..4 {
                sums[k] += w[k] * v[k];
            }
        }
        let rest: f64 = wr.iter().zip(vr).map(|(w, v)| w * v).sum();
        (sums[0] + sums[1]) + (sums[2] + sums[3]) + rest
    }
}

/// The first `LANES` blocks of `s` masses of `x`.
fn lanes(x: &[f64], s: usize) -> [&[f64]; LANES] {
    std::array::from_fn(|k| &x[k * s..(k + 1) * s])
}

/// The first `LANES` blocks of `s` masses of `x`, mutable.
fn lanes_mut(x: &mut [f64], s: usize) -> [&mut [f64]; LANES] {
    let mut blocks = x.chunks_exact_mut(s);
    std::array::from_fn(|_| blocks.next().unwrap_or_default())
}

/// Mass `j`'s value in the forward sweep's storage: `t` for the blocks'
/// first `LANES * s` masses (block `j / s`, step `j % s`), `r` after.
fn slot<'a>(t: &'a mut [Quad], r: &'a mut [f64], s: usize, j: usize) -> &'a mut f64 {
    if j < LANES * s {
        &mut t[j % s].0[j / s]
    } else {
        &mut r[j]
    }
}

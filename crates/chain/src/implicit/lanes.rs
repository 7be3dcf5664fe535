//! The fused kernel's layout: the chain cut into [`LANES`] blocks of
//! consecutive masses, stored side by side so that one row holds one mass
//! of every block, with ghost rows at both ends of each block that copy
//! its neighbours' masses.
//!
//! Why side by side. Each tridiagonal sweep is a linear recurrence: one
//! multiply and one subtraction on its critical path per mass. Eight
//! blocks swept together are eight independent recurrences, one vector
//! operation per row, so the sweeps run at the arithmetic's throughput
//! instead of its latency.
//!
//! Why ghost rows. A block's sweeps start from zero a halo of rows outside
//! the block (in the ghost rows) instead of from its neighbour's true
//! values. The sweeps' multipliers are below 1 (the matrix is strictly
//! diagonally dominant), so what the zero start leaves out has fallen below
//! [`super::plan::NEGLIGIBLE`] of the field by the block's first own row:
//! no fix-up pass, and the blocks need nothing from each other during a
//! pass. Between passes the ghost rows are refreshed from the neighbours'
//! own rows.

/// Blocks swept side by side: one AVX-512 register of doubles, two AVX2
/// ones, four SSE2 ones.
pub(crate) const LANES: usize = 8;

/// One mass of every block, element-wise arithmetic. Aligned to 64 bytes,
/// one AVX-512 register: the compiler then folds a row's loads into the
/// arithmetic.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[repr(C, align(64))]
pub(crate) struct Row(pub(crate) [f64; LANES]);

impl Row {
    /// Zero in every block.
    pub(crate) const ZERO: Row = Row([0.0; LANES]);

    /// `x` in every block.
    #[inline(always)]
    pub(crate) fn splat(x: f64) -> Row {
        Row([x; LANES])
    }
}

impl std::ops::Add for Row {
    type Output = Row;
    #[inline(always)]
    fn add(self, o: Row) -> Row {
        Row(std::array::from_fn(|k| self.0[k] + o.0[k]))
    }
}

impl std::ops::Sub for Row {
    type Output = Row;
    #[inline(always)]
    fn sub(self, o: Row) -> Row {
        Row(std::array::from_fn(|k| self.0[k] - o.0[k]))
    }
}

impl std::ops::Mul for Row {
    type Output = Row;
    #[inline(always)]
    fn mul(self, o: Row) -> Row {
        Row(std::array::from_fn(|k| self.0[k] * o.0[k]))
    }
}

/// Where each mass of a chain of `n` sits: block `b`, own row `i` holds
/// mass `b * rows + i`; masses past the top (the last block's padding) are
/// phantoms that stay at zero.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct LaneLayout {
    /// Masses in the chain.
    pub(crate) n: usize,
    /// Own rows per block.
    pub(crate) rows: usize,
    /// Ghost rows at each end of a block.
    pub(crate) ghosts: usize,
}

impl LaneLayout {
    /// `n` masses in blocks with `ghosts` ghost rows at each end, or `None`
    /// when a block would be shorter than its ghosts (a block's ghosts
    /// copy its neighbours' own rows) or than 32 rows. A pass sweeps each
    /// block's own rows and one halo of ghosts, so blocks as short as their
    /// halo double the rows swept: still about half the stage-by-stage kernel's
    /// time (`N = 10^3`, a viscous bottom: 2.0 against 3.7 ns a mass-step).
    pub(crate) fn new(n: usize, ghosts: usize) -> Option<Self> {
        let rows = n.div_ceil(LANES);
        (rows >= ghosts.max(32)).then_some(Self { n, rows, ghosts })
    }

    /// Rows of an array, ghosts included.
    pub(crate) fn stored(&self) -> usize {
        self.rows + 2 * self.ghosts
    }

    /// The mass at stored row `r` of block `b`, which may lie outside the
    /// chain (below 0 or from `n` on).
    pub(crate) fn mass_at(&self, b: usize, r: usize) -> isize {
        (b * self.rows + r) as isize - self.ghosts as isize
    }

    /// Block and stored row of mass `j` in its own block.
    pub(crate) fn place(&self, j: usize) -> (usize, usize) {
        (j / self.rows, j % self.rows + self.ghosts)
    }

    /// An array of zeros.
    pub(crate) fn zeros(&self) -> Vec<Row> {
        vec![Row::ZERO; self.stored()]
    }

    /// The chain's values in blocks, ghosts filled.
    pub(crate) fn scatter(&self, x: &[f64], out: &mut [Row]) {
        for (b_row, row) in out.iter_mut().enumerate() {
            for (b, value) in row.0.iter_mut().enumerate() {
                let j = self.mass_at(b, b_row);
                *value = usize::try_from(j)
                    .ok()
                    .and_then(|j| x.get(j))
                    .copied()
                    .unwrap_or(0.0);
            }
        }
    }

    /// The chain's values from the blocks' own rows.
    pub(crate) fn gather(&self, x: &[Row], out: &mut [f64]) {
        for (j, value) in out.iter_mut().enumerate().take(self.n) {
            let (b, r) = self.place(j);
            *value = x[r].0[b];
        }
    }

    /// Each block's ghost rows set to its neighbours' own rows (zero past
    /// the chain's ends: the wall below, the free top above).
    pub(crate) fn fill_ghosts(&self, x: &mut [Row]) {
        self.fill_near(x, self.ghosts, self.ghosts);
    }

    /// The `below` ghost rows nearest each block's bottom and the `above`
    /// nearest its top set to its neighbours' own rows: a pass's reads
    /// need no more (see `fused.rs`).
    #[inline]
    pub(crate) fn fill_near(&self, x: &mut [Row], below: usize, above: usize) {
        let (g, s) = (self.ghosts, self.rows);
        for i in 0..below {
            // below block b: the top of block b - 1
            let from = x[g + s - 1 - i].0;
            x[g - 1 - i] = Row(std::array::from_fn(
                |k| if k == 0 { 0.0 } else { from[k - 1] },
            ));
        }
        for i in 0..above {
            // above block b: the bottom of block b + 1
            let from = x[g + i].0;
            x[g + s + i] = Row(std::array::from_fn(|k| {
                if k == LANES - 1 { 0.0 } else { from[k + 1] }
            }));
        }
    }

    /// Value of mass `j` (`j < n`).
    pub(crate) fn get(&self, x: &[Row], j: usize) -> f64 {
        let (b, r) = self.place(j);
        x[r].0[b]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn scatter_then_gather_is_the_identity_and_ghosts_copy_neighbours() {
        let n = 8 * 40 - 5; // the last block padded with five phantoms
        let layout = LaneLayout::new(n, 10).unwrap();
        let x: Vec<f64> = (0..n).map(|j| j as f64 + 1.0).collect();
        let mut rows = layout.zeros();
        layout.scatter(&x, &mut rows);
        let mut back = vec![0.0; n];
        layout.gather(&rows, &mut back);
        assert_eq!(back, x);
        // refilling the ghosts from the own rows changes nothing
        let before = rows.clone();
        layout.fill_ghosts(&mut rows);
        assert_eq!(rows, before);
        // each stored value is its mass's, zero outside the chain
        for (r, row) in rows.iter().enumerate() {
            for (b, value) in row.0.iter().enumerate() {
                let j = layout.mass_at(b, r);
                let want = if (0..n as isize).contains(&j) {
                    j as f64 + 1.0
                } else {
                    0.0
                };
                assert_eq!(*value, want, "block {b}, row {r}");
            }
        }
        assert!(LaneLayout::new(8 * 31, 10).is_none());
        assert!(LaneLayout::new(8 * 39, 40).is_none());
    }
}

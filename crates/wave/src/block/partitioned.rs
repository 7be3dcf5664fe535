//! Long responses summed by FFT, in blocks of doubling size.
//!
//! A port's sums are a causal convolution of its arrivals with the block's
//! taps. Summed directly (`inputs.rs`), a response that rings for `L`
//! lattice points costs `L` multiply-adds a delivered point, so a block
//! whose response rings through the run costs the square of the run: on
//! the fast-bottom survey's rods 13 and 31 (seed 11), with their blocks
//! answered, the sums were four fifths of the time. Audio reverbs run long
//! impulse responses the way this module does (a non-uniformly partitioned
//! convolution): the first [`DIRECT`] taps are summed directly, and level
//! `c`, of block size `n = FIRST 2^c`, holds taps `[2n, 4n)` as two
//! partitions of `n` points; the top level, of [`TOP`] points, holds every
//! tap from `2n` on, in as many partitions as the response is long. A
//! level's block of `n` outputs is one inverse FFT of the sum of its
//! partitions' spectra times those of input blocks at least a block older,
//! whose points are final: an arrival lands on the point being delivered
//! or the one before, and one landing in a block a level has read makes
//! that level read its blocks again. A delivered point then costs `DIRECT`
//! multiply-adds and a few FFT butterflies for each of about `log L`
//! levels, and `8 L / TOP` more past `2 TOP` ([`adds_per_point`]).
//!
//! A level reads its partitions whole, so their taps must be final: the
//! trace of a response that has not rung out is extended only as far as a
//! port needs, and a level below the top waits until its taps are (its
//! taps are summed directly until then: extending the trace ahead for it
//! doubled the time of a layer-survey rod whose trace was all its time);
//! the top reads up to two of its partitions ahead of the span.
//!
//! The FFT is `rustfft`'s scalar one, in double precision: the same
//! numbers on every CPU. Arrivals and taps are real, so each block's FFT
//! of `2 n` real points is one of `n` complex points, untangled
//! (`real_fft.rs`), and a spectrum is its `n + 1` bins: half the
//! butterflies and half the products of a complex FFT of the real
//! points, which the first build took (fast-bottom rod 16's first level
//! 25.7 -> 21.5 G instructions). The work counted is still the complex
//! FFT's, the unit the blocks' price (`choice.rs`) was set in. Its
//! rounding is relative `1e-16` (times the logarithm of the block) of
//! the sizes of a whole block's inputs and a
//! partition's taps, not of one output's terms, so where one output
//! cancels beside large terms elsewhere in its block it can be far above
//! the direct sums'; the ladder's levels and twin measure it with the
//! rest. A double-double run sums directly ([`Real::FFT_SUMS`]).

use super::real_fft::RealFft;
use crate::real::Real;
use rustfft::num_complex::Complex;
use std::collections::VecDeque;

/// Points of the finest level's blocks.
pub(crate) const FIRST: i64 = 128;

/// Taps summed directly: those before the finest level's.
pub(crate) const DIRECT: i64 = 2 * FIRST;

/// Points of the top level's blocks (its FFTs are twice as long).
pub(crate) const TOP: i64 = FIRST << 7;

/// The levels: block sizes from [`FIRST`] up to the top's.
pub(crate) const LEVELS: usize = 8;

/// Multiply-adds (as counted) a delivered point costs when the arrivals
/// held reach `reach` taps back and the response has not rung out, so
/// that its taps are final only as far as the sums need them: the direct
/// sums, then per level its two FFTs and its partitions' products a
/// block, and the taps of the levels still waiting summed directly. What
/// the blocks' price (`choice.rs`) charges. A response that has rung out
/// costs about as much or less: a level is taken once its taps are final,
/// so a response ending a little past a level's first tap pays that
/// level's FFTs for a few taps (up to `4 log2(2n) + 8` multiply-adds a
/// point over the price), and the top's partitions may be one more than
/// priced where the oldest arrival is not on a block's first point.
pub(crate) fn adds_per_point(reach: f64) -> f64 {
    let direct = DIRECT as f64;
    if reach < direct {
        return reach.max(0.0);
    }
    let (mut adds, mut covered) = (direct, direct);
    for c in 0..LEVELS {
        let n = block_size(c) as f64;
        if 2.0 * n > reach || (n < TOP as f64 && 4.0 * n - 1.0 > reach) {
            break;
        }
        let parts = if n < TOP as f64 {
            2.0
        } else {
            (reach / n).floor() - 1.0
        };
        adds += (2 * fft_work(2 * n as i64)) as f64 / n + 8.0 * parts;
        covered = if n < TOP as f64 {
            4.0 * n
        } else {
            f64::INFINITY
        };
    }
    adds + (reach + 1.0 - covered).max(0.0)
}

/// Arrivals on consecutive lattice points from `first` on, as a level
/// reads them.
pub(crate) struct Points<'a, R> {
    pub first: i64,
    pub jumps: &'a [R],
}

impl<R: Real> Points<'_, R> {
    /// The points of `[from, from + n)` into the first half of `out`
    /// (the rest zero); whether any is not zero.
    fn block(&self, from: i64, n: usize, out: &mut [f64]) -> bool {
        out.fill(0.0);
        let mut any = false;
        for (i, c) in out.iter_mut().take(n).enumerate() {
            let k = from + i as i64 - self.first;
            if let Some(&x) = usize::try_from(k).ok().and_then(|k| self.jumps.get(k)) {
                *c = x.to_f64();
                any |= x != R::zero();
            }
        }
        any
    }
}

/// One level of the partitioned sums.
#[derive(Clone)]
pub(crate) struct Level {
    /// Points a block.
    n: i64,
    /// Whether it is the top level (partitions `2, 3, ...`; else `2, 3`).
    top: bool,
    /// FFTs of `2 n` real points.
    fft: RealFft,
    /// Spectra of the taps' partitions `p = 2, 3, ...` (taps from `p n`
    /// to `(p + 1) n`, padded to `2 n`; their bins `0..=n`); `None` where
    /// they are all zero.
    parts: Vec<Option<Vec<Complex<f64>>>>,
    /// Spectra of input blocks `inputs_from, ...`; `None` where the block
    /// holds no arrival.
    inputs: VecDeque<Option<Vec<Complex<f64>>>>,
    inputs_from: i64,
    /// The output block whose sums `current` holds, if any.
    block: Option<i64>,
    /// The level's part of that block's outputs, and of the next one's.
    current: Vec<f64>,
    carry: Vec<f64>,
    /// A spectrum's bins, and a block's `2 n` real points (room kept).
    buffer: Vec<Complex<f64>>,
    real: Vec<f64>,
}

impl std::fmt::Debug for Level {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Level")
            .field("n", &self.n)
            .field("top", &self.top)
            .field("parts", &self.parts.len())
            .field("block", &self.block)
            .finish()
    }
}

/// The size of level `c`'s blocks.
pub(crate) fn block_size(c: usize) -> i64 {
    (FIRST << c).min(TOP)
}

/// The taps a level reads for output point `m`, given the oldest arrival
/// held: its last one.
pub(crate) fn last_tap(c: usize, m: i64, oldest: i64) -> i64 {
    let n = block_size(c);
    if n < TOP {
        4 * n - 1
    } else {
        (m.div_euclid(n) - oldest.div_euclid(n) + 1) * n - 1
    }
}

impl Level {
    /// Level `c`.
    pub(crate) fn new(c: usize) -> Self {
        let n = block_size(c);
        let size = 2 * n as usize;
        let fft = RealFft::new(size);
        Self {
            n,
            top: n == TOP,
            buffer: vec![Complex::default(); fft.bins()],
            fft,
            parts: Vec::new(),
            inputs: VecDeque::new(),
            inputs_from: 0,
            block: None,
            current: vec![0.0; n as usize],
            carry: vec![0.0; n as usize],
            real: vec![0.0; size],
        }
    }

    /// Points before this have been read into the level's sums.
    pub(crate) fn read_before(&self) -> i64 {
        self.block.map_or(i64::MIN, |s| (s - 1) * self.n)
    }

    /// Forgets what it read: its sums are taken again at the next point.
    pub(crate) fn forget(&mut self) {
        self.block = None;
        self.inputs.clear();
    }

    /// The level's part of output point `m`: taps from `2 n` (to `4 n`
    /// below the top), final through [`last_tap`]; `taps` beyond their
    /// length are zero. Multiply-adds (about) are added to `work`.
    pub(crate) fn at<R: Real>(&mut self, m: i64, x: &Points<R>, taps: &[R], work: &mut u64) -> f64 {
        let s = m.div_euclid(self.n);
        if self.block != Some(s) {
            if self.block == Some(s - 1) {
                std::mem::swap(&mut self.current, &mut self.carry);
                self.carry.fill(0.0);
            } else {
                self.current.fill(0.0);
                self.carry.fill(0.0);
                self.inputs.clear();
                // the block before's second half, into this one
                self.add_block(s - 1, x, taps, work);
                std::mem::swap(&mut self.current, &mut self.carry);
                self.carry.fill(0.0);
            }
            self.add_block(s, x, taps, work);
            self.block = Some(s);
        }
        self.current[(m - s * self.n) as usize]
    }

    /// The outputs of input blocks `s - p` with partitions `p`: the first
    /// half into `current`, the second into `carry`.
    fn add_block<R: Real>(&mut self, s: i64, x: &Points<R>, taps: &[R], work: &mut u64) {
        let n = self.n;
        let oldest = x.first.div_euclid(n);
        let last_part = if self.top { s - oldest } else { 3 };
        if last_part < 2 {
            return;
        }
        // the input blocks `s - last_part ..= s - 2`, oldest first
        let (lo, hi) = (s - last_part, s - 2);
        if self.inputs.is_empty() || lo < self.inputs_from || hi + 1 < self.inputs_from {
            self.inputs.clear();
            self.inputs_from = lo;
        }
        while self.inputs_from < lo {
            self.inputs.pop_front();
            self.inputs_from += 1;
        }
        while self.inputs_from + (self.inputs.len() as i64) <= hi {
            let b = self.inputs_from + self.inputs.len() as i64;
            let spectrum = self.spectrum_of(b, x, work);
            self.inputs.push_back(spectrum);
        }
        self.compute_parts(last_part, taps, work);
        let mut sum = std::mem::take(&mut self.buffer);
        sum.fill(Complex::default());
        let mut any = false;
        for p in 2..=last_part {
            let Some(Some(input)) = self.inputs.get((s - p - self.inputs_from) as usize) else {
                continue;
            };
            let Some(Some(part)) = self.parts.get((p - 2) as usize) else {
                continue;
            };
            for ((z, a), b) in sum.iter_mut().zip(input).zip(part) {
                *z += a * b;
            }
            *work += 8 * n as u64;
            any = true;
        }
        if !any {
            self.buffer = sum;
            return;
        }
        self.fft.inverse(&sum, &mut self.real);
        *work += fft_work(2 * n);
        let scale = 1.0 / (2 * n) as f64;
        let (first, second) = self.real.split_at(n as usize);
        for (c, z) in self.current.iter_mut().zip(first) {
            *c += z * scale;
        }
        for (c, z) in self.carry.iter_mut().zip(second) {
            *c += z * scale;
        }
        self.buffer = sum;
    }

    /// The spectrum of input block `b`, if it holds an arrival.
    fn spectrum_of<R: Real>(
        &mut self,
        b: i64,
        x: &Points<R>,
        work: &mut u64,
    ) -> Option<Vec<Complex<f64>>> {
        if !x.block(b * self.n, self.n as usize, &mut self.real) {
            return None;
        }
        let mut spectrum = vec![Complex::default(); self.fft.bins()];
        self.fft.forward(&self.real, &mut spectrum);
        *work += fft_work(2 * self.n);
        Some(spectrum)
    }

    /// The spectra of partitions `2..=last`, each computed the first time
    /// it is asked for.
    fn compute_parts<R: Real>(&mut self, last: i64, taps: &[R], work: &mut u64) {
        while (self.parts.len() as i64) + 2 <= last {
            let p = self.parts.len() as i64 + 2;
            let from = (p * self.n) as usize;
            let part = taps.get(from..).unwrap_or(&[]);
            let part = &part[..part.len().min(self.n as usize)];
            if part.iter().all(|&t| t == R::zero()) {
                self.parts.push(None);
                continue;
            }
            self.real.fill(0.0);
            for (c, &t) in self.real.iter_mut().zip(part) {
                *c = t.to_f64();
            }
            self.fft.forward(&self.real, &mut self.buffer);
            *work += fft_work(2 * self.n);
            self.parts.push(Some(self.buffer.clone()));
        }
    }
}

/// An FFT of `size` points, counted in multiply-adds: about `size log2
/// size` (each radix-4 butterfly's complex products and sums).
fn fft_work(size: i64) -> u64 {
    let size = size as u64;
    size * u64::from(size.ilog2())
}

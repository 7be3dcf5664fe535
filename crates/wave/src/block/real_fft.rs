//! FFTs of real blocks by complex FFTs of half their length.
//!
//! The partitioned sums (`partitioned.rs`) transform real arrivals and
//! real taps and keep only the real part of the inverse: a complex FFT of
//! `N` points wastes half its work on an imaginary part that is zero. The
//! usual packing takes the even points as real parts and the odd ones as
//! imaginary parts, transforms those `N / 2` complex points, and untangles
//! the two halves with one twiddle a bin; the spectrum of a real block is
//! its bins `0..=N/2` (the rest are their conjugates), so the products of
//! spectra are half as many too. The FFT is still `rustfft`'s scalar one:
//! the same numbers on every CPU.

use rustfft::num_complex::Complex;
use rustfft::{Fft, FftPlannerScalar};
use std::sync::Arc;

/// Forward and inverse FFTs of `N` real points.
#[derive(Clone)]
pub(crate) struct RealFft {
    /// `N / 2`.
    half: usize,
    forward: Arc<dyn Fft<f64>>,
    inverse: Arc<dyn Fft<f64>>,
    /// `exp(-2 pi i k / N)`, `k = 0..N/2`.
    twiddles: Vec<Complex<f64>>,
    /// The packed points (room kept).
    packed: Vec<Complex<f64>>,
    scratch: Vec<Complex<f64>>,
}

impl RealFft {
    /// The transforms of `size` real points (even).
    pub(crate) fn new(size: usize) -> Self {
        debug_assert!(size >= 2 && size.is_multiple_of(2));
        let half = size / 2;
        let mut planner = FftPlannerScalar::new();
        let forward = planner.plan_fft_forward(half);
        let inverse = planner.plan_fft_inverse(half);
        let scratch = forward
            .get_inplace_scratch_len()
            .max(inverse.get_inplace_scratch_len());
        let twiddles = (0..half)
            .map(|k| {
                let angle = -2.0 * std::f64::consts::PI * k as f64 / size as f64;
                Complex::new(angle.cos(), angle.sin())
            })
            .collect();
        Self {
            half,
            forward,
            inverse,
            twiddles,
            packed: vec![Complex::default(); half],
            scratch: vec![Complex::default(); scratch],
        }
    }

    /// Bins of a real block's spectrum kept: `0..=N/2`.
    pub(crate) fn bins(&self) -> usize {
        self.half + 1
    }

    /// The spectrum of `x` (`N` points) into `out` (`N/2 + 1` bins):
    /// `X[k] = sum_t x[t] exp(-2 pi i k t / N)`.
    pub(crate) fn forward(&mut self, x: &[f64], out: &mut [Complex<f64>]) {
        let m = self.half;
        for (z, pair) in self.packed.iter_mut().zip(x.chunks_exact(2)) {
            *z = Complex::new(pair[0], pair[1]);
        }
        self.forward
            .process_with_scratch(&mut self.packed, &mut self.scratch);
        let z = &self.packed;
        // the even points' spectrum, and the odd ones', from bins `k` and
        // `N/2 - k` of the packed one (`N/2` itself is bin 0)
        let untangle = |a: Complex<f64>, b: Complex<f64>, w: Complex<f64>| {
            let even = (a + b) * 0.5;
            let odd = Complex::new(0.0, -0.5) * (a - b);
            even + w * odd
        };
        let (first, last) = (z[0], z[0].conj());
        out[0] = untangle(first, last, self.twiddles[0]);
        out[m] = untangle(first, last, Complex::new(-1.0, 0.0));
        for k in 1..m {
            out[k] = untangle(z[k], z[m - k].conj(), self.twiddles[k]);
        }
    }

    /// `N` times the real block whose spectrum's bins `0..=N/2` are
    /// `spectrum` into `out` (`N` points), unnormalised as `rustfft`'s
    /// inverse is: `out[t] = sum_k X[k] exp(2 pi i k t / N)` over all `N`
    /// bins.
    pub(crate) fn inverse(&mut self, spectrum: &[Complex<f64>], out: &mut [f64]) {
        let m = self.half;
        for ((k, z), w) in self.packed.iter_mut().enumerate().zip(&self.twiddles) {
            let a = spectrum[k];
            let b = spectrum[m - k].conj();
            let even = a + b;
            let odd = (a - b) * w.conj();
            *z = even + Complex::new(0.0, 1.0) * odd;
        }
        self.inverse
            .process_with_scratch(&mut self.packed, &mut self.scratch);
        for (pair, z) in out.chunks_exact_mut(2).zip(&self.packed) {
            pair[0] = z.re;
            pair[1] = z.im;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The spectrum and the inverse against the complex FFT of the same
    /// real points (the way `partitioned.rs` took them before), and the
    /// round trip, on sizes the levels use: to `1e-13` of the block's
    /// largest bin.
    #[test]
    fn a_real_block_transforms_as_its_complex_fft_does() {
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let mut next = move || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
        };
        for size in [2usize, 4, 8, 256, 1024, 32768] {
            let x: Vec<f64> = (0..size).map(|_| next()).collect();
            let mut full: Vec<Complex<f64>> = x.iter().map(|&v| Complex::new(v, 0.0)).collect();
            let mut planner = FftPlannerScalar::new();
            planner.plan_fft_forward(size).process(&mut full);
            let mut fft = RealFft::new(size);
            let mut half = vec![Complex::default(); fft.bins()];
            fft.forward(&x, &mut half);
            let scale = full.iter().map(|z| z.norm()).fold(0.0, f64::max);
            for (k, (a, b)) in half.iter().zip(&full).enumerate() {
                assert!(
                    (a - b).norm() <= 1e-13 * scale,
                    "size {size} bin {k}: {a} {b}"
                );
            }
            // an inverse of a product of spectra, as the levels take it:
            // against the complex inverse of the full spectrum
            let mut product = full.clone();
            for (k, z) in product.iter_mut().enumerate() {
                *z *= Complex::new(1.0 / (1.0 + k.min(size - k) as f64), 0.0);
            }
            let filtered: Vec<Complex<f64>> = product[..fft.bins()].to_vec();
            planner.plan_fft_inverse(size).process(&mut product);
            let mut real = vec![0.0; size];
            fft.inverse(&filtered, &mut real);
            let peak = product.iter().map(|z| z.re.abs()).fold(0.0, f64::max);
            for (t, (a, b)) in real.iter().zip(&product).enumerate() {
                assert!(
                    (a - b.re).abs() <= 1e-13 * peak,
                    "size {size} point {t}: {a} {b}"
                );
            }
            // the round trip: N times the block
            fft.inverse(&half, &mut real);
            for (a, b) in real.iter().zip(&x) {
                assert!((a / size as f64 - b).abs() <= 1e-14, "size {size}: {a} {b}");
            }
        }
    }
}

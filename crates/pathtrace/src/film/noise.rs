//! How much noise a film still holds, estimated from its own per-pixel variance.
//!
//! The estimate mirrors the relative MSE of `metrics::relative_mse`, (1/3N) Σ (a − b)² / (b² + 0.01),
//! with the unknown converged image b replaced by the pixel mean and the squared error (a − b)²
//! by its expectation, the variance of the mean s²/n:
//!
//! ```text
//! relative MSE ≈ (1/3N) Σ_pixels Σ_channels (s²/n) / (mean² + 0.01)
//! relative error = √(relative MSE)   (an RMS over pixels of stderr / √(mean² + 0.01))
//! ```
//!
//! So an estimated relative error of 0.05 means the image is expected to be within about 5% RMS
//! of the converged one, in the same units `pathtrace converge` measures against a reference.

use super::{Film, PixelStats};
use rayon::prelude::*;

/// The `0.01` of relative MSE: keeps black pixels from dominating (Rousselle et al. 2011).
pub const RELATIVE_EPSILON: f64 = 0.01;

/// A pixel's relative variance per sample, Σ_c s²_c / (mean_c² + 0.01): its contribution to the
/// relative MSE is this divided by its sample count (and by 3N).
pub fn relative_variance(p: &PixelStats) -> f64 {
    let mean = p.mean();
    let v = p.sample_variance_about(&mean);
    (0..3).map(|c| v[c] / (mean[c] * mean[c] + RELATIVE_EPSILON)).sum()
}

/// Pixels per part of the estimate's parallel pass. Fixed, so the parts and the order they are
/// added in, and with them the estimate's bits, do not depend on the number of threads.
const ESTIMATE_CHUNK: usize = 4096;

impl Film {
    /// The expected relative MSE of the current image against the converged one (see the module
    /// docs). `None` before every pixel has two samples (no variance estimate yet).
    ///
    /// The pass runs on the current rayon pool: a render computes it between waves, while its
    /// worker threads would otherwise wait; at about 70 ns a pixel, on one thread it held up a
    /// two-thread veach-mis render by 9% (docs/benchmarks.md, "The error
    /// estimate on every thread; waves …").
    pub fn relative_mse_estimate(&self) -> Option<f64> {
        let parts: Vec<Option<f64>> = self
            .pixels()
            .par_chunks(ESTIMATE_CHUNK)
            .map(|chunk| {
                let mut sum = 0.0;
                for p in chunk {
                    if p.count < 2 {
                        return None;
                    }
                    sum += relative_variance(p) / p.count as f64;
                }
                Some(sum)
            })
            .collect();
        let mut sum = 0.0;
        for part in parts {
            sum += part?;
        }
        Some(sum / (3 * self.pixels().len()).max(1) as f64)
    }

    /// √ of [`Film::relative_mse_estimate`]: the RMS relative error the image is expected to hold.
    pub fn relative_rms_error_estimate(&self) -> Option<f64> {
        self.relative_mse_estimate().map(f64::sqrt)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rgb;

    #[test]
    fn matches_the_formula_on_a_hand_made_film() {
        let mut film = Film::new(2, 1);
        // Pixel 0: samples 1 and 3 (mean 2, s² = 2); pixel 1: constant 0.5 (s² = 0).
        film.add_sample(0, 0, Rgb::splat(1.0));
        assert_eq!(film.relative_mse_estimate(), None);
        film.add_sample(0, 0, Rgb::splat(3.0));
        film.add_sample(1, 0, Rgb::splat(0.5));
        film.add_sample(1, 0, Rgb::splat(0.5));
        let expected = 3.0 * (2.0 / 2.0) / (4.0 + 0.01) / 6.0;
        assert!((film.relative_mse_estimate().unwrap() - expected).abs() < 1e-12);
        assert!((film.relative_rms_error_estimate().unwrap() - expected.sqrt()).abs() < 1e-12);
    }

    #[test]
    fn agrees_with_the_measured_error_of_noisy_pixels() {
        // 400 pixels of true value 0.5, each the mean of 16 uniform samples in [0, 1]: the
        // estimate and the actual relative MSE must agree to within a few percent.
        let mut film = Film::new(20, 20);
        let mut state = 12345u64;
        let mut next = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        for y in 0..20 {
            for x in 0..20 {
                for _ in 0..16 {
                    film.add_sample(x, y, Rgb::new(next(), next(), next()));
                }
            }
        }
        let actual: f64 = film
            .pixels()
            .iter()
            .flat_map(|p| p.mean().into_iter().map(|m| (m - 0.5) * (m - 0.5) / (0.25 + 0.01)))
            .sum::<f64>()
            / 1200.0;
        let estimate = film.relative_mse_estimate().unwrap();
        // Both are means of 1200 roughly independent terms: agreement within 10% is ~2.5σ.
        assert!((estimate / actual - 1.0).abs() < 0.1, "estimate {estimate} vs actual {actual}");
    }

    /// The parallel pass adds the same parts in the same order on any number of threads, and a
    /// pixel without two samples in any part (here the last) still means no estimate.
    #[test]
    fn the_estimate_does_not_depend_on_the_thread_count() {
        let (w, h) = (300u32, 50u32);
        assert!((w * h) as usize > 3 * ESTIMATE_CHUNK, "the film spans several parts");
        let mut film = Film::new(w, h);
        let mut state = 7u64;
        let mut next = || {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            (state >> 40) as f32 / (1u64 << 24) as f32
        };
        for y in 0..h {
            for x in 0..w {
                let scale = 1.0 + (x * y % 17) as f32;
                for _ in 0..3 {
                    film.add_sample(x, y, Rgb::new(next() * scale, next(), next() * 0.1));
                }
            }
        }
        let on = |threads: usize, film: &Film| {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            pool.install(|| film.relative_mse_estimate())
        };
        let one = on(1, &film).unwrap();
        for threads in [2, 3, 8] {
            assert_eq!(on(threads, &film).unwrap().to_bits(), one.to_bits(), "{threads} threads");
        }
        // The same value as the formula summed pixel by pixel, to rounding.
        let direct: f64 = film.pixels().iter().map(|p| relative_variance(p) / p.count as f64).sum::<f64>()
            / (3 * film.pixels().len()) as f64;
        assert!((one / direct - 1.0).abs() < 1e-12, "{one} vs {direct}");

        let mut short = Film::new(w, h);
        for y in 0..h {
            for x in 0..w {
                let samples = if (x, y) == (w - 1, h - 1) { 1 } else { 2 };
                for _ in 0..samples {
                    short.add_sample(x, y, Rgb::splat(next()));
                }
            }
        }
        assert_eq!(on(2, &short), None);
    }
}

//! Adaptive sampling: after a uniform start, each wave's samples go where the film's estimated
//! relative error is largest.
//!
//! **Rule.** With `vₚ` a pixel's relative variance per sample (Σ_c s²/(mean² + 0.01), see
//! `film::relative_variance`), the image's expected relative MSE after `nₚ` samples per pixel is
//! (1/3N) Σ vₚ/nₚ. For a fixed total Σ nₚ = T it is smallest when nₚ ∝ √vₚ (a Lagrange
//! multiplier on Σ vₚ/nₚ + λ Σ nₚ gives vₚ/nₚ² = λ — the same argument as Neyman's optimal
//! allocation in stratified sampling). Each adaptive wave therefore computes every pixel's ideal
//! count for the new total, T'·wₚ/Σw, and shares the wave's budget among pixels in proportion to
//! how far they are below it.
//!
//! **Bias, and how it is kept small.** Deciding how many samples a pixel gets from that pixel's own
//! samples makes the sample count depend on the sample values, which biases the mean slightly (a
//! pixel that looked calm by chance stops early with its calm estimate). Three things limit it:
//! every pixel first gets `min_spp` uniform samples; the weight wₚ is the √ of the relative
//! variance *averaged over the 3×3 neighbourhood*, so one pixel's own samples are a ninth of
//! what decides its share; and every pixel gets at least `floor` of the average weight, so every
//! pixel's count still grows without bound and the bias vanishes as the render goes on. The
//! engine test `tests/adaptive.rs` measures the remaining bias against a uniform render.

use crate::film::{relative_variance, Film};
use rayon::prelude::*;

/// Settings of adaptive sampling.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptiveSettings {
    /// Uniform samples every pixel gets before any adaptation.
    pub min_spp: u32,
    /// Stop once the film's estimated relative RMS error (`Film::relative_rms_error_estimate`)
    /// is at or below this; `None` spends the whole budget.
    pub target_error: Option<f64>,
    /// Least share of a pixel, as a fraction of the mean weight (keeps every pixel converging).
    pub floor: f64,
}

impl Default for AdaptiveSettings {
    fn default() -> Self {
        Self { min_spp: 16, target_error: None, floor: 0.1 }
    }
}

/// How many new samples each pixel gets from a wave of `budget` samples, given the film so far
/// and how many samples each pixel has been *given* (`given`, which counts dropped NaN samples
/// too). The result sums to `budget` exactly and depends only on its inputs (deterministic).
pub fn allocate(film: &Film, given: &[u32], budget: u64, floor: f64) -> Vec<u32> {
    let (w, h) = (film.width() as usize, film.height() as usize);
    // Per pixel on every thread of the pool (the render's workers wait for this between
    // waves); collecting keeps the pixel order, so the values do not depend on the threads.
    let rel: Vec<f64> = film.pixels().par_iter().map(relative_variance).collect();
    // √ of the 3×3 neighbourhood mean of the relative variance (clipped at the image border).
    let mut weight: Vec<f64> = (0..w * h)
        .into_par_iter()
        .map(|i| {
            let (x, y) = (i % w, i / w);
            let (mut sum, mut n) = (0.0, 0.0);
            for yy in y.saturating_sub(1)..(y + 2).min(h) {
                for xx in x.saturating_sub(1)..(x + 2).min(w) {
                    sum += rel[yy * w + xx];
                    n += 1.0;
                }
            }
            (sum / n).sqrt()
        })
        .collect();
    let mean_weight = weight.iter().sum::<f64>() / weight.len().max(1) as f64;
    if mean_weight > 0.0 && mean_weight.is_finite() {
        weight.iter_mut().for_each(|x| *x = x.max(floor * mean_weight));
    } else {
        // No variance anywhere (or none measurable): spread uniformly.
        weight.iter_mut().for_each(|x| *x = 1.0);
    }
    let total_weight: f64 = weight.iter().sum();
    let new_total = given.iter().map(|&n| n as f64).sum::<f64>() + budget as f64;
    let deficit: Vec<f64> =
        weight.iter().zip(given).map(|(&wt, &n)| (new_total * wt / total_weight - n as f64).max(0.0)).collect();
    distribute(&deficit, budget)
}

/// Splits `budget` into integers proportional to `shares` by systematic rounding (each pixel gets
/// the difference of the floors of the running sums), so the parts add up to `budget` exactly.
fn distribute(shares: &[f64], budget: u64) -> Vec<u32> {
    let total: f64 = shares.iter().sum();
    if total <= 0.0 || !total.is_finite() {
        // Every pixel is at its ideal count already: share evenly.
        let all = vec![1.0; shares.len()];
        return if shares.is_empty() { Vec::new() } else { distribute(&all, budget) };
    }
    let scale = budget as f64 / total;
    let mut running = 0.0;
    let mut given = 0u64;
    shares
        .iter()
        .enumerate()
        .map(|(i, &s)| {
            running += s * scale;
            let upto = if i + 1 == shares.len() { budget } else { (running.floor() as u64).min(budget) };
            let n = upto.saturating_sub(given);
            given += n;
            n.min(u32::MAX as u64) as u32
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Rgb;

    #[test]
    fn distribute_is_exact_and_proportional() {
        let parts = distribute(&[1.0, 2.0, 0.0, 1.0], 100);
        assert_eq!(parts.iter().sum::<u32>(), 100);
        assert_eq!(parts, vec![25, 50, 0, 25]);
        assert_eq!(distribute(&[0.0, 0.0], 5).iter().sum::<u32>(), 5);
        assert_eq!(distribute(&[1.0, 1.0, 1.0], 1).iter().sum::<u32>(), 1);
    }

    #[test]
    fn noisy_regions_get_more_samples_and_calm_ones_keep_a_floor() {
        // A 12×4 film: the left half constant, the right half noisy (values 0 and 2).
        let mut film = Film::new(12, 4);
        for y in 0..4 {
            for x in 0..12 {
                for s in 0..8 {
                    let v = if x < 6 { 1.0 } else { 2.0 * (s % 2) as f32 };
                    film.add_sample(x, y, Rgb::splat(v));
                }
            }
        }
        let given = vec![8u32; 48];
        let extra = allocate(&film, &given, 48 * 8, 0.1);
        assert_eq!(extra.iter().map(|&n| n as u64).sum::<u64>(), 48 * 8);
        let at = |x: usize, y: usize| extra[y * 12 + x];
        // Far from the noisy half: only the floor; in it: most of the budget.
        assert!(at(0, 0) <= 2, "{}", at(0, 0));
        assert!(at(11, 3) > 10 * at(0, 0).max(1), "{} vs {}", at(11, 3), at(0, 0));
        // A flat film spreads evenly.
        let flat = Film::new(3, 3);
        assert_eq!(allocate(&flat, &[0; 9], 18, 0.1), vec![2; 9]);
    }
}

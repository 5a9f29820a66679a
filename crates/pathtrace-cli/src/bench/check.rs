//! The bench's correctness check: does a run's image agree with the stored reference within
//! confidence intervals? The image is cut into square regions; each region's mean per channel
//! is compared with the reference's by a z-test whose variance is the film's own estimate
//! (Σ s²/n over the region's pixels, `Film::region_estimate`) plus the reference's, which is the
//! same estimator with `reference_spp` samples per pixel, so its variance is the run's scaled by
//! spp / reference_spp. All region × channel tests together keep a family-wise false-alarm rate
//! of [`FAMILY_ALPHA`] (Bonferroni).

use pathtrace::film::{Film, Image};
use serde::{Deserialize, Serialize};

/// Region side in pixels.
const REGION: u32 = 16;
/// Probability that a correct renderer fails the check of one scene.
pub const FAMILY_ALPHA: f64 = 1e-3;

/// The outcome for one scene.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Check {
    /// "PASS", "FAIL" or "SKIP" (no reference).
    pub status: String,
    /// Largest |z| over regions and channels.
    pub max_z: Option<f64>,
    /// The |z| above which a region fails (Bonferroni-corrected two-sided normal quantile).
    pub threshold: Option<f64>,
    pub regions: usize,
    pub failing_regions: usize,
    pub note: Option<String>,
}

impl Check {
    pub fn skipped(note: impl Into<String>) -> Self {
        Self {
            status: "SKIP".into(),
            max_z: None,
            threshold: None,
            regions: 0,
            failing_regions: 0,
            note: Some(note.into()),
        }
    }

    pub fn failed(&self) -> bool {
        self.status == "FAIL"
    }
}

/// Compares a uniform-spp film with the reference image rendered at `reference_spp`.
pub fn check_against_reference(film: &Film, reference: &Image, reference_spp: u32) -> Check {
    if (film.width(), film.height()) != (reference.width, reference.height) {
        return Check::skipped(format!(
            "reference is {}×{}, the render {}×{}",
            reference.width,
            reference.height,
            film.width(),
            film.height()
        ));
    }
    let (spp, _) = film.spp_range();
    let reference_share = spp as f64 / reference_spp.max(1) as f64;
    let mut zs = Vec::new();
    for y0 in (0..film.height()).step_by(REGION as usize) {
        for x0 in (0..film.width()).step_by(REGION as usize) {
            let (x1, y1) = ((x0 + REGION).min(film.width()), (y0 + REGION).min(film.height()));
            let run = film.region_estimate(x0, y0, x1, y1);
            let expected = reference.mean_over(x0, y0, x1, y1);
            let expected = [expected.r as f64, expected.g as f64, expected.b as f64];
            let z = (0..3)
                .map(|k| {
                    let sd = (run.variance_of_mean[k] * (1.0 + reference_share)).sqrt();
                    let d = (run.mean[k] - expected[k]).abs();
                    match (sd > 0.0, d == 0.0) {
                        (true, _) => d / sd,
                        (false, true) => 0.0,
                        (false, false) => f64::INFINITY,
                    }
                })
                .fold(0.0, f64::max);
            zs.push(z);
        }
    }
    let tests = 3 * zs.len();
    let threshold = two_sided_normal_quantile(FAMILY_ALPHA / tests as f64);
    let failing = zs.iter().filter(|&&z| z > threshold).count();
    Check {
        status: if failing == 0 { "PASS" } else { "FAIL" }.into(),
        max_z: Some(zs.iter().copied().fold(0.0, f64::max)),
        threshold: Some(threshold),
        regions: zs.len(),
        failing_regions: failing,
        note: None,
    }
}

/// The z with P(|Z| > z) = `alpha` for a standard normal Z, by bisection on
/// P(|Z| > z) = erfc(z / √2).
fn two_sided_normal_quantile(alpha: f64) -> f64 {
    let (mut lo, mut hi) = (0.0f64, 40.0f64);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if erfc(mid / std::f64::consts::SQRT_2) > alpha {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Complementary error function with fractional error below 1.2·10⁻⁷ everywhere: the Chebyshev
/// fit `erfcc` of Numerical Recipes in C, 2nd ed., §6.2.
fn erfc(x: f64) -> f64 {
    let z = x.abs();
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -z * z - 1.265_512_23
        + t * (1.000_023_68
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98 + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    let r = t * poly.exp();
    if x >= 0.0 {
        r
    } else {
        2.0 - r
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use pathtrace::math::Rgb;
    use pathtrace::sampling::Pcg32;

    #[test]
    fn normal_quantiles_match_tables() {
        // Standard two-sided critical values: 1.959964 (5%), 2.575829 (1%), 3.290527 (0.1%).
        for (alpha, z) in [(0.05, 1.959964), (0.01, 2.575829), (0.001, 3.290527)] {
            assert!((two_sided_normal_quantile(alpha) - z).abs() < 1e-5, "{alpha}");
        }
    }

    /// A film of Gaussian noise around `mean`, sample standard deviation `sd`.
    fn noisy_film(mean: f32, sd: f32, spp: u32, seed: u64) -> Film {
        let mut film = Film::new(32, 32);
        let mut rng = Pcg32::new(seed, 7);
        for y in 0..32 {
            for x in 0..32 {
                for _ in 0..spp {
                    // Box–Muller from two uniforms.
                    let (u1, u2) = (rng.next_f32().max(1e-7), rng.next_f32());
                    let g = (-2.0 * u1.ln()).sqrt() * (std::f32::consts::TAU * u2).cos();
                    film.add_sample(x, y, Rgb::splat(mean + sd * g));
                }
            }
        }
        film
    }

    #[test]
    fn agrees_with_the_truth_and_catches_a_three_percent_bias() {
        let truth = Image::from_pixels(32, 32, vec![Rgb::splat(1.0); 32 * 32]).unwrap();
        let film = noisy_film(1.0, 0.3, 64, 1);
        let c = check_against_reference(&film, &truth, 1 << 20);
        assert_eq!(c.status, "PASS", "{c:?}");
        assert_eq!(c.regions, 4);
        // 3% too bright: a region mean has sd 0.3/√(256·64) ≈ 0.0023, so z ≈ 13, far above ≈ 3.9.
        let biased = noisy_film(1.03, 0.3, 64, 2);
        let c = check_against_reference(&biased, &truth, 1 << 20);
        assert_eq!(c.status, "FAIL", "{c:?}");
        assert!(c.failed());
    }
}

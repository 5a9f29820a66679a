//! Adaptive sampling: it converges to the same image as uniform sampling (no visible bias),
//! puts samples where the noise is, and stops at a target error.

mod common;

use pathtrace::metrics::relative_mse;
use pathtrace::sampling::SamplerKind;
use pathtrace::{render, AdaptiveSettings, RenderSettings, Scene};
use std::sync::Arc;

/// Uneven noise: a glass sphere (caustic, refracted light) on a diffuse floor under a small
/// bright lamp, next to plain floor and empty sky.
fn scene() -> Arc<Scene> {
    common::glass_sphere_under_lamp(1.0, 40.0)
}

fn settings(spp: u32, seed: u64, adaptive: bool) -> RenderSettings {
    RenderSettings {
        width: 32,
        height: 24,
        spp,
        seed,
        sampler: SamplerKind::Independent,
        adaptive: adaptive.then(|| AdaptiveSettings { min_spp: 8, ..Default::default() }),
        ..Default::default()
    }
}

#[test]
fn adaptive_and_uniform_agree_within_confidence_intervals() {
    let uniform = render(scene(), settings(128, 1, false)).unwrap().film;
    let adaptive = render(scene(), settings(128, 2, true)).unwrap().film;
    let (lo, hi) = adaptive.spp_range();
    assert!(lo >= 8 && hi > 4 * 128, "adaptation did not happen: {lo}..{hi} spp");
    // 12 regions of 8×8 pixels × 3 channels = 36 z-scores; |z| > 4.5 has probability ~2e-4
    // for all of them together if both are unbiased.
    let mut worst = 0.0f64;
    for y in (0..24).step_by(8) {
        for x in (0..32).step_by(8) {
            let a = adaptive.region_estimate(x, y, x + 8, y + 8);
            let u = uniform.region_estimate(x, y, x + 8, y + 8);
            worst = worst.max(a.max_z_score(&u));
        }
    }
    eprintln!("max region z-score {worst:.2}");
    assert!(worst < 4.5, "adaptive differs from uniform: max z = {worst:.2}");
    // The whole image's mean as well (the most sensitive to a systematic bias).
    let z = adaptive.region_estimate(0, 0, 32, 24).max_z_score(&uniform.region_estimate(0, 0, 32, 24));
    assert!(z < 4.0, "image mean differs: z = {z:.2}");
}

#[test]
fn adaptive_lowers_the_error_at_equal_sample_count() {
    let reference = render(scene(), settings(2048, 99, false)).unwrap().film.image();
    let error = |adaptive: bool| -> f64 {
        // Averaged over a few seeds: one render's relative MSE is itself noisy.
        (0..4)
            .map(|seed| {
                relative_mse(&render(scene(), settings(64, seed, adaptive)).unwrap().film.image(), &reference).unwrap()
            })
            .sum::<f64>()
            / 4.0
    };
    let (uniform, adaptive) = (error(false), error(true));
    eprintln!("relative MSE at 64 spp: uniform {uniform:.4e}, adaptive {adaptive:.4e} ({:.2}×)", uniform / adaptive);
    assert!(adaptive * 2.0 < uniform, "uniform {uniform:.4e} vs adaptive {adaptive:.4e}");
}

#[test]
fn a_target_error_stops_the_render_when_reached() {
    let mut s = settings(0, 3, true);
    s.adaptive = Some(AdaptiveSettings { min_spp: 8, target_error: Some(0.05), ..Default::default() });
    let out = render(scene(), s).unwrap();
    let reached = out.film.relative_rms_error_estimate().unwrap();
    assert!(reached <= 0.05, "{reached}");
    assert_eq!(out.progress.error_estimate, Some(reached));
    assert_eq!(out.progress.target_error, Some(0.05));
    // It stopped soon after: the wave before did not reach the target, and waves at most double
    // the samples, so the error is not far below it (√2 per doubling; allow two).
    assert!(reached > 0.05 / 2.0, "{reached}");
    // A looser target stops with fewer samples.
    let mut loose = settings(0, 3, true);
    loose.adaptive = Some(AdaptiveSettings { min_spp: 8, target_error: Some(0.2), ..Default::default() });
    let fewer = render(scene(), loose).unwrap().film.total_samples();
    assert!(fewer < out.film.total_samples());
}

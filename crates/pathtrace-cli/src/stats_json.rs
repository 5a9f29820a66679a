//! Machine-readable render statistics (`--stats-json`, `bench --json`).

use pathtrace::{Progress, RenderSettings};
use serde::Serialize;

/// One render's numbers.
#[derive(Debug, Clone, Serialize)]
pub struct RenderStats {
    pub scene: String,
    pub width: u32,
    pub height: u32,
    /// Samples per pixel reached (the fewest of any pixel).
    pub spp: u32,
    pub spp_target: u32,
    pub strategy: String,
    pub sampler: String,
    pub max_depth: i32,
    pub seed: u64,
    pub threads: usize,
    /// Wall-clock seconds of rendering alone (no scene loading or image writing).
    pub render_seconds: f64,
    pub samples: u64,
    pub samples_per_second: f64,
    pub rays_per_second: f64,
    pub camera_rays: u64,
    pub extension_rays: u64,
    pub shadow_rays: u64,
    /// Path segments per sample: (camera + extension rays) / samples.
    pub mean_path_length: f64,
    pub dropped_samples: u64,
    /// Estimated relative RMS error of the image: √ of the expected relative MSE against the
    /// converged image (see `Film::relative_rms_error_estimate` and docs/sampling.md).
    pub relative_error_estimate: Option<f64>,
    /// Adaptive sampling was on.
    pub adaptive: bool,
    /// The adaptive target error, if one was given.
    pub target_error: Option<f64>,
    /// Samples per pixel on average (differs from `spp` with adaptive sampling).
    pub mean_spp: f64,
    pub interrupted: bool,
}

impl RenderStats {
    pub fn new(
        scene: &str,
        s: &RenderSettings,
        p: &Progress,
        spp_reached: u32,
        noise: Option<f64>,
        interrupted: bool,
    ) -> Self {
        let samples = p.samples.max(1) as f64;
        Self {
            scene: scene.to_string(),
            width: s.width,
            height: s.height,
            spp: spp_reached,
            spp_target: s.spp,
            strategy: s.path.strategy.to_string(),
            sampler: s.sampler.to_string(),
            max_depth: s.path.max_depth,
            seed: s.seed,
            threads: effective_threads(s.threads),
            render_seconds: p.elapsed.as_secs_f64(),
            samples: p.samples,
            samples_per_second: p.samples_per_second,
            rays_per_second: p.rays_per_second,
            camera_rays: p.rays.camera_rays,
            extension_rays: p.rays.extension_rays,
            shadow_rays: p.rays.shadow_rays,
            mean_path_length: (p.rays.camera_rays + p.rays.extension_rays) as f64 / samples,
            dropped_samples: p.dropped_samples,
            relative_error_estimate: noise,
            adaptive: s.adaptive.is_some(),
            target_error: s.adaptive.and_then(|a| a.target_error),
            mean_spp: p.samples as f64 / (s.width as f64 * s.height as f64).max(1.0),
            interrupted,
        }
    }
}

/// The thread count a setting of 0 ("all cores") resolves to.
pub fn effective_threads(requested: usize) -> usize {
    if requested > 0 {
        requested
    } else {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    }
}

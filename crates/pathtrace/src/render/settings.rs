//! What to render and how long for.

use super::adaptive::AdaptiveSettings;
use super::sample_range::SampleRange;
use crate::film::PixelFilter;
use crate::integrator::PathSettings;
use crate::sampling::SamplerKind;
use crate::wide::Kernel;
use std::time::Duration;

/// Settings of one render.
#[derive(Clone, Debug, PartialEq)]
pub struct RenderSettings {
    pub width: u32,
    pub height: u32,
    /// Samples per pixel to reach (with adaptive sampling: on average over the image); 0 means
    /// "until the time limit, the target error or cancel".
    pub spp: u32,
    /// Stop after this much wall-clock time (completed tiles are kept).
    pub time_limit: Option<Duration>,
    pub path: PathSettings,
    pub sampler: SamplerKind,
    /// Pixel reconstruction filter, sampled by importance (default: the pixel's own square).
    pub filter: PixelFilter,
    pub seed: u64,
    /// Worker threads; 0 means one per core.
    pub threads: usize,
    /// Tiles are `tile_size × tile_size` pixels.
    pub tile_size: u32,
    /// Samples per pixel of each wave after the first (which takes 1), at least: fast waves
    /// take more (see [`RenderSettings::next_wave`]).
    pub max_wave_spp: u32,
    /// Adaptive sampling (`None`, the default: every pixel gets `spp` samples).
    pub adaptive: Option<AdaptiveSettings>,
    /// How many paths run at once (default: groups of 16 or 32 SIMD lanes; `Scalar`: one).
    pub kernel: Kernel,
    /// Accumulate feature buffers (albedo, normal, depth) beside the image, over the same
    /// samples (`RenderOutcome::features`); off by default, costing nothing then.
    pub features: bool,
    /// Render only these sample indices of every pixel (`None`: all of `0..spp`); `spp` stays
    /// the whole render's, which the stratified sampler spreads its strata over. Not with
    /// adaptive sampling, whose choices depend on every sample so far.
    pub sample_range: Option<SampleRange>,
}

impl Default for RenderSettings {
    fn default() -> Self {
        Self {
            width: 512,
            height: 512,
            spp: 64,
            time_limit: None,
            path: PathSettings::default(),
            sampler: SamplerKind::default(),
            filter: PixelFilter::default(),
            seed: 0,
            threads: 0,
            tile_size: 16,
            max_wave_spp: 16,
            adaptive: None,
            kernel: Kernel::default(),
            features: false,
            sample_range: None,
        }
    }
}

impl RenderSettings {
    /// How many samples the stratified sampler spreads its strata over: the spp target, or
    /// one wave's worth for open-ended (time-limited) renders.
    pub fn strata_count(&self) -> u32 {
        if self.spp > 0 {
            self.spp
        } else {
            self.max_wave_spp.max(1)
        }
    }

    /// The sample indices this render takes: `sample_range`, or `0..spp` (`spp` = 0: endless).
    pub fn samples(&self) -> SampleRange {
        self.sample_range.unwrap_or(SampleRange::new(0, self.spp))
    }

    /// The samples per pixel of the next wave, `done` samples of [`RenderSettings::samples`]
    /// into it, or `None` when they are all done (never, when `spp` is 0: endless). The waves so
    /// far took `seconds_per_spp` per sample per pixel (`None` before the first). Waves start
    /// at the range's first sample; how a range is cut into waves does not change the film (its
    /// sums are integers).
    ///
    /// The first wave takes 1 sample per pixel: a whole image soon (the live view's first
    /// frame; a render stopped early still covers every pixel). After it, few and large waves:
    /// every wave costs a merge of every pixel into the film under its lock, a wait for its last
    /// tile and an error-estimate pass, and in waves of at least 16 samples per pixel a SIMD
    /// group starts 16 samples of one pixel, whose camera rays walk the BVH together. Doubling
    /// waves (1, 2, 4, 8, 16, …) were slower on 16-spp renders (docs/benchmarks.md, "The error
    /// estimate on every thread; waves of one sample per pixel, then whole waves"). So a wave
    /// takes `max_wave_spp`, or more while that would take under [`WAVE_SECONDS`] (at most
    /// [`WAVE_GROWTH`] times as many): the waves of a fast render (teapot-simple's 64 spp take
    /// 0.07 s) are then the first and one other.
    pub fn next_wave(&self, done: u32, seconds_per_spp: Option<f64>) -> Option<u32> {
        let total = self.samples().len();
        if self.spp > 0 && done >= total {
            return None;
        }
        let cap = self.max_wave_spp.max(1);
        let mut n = if done == 0 {
            1
        } else {
            let fits = seconds_per_spp.map_or(0.0, |s| WAVE_SECONDS / s);
            // `as` saturates (and takes NaN to 0): any measurement gives a count in range.
            (fits as u32).clamp(cap, cap.saturating_mul(WAVE_GROWTH))
        };
        if self.spp > 0 {
            n = n.min(total - done);
        }
        Some(n)
    }
}

/// Waves after the first grow past `max_wave_spp` while they would take less than this long
/// ([`RenderSettings::next_wave`]): a quarter of a second keeps the live view's error estimate
/// (refreshed at most every half second) as fresh as before.
pub const WAVE_SECONDS: f64 = 0.25;

/// How many times `max_wave_spp` a wave may grow to.
pub const WAVE_GROWTH: u32 = 16;

#[cfg(test)]
mod tests {
    use super::*;

    /// Every wave of `s` with each wave measured at `seconds_per_spp`.
    fn waves(s: &RenderSettings, seconds_per_spp: Option<f64>, at_most: usize) -> Vec<u32> {
        let mut out = Vec::new();
        let mut done = 0u32;
        while let Some(n) = s.next_wave(done, if done == 0 { None } else { seconds_per_spp }) {
            out.push(n);
            done += n;
            if out.len() == at_most {
                break;
            }
        }
        out
    }

    #[test]
    fn waves_start_with_one_sample_then_cap_and_sum_to_the_target() {
        let s = RenderSettings { spp: 64, max_wave_spp: 16, ..Default::default() };
        assert_eq!(waves(&s, None, 99), vec![1, 16, 16, 16, 15]);
        // Slow waves (a second per sample per pixel) stay at the cap.
        assert_eq!(waves(&s, Some(1.0), 99), vec![1, 16, 16, 16, 15]);
        let s = RenderSettings { spp: 16, ..Default::default() };
        assert_eq!(waves(&s, None, 99), vec![1, 15]);
        let s = RenderSettings { spp: 1, ..Default::default() };
        assert_eq!(waves(&s, None, 99), vec![1]);
        let s = RenderSettings { spp: 0, max_wave_spp: 4, ..Default::default() };
        assert_eq!(waves(&s, None, 4), vec![1, 4, 4, 4]);
        let s = RenderSettings { spp: 64, sample_range: Some(SampleRange::new(10, 30)), ..Default::default() };
        assert_eq!(waves(&s, None, 99), vec![1, 16, 3]);
    }

    /// Fast waves grow to what fits in `WAVE_SECONDS`, at most `WAVE_GROWTH` times the cap, and
    /// still sum to the target; nonsense measurements give waves of the cap.
    #[test]
    fn fast_waves_grow_within_bounds() {
        let s = RenderSettings { spp: 64, max_wave_spp: 16, ..Default::default() };
        assert_eq!(waves(&s, Some(0.001), 99), vec![1, 63]);
        let s = RenderSettings { spp: 4096, max_wave_spp: 16, ..Default::default() };
        assert_eq!(waves(&s, Some(WAVE_SECONDS / 100.0), 3), vec![1, 100, 100]);
        assert_eq!(waves(&s, Some(1e-9), 3), vec![1, 16 * WAVE_GROWTH, 16 * WAVE_GROWTH]);
        for odd in [-1.0, f64::NAN, f64::INFINITY] {
            assert_eq!(waves(&s, Some(odd), 3)[1..], [16, 16], "{odd}");
        }
        // A wave too quick for the clock to see is as fast as can be.
        assert_eq!(waves(&s, Some(0.0), 3)[1..], [16 * WAVE_GROWTH, 16 * WAVE_GROWTH]);
        let s = RenderSettings { spp: 0, max_wave_spp: 16, ..Default::default() };
        assert_eq!(waves(&s, Some(0.001), 3), vec![1, 250, 250]);
    }
}

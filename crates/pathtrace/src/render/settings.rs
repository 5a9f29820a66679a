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
    /// Samples per pixel of each wave after the first (which takes 1: see
    /// [`RenderSettings::waves`]).
    pub max_wave_spp: u32,
    /// Adaptive sampling (`None`, the default: every pixel gets `spp` samples).
    pub adaptive: Option<AdaptiveSettings>,
    /// How many paths run at once (default: groups of 8 or 32 SIMD lanes; `Scalar`: one).
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

    /// The sample counts of successive waves: 1 sample per pixel, then waves of
    /// `max_wave_spp` (the last one what is left), summing to the length of
    /// [`RenderSettings::samples`] (endless when `spp` is 0). Waves start at the range's first
    /// sample; how a range is cut into waves does not change the film.
    ///
    /// The 1-spp wave gives a whole image soon (the live view's first frame; a render stopped
    /// early still covers every pixel). After it, few and large waves: every wave costs a merge
    /// of every pixel into the film, a wait for its last tile and an error-estimate pass, and in
    /// waves of at least 16 samples per pixel a SIMD group starts 16 samples of one pixel, whose
    /// camera rays walk the BVH together. Doubling waves (1, 2, 4, 8, 16, …) were slower on
    /// 16-spp renders (docs/benchmarks.md, "The error estimate on every thread; waves of one
    /// sample per pixel, then whole waves").
    pub fn waves(&self) -> impl Iterator<Item = u32> + '_ {
        let cap = self.max_wave_spp.max(1);
        let total = self.samples().len();
        let mut done = 0u32;
        std::iter::from_fn(move || {
            if self.spp > 0 && done >= total {
                return None;
            }
            let mut n = if done == 0 { 1 } else { cap };
            if self.spp > 0 {
                n = n.min(total - done);
            }
            done = done.saturating_add(n);
            Some(n)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn waves_start_with_one_sample_then_cap_and_sum_to_the_target() {
        let s = RenderSettings { spp: 64, max_wave_spp: 16, ..Default::default() };
        let w: Vec<u32> = s.waves().collect();
        assert_eq!(w, vec![1, 16, 16, 16, 15]);
        let s = RenderSettings { spp: 16, ..Default::default() };
        assert_eq!(s.waves().collect::<Vec<_>>(), vec![1, 15]);
        let s = RenderSettings { spp: 1, ..Default::default() };
        assert_eq!(s.waves().collect::<Vec<_>>(), vec![1]);
        let s = RenderSettings { spp: 0, max_wave_spp: 4, ..Default::default() };
        assert_eq!(s.waves().take(4).collect::<Vec<_>>(), vec![1, 4, 4, 4]);
        let s = RenderSettings { spp: 64, sample_range: Some(SampleRange::new(10, 30)), ..Default::default() };
        assert_eq!(s.waves().collect::<Vec<_>>(), vec![1, 16, 3]);
    }
}

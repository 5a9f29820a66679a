//! Feature buffers (AOVs) accumulated beside the radiance: albedo, shading normal and depth of
//! what each camera sample sees, averaged over the same samples as the image so they are
//! anti-aliased like it and merge like it. A denoiser reads albedo and normal to tell texture and
//! geometry from noise (Intel Open Image Denoise's "auxiliary images"); depth is for compositing.
//!
//! The sums are exact fixed-point integers like the film's (`accumulator.rs`, whose conversion
//! they use): a render split into sample ranges and merged in any order has bit-identical
//! buffers, so a denoised merge is the denoised whole render. Kept apart from the film's radiance
//! statistics on purpose: renders that do not ask for features carry none of this.

use super::accumulator::{fixed, fixed_mean};
use super::allocation::FilmTooLarge;
use super::grid::{Mergeable, PixelGrid};
use super::Image;
use crate::math::{Rgb, Vec3};

/// What one camera sample saw, ready to be averaged.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FeatureSample {
    /// Directional albedo of the first non-specular surface (after mirror and glass chains); for
    /// a path that escapes, the environment's radiance clamped to [0, 1] (`integrator::features`).
    pub albedo: Rgb,
    /// Its shading normal in world space, facing the side the path arrived from; zero where the
    /// path escaped.
    pub normal: Vec3,
    /// Distance from the camera to the first surface the camera ray hits; 0 where it escapes.
    pub depth: f32,
}

/// The sums of one pixel's feature samples: Σ trunc(w·v · 2⁴⁰) per value, w the sample's
/// pixel-filter weight (exact integers: see the module docs).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct FeaturePixel {
    pub count: u32,
    pub albedo: [i128; 3],
    pub normal: [i128; 3],
    pub depth: i128,
}

/// The bytes one pixel's feature sums take in memory.
pub const FEATURE_BYTES_PER_PIXEL: u64 = std::mem::size_of::<FeaturePixel>() as u64;

impl FeaturePixel {
    /// Adds one sample with the weight the pixel filter gave its radiance (f/pdf; 1 for box and
    /// tent), so the features are filtered exactly like the image. `w · v` of two f32 is exact
    /// in f64, so the only rounding is the fixed-point truncation: a pure function of the sample.
    #[inline]
    pub fn add(&mut self, s: &FeatureSample, weight: f32) {
        let w = weight as f64;
        self.count += 1;
        for (sum, v) in self.albedo.iter_mut().zip(s.albedo.to_array()) {
            *sum += fixed(w * v as f64);
        }
        for (sum, v) in self.normal.iter_mut().zip([s.normal.x, s.normal.y, s.normal.z]) {
            *sum += fixed(w * v as f64);
        }
        self.depth += fixed(w * s.depth as f64);
    }

    fn mean(&self, sum: [i128; 3]) -> Rgb {
        let [r, g, b] = sum.map(|s| fixed_mean(s, self.count) as f32);
        Rgb::new(r, g, b)
    }
}

impl Mergeable for FeaturePixel {
    /// Combines two pixels' samples: integer addition, so any order gives the same bits.
    #[inline]
    fn merge(&mut self, o: &FeaturePixel) {
        self.count += o.count;
        for k in 0..3 {
            self.albedo[k] += o.albedo[k];
            self.normal[k] += o.normal[k];
        }
        self.depth += o.depth;
    }
}

/// The feature buffers of an image.
#[derive(Clone, Debug, PartialEq)]
pub struct FeatureBuffers {
    grid: PixelGrid<FeaturePixel>,
}

impl FeatureBuffers {
    /// Empty buffers of `width` × `height` pixels, or an error naming the memory they need.
    pub fn try_new(width: u32, height: u32) -> Result<Self, FilmTooLarge> {
        Ok(Self { grid: PixelGrid::try_new(width, height)? })
    }

    /// Buffers of the given pixel sums (row by row; `pixels.len()` must be `width × height`).
    pub(super) fn from_pixels(width: u32, height: u32, pixels: Vec<FeaturePixel>) -> Self {
        Self { grid: PixelGrid::from_pixels(width, height, pixels) }
    }

    pub fn width(&self) -> u32 {
        self.grid.width()
    }

    pub fn height(&self) -> u32 {
        self.grid.height()
    }

    /// Every pixel's sums, row by row.
    pub fn pixels(&self) -> &[FeaturePixel] {
        self.grid.pixels()
    }

    /// Adds one sample to pixel `(x, y)` (see [`FeaturePixel::add`]).
    pub fn add_sample(&mut self, x: u32, y: u32, s: &FeatureSample, weight: f32) {
        self.grid.pixel_mut(x, y).add(s, weight);
    }

    /// Merges a block of pixel sums covering the rectangle at `(x0, y0)` of width `w`.
    pub fn merge_block(&mut self, x0: u32, y0: u32, w: u32, block: &[FeaturePixel]) {
        self.grid.merge_block(x0, y0, w, block);
    }

    /// Adds every sample of buffers of the same size; `false` (and nothing changes) if the sizes
    /// differ.
    pub fn merge(&mut self, other: &FeatureBuffers) -> bool {
        self.grid.merge(&other.grid)
    }

    fn image(&self, f: impl Fn(&FeaturePixel) -> Rgb) -> Image {
        Image { width: self.width(), height: self.height(), pixels: self.pixels().iter().map(f).collect() }
    }

    /// Mean albedo per pixel (black before any sample).
    pub fn albedo(&self) -> Image {
        self.image(|p| p.mean(p.albedo))
    }

    /// Mean shading normal per pixel, world space, components in [-1, 1] (not renormalised: at
    /// silhouettes the average of two normals is shorter than one, as a denoiser expects).
    pub fn normal(&self) -> Image {
        self.image(|p| p.mean(p.normal))
    }

    /// Mean first-hit distance per pixel, the same in all three channels.
    pub fn depth(&self) -> Image {
        self.image(|p| Rgb::splat(fixed_mean(p.depth, p.count) as f32))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn merged_halves_equal_the_whole() {
        let samples: Vec<FeatureSample> = (0..9)
            .map(|i| FeatureSample {
                albedo: Rgb::splat(i as f32 * 0.1),
                normal: Vec3::new(0.0, 0.0, if i % 2 == 0 { 1.0 } else { -1.0 }),
                depth: i as f32,
            })
            .collect();
        let mut all = FeatureBuffers::try_new(2, 1).unwrap();
        let (mut a, mut b) = (all.clone(), all.clone());
        for (i, s) in samples.iter().enumerate() {
            all.add_sample(1, 0, s, 1.0);
            if i < 4 { &mut a } else { &mut b }.add_sample(1, 0, s, 1.0);
        }
        assert!(a.merge(&b));
        assert_eq!(a.pixels()[1].count, 9);
        assert!((a.depth().get(1, 0).r - 4.0).abs() < 1e-6);
        assert!((all.albedo().get(1, 0).g - 0.4).abs() < 1e-6);
        assert!((all.normal().get(1, 0).b - 1.0 / 9.0).abs() < 1e-6);
        assert_eq!(all.depth().get(0, 0), Rgb::BLACK);
        assert!(!a.merge(&FeatureBuffers::try_new(1, 1).unwrap()));
    }

    #[test]
    fn any_split_and_order_of_weighted_samples_gives_the_same_bits() {
        // Weights and values at wildly different scales: float sums would round differently in
        // each order; the fixed-point sums may not.
        let samples: Vec<(FeatureSample, f32)> = (0..12)
            .map(|i| {
                let x = [1e-7f32, 0.3, 7.0e4, 0.9, 1.0 / 3.0, 2.5e-3][i % 6];
                let s = FeatureSample {
                    albedo: Rgb::new(x, 1.0 - x.min(1.0), 0.25),
                    normal: Vec3::new(-x, 0.5, x * 0.1),
                    depth: x * 1e3,
                };
                (s, [1.0, 0.73, 1.9, -0.04][i % 4])
            })
            .collect();
        let mut whole = FeatureBuffers::try_new(1, 1).unwrap();
        for (s, w) in &samples {
            whole.add_sample(0, 0, s, *w);
        }
        for split in 1..samples.len() {
            // The two parts each add their samples in reverse order, then merge both ways.
            let mut parts = [FeatureBuffers::try_new(1, 1).unwrap(), FeatureBuffers::try_new(1, 1).unwrap()];
            for (i, (s, w)) in samples.iter().enumerate().rev() {
                parts[usize::from(i >= split)].add_sample(0, 0, s, *w);
            }
            let (mut ab, mut ba) = (parts[0].clone(), parts[1].clone());
            assert!(ab.merge(&parts[1]));
            ba.merge_block(0, 0, 1, parts[0].pixels());
            assert_eq!(ab, whole, "split at {split}");
            assert_eq!(ba, whole, "split at {split}, other order");
        }
        // The comparison can fail: a sample left out changes the sums.
        let mut short = FeatureBuffers::try_new(1, 1).unwrap();
        for (s, w) in &samples[1..] {
            short.add_sample(0, 0, s, *w);
        }
        assert_ne!(short, whole);
    }
}

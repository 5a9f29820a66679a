//! Feature buffers (AOVs) accumulated beside the radiance: albedo, shading normal and depth of
//! what each camera sample sees, averaged over the same samples as the image so they are
//! anti-aliased like it and merge like it. A denoiser reads albedo and normal to tell texture and
//! geometry from noise (Intel Open Image Denoise's "auxiliary images"); depth is for compositing.
//!
//! Kept apart from the film's radiance accumulator on purpose: renders that do not ask for
//! features carry none of this, and the film's own statistics stay as they are.

use super::allocation::FilmTooLarge;
use super::Image;
use crate::math::{Rgb, Vec3};

/// What one camera sample saw, ready to be averaged.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FeatureSample {
    /// Directional albedo of the first non-specular surface (after mirror and glass chains).
    pub albedo: Rgb,
    /// Its shading normal in world space, facing the side the path arrived from; zero where the
    /// path escaped.
    pub normal: Vec3,
    /// Distance from the camera to the first surface the camera ray hits; 0 where it escapes.
    pub depth: f32,
}

/// The sums of one pixel's feature samples (f64, so millions of samples lose no precision).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FeaturePixel {
    pub count: u32,
    pub albedo: [f64; 3],
    pub normal: [f64; 3],
    pub depth: f64,
}

impl FeaturePixel {
    /// Adds one sample with the weight the pixel filter gave its radiance (f/pdf; 1 for box and
    /// tent), so the features are filtered exactly like the image.
    #[inline]
    pub fn add(&mut self, s: &FeatureSample, weight: f32) {
        let w = weight as f64;
        self.count += 1;
        for (sum, v) in self.albedo.iter_mut().zip(s.albedo.to_array()) {
            *sum += w * v as f64;
        }
        for (sum, v) in self.normal.iter_mut().zip([s.normal.x, s.normal.y, s.normal.z]) {
            *sum += w * v as f64;
        }
        self.depth += w * s.depth as f64;
    }

    /// Combines two pixels' samples.
    #[inline]
    pub fn merge(&mut self, o: &FeaturePixel) {
        self.count += o.count;
        for k in 0..3 {
            self.albedo[k] += o.albedo[k];
            self.normal[k] += o.normal[k];
        }
        self.depth += o.depth;
    }

    fn mean(&self, sum: [f64; 3]) -> Rgb {
        let n = self.count.max(1) as f64;
        Rgb::new((sum[0] / n) as f32, (sum[1] / n) as f32, (sum[2] / n) as f32)
    }
}

/// The feature buffers of an image.
#[derive(Clone, Debug, PartialEq)]
pub struct FeatureBuffers {
    width: u32,
    height: u32,
    pixels: Vec<FeaturePixel>,
}

impl FeatureBuffers {
    /// Empty buffers of `width` × `height` pixels, or an error naming the memory they need.
    pub fn try_new(width: u32, height: u32) -> Result<Self, FilmTooLarge> {
        let len = u64::from(width) * u64::from(height);
        let bytes = len * std::mem::size_of::<FeaturePixel>() as u64;
        let mut pixels = Vec::new();
        usize::try_from(len).ok().and_then(|n| pixels.try_reserve_exact(n).ok()).ok_or(FilmTooLarge {
            width,
            height,
            bytes,
        })?;
        pixels.resize(len as usize, FeaturePixel::default());
        Ok(Self { width, height, pixels })
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    /// Every pixel's sums, row by row.
    pub fn pixels(&self) -> &[FeaturePixel] {
        &self.pixels
    }

    /// Adds one sample to pixel `(x, y)` (see [`FeaturePixel::add`]).
    pub fn add_sample(&mut self, x: u32, y: u32, s: &FeatureSample, weight: f32) {
        self.pixels[(y * self.width + x) as usize].add(s, weight);
    }

    /// Merges a block of pixel sums covering the rectangle at `(x0, y0)` of width `w`.
    pub fn merge_block(&mut self, x0: u32, y0: u32, w: u32, block: &[FeaturePixel]) {
        for (i, p) in block.iter().enumerate() {
            let (x, y) = (x0 + i as u32 % w, y0 + i as u32 / w);
            self.pixels[(y * self.width + x) as usize].merge(p);
        }
    }

    /// Adds every sample of buffers of the same size; `false` (and nothing changes) if the sizes
    /// differ.
    pub fn merge(&mut self, other: &FeatureBuffers) -> bool {
        if other.width != self.width || other.height != self.height {
            return false;
        }
        for (a, b) in self.pixels.iter_mut().zip(&other.pixels) {
            a.merge(b);
        }
        true
    }

    fn image(&self, f: impl Fn(&FeaturePixel) -> Rgb) -> Image {
        Image { width: self.width, height: self.height, pixels: self.pixels.iter().map(f).collect() }
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
        self.image(|p| Rgb::splat(p.mean([p.depth; 3]).r))
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
}

//! The film: the accumulation buffer of a render. Per pixel it keeps a sample count and exact
//! fixed-point sums of the samples and of their squares (`accumulator.rs`); the image is the mean
//! (sum / count), tone mapped only on output. A render whose filter is wider than the pixel also
//! keeps the splatted sums Σw and Σw·L (`splat.rs`), and its image is their ratio; the per-pixel
//! statistics of each pixel's own samples still drive the noise estimates (see `splat.rs`).
//! Films of the same size merge by adding their sums, which gives the same bits in any order.

use super::accumulator::PixelStats;
use super::allocation::FilmTooLarge;
use super::grid::{Mergeable, PixelGrid};
use super::splat::{SplatBlock, SplatPixel};
use super::Image;
use crate::math::Rgb;

/// The mean of a block of pixels and the estimated variance of that mean, per channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegionEstimate {
    pub mean: [f64; 3],
    pub variance_of_mean: [f64; 3],
    pub pixels: usize,
}

impl RegionEstimate {
    /// Largest per-channel z-score of the difference between two independent estimates.
    pub fn max_z_score(&self, other: &RegionEstimate) -> f64 {
        (0..3)
            .map(|k| {
                let sd = (self.variance_of_mean[k] + other.variance_of_mean[k]).sqrt();
                let d = (self.mean[k] - other.mean[k]).abs();
                if sd > 0.0 {
                    d / sd
                } else if d == 0.0 {
                    0.0
                } else {
                    f64::INFINITY
                }
            })
            .fold(0.0, f64::max)
    }

    /// Largest per-channel z-score against an exactly known value.
    pub fn max_z_score_against(&self, expected: [f64; 3]) -> f64 {
        let exact = RegionEstimate { mean: expected, variance_of_mean: [0.0; 3], pixels: 0 };
        self.max_z_score(&exact)
    }
}

impl Mergeable for PixelStats {
    #[inline]
    fn merge(&mut self, other: &Self) {
        PixelStats::merge(self, other);
    }
}

/// An accumulation buffer.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    grid: PixelGrid<PixelStats>,
    /// The splatted sums, for filters wider than the pixel (`None`: the image is the mean).
    splat: Option<PixelGrid<SplatPixel>>,
    /// Samples rejected because they were NaN or infinite.
    pub dropped_samples: u64,
}

impl Film {
    pub fn new(width: u32, height: u32) -> Self {
        let pixels = vec![PixelStats::default(); width as usize * height as usize];
        Self::from_pixels(width, height, pixels, None)
    }

    /// A film of `width` × `height` pixels, or an error naming the memory it needs when it cannot
    /// be allocated (renders ask for this one; [`Film::new`] aborts like any allocation).
    /// `splat`: with splatted sums (a filter wider than the pixel: [`super::PixelFilter::splats`]).
    pub fn try_new(width: u32, height: u32, splat: bool) -> Result<Self, FilmTooLarge> {
        let splat = if splat { Some(PixelGrid::try_new(width, height)?) } else { None };
        Ok(Self { grid: PixelGrid::try_new(width, height)?, splat, dropped_samples: 0 })
    }

    /// A film of the given pixels (row by row; `pixels.len()` must be `width × height`), with
    /// splatted sums if given (as many).
    pub(super) fn from_pixels(
        width: u32,
        height: u32,
        pixels: Vec<PixelStats>,
        splat: Option<Vec<SplatPixel>>,
    ) -> Self {
        let splat = splat.map(|s| PixelGrid::from_pixels(width, height, s));
        Self { grid: PixelGrid::from_pixels(width, height, pixels), splat, dropped_samples: 0 }
    }

    /// The splatted sums, row by row (`None` unless the filter is wider than the pixel).
    pub fn splat_pixels(&self) -> Option<&[SplatPixel]> {
        self.splat.as_ref().map(PixelGrid::pixels)
    }

    /// Merges a tile's splatted halo block (a film without splatted sums ignores it).
    pub fn merge_splat_block(&mut self, block: &SplatBlock) {
        if let Some(grid) = &mut self.splat {
            grid.merge_block(block.x0, block.y0, block.w, &block.sums());
        }
    }

    /// Pixel `i`'s (row by row) value in the image: the splatted ratio or the mean.
    fn value(&self, i: usize) -> [f64; 3] {
        match &self.splat {
            Some(grid) => grid.pixels()[i].value(),
            None => self.grid.pixels()[i].mean(),
        }
    }

    pub fn width(&self) -> u32 {
        self.grid.width()
    }

    pub fn height(&self) -> u32 {
        self.grid.height()
    }

    pub fn pixel(&self, x: u32, y: u32) -> &PixelStats {
        self.grid.pixel(x, y)
    }

    /// Every pixel's statistics, row by row.
    pub fn pixels(&self) -> &[PixelStats] {
        self.grid.pixels()
    }

    /// Adds one sample to pixel `(x, y)`; NaN or infinite samples are dropped and counted.
    pub fn add_sample(&mut self, x: u32, y: u32, c: Rgb) {
        if !c.is_finite() {
            self.dropped_samples += 1;
            return;
        }
        self.grid.pixel_mut(x, y).add(c);
    }

    /// Merges a block of pixel statistics covering the rectangle at `(x0, y0)` of width `w`.
    pub fn merge_block(&mut self, x0: u32, y0: u32, w: u32, block: &[PixelStats]) {
        self.grid.merge_block(x0, y0, w, block);
    }

    /// Adds every sample of another film of the same size; `false` (and nothing changes) if
    /// the sizes differ.
    /// Films with and without splatted sums do not merge either.
    pub fn merge(&mut self, other: &Film) -> bool {
        let same_kind = self.splat.is_some() == other.splat.is_some();
        let same_size = (self.width(), self.height()) == (other.width(), other.height());
        if !(same_kind && same_size) {
            return false;
        }
        self.grid.merge(&other.grid);
        if let (Some(mine), Some(theirs)) = (&mut self.splat, &other.splat) {
            mine.merge(theirs);
        }
        self.dropped_samples += other.dropped_samples;
        true
    }

    /// The current estimate: each pixel's mean, or its splatted ratio Σw·L / Σw (black where no
    /// sample landed yet).
    pub fn image(&self) -> Image {
        let pixels = match &self.splat {
            None => self.pixels().iter().map(PixelStats::mean_rgb).collect(),
            Some(grid) => grid
                .pixels()
                .iter()
                .map(|p| {
                    let v = p.value();
                    Rgb::new(v[0] as f32, v[1] as f32, v[2] as f32)
                })
                .collect(),
        };
        Image { width: self.width(), height: self.height(), pixels }
    }

    /// Per-pixel estimated variance of the mean (s²/n per channel).
    pub fn variance_image(&self) -> Image {
        let pixels = self
            .pixels()
            .iter()
            .map(|p| {
                let v = p.variance_of_mean();
                Rgb::new(v[0] as f32, v[1] as f32, v[2] as f32)
            })
            .collect();
        Image { width: self.width(), height: self.height(), pixels }
    }

    /// Mean radiance over the pixel rectangle `[x0, x1) × [y0, y1)` with the estimated variance
    /// of that mean per channel (pixels are independent, so variances add: Σ s²ₚ/nₚ / N²).
    /// For statistical tests that compare renders. With splatted sums the mean is the image's
    /// (the ratios) and the variance that of the block's own samples, which the splat only moves
    /// around within the block but for its edge (`splat.rs`): close for blocks much wider than
    /// the filter.
    pub fn region_estimate(&self, x0: u32, y0: u32, x1: u32, y1: u32) -> RegionEstimate {
        let (x1, y1) = (x1.min(self.width()), y1.min(self.height()));
        let mut mean = [0.0f64; 3];
        let mut var = [0.0f64; 3];
        let mut n = 0usize;
        for y in y0..y1 {
            for x in x0..x1 {
                let i = (y * self.width() + x) as usize;
                let (m, v) = (self.value(i), self.pixels()[i].variance_of_mean());
                for k in 0..3 {
                    mean[k] += m[k];
                    var[k] += v[k];
                }
                n += 1;
            }
        }
        let nf = n.max(1) as f64;
        RegionEstimate { mean: mean.map(|m| m / nf), variance_of_mean: var.map(|v| v / (nf * nf)), pixels: n }
    }

    /// Fewest and most samples held by any pixel.
    pub fn spp_range(&self) -> (u32, u32) {
        self.pixels().iter().fold((u32::MAX, 0), |(lo, hi), p| (lo.min(p.count), hi.max(p.count)))
    }

    /// Total samples accumulated.
    pub fn total_samples(&self) -> u64 {
        self.pixels().iter().map(|p| p.count as u64).sum()
    }

    /// Estimated relative RMS error of the image: √(Σ s²/n) / √(Σ mean²) over all pixels and
    /// channels — the noise left, as a fraction of the signal. `None` before every pixel has
    /// two samples.
    pub fn relative_error_estimate(&self) -> Option<f64> {
        let mut err = 0.0f64;
        let mut signal = 0.0f64;
        for p in self.pixels() {
            if p.count < 2 {
                return None;
            }
            err += p.variance_of_mean().iter().sum::<f64>();
            signal += p.mean().iter().map(|m| m * m).sum::<f64>();
        }
        (signal > 0.0).then(|| (err / signal).sqrt())
    }
}

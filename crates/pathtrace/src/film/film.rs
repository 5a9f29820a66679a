//! The film: the accumulation buffer of a render. Per pixel it keeps a sample count, the running
//! mean and the running variance; the image is the mean (sum / count), tone mapped only on
//! output. Films of the same size merge by adding their samples.

use super::accumulator::PixelStats;
use super::Image;
use crate::math::Rgb;

/// An accumulation buffer.
#[derive(Clone, Debug, PartialEq)]
pub struct Film {
    width: u32,
    height: u32,
    pixels: Vec<PixelStats>,
    /// Samples rejected because they were NaN or infinite.
    pub dropped_samples: u64,
}

impl Film {
    pub fn new(width: u32, height: u32) -> Self {
        Self { width, height, pixels: vec![PixelStats::default(); width as usize * height as usize], dropped_samples: 0 }
    }

    pub fn width(&self) -> u32 {
        self.width
    }

    pub fn height(&self) -> u32 {
        self.height
    }

    pub fn pixel(&self, x: u32, y: u32) -> &PixelStats {
        &self.pixels[(y * self.width + x) as usize]
    }

    /// Adds one sample to pixel `(x, y)`; NaN or infinite samples are dropped and counted.
    pub fn add_sample(&mut self, x: u32, y: u32, c: Rgb) {
        if !c.is_finite() {
            self.dropped_samples += 1;
            return;
        }
        self.pixels[(y * self.width + x) as usize].add(c);
    }

    /// Merges a block of pixel statistics covering the rectangle at `(x0, y0)` of width `w`.
    pub fn merge_block(&mut self, x0: u32, y0: u32, w: u32, block: &[PixelStats]) {
        for (i, s) in block.iter().enumerate() {
            let (x, y) = (x0 + i as u32 % w, y0 + i as u32 / w);
            self.pixels[(y * self.width + x) as usize].merge(s);
        }
    }

    /// Adds every sample of another film of the same size; `false` (and nothing changes) if
    /// the sizes differ.
    pub fn merge(&mut self, other: &Film) -> bool {
        if other.width != self.width || other.height != self.height {
            return false;
        }
        for (a, b) in self.pixels.iter_mut().zip(&other.pixels) {
            a.merge(b);
        }
        self.dropped_samples += other.dropped_samples;
        true
    }

    /// The current estimate: each pixel's mean (black where no sample landed yet).
    pub fn image(&self) -> Image {
        let pixels = self.pixels.iter().map(PixelStats::mean_rgb).collect();
        Image { width: self.width, height: self.height, pixels }
    }

    /// Per-pixel estimated variance of the mean (s²/n per channel).
    pub fn variance_image(&self) -> Image {
        let pixels = self
            .pixels
            .iter()
            .map(|p| {
                let v = p.variance_of_mean();
                Rgb::new(v[0] as f32, v[1] as f32, v[2] as f32)
            })
            .collect();
        Image { width: self.width, height: self.height, pixels }
    }

    /// Fewest and most samples held by any pixel.
    pub fn spp_range(&self) -> (u32, u32) {
        self.pixels.iter().fold((u32::MAX, 0), |(lo, hi), p| (lo.min(p.count), hi.max(p.count)))
    }

    /// Total samples accumulated.
    pub fn total_samples(&self) -> u64 {
        self.pixels.iter().map(|p| p.count as u64).sum()
    }

    /// Estimated relative RMS error of the image: √(Σ s²/n) / √(Σ mean²) over all pixels and
    /// channels — the noise left, as a fraction of the signal. `None` before every pixel has
    /// two samples.
    pub fn relative_error_estimate(&self) -> Option<f64> {
        let mut err = 0.0f64;
        let mut signal = 0.0f64;
        for p in &self.pixels {
            if p.count < 2 {
                return None;
            }
            err += p.variance_of_mean().iter().sum::<f64>();
            signal += p.mean.iter().map(|m| m * m).sum::<f64>();
        }
        (signal > 0.0).then(|| (err / signal).sqrt())
    }
}

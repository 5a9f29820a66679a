//! Path regeneration: a tile's pixel samples flow through a group of `N` lanes, and a lane
//! whose path ends starts the tile's next camera sample at once, so lanes stay busy instead of
//! waiting for the longest path of a batch (as wavefront renderers and Mitsuba 3's vectorised
//! variants do).

use super::lanes::{Output, Paths, TileSplat};
use super::path::vertex;
use crate::camera::Camera;
use crate::film::{FeaturePixel, PixelFilter, PixelStats, SplatBlock};
use crate::integrator::PathStats;
use crate::render::tile::{Tile, TileResult, WaveSamples};
use crate::sampling::Sampler;
use crate::scene::Scene;
use crate::wide::simd::{F32s, Ms};
use crate::wide::{LaneSamplers, WideScene};

/// What every tile of a render shares.
pub(crate) struct LaneJob<'a> {
    pub scene: &'a Scene,
    /// The scene's lane-parallel forms.
    pub lanes: &'a WideScene,
    pub camera: &'a Camera,
    pub filter: &'a PixelFilter,
    /// Record each sample's features (albedo, normal, depth) beside its radiance.
    pub features: bool,
}

/// The tile's pixel samples, pixel by pixel (so the camera rays of a batch are neighbours).
struct Queue<'a> {
    tile: Tile,
    samples: WaveSamples<'a>,
    /// The current pixel: its index in the tile and its film coordinates (kept as the index
    /// advances: two divisions per sample were 1.3% of the teapot's render).
    pixel: u32,
    x: u32,
    y: u32,
    next: u32,
    end: u32,
}

/// One pixel sample to start: index of the pixel in the tile, its coordinates, sample index.
struct Job {
    pixel: u32,
    x: u32,
    y: u32,
    sample: u32,
}

/// Samples for a whole lane group at once: lane `i` takes sample `first.sample + i %
/// per_pixel` of the pixel `i / per_pixel` to the right of `first`'s (`per_pixel` a power of
/// two).
struct Run {
    first: Job,
    per_pixel: u32,
}

impl<'a> Queue<'a> {
    fn new(tile: Tile, samples: WaveSamples<'a>) -> Self {
        let mut q = Self { tile, samples, pixel: 0, x: tile.x0, y: tile.y0, next: 0, end: 0 };
        q.enter_pixel();
        q
    }

    fn enter_pixel(&mut self) {
        if self.pixel < self.tile.w * self.tile.h {
            let (first, count) = self.samples.range(self.x, self.y);
            self.next = first;
            self.end = first + count;
        }
    }

    /// Moves to the tile's next pixel, row by row.
    fn advance(&mut self) {
        self.pixel += 1;
        self.x += 1;
        if self.x == self.tile.x0 + self.tile.w {
            self.x = self.tile.x0;
            self.y += 1;
        }
    }

    /// Moves past finished pixels; false when the tile has no samples left.
    #[inline(always)]
    fn skip_finished(&mut self) -> bool {
        let pixels = self.tile.w * self.tile.h;
        while self.next >= self.end {
            if self.pixel >= pixels {
                return false;
            }
            self.advance();
            self.enter_pixel();
        }
        self.pixel < pixels
    }

    #[inline(always)]
    fn pop(&mut self) -> Option<Job> {
        if !self.skip_finished() {
            return None;
        }
        let sample = self.next;
        self.next += 1;
        Some(Job { pixel: self.pixel, x: self.x, y: self.y, sample })
    }

    /// The next `n` samples (`n` a power of two) as a [`Run`], when they are a whole number of
    /// pixels' samples laid out evenly: `n` samples of one pixel, or the `c` samples of each of
    /// `n / c` pixels of one tile row in a uniform wave of `c` samples per pixel. Then the queue
    /// is where `n` calls of [`Queue::pop`] would leave it, and lane `i` of the run is what the
    /// `i`-th of those calls would give. Otherwise `None`, and the next `pop` gives what it would
    /// have.
    #[inline(always)]
    fn pop_run(&mut self, n: u32) -> Option<Run> {
        debug_assert!(n.is_power_of_two());
        // The same moves past finished pixels as `pop` makes first.
        if !self.skip_finished() {
            return None;
        }
        let first = Job { pixel: self.pixel, x: self.x, y: self.y, sample: self.next };
        let left = self.end - self.next;
        if left >= n {
            self.next += n;
            return Some(Run { first, per_pixel: n });
        }
        // Several pixels: each with all of the wave's samples still to take (so `left` is
        // the wave's count), the count dividing `n` (a power of two, so the lanes' pixel is a
        // shift away), and every pixel in this row of the tile.
        let WaveSamples::Uniform { count, .. } = self.samples else { return None };
        let span = n / left;
        if left != count || !n.is_multiple_of(left) || self.x + span > self.tile.x0 + self.tile.w {
            return None;
        }
        // Onto the run's last pixel, its samples taken (`pop` moves on from there).
        self.pixel += span - 1;
        self.x += span - 1;
        self.next = self.end;
        Some(Run { first, per_pixel: left })
    }
}

/// Renders the wave's samples of every pixel in `tile` in groups of `N` lanes. Each pixel
/// sample's random numbers come from a copy of `proto` started at (pixel, sample index), so the
/// result does not depend on the thread, the lane or the lane count.
#[inline(always)]
pub(crate) fn render_tile_lanes<const N: usize>(
    job: &LaneJob,
    proto: &Sampler,
    tile: Tile,
    samples: WaveSamples,
) -> TileResult {
    let mut samplers = LaneSamplers::<N>::new(proto);
    let tile_pixels = (tile.w * tile.h) as usize;
    let mut out = Output {
        pixels: vec![PixelStats::default(); tile_pixels],
        stats: PathStats::default(),
        dropped: 0,
        features: job.features.then(|| vec![FeaturePixel::default(); tile_pixels]),
        splat: job.filter.splats().then(|| TileSplat {
            block: SplatBlock::for_tile(
                job.filter,
                (tile.x0, tile.y0, tile.w, tile.h),
                job.camera.width,
                job.camera.height,
            ),
            filter: job.filter.clone(),
            x0: tile.x0,
            y0: tile.y0,
            w: tile.w,
        }),
    };
    let mut queue = Queue::new(tile, samples);
    let mut paths = Paths::<N>::new();
    let max_depth = job.lanes.settings.max_depth;
    let aperture = job.camera.needs_aperture_sample();
    loop {
        // Lanes whose path ended take the tile's next samples: their random numbers and pixel
        // offsets lane by lane, their camera rays together.
        let mut fresh = Ms::<N>::NONE;
        let mut pixel = [0u32; N];
        let mut at = [F32s::<N>::ZERO; 2];
        // When every lane is free and the next N samples are one pixel's (waves of N or more
        // samples per pixel) or whole pixels' of one tile row (uniform waves of fewer), the
        // lanes are filled as whole vectors; otherwise lane by lane. Both give lane i the same
        // sample.
        let run = if paths.active.any() { None } else { queue.pop_run(N as u32) };
        if let Some(Run { first, per_pixel }) = run {
            let shift = per_pixel.trailing_zeros();
            let step: [u32; N] = std::array::from_fn(|i| i as u32 >> shift);
            samplers.begin_run(first.x, first.y, first.sample, per_pixel);
            fresh = Ms::ALL;
            pixel = step.map(|k| first.pixel + k);
            at = [F32s(step.map(|k| (first.x + k) as f32)), F32s::splat(first.y as f32)];
        } else {
            for i in (!paths.active).lanes() {
                let Some(next) = queue.pop() else { break };
                samplers.begin(i, next.x, next.y, next.sample);
                fresh.0[i] = u32::MAX;
                pixel[i] = next.pixel;
                (at[0].0[i], at[1].0[i]) = (next.x as f32, next.y as f32);
            }
        }
        if fresh.any() {
            let (u_filter, u_aperture) = samplers.camera_points(fresh, aperture);
            // Where in the pixel the ray goes (film/filter.rs); filters wider than the pixel
            // weight the sample when it is splatted (film/splat.rs). Lanes not started are
            // ignored from here on.
            let jitter = job.filter.sample_lanes(u_filter);
            let (origin, dir) = job.camera.generate_rays(at, jitter, u_aperture);
            paths.start(fresh, &pixel, &origin, &dir, job.scene.camera_medium(), &jitter, job.features);
            if max_depth == 0 {
                paths.finish_all(fresh, &mut out);
            }
            out.stats.camera_rays += u64::from(fresh.bitmask().count_ones());
        }
        if !paths.active.any() {
            break;
        }
        vertex(job, &mut paths, &mut samplers, &mut out);
    }
    TileResult {
        tile,
        pixels: out.pixels,
        stats: out.stats,
        dropped: out.dropped,
        features: out.features,
        splat: out.splat.map(|s| s.block),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Taking runs of samples where they fit, and single samples elsewhere, hands out the same
    /// samples in the same order as taking them one by one: uniform waves of several sizes
    /// (runs within a pixel, runs across a row's pixels, counts that do not divide the run) and
    /// per-pixel counts (adaptive waves, with empty pixels), in a narrow and a wide tile.
    #[test]
    fn runs_hand_out_the_samples_one_by_one_pops_do() {
        let counts: Vec<u32> = (0..12 * 4).map(|i| [0, 16, 5, 33, 16, 1][i % 6]).collect();
        let firsts: Vec<u32> = (0..12 * 4).map(|i| 7 * i as u32).collect();
        let key = |j: Job| (j.pixel, j.x, j.y, j.sample);
        let mut across_pixels = 0;
        for tile in [Tile { x0: 2, y0: 1, w: 3, h: 2 }, Tile { x0: 1, y0: 0, w: 9, h: 3 }] {
            let waves = [
                WaveSamples::Uniform { first: 0, count: 16 },
                WaveSamples::Uniform { first: 3, count: 40 },
                WaveSamples::Uniform { first: 0, count: 4 },
                WaveSamples::Uniform { first: 5, count: 2 },
                WaveSamples::Uniform { first: 0, count: 1 },
                WaveSamples::Uniform { first: 1, count: 3 },
                WaveSamples::PerPixel { width: 12, first: &firsts, count: &counts },
            ];
            for samples in waves {
                let mut one = Queue::new(tile, samples);
                let expected: Vec<_> = std::iter::from_fn(|| one.pop()).map(key).collect();
                for n in [4, 8, 16] {
                    let mut q = Queue::new(tile, samples);
                    let mut got = Vec::new();
                    loop {
                        if let Some(Run { first: j, per_pixel: c }) = q.pop_run(n) {
                            across_pixels += usize::from(c < n);
                            got.extend((0..n).map(|k| (j.pixel + k / c, j.x + k / c, j.y, j.sample + k % c)));
                        } else if let Some(j) = q.pop() {
                            got.push(key(j));
                        } else {
                            break;
                        }
                    }
                    assert_eq!(got, expected, "{tile:?}, {samples:?}, runs of {n}");
                }
            }
        }
        assert!(across_pixels > 0);
    }
}
